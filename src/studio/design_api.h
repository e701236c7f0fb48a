#pragma once
// Trajectory design (issue 18): keyframes placed on the page (a time, a position and a point
// looked at) become a smooth camera path, checked against the layout's exact free space, and
// exported in any trajectory format we write.
//
// Request (POST /api/design/path and /api/design/export; /api/jobs/sequence adds its own keys):
//   {"keyframes": [{"t": s >= 0, rising, "position": [x, y, z], "look_at": [x, y, z]}, ...]
//                 (1..1000; world Z up, metres),
//    "fps": (0, 1000] (25), "clearance": 0..5 m (0.25),
//    "max_speed": m/s (1.5), "max_turn_rate": deg/s (120)}
// The path: each keyframe is the pose at `position` looking at `look_at` with the image's x
// axis level (Pose::lookAt with world up +z); the poses go through resampleUniform
// (trajectory/spectrum.h: a Catmull-Rom cubic through the keyframes in position and quaternion,
// C1 and interpolating) at `fps` from the first keyframe's time to the last's.
// Checks: a keyframe or path pose that is not indoors or closer than `clearance` to the
// triangles (FreeSpace::hasClearance: the exact distance where the grid cannot decide) is a
// warning; so is a speed or turn rate over the limits between two poses.
// Response of /api/design/path:
//   {"frames", "fps", "duration_s", "max_speed_mps", "max_turn_rate_dps", "compute_ms",
//    "poses": [as posesJson], "keyframes": [{"index", "free", "indoors", "distance_m"}],
//    "warnings": [{"kind": "keyframe"|"path"|"speed"|"turn", "index" (keyframes), "from_s",
//                  "to_s" (path), "message"}]}
#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <vector>

#include "studio/studio_layout.h"
#include "trajectory/formats.h"
#include "trajectory/trajectory.h"

namespace inet::studio {

struct Keyframe {
  TimeNs t_ns = 0;
  Vec3 position = Vec3::Zero();
  Vec3 look_at = Vec3::UnitX();
};

struct DesignRequest {
  std::vector<Keyframe> keyframes;
  double fps = 25.0;
  double clearance = 0.25;
  double max_speed_mps = 1.5;
  double max_turn_rate_dps = 120.0;
};

/// Throws unless `body` is an object whose keys are the design keys above or in `extra` (the
/// route's own).
void checkDesignKeys(const nlohmann::json& body, std::set<std::string> extra);
/// Parses and checks the keys above (others are left to the caller: checkDesignKeys). Throws
/// InputError("", key, problem); a keyframe's key is named "keyframes[3].position".
DesignRequest parseDesignRequest(const nlohmann::json& body);

/// The camera path through the keyframes (see above).
Trajectory designTrajectory(const DesignRequest& req);

/// The path's poses with the free-space checks: the response above.
nlohmann::json runDesignRequest(const StudioLayout& layout, const DesignRequest& req);

/// The IMU an IMU at the camera would measure along the path (POST /api/design/imu): the
/// design keys plus "imu_rate" (Hz, 1..2000, 200) and "noise" (none | euroc: the ADIS16448's
/// densities, seed 0). sensors/imu.h's simulateImu: the poses, a B-spline through them, its
/// acceleration and body rate; gravity (0, 0, -9.81) is measured as the accelerometer does.
/// {"rate_hz", "noise", "samples": [{"t_ns", "gyro": [x, y, z] rad/s, "accel": [x, y, z]
///  m/s^2}, ...] (IMU frame = camera frame, t from the first pose), "max_gyro_rad_s",
///  "max_accel_m_s2"}
nlohmann::json runImuRequest(const nlohmann::json& body);

/// An export: the trajectory file's text in `format` (formats.h's names) and the file name a
/// download gets (TUM groundtruth.txt, EuRoC data.csv, ...).
struct DesignExport {
  std::string text, file_name, content_type;
};
/// Throws InputError("", "format", ...) for an unknown format or poses it cannot hold.
DesignExport exportDesign(const DesignRequest& req, const std::string& format);

}  // namespace inet::studio
