#include "dataset/boxes_json.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/nyu40.h"

namespace inet {
namespace {

using nlohmann::json;

double round6(double v) {
  const double r = std::round(v * 1e6) / 1e6;
  return r == 0 ? 0.0 : r;  // no "-0.0"
}
double round9(double v) {
  const double r = std::round(v * 1e9) / 1e9;
  return r == 0 ? 0.0 : r;
}
json vec(const Vec3& v) {
  return {round6(v.x()), round6(v.y()), round6(v.z())};
}
/// Hamilton quaternion as [w, x, y, z] with w >= 0.
json quat(Quat q) {
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;
  return {round9(q.w()), round9(q.x()), round9(q.y()), round9(q.z())};
}

json worldBox(const OrientedBox& b) {
  json corners = json::array();
  for (const Vec3& c : b.corners()) corners.push_back(vec(c));
  return {{"centre", vec(b.centre)},
          {"size", vec(b.size)},
          {"q_world_box", quat(b.q_world_box)},
          {"yaw_rad", round9(b.yaw())},
          {"corners", corners}};
}

}  // namespace

std::vector<InstanceVisibility> instanceVisibility(const ImageU16& instance) {
  std::map<int, InstanceVisibility> seen;
  for (int y = 0; y < instance.height; ++y)
    for (int x = 0; x < instance.width; ++x) {
      const int id = instance.at(x, y);
      if (id == 0) continue;
      auto [it, fresh] = seen.try_emplace(id, InstanceVisibility{id, 0, x, y, x, y});
      InstanceVisibility& v = it->second;
      ++v.pixels;
      v.x0 = std::min(v.x0, x);
      v.x1 = std::max(v.x1, x);
      v.y0 = std::min(v.y0, y);
      v.y1 = std::max(v.y1, y);
    }
  std::vector<InstanceVisibility> out;
  out.reserve(seen.size());
  for (auto& [id, v] : seen) out.push_back(v);
  return out;
}

std::string boxesJson(const Scene& scene, const std::vector<InstanceBox>& boxes,
                      const Trajectory& frames,
                      const std::vector<std::vector<InstanceVisibility>>& visible) {
  INET_CHECK(visible.size() == frames.size());
  json root;
  root["format"] = "interiornet boxes 1";
  root["conventions"] = {
      {"world", "right-handed, z up, metres"},
      {"camera", "x right, y down, z forward (OpenCV); the frame's T_world_camera"},
      {"box",
       "points centre + R(q) * (s .* size / 2), s in [-1, 1]^3; gravity-aligned at rest (box z "
       "= world up), heading yaw_rad about world z; corners in bit order x = bit 0, y = bit 1, "
       "z = bit 2 (0 = negative side), corners 0-3 the bottom face"},
      {"quaternion", "Hamilton [w, x, y, z], w >= 0"},
      {"visibility",
       "pixels: count of pixels of the instance pass with this id; bbox2d [x0, y0, x1, y1]: "
       "inclusive pixel indices of those pixels (modal, what is seen)"},
      {"scene_time", "t_ns - first frame's t_ns (moving objects are placed by it)"}};
  json objects = json::array();
  std::map<int, const InstanceBox*> by_id;
  for (const InstanceBox& b : boxes) {
    by_id[b.instance] = &b;
    json o = {{"instance", b.instance},
              {"nyu40", b.nyu40},
              {"class", std::string(nyu40Name(b.nyu40))},
              {"name", b.name},
              {"kind", b.kind},
              {"room", b.room >= 0 && b.room < static_cast<int>(scene.rooms.size())
                           ? json(scene.rooms[b.room].id)
                           : json(nullptr)},
              {"moving", b.moving}};
    o["box"] = worldBox(b.box);
    objects.push_back(std::move(o));
  }
  root["objects"] = std::move(objects);
  json out_frames = json::array();
  const TimeNs t0 = frames.empty() ? 0 : frames.poses.front().t_ns;
  for (size_t k = 0; k < frames.size(); ++k) {
    const Pose& T_wc = frames.poses[k].T_world_camera;
    const Pose T_cw = T_wc.inverse();
    const double t_s = static_cast<double>(frames.poses[k].t_ns - t0) * 1e-9;
    json vis = json::array();
    for (const InstanceVisibility& v : visible[k]) {
      json e = {{"instance", v.instance},
                {"pixels", v.pixels},
                {"bbox2d", {v.x0, v.y0, v.x1, v.y1}}};
      auto it = by_id.find(v.instance);
      if (it != by_id.end()) {
        const OrientedBox wb = boxAt(scene, *it->second, t_s);
        const OrientedBox cb = wb.transformed(T_cw);
        e["centre_cam"] = vec(cb.centre);
        e["q_cam_box"] = quat(cb.q_world_box);
        if (it->second->moving) e["box_world"] = worldBox(wb);
      }
      vis.push_back(std::move(e));
    }
    out_frames.push_back({{"t_ns", frames.poses[k].t_ns}, {"visible", std::move(vis)}});
  }
  root["frames"] = std::move(out_frames);
  return root.dump(1) + "\n";
}

}  // namespace inet
