#include "render/camera.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"

namespace inet {

void CameraIntrinsics::validate(const std::string& where) const {
  if (width < 1 || width > 32768)
    throw InputError(where, "width", fmt::format("{} is outside 1..32768", width));
  if (height < 1 || height > 32768)
    throw InputError(where, "height", fmt::format("{} is outside 1..32768", height));
  if (!(fx > 0 && std::isfinite(fx))) throw InputError(where, "fx", "focal length must be > 0");
  if (!(fy > 0 && std::isfinite(fy))) throw InputError(where, "fy", "focal length must be > 0");
  if (!std::isfinite(cx)) throw InputError(where, "cx", "must be finite");
  if (!std::isfinite(cy)) throw InputError(where, "cy", "must be finite");
}

std::string CameraIntrinsics::toString() const {
  return fmt::format("Pinhole[{}x{} fx={} fy={} cx={} cy={} (OpenCV cx={} cy={})]", width, height,
                     fx, fy, cx, cy, cxOpenCV(), cyOpenCV());
}

namespace {
using nlohmann::json;

double number(const json& j, const std::string& key, const std::string& path) {
  if (!j.contains(key)) throw InputError(path, key, "missing");
  if (!j[key].is_number()) throw InputError(path, key, "must be a number");
  return j[key].get<double>();
}

Vec3 vec3(const json& j, const std::string& key, const std::string& path) {
  if (!j.contains(key)) throw InputError(path, key, "missing");
  const json& v = j[key];
  if (!v.is_array() || v.size() != 3) throw InputError(path, key, "must be an array of 3 numbers");
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) throw InputError(path, key, "must be an array of 3 numbers");
    out[i] = v[i].get<double>();
  }
  if (!out.allFinite()) throw InputError(path, key, "must be finite");
  return out;
}
}  // namespace

CameraFile loadCameraJson(const std::string& path) {
  return parseCameraJson(readTextFile(path), path);
}

CameraFile parseCameraJson(const std::string& text, const std::string& path) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for huge numbers (fuzzer)
    throw InputError(path, "", std::string("malformed JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(path, "", "top level must be an object");
  CameraFile cam;
  CameraIntrinsics& k = cam.intrinsics;
  double w = number(j, "width", path), h = number(j, "height", path);
  if (w != std::floor(w) || h != std::floor(h))
    throw InputError(path, "width/height", "must be integers");
  if (!(w >= 1 && w <= 32768)) throw InputError(path, "width", "must be in 1..32768");
  if (!(h >= 1 && h <= 32768)) throw InputError(path, "height", "must be in 1..32768");
  k.width = static_cast<int>(w);
  k.height = static_cast<int>(h);
  k.fx = number(j, "fx", path);
  k.fy = number(j, "fy", path);
  k.cx = j.contains("cx") ? number(j, "cx", path) : k.width / 2.0;
  k.cy = j.contains("cy") ? number(j, "cy", path) : k.height / 2.0;
  k.validate(path);
  if (j.contains("cam_to_world")) {
    const json& m = j["cam_to_world"];
    if (!m.is_array() || m.size() != 4)
      throw InputError(path, "cam_to_world", "must be 4 rows of 4 numbers");
    Mat4 mat;
    for (int r = 0; r < 4; ++r) {
      if (!m[r].is_array() || m[r].size() != 4)
        throw InputError(path, "cam_to_world", "must be 4 rows of 4 numbers");
      for (int c = 0; c < 4; ++c) {
        if (!m[r][c].is_number())
          throw InputError(path, "cam_to_world", "must be 4 rows of 4 numbers");
        mat(r, c) = m[r][c].get<double>();
      }
    }
    Mat3 rot = mat.block<3, 3>(0, 0);
    if ((rot.transpose() * rot - Mat3::Identity()).norm() > 1e-4 || rot.determinant() < 0)
      throw InputError(path, "cam_to_world", "rotation part is not a proper rotation");
    cam.T_world_camera = Pose::fromMatrix(mat);
  } else {
    Vec3 eye = vec3(j, "position", path), target = vec3(j, "look_at", path);
    Vec3 up = j.contains("up") ? vec3(j, "up", path) : Vec3(0, 0, 1);
    if ((target - eye).norm() < 1e-9) throw InputError(path, "look_at", "equals position");
    if ((target - eye).normalized().cross(up.normalized()).norm() < 1e-6)
      throw InputError(path, "up", "is parallel to the viewing direction");
    cam.T_world_camera = Pose::lookAt(eye, target, up);
  }
  return cam;
}

}  // namespace inet
