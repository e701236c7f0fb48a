#include "studio/design_api.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>

#include "core/error.h"
#include "sensors/imu.h"
#include "studio/json_fields.h"
#include "trajectory/spectrum.h"

namespace inet::studio {

using nlohmann::json;

namespace {

constexpr size_t kMaxKeyframes = 1000;
constexpr double kMaxPoses = 100000;  ///< poses of one path (fps x duration)

Keyframe parseKeyframe(const json& k, size_t i) {
  const std::string at = fmt::format("keyframes[{}]", i);
  try {
    checkKeys(k, {"t", "position", "look_at"}, at);
    Keyframe f;
    const double t = number(k, "t", -1.0);
    if (!k.contains("t")) throw InputError("", "t", "is missing");
    if (!(t >= 0 && t <= 1e6)) throw InputError("", "t", "must be in 0..1e6 s");
    f.t_ns = static_cast<TimeNs>(std::llround(t * 1e9));
    f.position = vec3(k, "position");
    f.look_at = vec3(k, "look_at");
    const Vec3 d = f.look_at - f.position;
    if (d.head<2>().norm() < 1e-3 * std::max(1e-3, d.norm()) || d.norm() < 1e-3)
      throw InputError("", "look_at",
                       "must differ from position and not be straight above or below it (the "
                       "image's x axis is kept level)");
    return f;
  } catch (const InputError& e) {
    throw InputError(e.file(), e.field().empty() ? at : at + "." + e.field(), e.problem());
  }
}

/// Runs of consecutive path poses that fail the check, as warnings.
void pathWarnings(const Trajectory& path, const std::vector<char>& bad, double clearance,
                  json& warnings) {
  const TimeNs t0 = path.poses.front().t_ns;
  for (size_t i = 0; i < bad.size();) {
    if (!bad[i]) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j + 1 < bad.size() && bad[j + 1]) ++j;
    const double from = (path.poses[i].t_ns - t0) * 1e-9, to = (path.poses[j].t_ns - t0) * 1e-9;
    warnings.push_back(
        {{"kind", "path"},
         {"from_s", from},
         {"to_s", to},
         {"message", fmt::format("the path between {:.2f} s and {:.2f} s leaves the free space "
                                 "(inside furniture or a wall, outside the rooms, or closer than "
                                 "{} m to the geometry)",
                                 from, to, clearance)}});
    i = j + 1;
  }
}

}  // namespace

void checkDesignKeys(const json& body, std::set<std::string> extra) {
  extra.insert({"keyframes", "fps", "clearance", "max_speed", "max_turn_rate"});
  checkKeys(body, extra);
}

DesignRequest parseDesignRequest(const json& body) {
  if (!body.is_object())
    throw InputError("request body", "",
                     "must be a JSON object, not " + std::string(body.type_name()));
  DesignRequest r;
  if (!body.contains("keyframes") || !body.at("keyframes").is_array())
    throw InputError("", "keyframes", "must be an array of {t, position, look_at}");
  const json& ks = body.at("keyframes");
  if (ks.empty() || ks.size() > kMaxKeyframes)
    throw InputError("", "keyframes", fmt::format("must hold 1..{} keyframes", kMaxKeyframes));
  for (size_t i = 0; i < ks.size(); ++i) {
    r.keyframes.push_back(parseKeyframe(ks[i], i));
    if (i > 0 && r.keyframes[i].t_ns <= r.keyframes[i - 1].t_ns)
      throw InputError("", fmt::format("keyframes[{}].t", i),
                       "must be later than the keyframe before");
  }
  r.fps = number(body, "fps", r.fps);
  if (!(r.fps > 0 && r.fps <= 1000)) throw InputError("", "fps", "must be in (0, 1000]");
  const double span_s = (r.keyframes.back().t_ns - r.keyframes.front().t_ns) * 1e-9;
  if (span_s * r.fps > kMaxPoses)
    throw InputError("", "fps",
                     fmt::format("{} s at {} fps is over {} poses", span_s, r.fps, kMaxPoses));
  r.clearance = number(body, "clearance", r.clearance);
  if (!(r.clearance >= 0 && r.clearance <= 5))
    throw InputError("", "clearance", "must be in 0..5 m");
  r.max_speed_mps = number(body, "max_speed", r.max_speed_mps);
  if (!(r.max_speed_mps > 0 && r.max_speed_mps <= 100))
    throw InputError("", "max_speed", "must be in (0, 100] m/s");
  r.max_turn_rate_dps = number(body, "max_turn_rate", r.max_turn_rate_dps);
  if (!(r.max_turn_rate_dps > 0 && r.max_turn_rate_dps <= 10000))
    throw InputError("", "max_turn_rate", "must be in (0, 10000] deg/s");
  return r;
}

Trajectory designTrajectory(const DesignRequest& req) {
  Trajectory keys;
  for (const Keyframe& k : req.keyframes)
    keys.poses.push_back({k.t_ns, Pose::lookAt(k.position, k.look_at, Vec3::UnitZ())});
  Trajectory path = resampleUniform(keys, req.fps);
  for (TimedPose& p : path.poses) p.T_world_camera.q = canonicalQuat(p.T_world_camera.q);
  return path;
}

json runDesignRequest(const StudioLayout& layout, const DesignRequest& req) {
  const auto t0 = std::chrono::steady_clock::now();
  const FreeSpace& space = *layout.space;
  json keyframes = json::array(), warnings = json::array();
  for (size_t i = 0; i < req.keyframes.size(); ++i) {
    const Vec3& p = req.keyframes[i].position;
    const bool indoors = space.isIndoors(p);
    const bool free = space.hasClearance(p, req.clearance);
    const double d = space.exactDistance(p);
    keyframes.push_back({{"index", i}, {"free", free}, {"indoors", indoors}, {"distance_m", d}});
    if (!free)
      warnings.push_back(
          {{"kind", "keyframe"},
           {"index", i},
           {"message",
            indoors ? fmt::format("keyframe {} is inside furniture or a wall, or {:.2f} m from "
                                  "the geometry (clearance {} m)",
                                  i + 1, d, req.clearance)
                    : fmt::format("keyframe {} is outside the free space (inside closed "
                                  "furniture, a wall, or outside the rooms)",
                                  i + 1)}});
  }
  const Trajectory path = designTrajectory(req);
  std::vector<char> bad(path.size());
  double max_speed = 0, max_turn = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    bad[i] = !space.hasClearance(path.poses[i].T_world_camera.t, req.clearance);
    if (i == 0) continue;
    const Pose& a = path.poses[i - 1].T_world_camera;
    const Pose& b = path.poses[i].T_world_camera;
    const double dt = (path.poses[i].t_ns - path.poses[i - 1].t_ns) * 1e-9;
    max_speed = std::max(max_speed, (b.t - a.t).norm() / dt);
    max_turn = std::max(max_turn, a.q.angularDistance(b.q) * 180 / M_PI / dt);
  }
  pathWarnings(path, bad, req.clearance, warnings);
  if (max_speed > req.max_speed_mps)
    warnings.push_back({{"kind", "speed"},
                        {"message", fmt::format("the camera reaches {:.2f} m/s, over the limit "
                                                "of {} m/s: give the keyframes more time",
                                                max_speed, req.max_speed_mps)}});
  if (max_turn > req.max_turn_rate_dps)
    warnings.push_back({{"kind", "turn"},
                        {"message", fmt::format("the camera turns at {:.0f} deg/s, over the "
                                                "limit of {} deg/s: give the keyframes more time",
                                                max_turn, req.max_turn_rate_dps)}});
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double duration = (path.poses.back().t_ns - path.poses.front().t_ns) * 1e-9;
  return {{"frames", path.size()},          {"fps", req.fps},
          {"duration_s", duration},         {"max_speed_mps", max_speed},
          {"max_turn_rate_dps", max_turn},  {"compute_ms", std::round(ms * 10) / 10},
          {"poses", posesJson(path)},       {"keyframes", std::move(keyframes)},
          {"warnings", std::move(warnings)}};
}

json runImuRequest(const json& body) {
  checkDesignKeys(body, {"imu_rate", "noise"});
  const DesignRequest req = parseDesignRequest(body);
  ImuOptions opt;
  opt.rate_hz = number(body, "imu_rate", 200.0);
  if (!(opt.rate_hz >= 1 && opt.rate_hz <= 2000))
    throw InputError("", "imu_rate", "must be in 1..2000 Hz");
  const std::string noise = text(body, "noise", "none");
  if (noise != "none" && noise != "euroc")
    throw InputError("", "noise", "unknown IMU noise '" + noise + "' (none, euroc)");
  opt.noise = noise == "euroc" ? ImuNoise::euroc() : ImuNoise::none();
  Trajectory path = designTrajectory(req);
  if (path.size() < 2) throw InputError("", "keyframes", "an IMU needs a path of at least 2 poses");
  const TimeNs t0 = path.poses.front().t_ns;
  for (TimedPose& p : path.poses) p.t_ns -= t0;
  const ImuSequence imu = simulateImu(path, opt);
  json samples = json::array();
  double max_gyro = 0, max_accel = 0;
  for (const ImuSample& m : imu.measured) {
    samples.push_back({{"t_ns", m.t_ns},
                       {"gyro", {m.gyro.x(), m.gyro.y(), m.gyro.z()}},
                       {"accel", {m.accel.x(), m.accel.y(), m.accel.z()}}});
    max_gyro = std::max(max_gyro, m.gyro.norm());
    max_accel = std::max(max_accel, m.accel.norm());
  }
  return {{"rate_hz", opt.rate_hz},
          {"noise", noise},
          {"samples", std::move(samples)},
          {"max_gyro_rad_s", max_gyro},
          {"max_accel_m_s2", max_accel}};
}

DesignExport exportDesign(const DesignRequest& req, const std::string& format) {
  const TrajectoryFormat f = parseTrajectoryFormat(format, "format");
  Trajectory path = designTrajectory(req);
  // the files count time from the first pose, as the previews do
  const TimeNs t0 = path.poses.front().t_ns;
  for (TimedPose& p : path.poses) p.t_ns -= t0;
  TrajectoryFormatOptions opt;
  opt.icl_fps = opt.pose_list_fps = opt.kitti_fps = req.fps;
  DesignExport out;
  try {
    out.text = formatTrajectory(path, f, opt);
  } catch (const InputError& e) {
    throw InputError("", "format", e.problem());
  }
  // the names the datasets give these files
  static const std::map<TrajectoryFormat, const char*> names = {
      {TrajectoryFormat::Tum, "groundtruth.txt"},
      {TrajectoryFormat::Euroc, "data.csv"},
      {TrajectoryFormat::Icl, "trajectory.gt.freiburg"},
      {TrajectoryFormat::SlamBench, "groundtruth_slambench.txt"},
      {TrajectoryFormat::SceneNet, "trajectory.log"},
      {TrajectoryFormat::SceneNetV1, "trajectory_random_poses_SE3_3x4.txt"},
      {TrajectoryFormat::Kitti, "poses.txt"}};
  out.file_name = names.at(f);
  out.content_type = f == TrajectoryFormat::Euroc ? "text/csv" : "text/plain";
  return out;
}

}  // namespace inet::studio
