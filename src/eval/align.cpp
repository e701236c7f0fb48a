#include "eval/align.h"

#include <Eigen/Geometry>

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {

AlignMode parseAlignMode(const std::string& name, const std::string& field) {
  if (name == "none") return AlignMode::None;
  if (name == "se3") return AlignMode::SE3;
  if (name == "sim3") return AlignMode::Sim3;
  throw InputError("", field, "unknown alignment '" + name + "'; valid: none, se3, sim3");
}

const char* alignModeName(AlignMode mode) {
  switch (mode) {
    case AlignMode::None:
      return "none";
    case AlignMode::SE3:
      return "se3";
    case AlignMode::Sim3:
      return "sim3";
  }
  return "?";
}

Alignment alignPositions(const std::vector<Vec3>& est, const std::vector<Vec3>& gt,
                         AlignMode mode) {
  INET_CHECK(est.size() == gt.size());
  Alignment a;
  if (mode == AlignMode::None) return a;
  if (est.size() < 3)
    throw InputError("", "alignment",
                     fmt::format("{} alignment needs at least 3 matched poses, found {}",
                                 alignModeName(mode), est.size()));
  Eigen::Matrix3Xd src(3, est.size()), dst(3, gt.size());
  for (size_t i = 0; i < est.size(); ++i) src.col(i) = est[i], dst.col(i) = gt[i];
  if (mode == AlignMode::Sim3) {
    const double spread = (src.colwise() - src.rowwise().mean()).squaredNorm();
    if (!(spread > 0))
      throw InputError("", "alignment",
                       "the estimate does not move: its Sim(3) scale is undefined (use se3)");
  }
  const Mat4 T = Eigen::umeyama(src, dst, mode == AlignMode::Sim3);
  // umeyama returns [s R, t; 0 1]
  const Mat3 sR = T.block<3, 3>(0, 0);
  a.scale = mode == AlignMode::Sim3 ? std::cbrt(sR.determinant()) : 1.0;
  a.T_gt_est.q = Quat(Mat3(sR / a.scale)).normalized();
  a.T_gt_est.t = T.block<3, 1>(0, 3);
  INET_CHECK(std::isfinite(a.scale) && a.scale > 0 && a.T_gt_est.t.allFinite());
  return a;
}

}  // namespace inet
