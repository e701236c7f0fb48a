#include "studio/json_fields.h"

#include <fmt/format.h>

#include <cmath>
#include <regex>

#include "core/error.h"

namespace inet::studio {

using nlohmann::json;

void checkKeys(const json& body, const std::set<std::string>& keys, const std::string& where) {
  if (!body.is_object())
    throw InputError(where, "", "must be a JSON object, not " + std::string(body.type_name()));
  for (const auto& [key, value] : body.items())
    if (keys.count(key) == 0) {
      std::string names;
      for (const std::string& k : keys) names += (names.empty() ? "" : ", ") + k;
      throw InputError("", key, "unknown key (" + names + ")");
    }
}

std::string flagToKey(const std::string& text) {
  static const std::regex flag("--([a-z][a-z0-9]*(?:-[a-z0-9]+)*)");
  std::string out;
  auto it = std::sregex_iterator(text.begin(), text.end(), flag);
  size_t last = 0;
  for (; it != std::sregex_iterator(); ++it) {
    out += text.substr(last, it->position() - last);
    std::string key = (*it)[1].str();
    for (char& c : key)
      if (c == '-') c = '_';
    out += key;
    last = it->position() + it->length();
  }
  return out + text.substr(last);
}

double number(const json& body, const std::string& key, double fallback) {
  if (!body.contains(key)) return fallback;
  const json& v = body.at(key);
  if (!v.is_number()) throw InputError("", key, "must be a number, not " + v.dump());
  return v.get<double>();
}

int64_t integer(const json& body, const std::string& key, int64_t fallback) {
  if (!body.contains(key)) return fallback;
  const json& v = body.at(key);
  if (!v.is_number_integer()) throw InputError("", key, "must be an integer, not " + v.dump());
  if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX))
    throw InputError("", key, "is too large");
  return v.get<int64_t>();
}

int integerIn(const json& body, const std::string& key, int fallback, int lo, int hi) {
  const int64_t v = integer(body, key, fallback);
  if (v < lo || v > hi) throw InputError("", key, fmt::format("must be in {}..{}", lo, hi));
  return static_cast<int>(v);
}

std::string text(const json& body, const std::string& key, const std::string& fallback) {
  if (!body.contains(key)) return fallback;
  const json& v = body.at(key);
  if (!v.is_string()) throw InputError("", key, "must be a string, not " + v.dump());
  return v.get<std::string>();
}

Vec3 vec3(const json& body, const std::string& key) {
  if (!body.contains(key)) throw InputError("", key, "is missing");
  const json& v = body.at(key);
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    throw InputError("", key, "must be [x, y, z] (metres), not " + v.dump());
  const Vec3 p(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  if (!p.allFinite() || p.cwiseAbs().maxCoeff() > 1e6)
    throw InputError("", key, "must be finite and within 1e6 m");
  return p;
}

json posesJson(const Trajectory& traj) {
  json poses = json::array();
  const TimeNs t_first = traj.empty() ? 0 : traj.poses.front().t_ns;
  for (const TimedPose& p : traj.poses) {
    const Pose& T = p.T_world_camera;
    const Quat q = canonicalQuat(T.q);
    poses.push_back({{"t_ns", p.t_ns - t_first},
                     {"position", {T.t.x(), T.t.y(), T.t.z()}},
                     {"quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}});
  }
  return poses;
}

}  // namespace inet::studio
