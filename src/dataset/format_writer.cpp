#include "dataset/format_writer.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "dataset/asl_writer.h"
#include "dataset/image_encode.h"
#include "core/image_io.h"
#include "dataset/tum_writer.h"
#include "sensors/flow_io.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

struct FormatEntry {
  const char* name;
  FormatFactory make;
};

// The registry: one line per format.
constexpr FormatEntry kFormats[] = {
    {"asl", makeAslWriter},
    {"tum", makeTumWriter},
};

/// The float image a pass is stored in (kPassTable's member; another pixel type is a bug).
const ImageF Frame::*floatMember(Pass pass) {
  const PassInfo& info = passInfo(pass);
  INET_CHECK_MSG(info.pixel == PixelType::Float,
                 "pass '" + std::string(info.name) + "' is not a float image");
  return info.member.f;
}

std::string joinedFormatNames() {
  std::string s;
  for (const auto& n : formatNames()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

std::string SequenceContext::sequenceName() const {
  if (!spec.name.empty()) return spec.name;
  fs::path p = spec.dir.lexically_normal();
  if (p.filename().empty()) p = p.parent_path();  // "out/seq/" -> "out/seq"
  return p.filename().string();
}

LensModel SequenceContext::lens() const {
  return spec.lens ? *spec.lens : LensModel::pinhole(spec.intrinsics);
}

Pass SequenceContext::depthPngPass() const {
  return groundTruthDepthKind(lens().type) == DepthKind::ZDepth ? Pass::DepthZ : Pass::DepthRay;
}

std::vector<fs::path> FormatWriter::frameFiles(size_t k) const {
  std::vector<fs::path> files;
  const std::string stem = frameStem(k);
  for (const auto& o : outputs_)
    if (o.writtenFor(k, ctx_->traj.size()))
      files.push_back(ctx_->spec.dir / o.folder / (stem + o.suffix));
  return files;
}

void FormatWriter::addOutput(std::string folder, std::string suffix, FrameEncoder encoder,
                             int camera) {
  if (!has(ctx_->spec.passes, encoder.pass)) return;
  const Neighbour neighbour = passInfo(encoder.pass).neighbour;
  const bool next = neighbour == Neighbour::Next, previous = neighbour == Neighbour::Previous;
  outputs_.push_back(
      {std::move(folder), std::move(suffix), std::move(encoder), camera, next, previous});
}

std::vector<std::string> formatNames() {
  std::vector<std::string> names;
  for (const auto& e : kFormats) names.emplace_back(e.name);
  std::sort(names.begin(), names.end());
  return names;
}

std::unique_ptr<FormatWriter> createFormat(const std::string& name,
                                           std::shared_ptr<const SequenceContext> ctx) {
  for (const auto& e : kFormats)
    if (name == e.name) return e.make(std::move(ctx));
  throw InputError(
      "", "--format",
      fmt::format("unknown format '{}'; valid formats: {}", name, joinedFormatNames()));
}

std::vector<std::string> parseFormatList(const std::string& list) {
  std::vector<std::string> names;
  size_t begin = 0;
  while (begin <= list.size()) {
    size_t end = std::min(list.find(',', begin), list.size());
    std::string item = list.substr(begin, end - begin);
    item.erase(std::remove(item.begin(), item.end(), ' '), item.end());
    if (item.empty())
      throw InputError(
          "", "--format",
          fmt::format("empty entry in '{}'; valid formats: {}", list, joinedFormatNames()));
    bool known = false;
    for (const auto& e : kFormats) known = known || item == e.name;
    if (!known)
      throw InputError(
          "", "--format",
          fmt::format("unknown format '{}'; valid formats: {}", item, joinedFormatNames()));
    if (std::find(names.begin(), names.end(), item) != names.end())
      throw InputError("", "--format", fmt::format("format '{}' is listed twice", item));
    names.push_back(item);
    begin = end + 1;
  }
  return names;
}

FrameEncoder srgbPng(Pass pass) {
  const std::string key = "png8-srgb/" + passName(pass);
  if (pass == Pass::Rgb)  // the displayed colour: after the camera response
    return {pass, key,
            [](const fs::path& p, const FrameView& v) { writePng(p, encodeSrgb8(v.rgb_display), v.storage.png_level);
            }};
  const ImageF Frame::*m = floatMember(pass);
  return {pass, key,
          [m](const fs::path& p, const FrameView& v) {
            writePng(p, encodeSrgb8(v.frame.*m), v.storage.png_level);
          }};
}

FrameEncoder depthPng(Pass pass, double scale) {
  const ImageF Frame::*m = floatMember(pass);
  return {pass, fmt::format("png16-depth-x{}/{}", scale, passName(pass)),
          [m, scale](const fs::path& p, const FrameView& v) {
            writePng(p, encodeDepth16(v.frame.*m, scale), v.storage.png_level);
          }};
}

FrameEncoder floatExr(Pass pass, std::vector<std::string> channel_names) {
  const ImageF Frame::*m = floatMember(pass);
  std::string key = "exr-float";
  for (const auto& c : channel_names) key += "-" + c;
  return {pass, key + "/" + passName(pass),
          [pass, m, names = std::move(channel_names)](const fs::path& p, const FrameView& v) {
            ExrOptions o{v.storage.exr};
            o.half = pass == Pass::Rgb && v.storage.rgb_exr_half;
            writeExr(p, v.frame.*m, names, o);
          }};
}

FrameEncoder normalPng(Pass pass) {
  const ImageF Frame::*m = floatMember(pass);
  return {pass, "png16-normal/" + passName(pass),
          [m](const fs::path& p, const FrameView& v) {
            writePng(p, encodeNormal16(v.frame.*m), v.storage.png_level);
          }};
}

FrameEncoder rawPng(Pass pass) {
  const PassInfo& info = passInfo(pass);
  const std::string key = "png-raw/" + passName(pass);
  if (info.pixel == PixelType::U8)
    return {pass, key, [m = info.member.u8](const fs::path& p, const FrameView& v) {
              writePng(p, v.frame.*m, v.storage.png_level);
            }};
  INET_CHECK_MSG(info.pixel == PixelType::U16, "rawPng takes an 8- or 16-bit integer pass");
  return {pass, key, [m = info.member.u16](const fs::path& p, const FrameView& v) {
            writePng(p, v.frame.*m, v.storage.png_level);
          }};
}

namespace {
/// The flow field of a flow pass (kPassTable's member; another pixel type is a bug).
const FlowField Frame::*flowMember(Pass pass) {
  const PassInfo& info = passInfo(pass);
  INET_CHECK_MSG(info.pixel == PixelType::Flow, "a flow encoder takes flow or flow_bwd");
  return info.member.flow;
}
}  // namespace

FrameEncoder flowFlo(Pass pass) {
  return {pass, "flo/" + passName(pass),
          [m = flowMember(pass)](const fs::path& p, const FrameView& v) {
            writeFlo(p, v.frame.*m);
          }};
}

FrameEncoder flowKittiPng(Pass pass) {
  return {pass, "png16-kitti/" + passName(pass),
          [m = flowMember(pass)](const fs::path& p, const FrameView& v) {
            writeKittiFlowPng(p, v.frame.*m, false, v.storage.png_level);
          }};
}

FrameEncoder flowExr(Pass pass) {
  return {pass, "exr-flow/" + passName(pass),
          [m = flowMember(pass)](const fs::path& p, const FrameView& v) {
            writeFlowExr(p, v.frame.*m, v.storage.exr);
          }};
}

FrameEncoder flowOcclusionPng(Pass pass) {
  return {pass, "png8-occlusion/" + passName(pass),
          [m = flowMember(pass)](const fs::path& p, const FrameView& v) {
            ImageU8 mask = (v.frame.*m).occluded;
            for (uint8_t& m : mask.data) m = m ? 255 : 0;
            writePng(p, mask, v.storage.png_level);
          }};
}

void parseFlowFiles(const std::string& list, StorageOptions& storage, const std::string& file,
                    const std::string& field) {
  StorageOptions o = storage;
  o.flow_flo = o.flow_kitti = o.flow_exr = false;
  std::string item;
  const auto take = [&] {
    if (item == "flo") o.flow_flo = true;
    else if (item == "kitti") o.flow_kitti = true;
    else if (item == "exr") o.flow_exr = true;
    else if (item == "both") o.flow_flo = o.flow_kitti = true;
    else
      throw InputError(file, field,
                       "'" + item + "' is not a flow file (flo, kitti, exr, or both = flo+kitti)");
    item.clear();
  };
  for (char ch : list + ",") {
    if (ch == ',' || ch == '+') take();
    else if (ch != ' ') item += ch;
  }
  storage = o;
}

std::string flowFilesName(const StorageOptions& storage) {
  std::string s;
  if (storage.flow_flo) s += "+flo";
  if (storage.flow_kitti) s += "+kitti";
  if (storage.flow_exr) s += "+exr";
  return s.empty() ? s : s.substr(1);
}

std::string formatFixed(double v, int decimals) {
  std::string s = fmt::format("{:.{}f}", v, decimals);
  if (!s.empty() && s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

std::string formatFloat(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // 'n': nan/inf stay as they are
  return s;
}

}  // namespace inet
