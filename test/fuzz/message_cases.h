// Seed messages and their seeded mutations for the fuzz tests and for the
// libFuzzer seed corpus. A seed is a valid message of the kind the package's
// own nodes publish (or a real sensor driver would); a mutation breaks one to
// four things in it, from hostile values (NaN, Inf, zero, huge depth) to
// broken layouts (wrong step or point_step, truncated data, missing,
// overlapping or oddly typed fields, bad block arrays, bad times).
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "fuzz_mutator.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/map/tsdf_map.h"

namespace surface_nbv {
namespace fuzz {

// 32 x 32 x 16 voxels of 0.25 m: a 4 x 4 x 2 block grid, at most 24 blocks
// (so an update that needs more is refused as incompatible).
TsdfConfig fuzzMapConfig();

// Allocates (or rewrites) up to `blocks` blocks of `map` at seeded indices
// with seeded finite voxels, stamping each as an integrator would.
void scribbleMap(TsdfMap* map, int blocks, Mutator& m);

// A valid depth image: 32FC1, 16UC1 or mono16, little or big endian, rows
// possibly padded, with some no-return pixels.
sensor_msgs::Image seedImage(Mutator& m);
void mutateImage(Mutator& m, sensor_msgs::Image* msg);

// A valid CameraInfo of a pinhole camera of 8 to 640 pixels a side.
sensor_msgs::CameraInfo seedCameraInfo(Mutator& m);
void mutateCameraInfo(Mutator& m, sensor_msgs::CameraInfo* msg);

// A valid cloud with float32 x, y, z at varying offsets, possibly with extra
// fields and padding, organised or not.
sensor_msgs::PointCloud2 seedCloud(Mutator& m);
void mutateCloud(Mutator& m, sensor_msgs::PointCloud2* msg);

void mutateUpdate(Mutator& m, surface_nbv::TsdfUpdate* msg);

// A valid trajectory of 1 to 12 points starting within 1 m of `start_W`.
trajectory_msgs::MultiDOFJointTrajectory seedTrajectory(Mutator& m, const Eigen::Vector3d& start_W);
void mutateTrajectory(Mutator& m, trajectory_msgs::MultiDOFJointTrajectory* msg);

}  // namespace fuzz
}  // namespace surface_nbv
