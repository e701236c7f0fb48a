#include "dataset/sequence_writer.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "dataset/asl_writer.h"
#include "dataset/image_encode.h"
#include "sensors/imu_io.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace inet {
namespace {

/// The files of imu0/, in the order they are written (sensor.yaml last).
constexpr const char* kImuFiles[] = {"data.csv", "data_noise_free.csv", "biases.csv",
                                     "sensor.yaml"};

void validateTrajectory(const Trajectory& traj) {
  if (traj.empty()) throw InputError("trajectory", "", "has no poses, nothing to write");
  for (size_t k = 0; k < traj.size(); ++k) {
    const TimedPose& p = traj.poses[k];
    const std::string where = fmt::format("pose {}", k);
    if (!p.T_world_camera.t.allFinite() || !p.T_world_camera.q.coeffs().allFinite() ||
        p.T_world_camera.q.norm() < 1e-6)
      throw InputError("trajectory", where, "pose is not finite or has a zero quaternion");
    if (p.t_ns < 0) throw InputError("trajectory", where, "negative timestamp");
    if (k > 0 && p.t_ns <= traj.poses[k - 1].t_ns)
      throw InputError("trajectory", where,
                       fmt::format("timestamps must increase strictly ({} ns after {} ns)", p.t_ns,
                                   traj.poses[k - 1].t_ns));
  }
}

void validateFormatNames(const std::vector<std::string>& formats) {
  std::string valid;
  for (const auto& n : formatNames()) valid += (valid.empty() ? "" : ", ") + n;
  if (formats.empty()) throw InputError("", "--format", "no format given; valid formats: " + valid);
  for (size_t i = 0; i < formats.size(); ++i) {
    const auto names = formatNames();
    if (std::find(names.begin(), names.end(), formats[i]) == names.end())
      throw InputError("", "--format",
                       fmt::format("unknown format '{}'; valid formats: {}", formats[i], valid));
    for (size_t j = 0; j < i; ++j)
      if (formats[j] == formats[i])
        throw InputError("", "--format", fmt::format("format '{}' is listed twice", formats[i]));
  }
}

template <typename T>
void checkImage(const Image<T>& img, Pass pass, int channels, const CameraIntrinsics& K, size_t k) {
  INET_CHECK_MSG(
      img.width == K.width && img.height == K.height && img.channels == channels &&
          img.data.size() == img.pixelCount() * channels,
      fmt::format("frame {}: pass '{}' image is {}x{}x{}, expected {}x{}x{}", k, passName(pass),
                  img.width, img.height, img.channels, K.width, K.height, channels));
}

/// A frame that does not match the spec is a caller bug (the renderer was asked for these
/// passes at this size), not bad user input. Each pass's member and shape come from kPassTable.
void checkFrame(const Frame& f, const ImageF& rgb_display, PassMask mask, const CameraIntrinsics& K,
                size_t k, bool first, bool last) {
  for (const PassInfo& info : kPassTable) {
    const Pass p = info.pass;
    if (!has(mask, p)) continue;
    if ((last && info.neighbour == Neighbour::Next) ||
        (first && info.neighbour == Neighbour::Previous))
      continue;  // no next (previous) frame, no forward (backward) flow
    INET_CHECK_MSG(has(f.passes, p),
                   fmt::format("frame {} lacks pass '{}' that the sequence writes", k, info.name));
    switch (info.pixel) {
      case PixelType::Float:
        checkImage(f.*info.member.f, p, info.channels, K, k);
        break;
      case PixelType::U8:
        checkImage(f.*info.member.u8, p, info.channels, K, k);
        break;
      case PixelType::U16:
        checkImage(f.*info.member.u16, p, info.channels, K, k);
        break;
      case PixelType::Flow: {
        const FlowField& flow = f.*info.member.flow;
        checkImage(flow.flow, p, info.channels, K, k);
        checkImage(flow.valid, p, 1, K, k);
        checkImage(flow.occluded, p, 1, K, k);
        break;
      }
    }
  }
  if (has(mask, Pass::Rgb)) checkImage(rgb_display, Pass::Rgb, passInfo(Pass::Rgb).channels, K, k);
}

bool sameIntrinsics(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy &&
         a.cx == b.cx && a.cy == b.cy;
}

/// The lens checks that need no disk: valid model, and no z-depth pass where z is undefined.
void validateLens(const SequenceSpec& spec) {
  if (!spec.lens) return;
  INET_CHECK_MSG(sameIntrinsics(spec.lens->K, spec.intrinsics),
                 "SequenceSpec::lens->K must equal SequenceSpec::intrinsics");
  spec.lens->validate("camera");
  if (groundTruthDepthKind(spec.lens->type) == DepthKind::RayDistance &&
      has(spec.passes, Pass::DepthZ))
    throw InputError("", "--passes",
                     fmt::format("'depth' (z-depth) is undefined for a {} lens, whose image holds "
                                 "directions at and beyond 90 degrees from the axis; select "
                                 "'ray_depth' (its depth PNG and EXR hold the ray distance)",
                                 lensTypeName(spec.lens->type)));
}

/// Gives `dst` the bytes of `src` atomically: a hard link (no extra disk space), or a copy where
/// the file system has no hard links.
void linkOrCopy(const fs::path& src, const fs::path& dst) {
  writeFileAtomic(dst, [&](const fs::path& tmp) {
    std::error_code ec;
    fs::create_hard_link(src, tmp, ec);
    if (!ec) return;
    fs::copy_file(src, tmp, fs::copy_options::overwrite_existing, ec);
    if (ec) throw InputError(dst.string(), "", "cannot copy " + src.string() + ": " + ec.message());
  });
}

/// The projection of each lens in words, renderer convention (docs/cameras.md section 3).
const char* projectionText(LensType type) {
  switch (type) {
    case LensType::Pinhole:
    case LensType::ThinLens:
      return "perspective: u = fx X/Z + cx, v = fy Y/Z + cy (then radial-tangential distortion)";
    case LensType::Fisheye:
      return "equidistant: r = f theta, r = |(u - cx, v - cy)| in pixels, theta = angle from "
             "+z in radians, f = fx = fy pixels per radian; rays up to theta = fov_deg / 2";
    case LensType::Panorama:
      return "equirectangular: longitude = (u - cx) / fx (0 = +z forward, +pi/2 = +x right), "
             "latitude = (v - cy) / fy (-pi/2 = -y up); ray = (cos lat sin lon, sin lat, "
             "cos lat cos lon)";
  }
  return "";
}

json cameraJson(const LensModel& lens) {
  const CameraIntrinsics& K = lens.K;
  const OpenCvCamera cv = toOpenCv(lens);
  const char* distortion = cv.model == "radtan"        ? "radial-tangential"
                           : cv.model == "equidistant" ? "equidistant"
                                                       : "none";
  return {
      {"width", K.width},
      {"height", K.height},
      {"lens", lensTypeName(lens.type)},
      {"projection", projectionText(lens.type)},
      {"distortion_model", distortion},
      {"distortion_coefficients", cv.distortion},
      {"opencv", {{"fx", cv.fx}, {"fy", cv.fy}, {"cx", cv.cx}, {"cy", cv.cy}}},
      {"renderer", {{"fx", K.fx}, {"fy", K.fy}, {"cx", K.cx}, {"cy", K.cy}}},
      {"pixel_centre_convention",
       "opencv: pixel (i, j) is centred at (i, j); this is what every calibration file of the "
       "sequence states (sensor.yaml, camera.txt). renderer: pixel (i, j) covers [i, i+1) x "
       "[j, j+1) and is centred at (i + 0.5, j + 0.5), so cx = cx_opencv + 0.5"},
  };
}

/// meta.json "lens": the model and every parameter it uses.
json lensJson(const LensModel& lens) {
  json j = {{"type", lensTypeName(lens.type)},
            {"depth", groundTruthDepthKind(lens.type) == DepthKind::ZDepth
                          ? "z-depth along the optical axis"
                          : "Euclidean ray distance from the camera centre"}};
  switch (lens.type) {
    case LensType::Pinhole:
      break;
    case LensType::ThinLens:
      j["aperture_radius_m"] = lens.aperture_radius_m;
      j["focus_distance_m"] = lens.focus_distance_m;
      break;
    case LensType::Fisheye:
      j["projection"] = "equidistant, r = f theta";
      j["fov_deg"] = lens.fisheye_fov_deg;
      j["focal_px_per_rad"] = lens.K.fx;
      break;
    case LensType::Panorama:
      j["projection"] = "equirectangular";
      // 360 x 180 for the full sphere; rounded so that 2 pi / (2 pi) prints as 360, not 359.99..
      auto deg = [](double rad) { return std::round(rad * 180 / std::numbers::pi * 1e9) / 1e9; };
      j["fov_deg"] = {deg(lens.K.width / lens.K.fx), deg(lens.K.height / lens.K.fy)};
      break;
  }
  return j;
}

json encodingsJson(const SequenceContext& c) {
  const bool z = c.depthPngPass() == Pass::DepthZ;
  const std::string depth = z ? "z-depth along the optical axis"
                              : "Euclidean ray distance camera centre to surface (a " +
                                    std::string(lensTypeName(c.lens().type)) +
                                    " lens has no usable z-depth)";
  json j = {
      {"rgb",
       "8-bit sRGB (IEC 61966-2-1 OETF of the colour clamped to [0, 1]; the camera response, if "
       "any, is applied to the linear radiance first)"},
      {"depth_png", depth + ", uint16, value = round(depth_m * scale), scale 1000 (asl depth0, "
                            "mm) or 5000 (tum depth); 0 = no surface or too far"},
      {"ray_depth_exr",
       "Euclidean distance camera centre to surface, float32 metres, channel Z; "
       "0 = no surface"},
      {"normal_png",
       "camera-frame unit normal, uint16 RGB, value = round((n + 1) / 2 * 65535); "
       "(0, 0, 0) = no surface"},
      {"label_png", "NYU40 class id, uint8, 0 = void"},
      {"instance_png", "instance id, uint16, 0 = none"},
      {"poses",
       "T_world_camera: camera x right, y down, z forward (OpenCV); world right-handed, "
       "z up, metres; quaternions Hamilton with w >= 0"},
  };
  if (has(c.spec.passes, Pass::DepthNoisy))
    j["depth_noisy_png"] =
        "Kinect-like z-depth (sensors/depth_noise.h; parameters in meta.json depth_noise), uint16 "
        "millimetres, 0 = no return (shadow, grazing angle, edge, out of range)";
  if (has(c.spec.passes, Pass::Flow))
    j["flow"] =
        "forward optical flow frame k -> k + 1 in pixels (x right, y down), for every frame but "
        "the last, from the exact depth, both camera poses and the objects' motion: <t>.flo "
        "Middlebury (float32 u, v; 1e10 = no surface), <t>.png KITTI (uint16 RGB = 64 u + "
        "32768, 64 v + 32768, valid), <t>.exr (float32 channels U, V; NaN = no surface), those "
        "of the three that storage.flow names; <t>_occ.png 8-bit, 255 = hidden in frame k + 1 "
        "or outside its image";
  if (has(c.spec.passes, Pass::FlowBackward))
    j["flow_bwd"] =
        "backward optical flow frame k -> k - 1 (flow0_bwd/), for every frame but the first, "
        "encoded as flow";
  if (c.spec.rgb_exr)
    j["rgb_exr"] =
        "asl cam0/data/<t>.exr: linear RGB radiance as rendered (before exposure, sensor noise, "
        "tone curve and sRGB encoding), channels R, G, B: float32, or float16 when "
        "storage.rgb_exr is half";
  return j;
}

}  // namespace

void checkOutputFolder(const fs::path& dir) {
  std::error_code ec;
  if (dir.empty()) throw InputError("", "--out", "no output folder given");
  fs::path abs = fs::absolute(dir, ec).lexically_normal();
  if (ec) throw InputError(dir.string(), "--out", "bad path: " + ec.message());
  if (abs.filename().empty()) abs = abs.parent_path();
  if (fs::exists(abs, ec)) {
    if (!fs::is_directory(abs, ec))
      throw InputError(dir.string(), "--out", "exists and is not a folder");
    if (::access(abs.c_str(), W_OK | X_OK) != 0)
      throw InputError(dir.string(), "--out",
                       std::string("folder is not writable: ") + std::strerror(errno));
    return;
  }
  fs::path ancestor = abs.parent_path();
  while (!fs::exists(ancestor, ec) && ancestor.has_parent_path() &&
         ancestor.parent_path() != ancestor)
    ancestor = ancestor.parent_path();
  if (!fs::is_directory(ancestor, ec))
    throw InputError(dir.string(), "--out",
                     "cannot be created: " + ancestor.string() + " is not a folder");
  if (::access(ancestor.c_str(), W_OK | X_OK) != 0)
    throw InputError(dir.string(), "--out",
                     "cannot be created: no write permission in " + ancestor.string());
}

SequenceWriter::SequenceWriter(SequenceSpec spec, const Trajectory& traj,
                               const std::vector<std::string>& formats) {
  // Phase 1: validate everything; nothing touches the disk.
  validateFormatNames(formats);
  if (spec.passes == 0 || (spec.passes & ~kAllPasses) != 0)
    throw InputError("", "--passes", "no valid pass selected");
  spec.intrinsics.validate("camera");
  INET_CHECK_MSG(spec.meta.is_object() || spec.meta.is_null(),
                 "SequenceSpec::meta must be an object");
  validateTrajectory(traj);
  validateLens(spec);
  if (spec.rgb_exr && !has(spec.passes, Pass::Rgb))
    throw InputError("", "--hdr", "needs the rgb pass in --passes");
  if (!(spec.stereo_baseline_m >= 0 && spec.stereo_baseline_m <= 10))
    throw InputError("", "--stereo", "the baseline must be in 0..10 m");
  ctx_ = std::make_shared<const SequenceContext>(SequenceContext{std::move(spec), traj});
  bool rgb_exr_written = false;
  for (const auto& name : formats) {
    formats_.push_back(createFormat(name, ctx_));
    for (const auto& o : formats_.back()->outputs())
      rgb_exr_written |= o.encoder.pass == Pass::Rgb && o.suffix.ends_with(".exr");
  }
  if (ctx_->spec.rgb_exr && !rgb_exr_written)
    throw InputError("", "--hdr",
                     "the linear EXR goes to the ASL cam0 folder: add asl to --format");
  const fs::path& dir = ctx_->spec.dir;
  checkOutputFolder(dir);
  const std::string meta = metaJson();

  // Phase 2: create the folder; meta.json is the first file and doubles as a write probe.
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), "--out", "cannot create folder: " + ec.message());
  writeTextAtomic(dir / "meta.json", meta);
  if (ctx_->spec.remove_stale_temporaries) removeStaleTemporaries(dir);
  // Create every image folder now, so concurrent writeFrame calls never race on mkdir.
  for (const auto& f : formats_)
    for (const auto& o : f->outputs()) {
      fs::create_directories(dir / o.folder, ec);
      if (ec)
        throw InputError((dir / o.folder).string(), "", "cannot create folder: " + ec.message());
    }
}

SequenceWriter::~SequenceWriter() = default;

size_t SequenceWriter::frameCount() const {
  return ctx_->traj.size();
}
const SequenceSpec& SequenceWriter::spec() const {
  return ctx_->spec;
}

std::vector<std::string> SequenceWriter::formats() const {
  std::vector<std::string> names;
  for (const auto& f : formats_) names.push_back(f->name());
  return names;
}

std::vector<fs::path> SequenceWriter::frameFiles(size_t k) const {
  INET_CHECK(k < frameCount());
  std::vector<fs::path> files;
  for (const auto& f : formats_)
    for (auto& p : f->frameFiles(k)) files.push_back(std::move(p));
  return files;
}

bool SequenceWriter::frameComplete(size_t k) const {
  std::error_code ec;
  for (const auto& p : frameFiles(k))
    if (!fs::is_regular_file(p, ec)) return false;
  return true;
}

void SequenceWriter::writeFrame(size_t k, const Frame& frame, const ImageF* rgb_display,
                                const Frame* right, const ImageF* right_display) const {
  INET_CHECK_MSG(k < frameCount(), fmt::format("frame {} of {}", k, frameCount()));
  const bool last = k + 1 == frameCount();
  const FrameView view{frame, rgb_display ? *rgb_display : frame.rgb, ctx_->spec.storage};
  checkFrame(frame, view.rgb_display, ctx_->spec.passes, ctx_->spec.intrinsics, k, k == 0, last);
  const bool stereo = ctx_->spec.stereo_baseline_m > 0;
  INET_CHECK_MSG(stereo == (right != nullptr),
                 "writeFrame takes cam1's frame exactly when the spec has a stereo baseline");
  const FrameView right_view{right ? *right : frame,
                             right_display ? *right_display : (right ? right->rgb : frame.rgb),
                             ctx_->spec.storage};
  if (right)
    checkFrame(*right, right_view.rgb_display, ctx_->spec.passes, ctx_->spec.intrinsics, k, k == 0,
               last);
  // One job per distinct encoding: outputs with the same key (ASL cam0 and TUM rgb) are encoded
  // once and the other names get a hard link or a copy of the finished file.
  struct Job {
    const FrameEncoder* encoder;
    int camera;
    std::vector<fs::path> paths;
  };
  std::vector<Job> jobs;
  std::map<std::pair<int, std::string>, size_t> by_key;
  for (const auto& f : formats_) {
    const std::string stem = f->frameStem(k);
    for (const auto& o : f->outputs()) {
      if (!o.writtenFor(k, frameCount())) continue;
      auto [it, fresh] = by_key.emplace(std::pair(o.camera, o.encoder.key), jobs.size());
      if (fresh) jobs.push_back({&o.encoder, o.camera, {}});
      jobs[it->second].paths.push_back(ctx_->spec.dir / o.folder / (stem + o.suffix));
    }
  }
  // Jobs are independent: run them in parallel (TBB rethrows the first exception here).
  tbb::parallel_for(size_t{0}, jobs.size(), [&](size_t i) {
    const Job& job = jobs[i];
    job.encoder->write(job.paths[0], job.camera == 1 ? right_view : view);
    for (size_t j = 1; j < job.paths.size(); ++j) linkOrCopy(job.paths[0], job.paths[j]);
  });
}

void SequenceWriter::finish() const {
  std::error_code ec;
  for (size_t k = 0; k < frameCount(); ++k)
    for (const auto& p : frameFiles(k))
      if (!fs::is_regular_file(p, ec))
        throw InputError(p.string(), "",
                         fmt::format("frame {} was not written; index files are written only "
                                     "after every frame exists",
                                     k));
  for (const auto& f : formats_)
    for (const auto& file : f->indexFiles()) writeTextAtomic(ctx_->spec.dir / file.path, file.text);
}

std::vector<fs::path> SequenceWriter::sequenceFiles() const {
  const fs::path& dir = ctx_->spec.dir;
  std::vector<fs::path> files;
  for (const auto& f : formats_)
    for (const auto& file : f->indexFiles()) files.push_back(dir / file.path);
  if (ctx_->spec.imu)
    for (const char* name : kImuFiles) files.push_back(dir / "imu0" / name);
  if (ctx_->spec.boxes) files.push_back(dir / "boxes.json");
  if (ctx_->spec.events) files.push_back(dir / "events0" / "sensor.yaml");
  return files;
}

bool SequenceWriter::finished() const {
  std::error_code ec;
  for (size_t k = 0; k < frameCount(); ++k)
    if (!frameComplete(k)) return false;
  for (const auto& p : sequenceFiles())
    if (!fs::is_regular_file(p, ec)) return false;
  return true;
}

void SequenceWriter::writeImu(const ImuSequence& seq, const ImuOptions& opt,
                              const std::string& comment) const {
  INET_CHECK_MSG(ctx_->spec.imu, "writeImu needs SequenceSpec::imu");
  writeImuFolder(ctx_->spec.dir, seq, opt, comment);
}

void SequenceWriter::writeBoxes(const Scene& scene, const std::vector<InstanceBox>& boxes,
                                const std::vector<std::vector<InstanceVisibility>>& visible) const {
  INET_CHECK_MSG(ctx_->spec.boxes, "writeBoxes needs SequenceSpec::boxes");
  writeTextAtomic(ctx_->spec.dir / "boxes.json", boxesJson(scene, boxes, ctx_->traj, visible));
}

bool SequenceWriter::eventsComplete() const {
  return EventsFolder::complete(ctx_->spec.dir);
}

std::unique_ptr<EventsFolder> SequenceWriter::openEvents(const CameraIntrinsics& K_events) const {
  INET_CHECK_MSG(ctx_->spec.events, "openEvents needs SequenceSpec::events");
  return std::make_unique<EventsFolder>(ctx_->spec.dir, ctx_->traj.poses.front().t_ns, K_events);
}

void writeImuFolder(const fs::path& dir, const ImuSequence& seq, const ImuOptions& opt,
                    const std::string& comment) {
  const fs::path out = dir / "imu0";
  // sensor.yaml last, as in every sensor folder
  writeTextAtomic(out / kImuFiles[0], formatImuCsv(seq.measured));
  writeTextAtomic(out / kImuFiles[1], formatImuCsv(seq.ideal));
  writeTextAtomic(out / kImuFiles[2], formatImuBiasCsv(seq.measured, seq.bias));
  writeTextAtomic(out / kImuFiles[3], formatImuSensorYaml(opt, comment));
}

NoisyDepthFolder::NoisyDepthFolder(const fs::path& sequence)
    : sequence_(sequence),
      out_(sequence / "depth0_noisy"),
      frames_(readAslFrameList(sequence / "depth0" / "data.csv")),
      depth_yaml_(readTextFile(sequence / "depth0" / "sensor.yaml")) {
  const fs::path csv = sequence / "depth0" / "data.csv";
  for (size_t k = 0; k < frames_.size(); ++k)
    if (frames_[k].file != frames_[k].stamp + ".png")
      throw InputError(csv.string(), fmt::format("row {}", k + 1),
                       fmt::format("expected the file {}.png (a depth PNG named by its stamp), "
                                   "got '{}'",
                                   frames_[k].stamp, frames_[k].file));
  const size_t at = depth_yaml_.find("\ncomment: ");
  if (at == std::string::npos)
    throw InputError((sequence / "depth0" / "sensor.yaml").string(), "comment",
                     "missing: not a sensor.yaml written by interiornet generate");
  const size_t from = at + std::string("\ncomment: ").size();
  depth_yaml_.replace(from, depth_yaml_.find('\n', from) - from,
                      aslSensorComment("depth0_noisy"));
  std::error_code ec;
  fs::create_directories(out_ / "data", ec);
  if (ec) throw InputError(out_.string(), "", "cannot create folder: " + ec.message());
  fs::remove(out_ / "data.csv", ec);
  if (ec) throw InputError((out_ / "data.csv").string(), "", "cannot remove: " + ec.message());
}

void NoisyDepthFolder::writeFrame(size_t k, const ImageF& depth_m) const {
  writePng(out_ / "data" / frames_.at(k).file, encodeDepth16(depth_m, kDepthScaleMm));
}

void NoisyDepthFolder::finish(const std::string& noise_yaml) const {
  std::string csv = std::string(kEurocCameraCsvHeader) + "\n";
  for (const SequenceFrame& f : frames_) {
    std::error_code ec;
    if (!fs::is_regular_file(out_ / "data" / f.file, ec))
      throw InputError((out_ / "data" / f.file).string(), "", "frame not written");
    csv += f.stamp + "," + f.file + "\n";
  }
  writeTextAtomic(out_ / "noise.yaml", noise_yaml);
  writeTextAtomic(out_ / "sensor.yaml", depth_yaml_);
  writeTextAtomic(out_ / "data.csv", csv);  // last: its presence means the folder is complete
}

bool NoisyDepthFolder::complete(const fs::path& sequence) {
  std::error_code ec;
  return fs::is_regular_file(sequence / "depth0_noisy" / "data.csv", ec);
}

namespace {
fs::path makeEventsFolders(const fs::path& dir) {
  const fs::path out = dir / "events0";
  std::error_code ec;
  fs::create_directories(out / "frames" / "data", ec);
  if (ec) throw InputError(out.string(), "--out", "cannot create folder: " + ec.message());
  return out;
}
}  // namespace

EventsFolder::EventsFolder(const fs::path& dir, TimeNs t0_ns, const CameraIntrinsics& K)
    : out_(makeEventsFolders(dir)),
      t0_ns_(t0_ns),
      K_(K),
      txt_(out_ / "events.txt", t0_ns),
      h5_(out_ / "events.h5", t0_ns, K.width, K.height),
      csv_("#timestamp [ns],filename\n") {}

EventsFolder::~EventsFolder() = default;

bool EventsFolder::complete(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "events0" / "sensor.yaml", ec);
}

void EventsFolder::add(TimeNs t_ns, const ImageF& intensity, const std::vector<Event>& events) {
  const std::string name = aslStamp(t_ns) + ".exr";
  writeExr(out_ / "frames" / "data" / name, intensity, {"Y"});
  csv_ += aslStamp(t_ns) + "," + name + "\n";
  txt_.write(events);
  h5_.write(events);
}

void EventsFolder::finish(const EventOptions& sim, size_t samples, size_t events) {
  txt_.close();
  h5_.close();
  writeTextAtomic(out_ / "frames" / "data.csv", csv_);
  // sensor.yaml last: its presence means the folder is complete
  const std::string yaml = fmt::format(
      "# General sensor definitions.\n"
      "sensor_type: camera\n"
      "comment: interiornet events0, a simulated event camera (ESIM model) at cam0's centre "
      "with cam0's horizontal field of view. events.txt lines 't x y p' (t in s from the first "
      "frame {} ns, p 1 = ON, 0 = OFF); events.h5 DSEC layout (/events/t us since /t_offset). "
      "frames/ holds the linear intensity of each sample the simulator used (EXR, channel Y)\n\n"
      "# Sensor extrinsics wrt. the body-frame.\n{}\n"
      "# Camera specific definitions.\n"
      "rate_hz: 0  # asynchronous\n"
      "resolution: [{}, {}]\n"
      "camera_model: pinhole\n"
      "intrinsics: [{}, {}, {}, {}] #fu, fv, cu, cv (OpenCV convention, pixel centres at "
      "integers)\n"
      "distortion_model: radial-tangential\n"
      "distortion_coefficients: [0.0, 0.0, 0.0, 0.0]\n\n"
      "# Event specific definitions.\n"
      "contrast_threshold_pos: {}\n"
      "contrast_threshold_neg: {}\n"
      "contrast_threshold_sigma: {}  # per crossing\n"
      "threshold_spread: {}  # per pixel, fixed\n"
      "refractory_period_ns: {}\n"
      "log_eps: {}\n"
      "leak_rate_hz: {}\n"
      "shot_noise_rate_hz: {}\n"
      "samples: {}\n"
      "events: {}\n",
      t0_ns_, translationTbs(Vec3::Zero()), K_.width, K_.height, formatFloat(K_.fx),
      formatFloat(K_.fy), formatFloat(K_.cx - 0.5), formatFloat(K_.cy - 0.5),
      formatFloat(sim.c_pos), formatFloat(sim.c_neg), formatFloat(sim.sigma_c),
      formatFloat(sim.threshold_spread), sim.refractory_ns, formatFloat(sim.log_eps),
      formatFloat(sim.leak_rate_hz), formatFloat(sim.shot_noise_rate_hz), samples, events);
  writeTextAtomic(out_ / "sensor.yaml", yaml);
}

std::string SequenceWriter::metaJson() const {
  const SequenceContext& c = *ctx_;
  json j = c.spec.meta.is_null() ? json::object() : c.spec.meta;
  auto put = [&j](const std::string& key, json value) {
    INET_CHECK_MSG(!j.contains(key),
                   "SequenceSpec::meta must not set the reserved key '" + key + "'");
    j[key] = std::move(value);
  };
  json passes = json::array();
  for (const PassInfo& p : kPassTable)
    if (has(c.spec.passes, p.pass)) passes.push_back(p.name);
  put("meta_format_version", 1);
  put("sequence", c.sequenceName());
  put("formats", formats());
  put("passes", passes);
  put("frame_count", c.traj.size());
  put("first_timestamp_ns", c.traj.poses.front().t_ns);
  put("last_timestamp_ns", c.traj.poses.back().t_ns);
  put("camera", cameraJson(c.lens()));
  put("lens", lensJson(c.lens()));
  put("encodings", encodingsJson(c));
  put("storage", {{"png_level", c.spec.storage.png_level},
                  {"exr_compression", exrCompressionName(c.spec.storage.exr)},
                  {"rgb_exr", c.spec.rgb_exr ? (c.spec.storage.rgb_exr_half ? "half" : "float")
                                             : "none"},
                  {"flow", flowFilesName(c.spec.storage)}});
  if (c.spec.stereo_baseline_m > 0)
    put("stereo", {{"baseline_m", c.spec.stereo_baseline_m},
                   {"T_cam0_cam1",
                    "translation (baseline_m, 0, 0): cam1 is right of cam0, same orientation and "
                    "lens; its images are in the folders of cam0's with 0 -> 1 (cam1, depth1, ...)"}});
  return j.dump(2) + "\n";
}

}  // namespace inet
