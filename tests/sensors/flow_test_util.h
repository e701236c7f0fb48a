#pragma once
// Shared by the optical flow tests: degrees and rotations about an axis.
#include <numbers>

#include <Eigen/Geometry>

#include "core/pose.h"

namespace inet::test {

constexpr double kDeg = std::numbers::pi / 180;

/// Rotation by `rad` about `axis` (any length).
inline Quat axisAngle(const Vec3& axis, double rad) {
  return Quat(Eigen::AngleAxisd(rad, axis.normalized()));
}

}  // namespace inet::test
