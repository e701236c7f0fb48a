#include "studio/frame_preview.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/color.h"
#include "core/error.h"
#include "core/image_io.h"
#include "render/renderer.h"
#include "render/tonemap.h"
#include "scene/nyu40.h"
#include "studio/camera_keys.h"
#include "studio/json_fields.h"

namespace inet::studio {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

Pass parsePreviewPass(const std::string& name) {
  if (name == "rgb") return Pass::Rgb;
  if (name == "depth") return Pass::DepthZ;
  if (name == "normal") return Pass::Normal;
  if (name == "label") return Pass::Label;
  if (name == "albedo") return Pass::Albedo;
  throw InputError("", "pass", "unknown pass '" + name + "' (rgb, depth, normal, label, albedo)");
}

ImageU8 depthGrey(const ImageF& depth) {
  float far = 0;
  for (float d : depth.data)
    if (std::isfinite(d)) far = std::max(far, d);
  ImageU8 out(depth.width, depth.height, 1);
  for (size_t i = 0; i < depth.data.size(); ++i) {
    const float d = depth.data[i];
    out.data[i] = d > 0 && std::isfinite(d) && far > 0
                      ? static_cast<uint8_t>(std::lround(255 * (1 - 0.8 * d / far)))
                      : 0;
  }
  return out;
}

ImageU8 normalColours(const ImageF& n) {
  ImageU8 out(n.width, n.height, 3);
  for (size_t i = 0; i < n.data.size(); ++i)
    out.data[i] =
        static_cast<uint8_t>(std::lround(255 * std::clamp((n.data[i] + 1) / 2, 0.f, 1.f)));
  return out;
}

ImageU8 labelColours(const ImageU8& label) {
  ImageU8 out(label.width, label.height, 3);
  for (size_t i = 0; i < label.pixelCount(); ++i) nyu40Color(label.data[i], &out.data[i * 3]);
  return out;
}

}  // namespace

FramePreviewRequest parseFramePreview(const json& body) {
  std::set<std::string> keys = {"position", "quaternion_xyzw", "width", "height", "fx", "spp",
                                "pass"};
  keys.insert(lensKeys().begin(), lensKeys().end());
  keys.insert(responseKeys().begin(), responseKeys().end());
  checkKeys(body, keys);
  FramePreviewRequest r;
  r.T_world_camera.t = vec3(body, "position");
  const json& q = body.value("quaternion_xyzw", json());
  if (!q.is_array() || q.size() != 4 ||
      !std::all_of(q.begin(), q.end(), [](const json& v) { return v.is_number(); }))
    throw InputError("", "quaternion_xyzw", "must be [x, y, z, w]");
  const Quat quat(q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
  if (!(std::abs(quat.norm() - 1) < 1e-3))
    throw InputError("", "quaternion_xyzw", "must have unit length");
  r.T_world_camera.q = quat.normalized();
  const int w = integerIn(body, "width", 160, 16, 1024);
  const int h = integerIn(body, "height", 120, 16, 1024);
  const double fx = number(body, "fx", 150.0);
  if (!(fx > 0 && fx <= 100000)) throw InputError("", "fx", "must be in (0, 100000]");
  r.lens = lensModelOf(parseLensKeys(body), CameraIntrinsics::centred(w, h, fx));
  const ResponseKeys response = parseResponseKeys(body);
  r.response = response.response;
  r.auto_exposure = response.exposure == "auto";
  r.spp = integerIn(body, "spp", 4, 1, 64);
  r.pass = parsePreviewPass(text(body, "pass", "rgb"));
  // a fisheye or panorama has no z-depth: its depth is the ray distance (docs/cameras.md)
  if (r.pass == Pass::DepthZ && groundTruthDepthKind(r.lens.type) == DepthKind::RayDistance)
    r.pass = Pass::DepthRay;
  return r;
}

FramePreviewer::FramePreviewer(std::shared_ptr<const StudioLayout> layout, fs::path tmp_dir)
    : layout_(std::move(layout)), tmp_dir_(std::move(tmp_dir)) {}

FramePreviewer::~FramePreviewer() = default;

const Renderer& FramePreviewer::renderer() {
  std::lock_guard lock(mutex_);
  if (!renderer_) renderer_ = std::make_unique<Renderer>(layout_->scene);
  return *renderer_;
}

std::string FramePreviewer::png(const FramePreviewRequest& req) {
  const Renderer& r = renderer();
  Frame frame;
  ImageU8 image;
  if (req.pass == Pass::Rgb) {
    RenderOptions opt;
    opt.spp = req.spp;
    opt.passes = bit(Pass::Rgb);
    opt.denoise = true;  // a few samples per pixel: the edge-aware filter makes them readable
    r.render(req.lens, req.T_world_camera, opt, 0, frame);
    ResponseSettings response = req.response;
    if (req.auto_exposure) {  // as the sequence's auto exposure would if this were its preview
      ExposureMeter meter;
      meter.add(frame.rgb);
      response.exposure_scale = meter.scale();
    }
    image = encodeSrgb8(response.apply(frame.rgb, 0, 0));
  } else {
    r.renderGroundTruth(req.lens, req.T_world_camera, bit(req.pass), frame);
    image = req.pass == Pass::DepthZ     ? depthGrey(frame.depth_z)
            : req.pass == Pass::DepthRay ? depthGrey(frame.depth_ray)
            : req.pass == Pass::Normal   ? normalColours(frame.normal)
            : req.pass == Pass::Label    ? labelColours(frame.label)
                                         : encodeSrgb8(frame.albedo);
  }
  fs::path file;
  {
    std::lock_guard lock(mutex_);
    file = tmp_dir_ / fmt::format("preview_{}.png", ++serial_);
  }
  writePng(file, image);
  std::ifstream in(file, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  std::error_code ec;
  fs::remove(file, ec);
  return bytes.str();
}

}  // namespace inet::studio
