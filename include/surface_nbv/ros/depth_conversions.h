// Conversions between the core's depth, point and mesh types and ROS
// messages. Depth images follow REP 118 / REP 117: 32FC1 in metres with +Inf
// for no return within range, -Inf for too close and NaN for invalid, or
// 16UC1 in millimetres with 0 for no return.
#pragma once

#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/Marker.h>

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/depth_image.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

void toImageMsg(const DepthImage& depth, const std_msgs::Header& header, sensor_msgs::Image* msg);
// 16UC1 in millimetres, as OpenNI-style drivers publish: depths rounded to a
// millimetre, 0 for everything without one (NaN, +-Inf, beyond 65.535 m).
void toImageMsgMillimetres(const DepthImage& depth, const std_msgs::Header& header, sensor_msgs::Image* msg);

// Reads a 32FC1 or 16UC1 image; checks encoding, size, step and buffer length.
// +-Inf are kept (REP 117); NaN, zero or negative depths become NaN.
Status fromImageMsg(const sensor_msgs::Image& msg, DepthImage* depth);

void toCameraInfoMsg(const DepthCamera& camera, const std_msgs::Header& header, sensor_msgs::CameraInfo* msg);

// Reads the size and K of a CameraInfo into `camera`, with the depth range of
// `base`. Refuses a size outside [1, 16384], non-finite or non-positive focal
// lengths, a focal length so small that the field of view rounds to 180
// degrees, and a principal point more than one image size outside the image.
Status fromCameraInfoMsg(const sensor_msgs::CameraInfo& msg, const CameraConfig& base, DepthCamera* camera);

// An unorganised cloud with float32 x, y, z fields.
void toPointCloud2Msg(const std::vector<Eigen::Vector3f>& points, const std_msgs::Header& header,
                      sensor_msgs::PointCloud2* msg);

// Reads the float32 x, y, z fields of any PointCloud2 layout; checks field
// types, that x, y and z do not overlap, point_step, row_step and the buffer
// length. Non-finite points are
// kept (the integrator treats them as invalid pixels).
Status fromPointCloud2Msg(const sensor_msgs::PointCloud2& msg, std::vector<Eigen::Vector3f>* points);

// A TRIANGLE_LIST marker of `mesh` (grey, opaque).
void toMeshMarker(const TriangleMesh& mesh, const std_msgs::Header& header, const std::string& ns,
                  visualization_msgs::Marker* marker);

// Converts a transform message, refusing non-finite values and quaternions
// whose norm is off by more than 1e-3 (then normalising the rest).
Status fromTransformMsg(const geometry_msgs::Transform& msg, Transform* T);

}  // namespace surface_nbv
