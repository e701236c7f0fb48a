#include "eval/sequence_reader.h"

#include <sstream>
#include <unordered_map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "dataset/image_encode.h"
#include "sensors/flow_io.h"
#include "trajectory/formats.h"

namespace inet {

namespace fs = std::filesystem;

SequenceReader::SequenceReader(const fs::path& dir) : dir_(dir) {
  std::error_code ec;
  if (!fs::is_directory(dir_, ec))
    throw InputError(dir_.string(), "",
                     fs::exists(dir_, ec) ? "not a folder: expected a sequence folder"
                                          : "sequence folder not found");
  const fs::path meta_path = dir_ / "meta.json";
  const std::string where = meta_path.string();
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(readTextFile(meta_path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, "", std::string("not valid JSON: ") + e.what());
  }
  // field by field, so that the message names the one that is missing or of the wrong type
  auto field = [&](const nlohmann::json& obj, const char* key, const std::string& path) {
    if (!obj.is_object() || !obj.contains(key)) throw InputError(where, path, "missing");
    return obj.at(key);
  };
  auto number = [&](const nlohmann::json& obj, const char* key, const std::string& path) {
    const nlohmann::json v = field(obj, key, path);
    if (!v.is_number()) throw InputError(where, path, "expected a number, got " + v.dump());
    return v.get<double>();
  };
  auto integer = [&](const nlohmann::json& obj, const char* key, const std::string& path) {
    const nlohmann::json v = field(obj, key, path);
    if (!v.is_number_integer())
      throw InputError(where, path, "expected an integer, got " + v.dump());
    return v.get<int64_t>();
  };
  const int64_t version = integer(meta, "meta_format_version", "meta_format_version");
  if (version != 1)
    throw InputError(where, "meta_format_version",
                     fmt::format("is {}; this reader knows version 1", version));
  const nlohmann::json cam = field(meta, "camera", "camera");
  const nlohmann::json lens = field(cam, "lens", "camera.lens");
  if (!lens.is_string()) throw InputError(where, "camera.lens", "expected a lens name");
  lens_ = parseLensType(lens.get<std::string>(), where, "camera.lens");
  const nlohmann::json r = field(cam, "renderer", "camera.renderer");
  const int64_t width = integer(cam, "width", "camera.width");
  const int64_t height = integer(cam, "height", "camera.height");
  if (width <= 0 || height <= 0 || width > 100000 || height > 100000)
    throw InputError(where, "camera.width",
                     fmt::format("{}x{} is not an image size", width, height));
  K_.width = static_cast<int>(width);
  K_.height = static_cast<int>(height);
  K_.fx = number(r, "fx", "camera.renderer.fx");
  K_.fy = number(r, "fy", "camera.renderer.fy");
  K_.cx = number(r, "cx", "camera.renderer.cx");
  K_.cy = number(r, "cy", "camera.renderer.cy");
  K_.validate(where);
  const fs::path cam0 = dir_ / "cam0" / "data.csv";
  if (!fs::exists(cam0, ec))
    throw InputError(cam0.string(), "",
                     "file not found: the evaluation reads the ASL layout (generate --format "
                     "asl, the default)");
  frames_ = readAslFrameList(cam0);
}

std::string SequenceReader::name() const {
  const fs::path p = dir_.filename().empty() ? dir_.parent_path() : dir_;
  return p.filename().string();
}

fs::path SequenceReader::framePath(const char* folder, size_t k, const char* suffix) const {
  INET_CHECK(k < frames_.size());
  return dir_ / folder / "data" / (frames_[k].stamp + suffix);
}

template <class Img>
void SequenceReader::checkSize(const Img& img, int channels, const fs::path& path) const {
  if (img.width != K_.width || img.height != K_.height || img.channels != channels)
    throw InputError(
        path.string(), "size",
        fmt::format("{}x{} with {} channel(s), expected {}x{} with {} (meta.json)", img.width,
                    img.height, img.channels, K_.width, K_.height, channels));
}

bool SequenceReader::hasLabels() const {
  std::error_code ec;
  return fs::is_directory(dir_ / "label0" / "data", ec);
}

void SequenceReader::requireFlow() const {
  const fs::path csv = dir_ / "flow0" / "data.csv";
  std::error_code ec;
  if (!fs::exists(csv, ec))
    throw InputError(csv.string(), "",
                     "file not found: the sequence has no forward flow (generate with the "
                     "flow pass, part of --passes default)");
}

ImageU8 SequenceReader::png8(const char* folder, size_t k, const char* suffix,
                             int channels) const {
  const fs::path p = framePath(folder, k, suffix);
  ImageU8 img = readPng8(p);
  checkSize(img, channels, p);
  return img;
}

ImageU8 SequenceReader::colour(size_t k) const {
  return png8("cam0", k, ".png", 3);
}

ImageF SequenceReader::depth(size_t k) const {
  const fs::path p = framePath("depth0", k, ".png");
  const ImageU16 mm = readPng16(p);
  checkSize(mm, 1, p);
  return decodeDepth16(mm, kDepthScaleMm);
}

ImageU8 SequenceReader::labels(size_t k) const {
  return png8("label0", k, "_nyu.png", 1);
}

FlowField SequenceReader::flow(size_t k) const {
  INET_CHECK(k + 1 < frames_.size());
  // the exact files first (.flo, then the EXR of the same floats), KITTI's 1/64 px PNG last
  fs::path file = framePath("flow0", k, ".flo");
  std::error_code ec;
  for (const char* ext : {".exr", ".png"}) {
    if (fs::exists(file, ec)) break;
    const fs::path next = framePath("flow0", k, ext);
    if (fs::exists(next, ec)) file = next;
  }
  // a missing .flo (no other file either) is reported by readFlo, naming it
  FlowField f = file.extension() == ".exr"   ? readFlowExr(file)
                : file.extension() == ".png" ? readKittiFlowPng(file)
                                             : readFlo(file);
  checkSize(f.flow, 2, file);
  const fs::path occ_path = framePath("flow0", k, "_occ.png");
  f.occluded = readPng8(occ_path);
  checkSize(f.occluded, 1, occ_path);
  for (uint8_t& o : f.occluded.data) o = o != 0;
  return f;
}

Trajectory SequenceReader::groundTruth() const {
  fs::path path = dir_ / "state_groundtruth_estimate0" / "data.csv";
  std::error_code ec;
  std::optional<TrajectoryFormat> fmt = TrajectoryFormat::Euroc;
  if (!fs::exists(path, ec) && fs::exists(dir_ / "groundtruth.txt", ec)) {
    path = dir_ / "groundtruth.txt";
    fmt = TrajectoryFormat::Tum;
  }
  const Trajectory all = readTrajectory(path.string(), fmt);
  std::unordered_map<TimeNs, Pose> by_stamp;
  for (const TimedPose& p : all.poses) by_stamp.emplace(p.t_ns, p.T_world_camera);
  Trajectory gt;
  for (const SequenceFrame& f : frames_) {
    const auto it = by_stamp.find(f.t_ns);
    if (it == by_stamp.end())
      throw InputError(path.string(), "timestamp " + f.stamp,
                       "no ground-truth pose at this cam0 frame's stamp");
    gt.poses.push_back({f.t_ns, it->second});
  }
  return gt;
}

}  // namespace inet
