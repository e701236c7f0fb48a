#include "studio/trajectory_api.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <set>

#include "core/error.h"
#include "studio/json_fields.h"

namespace inet::studio {

namespace {

using nlohmann::json;

const std::set<std::string> kKeys = {"type",   "frames",    "fps",        "seed",       "v_mult",
                                     "w_mult", "clearance", "min_height", "max_height", "style"};

}  // namespace

RandomTrajectoryOptions TrajectoryRequest::options() const {
  return motion.options(type, seed, frames, fps);
}

TrajectoryRequest parseTrajectoryRequest(const json& body, int max_frames) {
  checkKeys(body, kKeys);
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
  json poses = posesJson(traj.frames);
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
