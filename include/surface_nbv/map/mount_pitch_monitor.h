// Whether a depth camera's frames agree with the mount pitch the planner
// assumes (CameraConfig::pitch_deg: eq. 2's elevation window, C_q's
// frustum). The mapper takes each frame's pose from TF, the planner's views
// come from the config: a camera pitched otherwise than configured is mapped
// correctly but planned for wrongly. A flying multirotor tilts with its
// accelerations, so the check is on the mean pitch of many frames.
#pragma once

#include <cstddef>

#include "surface_nbv/common.h"

namespace surface_nbv {

class MountPitchMonitor {
 public:
  // Degrees below the horizon of the optical axis (z) of T_W_C.
  static double axisPitchDeg(const Transform& T_W_C);

  void add(const Transform& T_W_C);
  size_t frames() const { return frames_; }
  // Mean axisPitchDeg() of the frames added; NaN before the first.
  double meanPitchDeg() const;
  // True once `min_frames` frames are in and their mean pitch differs from
  // `pitch_deg` by more than `tolerance_deg`.
  bool mismatch(double pitch_deg, double tolerance_deg = 2.0, size_t min_frames = 30) const;

 private:
  size_t frames_ = 0;
  double sum_deg_ = 0.0;
};

}  // namespace surface_nbv
