// Yaw from the structure (issue #40): an odometry's heading drifts without
// bound (gravity fixes roll and pitch, nothing fixes yaw), and a heading off
// by a degree misplaces everything seen 100 m later by 1.7 m. Man-made
// structures (plants, buildings, parking decks) stand on walls in a few
// directions 90 degrees apart (a Manhattan world). Each frame's vertical
// surfaces give their direction modulo 90 degrees; against the direction
// the first frames saw, that is an absolute yaw reference the map cannot
// drag along (unlike aligning a frame to the map it is being fused into).
//
// Per frame: normals from the depth image (cross products over `baseline`
// metres, depths up to max_depth), those within 20 degrees of horizontal
// vote with their azimuth a as (cos 4a, sin 4a) (a and a + 90 deg vote the
// same); the frame's direction is the resultant's angle / 4, trusted when
// at least min_normals voted and the votes agree (min_significance). The first trusted frame sets the reference; later ones
// give a yaw error within +-45 deg, of which `gain` is corrected per frame.
// ROS-free, deterministic, one thread.
#pragma once

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/depth_image.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct ManhattanYawConfig {
  bool enabled = false;          // mission/manhattan_yaw
  int grid = 8;                  // a normal every `grid` pixels
  double baseline = 0.25;        // m between the points a normal is taken from (in pixels at each depth)
  double max_depth = 5.0;        // m: farther stereo depth is too noisy for normals
  int min_normals = 200;         // votes a frame needs
  // |resultant| sqrt(votes) a frame needs (Rayleigh's test: about 1 for
  // directions at random); noise spreads the votes, many of them still agree.
  double min_significance = 10.0;
  double gain = 0.05;            // share of a frame's yaw error corrected, (0, 1]
  double max_error_deg = 10.0;   // larger errors are outliers (another structure), not drift

  Status validate() const;
};

struct ManhattanYawFrame {
  bool trusted = false;
  int normals = 0;
  double concentration = 0.0;  // |resultant| / votes
  double direction = 0.0;  // rad in [-pi/4, pi/4): the walls' direction modulo 90 deg
};

// The walls' direction in `depth` seen from T_W_C.
ManhattanYawFrame manhattanDirection(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C,
                                     const ManhattanYawConfig& config);

class ManhattanYaw {
 public:
  explicit ManhattanYaw(const ManhattanYawConfig& config) : config_(config) {}
  // The yaw [rad] to turn this frame's pose by (0 until a reference exists).
  double update(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C);
  bool hasReference() const { return has_reference_; }
  double reference() const { return reference_; }
  size_t corrections() const { return corrections_; }

 private:
  ManhattanYawConfig config_;
  bool has_reference_ = false;
  double reference_ = 0.0;
  size_t corrections_ = 0;
};

}  // namespace surface_nbv
