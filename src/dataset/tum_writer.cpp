#include "dataset/tum_writer.h"

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dataset/image_encode.h"

namespace inet {
namespace {

class TumWriter final : public FormatWriter {
 public:
  explicit TumWriter(std::shared_ptr<const SequenceContext> c) : FormatWriter(std::move(c)) {
    const PassMask passes = ctx().spec.passes;
    const Pass depth = ctx().depthPngPass();
    if (!has(passes, Pass::Rgb) || !has(passes, depth))
      throw InputError("", "--passes",
                       depth == Pass::DepthZ
                           ? "format 'tum' needs the 'rgb' and 'depth' passes (colour and z-depth "
                             "images)"
                           : "format 'tum' needs the 'rgb' and 'ray_depth' passes (colour and "
                             "depth images; a fisheye or panorama has no z-depth)");
    const Trajectory& traj = ctx().traj;
    stems_.reserve(traj.size());
    for (size_t k = 0; k < traj.size(); ++k) {
      stems_.push_back(tumStamp(traj.poses[k].t_ns));
      if (k > 0 && stems_[k] == stems_[k - 1])
        throw InputError(
            "trajectory", fmt::format("pose {}", k),
            fmt::format("timestamps {} ns and {} ns both round to {} s; TUM names files by "
                        "microsecond, so frames must be at least 1 us apart",
                        traj.poses[k - 1].t_ns, traj.poses[k].t_ns, stems_[k]));
    }
    addOutput("rgb", ".png", srgbPng(Pass::Rgb));
    addOutput("depth", ".png", depthPng(depth, kDepthScaleTum));
  }

  std::string name() const override { return "tum"; }
  std::string frameStem(size_t k) const override { return stems_.at(k); }

  std::vector<IndexFile> indexFiles() const override {
    const std::string file_line = "# file: '" + ctx().sequenceName() + "'\n";
    std::string rgb = "# color images\n" + file_line + "# timestamp filename\n";
    std::string depth = "# depth maps\n" + file_line + "# timestamp filename\n";
    std::string assoc;
    for (const auto& ts : stems_) {
      rgb += fmt::format("{} rgb/{}.png\n", ts, ts);
      depth += fmt::format("{} depth/{}.png\n", ts, ts);
      assoc += fmt::format("{} rgb/{}.png {} depth/{}.png\n", ts, ts, ts, ts);
    }
    return {{"rgb.txt", rgb},
            {"depth.txt", depth},
            {"associations.txt", assoc},
            {"groundtruth.txt", groundTruth(file_line)},
            {"accelerometer.txt", "# accelerometer data\n" + file_line + "# timestamp ax ay az\n"},
            {"camera.txt", cameraText()}};
  }

 private:
  std::string groundTruth(const std::string& file_line) const {
    std::string s =
        "# ground truth trajectory\n" + file_line + "# timestamp tx ty tz qx qy qz qw\n";
    const Trajectory& traj = ctx().traj;
    for (size_t k = 0; k < traj.size(); ++k) {
      const Pose& T = traj.poses[k].T_world_camera;
      const Quat q = canonicalQuat(T.q);
      s += stems_[k];
      for (double x : {T.t.x(), T.t.y(), T.t.z(), q.x(), q.y(), q.z(), q.w()})
        s.append(" ").append(formatFixed(x, 9));
      s += "\n";
    }
    return s;
  }

  /// Our side file with the lens (TUM tools read none and assume a 525 px pinhole): two lines,
  /// a comment naming the values, then the values (OpenCV convention).
  std::string cameraText() const {
    const LensModel lens = ctx().lens();
    const OpenCvCamera cv = toOpenCv(lens);
    const std::string image = fmt::format("image {}x{}", cv.width, cv.height);
    const std::string k = fmt::format("{} {} {} {}", formatFloat(cv.fx), formatFloat(cv.fy),
                                      formatFloat(cv.cx), formatFloat(cv.cy));
    const std::string convention =
        "pixels, OpenCV convention: pixel centres at integer coordinates";
    switch (lens.type) {
      case LensType::Pinhole:
      case LensType::ThinLens: {
        std::string thin;
        if (lens.type == LensType::ThinLens)
          thin =
              fmt::format("; thin lens: aperture radius {} m, focus distance {} m",
                          formatFloat(lens.aperture_radius_m), formatFloat(lens.focus_distance_m));
        std::string d;
        for (double c : cv.distortion) d.append(" ").append(formatFloat(c));
        return fmt::format("# fx fy cx cy k1 k2 p1 p2 k3 ({}; {}{})\n{}{}\n", convention, image,
                           thin, k, d);
      }
      case LensType::Fisheye:
        return fmt::format(
            "# fx fy cx cy k1 k2 k3 k4 (NOT a pinhole: equidistant fisheye r = f * theta up to a "
            "field of view of {} deg, OpenCV cv::fisheye / Kalibr pinhole-equi; {}; {}; depth/ "
            "holds the ray distance)\n{} 0.0 0.0 0.0 0.0\n",
            formatFloat(lens.fisheye_fov_deg), convention, image, k);
      case LensType::Panorama:
        return fmt::format(
            "# fu fv cu cv (NOT a pinhole: equirectangular panorama, longitude = (i - cu) / fu "
            "(0 = +z, +pi/2 = +x), latitude = (j - cv) / fv (-pi/2 = -y, up), radians; {}; {}; "
            "depth/ holds the ray distance)\n{}\n",
            convention, image, k);
    }
    return "";
  }

  std::vector<std::string> stems_;
};

}  // namespace

std::string tumStamp(TimeNs t_ns) {
  return nsToSecondsString(t_ns, 6);
}

std::unique_ptr<FormatWriter> makeTumWriter(std::shared_ptr<const SequenceContext> ctx) {
  return std::make_unique<TumWriter>(std::move(ctx));
}

}  // namespace inet
