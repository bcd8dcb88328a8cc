#include "surface_nbv/ros/map_conversions.h"

#include <tf2_eigen/tf2_eigen.h>

namespace surface_nbv {

void toUpdateMsg(const MapUpdate& update, const std_msgs::Header& header, surface_nbv::TsdfUpdate* msg) {
  msg->header = header;
  msg->sequence = update.sequence;
  msg->snapshot = update.snapshot;
  msg->voxel_size = update.voxel_size;
  msg->w_th = update.w_th;
  msg->bounds_min = tf2::toMsg(update.bounds.min);
  msg->bounds_max = tf2::toMsg(update.bounds.max);
  msg->blocks.resize(update.blocks.size());
  for (size_t i = 0; i < update.blocks.size(); ++i) {
    const BlockData& data = update.blocks[i];
    surface_nbv::TsdfVoxelBlock& block = msg->blocks[i];
    block.x = data.index.x();
    block.y = data.index.y();
    block.z = data.index.z();
    block.phi = data.phi;
    block.w = data.w;
  }
}

void fromUpdateMsg(const surface_nbv::TsdfUpdate& msg, MapUpdate* update) {
  update->sequence = msg.sequence;
  update->snapshot = msg.snapshot;
  update->voxel_size = msg.voxel_size;
  update->w_th = msg.w_th;
  update->bounds = AlignedBox(Eigen::Vector3d(msg.bounds_min.x, msg.bounds_min.y, msg.bounds_min.z),
                              Eigen::Vector3d(msg.bounds_max.x, msg.bounds_max.y, msg.bounds_max.z));
  update->blocks.resize(msg.blocks.size());
  for (size_t i = 0; i < msg.blocks.size(); ++i) {
    const surface_nbv::TsdfVoxelBlock& block = msg.blocks[i];
    BlockData& data = update->blocks[i];
    data.index = Eigen::Vector3i(block.x, block.y, block.z);
    data.phi = block.phi;
    data.w = block.w;
  }
}

}  // namespace surface_nbv
