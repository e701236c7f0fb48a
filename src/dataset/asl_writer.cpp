#include "dataset/asl_writer.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dataset/image_encode.h"

namespace inet {
namespace {

/// One ASL sensor folder holding images. `comment` goes into its sensor.yaml; it is a YAML plain
/// scalar, so it must not contain ": " or " #". Empty: built by sensorComment (depends on the
/// lens and the outputs).
struct AslSensor {
  const char* folder;
  const char* comment;
};

constexpr AslSensor kImageSensors[] = {
    {"cam0", ""},
    {"depth0", ""},
    {"normal0",
     "interiornet normal0, registered to cam0. Unit surface normal in the camera frame (x right, "
     "y down, z forward) as 16-bit RGB, code = round((n + 1) / 2 * 65535), (0, 0, 0) = none"},
    {"albedo0", "interiornet albedo0, registered to cam0. Diffuse albedo, 8-bit sRGB RGB PNG"},
    {"shading0",
     "interiornet shading0, registered to cam0. Illumination only (cam0 linear RGB / albedo), "
     "8-bit sRGB RGB PNG, clipped at 1"},
    {"label0",
     "interiornet label0, registered to cam0. <t>_nyu.png NYU40 class id (8-bit, 0 = void), "
     "<t>_instance.png instance id (16-bit, 0 = none); never anti-aliased"},
    {"depth0_noisy",
     "interiornet depth0_noisy, registered to cam0. Kinect-like z-depth (projector shadow, "
     "grazing-angle, range and edge dropouts, lateral and axial noise after Nguyen et al. 2012, "
     "1/8 px disparity steps) as 16-bit millimetres, 0 = no return"},
    {"flow0",
     "interiornet flow0, registered to cam0. Forward optical flow to the next frame (none for the "
     "last), pixels. <t>.flo Middlebury float32 (1e10 = no surface), <t>.png KITTI 16-bit "
     "(64 u + 32768, 64 v + 32768, valid), <t>.exr float32 U V (NaN = no surface), as many of "
     "the three as meta.json storage.flow names; <t>_occ.png 8-bit, 255 = occluded in the next frame"},
    {"flow0_bwd",
     "interiornet flow0_bwd, registered to cam0. Backward optical flow to the previous frame "
     "(none for the first), pixels. <t>.flo Middlebury float32 (1e10 = no surface), <t>.png "
     "KITTI 16-bit (64 u + 32768, 64 v + 32768, valid), <t>.exr float32 U V (NaN = no surface), "
     "as many of the three as meta.json storage.flow names; <t>_occ.png 8-bit, 255 = occluded in "
     "the previous frame"},
};

// Layout of the EuRoC files in ../shared/data/formats/euroc_asl (comments, blank lines, the T_BS
// block), so that tools and people reading the real files find the same structure.
constexpr const char* kIdentityTbs =
    "T_BS:\n"
    "  cols: 4\n"
    "  rows: 4\n"
    "  data: [1.0, 0.0, 0.0, 0.0,\n"
    "         0.0, 1.0, 0.0, 0.0,\n"
    "         0.0, 0.0, 1.0, 0.0,\n"
    "         0.0, 0.0, 0.0, 1.0]\n";

}  // namespace

std::string translationTbs(const Vec3& t) {
  return fmt::format(
      "T_BS:\n"
      "  cols: 4\n"
      "  rows: 4\n"
      "  data: [1.0, 0.0, 0.0, {},\n"
      "         0.0, 1.0, 0.0, {},\n"
      "         0.0, 0.0, 1.0, {},\n"
      "         0.0, 0.0, 0.0, 1.0]\n",
      formatFloat(t.x()), formatFloat(t.y()), formatFloat(t.z()));
}

namespace {

/// Nominal frame rate for rate_hz: 1 s over the median frame interval, to 3 decimals ("25" for
/// 40 ms frames, robust to a jittered stamp); 0 for a single frame.
std::string rateText(const Trajectory& traj) {
  if (traj.size() < 2) return "0";
  std::vector<TimeNs> dt;
  for (size_t k = 1; k < traj.size(); ++k)
    dt.push_back(traj.poses[k].t_ns - traj.poses[k - 1].t_ns);
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  double rate = std::round(1e9 / static_cast<double>(dt[dt.size() / 2]) * 1000.0) / 1000.0;
  if (rate == std::round(rate)) return fmt::format("{}", std::llround(rate));
  return formatFloat(rate);
}

/// Kalibr's numbers: intrinsics in the OpenCV convention, with the comment every line carries.
std::string intrinsicsLine(const OpenCvCamera& cv) {
  return fmt::format(
      "intrinsics: [{}, {}, {}, {}] #fu, fv, cu, cv (OpenCV convention, pixel centres at "
      "integers)\n",
      formatFloat(cv.fx), formatFloat(cv.fy), formatFloat(cv.cx), formatFloat(cv.cy));
}

/// camera_model, intrinsics and distortion of a lens as Kalibr states them, with a comment
/// where the model needs one (docs/output.md section 4).
std::string lensYaml(const LensModel& lens) {
  const OpenCvCamera cv = toOpenCv(lens);
  switch (lens.type) {
    case LensType::Pinhole:
    case LensType::ThinLens: {
      std::string s;
      if (lens.type == LensType::ThinLens)
        s = fmt::format(
            "# Thin lens (depth of field): aperture radius {} m, focused on the plane z = {} "
            "m.\n# Its chief rays, and so all ground truth, follow the pinhole below.\n",
            formatFloat(lens.aperture_radius_m), formatFloat(lens.focus_distance_m));
      return s + "camera_model: pinhole\n" + intrinsicsLine(cv) +
             fmt::format(
                 "distortion_model: radial-tangential\n"
                 "distortion_coefficients: [{}, {}, {}, {}]\n",
                 formatFloat(lens.k1), formatFloat(lens.k2), formatFloat(lens.p1),
                 formatFloat(lens.p2));
    }
    case LensType::Fisheye:
      return fmt::format(
                 "# Equidistant fisheye: r = f * theta, r = distance from the principal point "
                 "(px),\n# theta = angle from the optical axis (rad), f = fu = fv (px per rad); "
                 "rays up to\n# theta = {} deg (field of view {} deg); pixels outside that "
                 "circle hold every\n# pass's 'none' value. Kalibr pinhole-equi, OpenCV "
                 "cv::fisheye with k1..k4 = 0.\n",
                 formatFloat(lens.fisheye_fov_deg / 2), formatFloat(lens.fisheye_fov_deg)) +
             "camera_model: pinhole\n" + intrinsicsLine(cv) +
             "distortion_model: equidistant\n"
             "distortion_coefficients: [0.0, 0.0, 0.0, 0.0]\n";
    case LensType::Panorama:
      return fmt::format(
          "# Equirectangular panorama; NOT a Kalibr camera model (no intrinsics, no "
          "distortion).\n"
          "# Pixel centre (i, j), OpenCV convention (integers), in the camera frame (x right, y "
          "down, z forward):\n"
          "#   longitude = (i - {}) / {} rad (0 = +z forward, +pi/2 = +x right, seam at -z)\n"
          "#   latitude  = (j - {}) / {} rad (-pi/2 = -y up, +pi/2 down)\n"
          "#   ray = (cos(lat) sin(lon), sin(lat), cos(lat) cos(lon))\n"
          "camera_model: equirectangular\n",
          formatFloat(cv.cx), formatFloat(cv.fx), formatFloat(cv.cy), formatFloat(cv.fy));
  }
  return "";
}

class AslWriter final : public FormatWriter {
 public:
  explicit AslWriter(std::shared_ptr<const SequenceContext> c) : FormatWriter(std::move(c)) {
    for (size_t k = 0; k < ctx().traj.size(); ++k)
      if (ctx().traj.poses[k].t_ns < 0)
        throw InputError("trajectory", fmt::format("pose {}", k),
                         "negative timestamp; ASL file names need t >= 0 ns");
    if (ctx().lens().k3 != 0)
      throw InputError("camera", "k3",
                       "the ASL sensor.yaml (Kalibr radial-tangential: k1 k2 p1 p2) has no k3");
    addOutput("cam0/data", ".png", srgbPng(Pass::Rgb));
    if (ctx().spec.rgb_exr) addOutput("cam0/data", ".exr", floatExr(Pass::Rgb, {"R", "G", "B"}));
    addOutput("depth0/data", ".png", depthPng(ctx().depthPngPass(), kDepthScaleMm));
    addOutput("depth0/data", ".exr", floatExr(Pass::DepthRay, {"Z"}));
    addOutput("normal0/data", ".png", normalPng(Pass::Normal));
    addOutput("albedo0/data", ".png", srgbPng(Pass::Albedo));
    addOutput("shading0/data", ".png", srgbPng(Pass::Shading));
    addOutput("label0/data", "_nyu.png", rawPng(Pass::Label));
    addOutput("label0/data", "_instance.png", rawPng(Pass::Instance));
    addOutput("depth0_noisy/data", ".png", depthPng(Pass::DepthNoisy, kDepthScaleMm));
    const StorageOptions& st = ctx().spec.storage;
    for (const auto& [folder, pass] : {std::pair{"flow0/data", Pass::Flow},
                                       std::pair{"flow0_bwd/data", Pass::FlowBackward}}) {
      if (st.flow_flo) addOutput(folder, ".flo", flowFlo(pass));
      if (st.flow_kitti) addOutput(folder, ".png", flowKittiPng(pass));
      if (st.flow_exr) addOutput(folder, ".exr", flowExr(pass));
      addOutput(folder, "_occ.png", flowOcclusionPng(pass));
    }
    if (ctx().spec.stereo_baseline_m > 0) {
      // cam1 writes every output of cam0 into the twin folder (cam0 -> cam1, depth0 -> depth1)
      const std::vector<FrameOutput> left = outputs();
      for (const FrameOutput& o : left) addOutput(rightFolder(o.folder), o.suffix, o.encoder, 1);
    }
  }

  /// The stereo twin of a cam0 folder: its sensor number 0 -> 1 ("depth0_noisy/data" ->
  /// "depth1_noisy/data").
  static std::string rightFolder(std::string folder) {
    const size_t zero = folder.find('0');
    INET_CHECK(zero != std::string::npos);
    folder[zero] = '1';
    return folder;
  }

  std::string name() const override { return "asl"; }
  std::string frameStem(size_t k) const override { return aslStamp(ctx().traj.poses.at(k).t_ns); }

  std::vector<IndexFile> indexFiles() const override {
    std::vector<IndexFile> files;
    files.push_back({"body.yaml",
                     "comment: interiornet virtual camera rig; body frame B = cam0 frame "
                     "(x right, y down, z forward)\n"});
    for (int camera = 0; camera < (ctx().spec.stereo_baseline_m > 0 ? 2 : 1); ++camera)
      for (const auto& sensor : kImageSensors) {
        // data.csv lists the first file of each frame in this folder (e.g. the depth PNG; the
        // .exr or _instance.png sibling has the same <t>).
        const std::string folder =
            camera == 0 ? std::string(sensor.folder) : rightFolder(sensor.folder);
        for (const auto& o : outputs()) {
          if (o.folder != folder + "/data") continue;
          files.push_back({folder + "/data.csv", cameraCsv(o)});
          files.push_back({folder + "/sensor.yaml",
                           cameraYaml(sensorComment(sensor, camera), camera)});
          break;
        }
      }
    files.push_back({"state_groundtruth_estimate0/data.csv", groundTruthCsv()});
    files.push_back({"state_groundtruth_estimate0/sensor.yaml", groundTruthYaml()});
    return files;
  }

 private:
  bool writes(const std::string& folder, const std::string& suffix) const {
    for (const auto& o : outputs())
      if (o.folder == folder && o.suffix == suffix) return true;
    return false;
  }

  /// The comment of a folder whose files depend on the lens or on the options.
  std::string sensorComment(const AslSensor& sensor, int camera) const {
    std::string c = sensorComment(sensor);
    if (camera == 0) return c;
    // the right camera's folders name themselves and are registered to cam1
    for (const std::string& from : {std::string(sensor.folder), std::string("cam0")}) {
      const std::string to = rightFolder(from);
      for (size_t at = 0; (at = c.find(from, at)) != std::string::npos; at += to.size())
        c.replace(at, from.size(), to);
    }
    return c + fmt::format(" (stereo right camera, {} m right of cam0)",
                           formatFloat(ctx().spec.stereo_baseline_m));
  }

  std::string sensorComment(const AslSensor& sensor) const {
    const std::string folder = sensor.folder;
    if (folder == "cam0") {
      std::string s = "interiornet cam0, path-traced colour. <t>.png 8-bit sRGB RGB";
      if (writes("cam0/data", ".exr"))
        s += ". <t>.exr linear RGB radiance before exposure, noise, tone curve and sRGB, "
             "float32 channels R G B";
      return s;
    }
    if (folder != "depth0") return sensor.comment;
    const bool z = ctx().depthPngPass() == Pass::DepthZ;
    return std::string("interiornet depth0, registered to cam0. <t>.png ") +
           (z ? "z-depth along the optical axis"
              : "Euclidean ray depth (camera centre to surface, the " +
                    std::string(lensTypeName(ctx().lens().type)) + " lens has no z-depth)") +
           " as 16-bit millimetres (0 = no depth or beyond 65.535 m). <t>.exr Euclidean ray "
           "depth (camera centre to surface) in metres, float channel Z, 0 = no depth";
  }

  /// data.csv of a folder: one row per frame that has the output `o`.
  std::string cameraCsv(const FrameOutput& o) const {
    const std::string& suffix = o.suffix;
    std::string s = std::string(kEurocCameraCsvHeader) + "\n";
    for (size_t k = 0; k < ctx().traj.size(); ++k) {
      if (!o.writtenFor(k, ctx().traj.size())) continue;
      const std::string stem = frameStem(k);
      s += stem + "," + stem + suffix + "\n";
    }
    return s;
  }

  std::string cameraYaml(const std::string& comment, int camera = 0) const {
    const CameraIntrinsics& K = ctx().spec.intrinsics;
    return fmt::format(
               "# General sensor definitions.\nsensor_type: camera\ncomment: {}\n\n"
               "# Sensor extrinsics wrt. the body-frame.\n{}\n",
               comment,
               camera == 0 ? std::string(kIdentityTbs)
                           : translationTbs(Vec3(ctx().spec.stereo_baseline_m, 0, 0))) +
           fmt::format("# Camera specific definitions.\nrate_hz: {}\nresolution: [{}, {}]\n",
                       rateText(ctx().traj), K.width, K.height) +
           lensYaml(ctx().lens()) + "\n";
  }

  std::string groundTruthCsv() const {
    std::string s = std::string(kEurocGroundTruthCsvHeader) + "\n";
    const Trajectory& traj = ctx().traj;
    for (size_t k = 0; k < traj.size(); ++k) {
      const Pose& T = traj.poses[k].T_world_camera;
      const Quat q = canonicalQuat(T.q);
      const Vec3 v = traj.velocityWorld(k);
      s += aslStamp(traj.poses[k].t_ns);
      for (double x : {T.t.x(), T.t.y(), T.t.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z()})
        s.append(",").append(formatFixed(x, 9));
      s += ",0.0,0.0,0.0,0.0,0.0,0.0\n";  // no IMU here: true biases are zero
    }
    return s;
  }

  static std::string groundTruthYaml() {
    return fmt::format(
        "# General sensor definitions.\nsensor_type: visual-inertial\n"
        "comment: interiornet ground truth, exact rendered pose T_world_camera (R = world, "
        "S = body = cam0), velocity of the camera centre in the world frame, zero biases\n\n"
        "# Sensor extrinsics wrt. the body-frame (identity, the ground truth is the body "
        "pose).\n{}",
        kIdentityTbs);
  }
};

}  // namespace

std::string aslStamp(TimeNs t_ns) {
  INET_CHECK(t_ns >= 0);
  return fmt::format("{:019d}", t_ns);
}

std::unique_ptr<FormatWriter> makeAslWriter(std::shared_ptr<const SequenceContext> ctx) {
  return std::make_unique<AslWriter>(std::move(ctx));
}

std::string aslSensorComment(std::string_view folder) {
  if (folder == "cam0" || folder == "depth0") return "";  // these depend on the lens and options
  for (const AslSensor& sensor : kImageSensors)
    if (folder == sensor.folder) return sensor.comment;
  return "";
}

std::vector<SequenceFrame> readAslFrameList(const std::filesystem::path& csv) {
  std::istringstream in(readTextFile(csv));
  std::vector<SequenceFrame> frames;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const size_t comma = line.find(',');
    SequenceFrame f;
    f.stamp = line.substr(0, comma);
    f.file = comma == std::string::npos ? "" : line.substr(comma + 1);
    // 18 digits keep the stamp below 2^63 ns; the writer pads to 19 with leading zeros
    const size_t digits_end = f.stamp.find_first_not_of('0');
    const bool digits = !f.stamp.empty() &&
                        f.stamp.find_first_not_of("0123456789") == std::string::npos &&
                        (digits_end == std::string::npos || f.stamp.size() - digits_end <= 18);
    if (!digits || f.file.empty() || f.file.find_first_of("/,") != std::string::npos)
      throw InputError(csv.string(), fmt::format("line {}", n),
                       "expected '<timestamp ns>,<file>', got '" + line + "'");
    f.t_ns = std::stoll(f.stamp);
    if (!frames.empty() && f.t_ns <= frames.back().t_ns)
      throw InputError(csv.string(), fmt::format("line {}", n),
                       fmt::format("timestamp {} does not increase (previous row {})", f.stamp,
                                   frames.back().stamp));
    frames.push_back(std::move(f));
  }
  if (frames.empty()) throw InputError(csv.string(), "", "no frames listed");
  return frames;
}

}  // namespace inet
