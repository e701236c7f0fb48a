#include "eval/rgbd_odometry.h"

#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <opencv2/rgbd.hpp>

#include "core/error.h"
#include "eval/cv_image.h"
#include "eval/sequence_reader.h"

namespace inet {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

cv::Ptr<cv::rgbd::Odometry> makeOdometry(OdometryMethod m, const cv::Mat& K) {
  switch (m) {
    case OdometryMethod::Rgbd:
      return cv::rgbd::RgbdOdometry::create(K);
    case OdometryMethod::Icp:
      return cv::rgbd::ICPOdometry::create(K);
    case OdometryMethod::RgbdIcp:
      return cv::rgbd::RgbdICPOdometry::create(K);
  }
  INET_CHECK(false);
}

/// A 4x4 CV_64F rigid transform as a Pose (rotation re-orthonormalised by the quaternion).
Pose poseFromCv(const cv::Mat& Rt) {
  INET_CHECK(Rt.rows == 4 && Rt.cols == 4 && Rt.type() == CV_64FC1);
  Mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = Rt.at<double>(r, c);
  Pose p;
  p.q = Quat(m.block<3, 3>(0, 0)).normalized();
  p.t = m.block<3, 1>(0, 3);
  return p;
}

/// A Pose as a 4x4 CV_64F rigid transform (compute()'s initRt).
cv::Mat poseToCv(const Pose& p) {
  cv::Mat Rt = cv::Mat::eye(4, 4, CV_64FC1);
  const Mat3 R = p.q.toRotationMatrix();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) Rt.at<double>(r, c) = R(r, c);
    Rt.at<double>(r, 3) = p.t[r];
  }
  return Rt;
}

/// One used frame as OpenCV's odometry wants it.
struct CvFrame {
  cv::Mat grey, depth;
};

CvFrame loadFrame(const SequenceReader& seq, size_t k) {
  CvFrame f;
  // ICP ignores the image, but compute() still checks that one is there
  f.grey = cvimage::grey(seq.colour(k));
  f.depth = cvimage::depth(seq.depth(k), std::numeric_limits<float>::quiet_NaN());
  return f;
}

/// OpenCV's camera matrix: its pixel centres are at integers, ours at +0.5 (render/camera.h).
cv::Mat cameraMatrix(const CameraIntrinsics& K) {
  cv::Mat m = cv::Mat::eye(3, 3, CV_64FC1);
  m.at<double>(0, 0) = K.fx;
  m.at<double>(1, 1) = K.fy;
  m.at<double>(0, 2) = K.cxOpenCV();
  m.at<double>(1, 2) = K.cyOpenCV();
  return m;
}

/// Frames 0, stride, 2 stride, ... (at most max_frames); InputError below the 3 that SE(3)
/// alignment needs.
std::vector<size_t> usedFrames(const SequenceReader& seq, const OdometryOptions& opt) {
  std::vector<size_t> used;
  for (size_t k = 0; k < seq.frameCount(); k += opt.stride) {
    if (opt.max_frames && used.size() == opt.max_frames) break;
    used.push_back(k);
  }
  if (used.size() < 3)
    throw InputError((seq.dir() / "cam0" / "data.csv").string(), "",
                     fmt::format("{} frame(s) to use (stride {}): SE(3) alignment of the "
                                 "trajectory needs at least 3",
                                 used.size(), opt.stride));
  return used;
}

}  // namespace

OdometryMethod parseOdometryMethod(const std::string& name, const std::string& field) {
  if (name == "rgbd") return OdometryMethod::Rgbd;
  if (name == "icp") return OdometryMethod::Icp;
  if (name == "rgbd-icp") return OdometryMethod::RgbdIcp;
  throw InputError("", field,
                   fmt::format("unknown method '{}' (valid: rgbd, icp, rgbd-icp)", name));
}

const char* odometryMethodName(OdometryMethod m) {
  switch (m) {
    case OdometryMethod::Rgbd:
      return "rgbd";
    case OdometryMethod::Icp:
      return "icp";
    case OdometryMethod::RgbdIcp:
      return "rgbd-icp";
  }
  INET_CHECK(false);
}

OdometryReference parseOdometryReference(const std::string& name, const std::string& field) {
  if (name == "frame") return OdometryReference::Previous;
  if (name == "keyframe") return OdometryReference::Keyframe;
  throw InputError("", field,
                   fmt::format("unknown reference '{}' (valid: frame, keyframe)", name));
}

const char* odometryReferenceName(OdometryReference r) {
  return r == OdometryReference::Previous ? "frame" : "keyframe";
}

void OdometryOptions::validate() const {
  if (!(max_step_m > 0) || !std::isfinite(max_step_m))
    throw InputError("", "odometry.max_step_m", fmt::format("must be > 0 m, got {}", max_step_m));
  if (!(max_step_deg > 0) || !(max_step_deg <= 180))
    throw InputError("", "odometry.max_step_deg",
                     fmt::format("must be in (0, 180] degrees, got {}", max_step_deg));
  if (stride < 1) throw InputError("", "odometry.stride", "must be at least 1");
  if (!(keyframe_m >= 0) || !std::isfinite(keyframe_m))
    throw InputError("", "odometry.keyframe_m", fmt::format("must be >= 0 m, got {}", keyframe_m));
  if (!(keyframe_deg >= 0) || !(keyframe_deg <= 180))
    throw InputError("", "odometry.keyframe_deg",
                     fmt::format("must be in [0, 180] degrees, got {}", keyframe_deg));
  if (max_frames == 1 || max_frames == 2)
    throw InputError("", "odometry.max_frames",
                     fmt::format("{} frames: SE(3) alignment needs at least 3", max_frames));
}

std::string OdometryOptions::toString() const {
  return fmt::format(
      "OdometryOptions[method={} reference={} keyframe_m={} keyframe_deg={} max_step_m={} "
      "max_step_deg={} stride={} max_frames={}]",
      odometryMethodName(method), odometryReferenceName(reference), keyframe_m, keyframe_deg,
      max_step_m, max_step_deg, stride, max_frames);
}

OdometryResult rgbdOdometry(const std::filesystem::path& sequence, const OdometryOptions& opt) {
  opt.validate();
  const auto t_start = Clock::now();
  const SequenceReader seq(sequence);
  if (groundTruthDepthKind(seq.lens()) != DepthKind::ZDepth)
    throw InputError((sequence / "meta.json").string(), "camera.lens",
                     fmt::format("a {} sequence stores ray distance in depth0; the RGB-D "
                                 "odometry needs z-depth (pinhole or thin_lens)",
                                 lensTypeName(seq.lens())));
  const std::vector<size_t> used = usedFrames(seq, opt);
  const Trajectory gt_all = seq.groundTruth();

  const cv::Ptr<cv::rgbd::Odometry> odometry =
      makeOdometry(opt.method, cameraMatrix(seq.intrinsics()));

  OdometryResult res;
  res.sequence = sequence.string();
  res.options = opt;
  res.ground_truth.poses.push_back(gt_all.poses[used[0]]);
  res.estimate.poses.push_back(gt_all.poses[used[0]]);
  Pose velocity;  // the last frame-to-frame motion, for bridging; identity until the first
  CvFrame ref = loadFrame(seq, used[0]);
  Pose T_world_ref = gt_all.poses[used[0]].T_world_camera;
  bool ref_is_prev = true;  // the reference is the frame before the current one
  const cv::Mat no_mask;  // OpenCV derives the mask from the valid depth range
  for (size_t n = 1; n < used.size(); ++n) {
    const size_t j = used[n];
    CvFrame cur = loadFrame(seq, j);
    OdometryStep step;
    step.frame = j;
    cv::Mat Rt;
    const Pose T_world_prev = res.estimate.poses.back().T_world_camera;
    // the first guess: where constant velocity puts the frame, seen from the reference (a
    // keyframe may be many frames back; OpenCV's own default, identity, suits the previous
    // frame, and frame-to-frame keeps it)
    const cv::Mat init = ref_is_prev ? cv::Mat()
                                     : poseToCv(T_world_ref.inverse() * T_world_prev * velocity);
    const auto t0 = Clock::now();
    // src = the new frame, dst = the reference: Rt = T_ref_new (see the header)
    step.converged = odometry->compute(cur.grey, cur.depth, no_mask, ref.grey, ref.depth,
                                       no_mask, Rt, init);
    step.seconds = secondsSince(t0);
    res.odometry_seconds += step.seconds;
    Pose T_world_j = T_world_prev * velocity;
    Pose measured;
    if (step.converged) {
      measured = poseFromCv(Rt);
      step.translation_m = measured.t.norm();
      step.rotation_deg = rotationAngleDeg(measured.q);
      step.tracked = step.translation_m < opt.max_step_m && step.rotation_deg < opt.max_step_deg;
      if (step.tracked) T_world_j = T_world_ref * measured;
    }
    res.tracked += step.tracked;
    // frame-to-frame keeps the measured step itself (the same bytes as before keyframes)
    if (step.tracked) velocity = ref_is_prev ? measured : T_world_prev.inverse() * T_world_j;
    step.keyframe = opt.reference == OdometryReference::Previous || !step.tracked ||
                    step.translation_m > opt.keyframe_m || step.rotation_deg > opt.keyframe_deg;
    res.estimate.poses.push_back({gt_all.poses[j].t_ns, T_world_j});
    res.ground_truth.poses.push_back(gt_all.poses[j]);
    res.steps.push_back(step);
    ref_is_prev = step.keyframe;
    if (step.keyframe) {
      ref = std::move(cur);
      T_world_ref = T_world_j;
      ++res.keyframes;
    }
  }
  AteOptions ate;
  ate.align = AlignMode::SE3;
  res.ate = computeAte(res.ground_truth, res.estimate, ate);
  ate.align = AlignMode::None;
  res.drift = computeAte(res.ground_truth, res.estimate, ate);
  res.seconds = secondsSince(t_start);
  return res;
}

std::string OdometryResult::toString() const {
  return fmt::format(
      "OdometryResult[{} method={} frames={} tracked={}/{} ate_rmse_m={:.6f} "
      "drift_rmse_m={:.6f} drift_rmse_deg={:.4f} odometry_s={:.3f}]",
      sequence, odometryMethodName(options.method), estimate.size(), tracked, steps.size(),
      ate.translation_m.rmse, drift.translation_m.rmse, drift.rotation_deg.rmse, odometry_seconds);
}

}  // namespace inet
