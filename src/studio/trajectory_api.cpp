#include "studio/trajectory_api.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <regex>
#include <set>

#include "core/error.h"

namespace inet::studio {

namespace {

using nlohmann::json;

const std::set<std::string> kKeys = {"type",   "frames",    "fps",        "seed",       "v_mult",
                                     "w_mult", "clearance", "min_height", "max_height", "style"};

/// "--v-mult" -> "v_mult": the command line's flag as the request's key, in a field name or
/// inside a message ("need 0 <= --min-height < --max-height").
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

std::string text(const json& body, const std::string& key, const std::string& fallback) {
  if (!body.contains(key)) return fallback;
  const json& v = body.at(key);
  if (!v.is_string()) throw InputError("", key, "must be a string, not " + v.dump());
  return v.get<std::string>();
}

}  // namespace

RandomTrajectoryOptions TrajectoryRequest::options() const {
  return motion.options(type, seed, frames, fps);
}

TrajectoryRequest parseTrajectoryRequest(const json& body, int max_frames) {
  if (!body.is_object())
    throw InputError("request body", "",
                     "must be a JSON object, not " + std::string(body.type_name()));
  for (const auto& [key, value] : body.items())
    if (kKeys.count(key) == 0)
      throw InputError("", key,
                       "unknown key (type, frames, fps, seed, v_mult, w_mult, clearance, "
                       "min_height, max_height, style)");
  TrajectoryRequest r;
  r.type = parseMotionType(text(body, "type", "two-body"), "type");
  const int64_t frames = integer(body, "frames", 250);
  if (frames < 1 || frames > max_frames)
    throw InputError("", "frames", fmt::format("must be in 1..{}", max_frames));
  r.frames = static_cast<int>(frames);
  r.fps = number(body, "fps", 25.0);
  if (!(r.fps > 0 && r.fps <= 10000)) throw InputError("", "fps", "must be in (0, 10000]");
  if (body.contains("seed") && !body.at("seed").is_number_unsigned())
    throw InputError("", "seed", "must be an integer >= 0, not " + body.at("seed").dump());
  r.seed = body.value("seed", uint64_t{0});
  r.motion.v_mult = number(body, "v_mult", 0.0);
  r.motion.w_mult = number(body, "w_mult", 0.0);
  r.motion.clearance = number(body, "clearance", r.motion.clearance);
  r.motion.min_height = number(body, "min_height", r.motion.min_height);
  r.motion.max_height = number(body, "max_height", r.motion.max_height);
  r.motion.style = text(body, "style", "none");
  try {
    r.options();  // the command line's checks, with its messages
  } catch (const InputError& e) {
    throw InputError(e.file(), flagToKey(e.field()), flagToKey(e.problem()));
  }
  return r;
}

json runTrajectoryRequest(const StudioLayout& layout, const TrajectoryRequest& req) {
  const auto t0 = std::chrono::steady_clock::now();
  const RandomTrajectory traj =
      generateRandomTrajectory(*layout.space, req.options(), layout.source);
  json poses = json::array();
  const TimeNs t_first = traj.frames.empty() ? 0 : traj.frames.poses.front().t_ns;
  for (const TimedPose& p : traj.frames.poses) {
    const Pose& T = p.T_world_camera;
    const Quat q = canonicalQuat(T.q);
    poses.push_back({{"t_ns", p.t_ns - t_first},
                     {"position", {T.t.x(), T.t.y(), T.t.z()}},
                     {"quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}});
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return {{"layout", layout.scene.name},
          {"type", motionTypeName(req.type)},
          {"seed", req.seed},
          {"frames", req.frames},
          {"fps", req.fps},
          {"v_mult", traj.v_mult},
          {"w_mult", traj.w_mult},
          {"style", req.motion.style},
          {"compute_ms", std::round(ms * 10) / 10},
          {"poses", std::move(poses)}};
}

}  // namespace inet::studio
