#include "trajectory/builtin_trajectory.h"

#include <cmath>

#include "core/error.h"

namespace inet {

Trajectory builtinTrajectory(int frames, double fps, TimeNs t0_ns) {
  INET_CHECK(frames >= 1 && fps > 0);
  const double period_s = 16.0;
  const Vec3 centre(2.5, 2.0, 0.0);
  Trajectory traj;
  traj.poses.reserve(frames);
  for (int k = 0; k < frames; ++k) {
    // integer nanosecond stamps: round(k / fps * 1e9), no accumulated drift
    TimeNs dt = static_cast<TimeNs>(std::llround(k * 1e9 / fps));
    double t = dt * 1e-9;
    double theta = 2.0 * M_PI * t / period_s;
    Vec3 eye = centre + Vec3(0.8 * std::cos(theta), 0.55 * std::sin(theta),
                             1.45 + 0.08 * std::sin(2 * theta));
    double heading = theta + M_PI - 0.35;  // look across the room centre
    Vec3 target = eye + Vec3(2.0 * std::cos(heading), 2.0 * std::sin(heading), -0.55);
    traj.poses.push_back({t0_ns + dt, Pose::lookAt(eye, target, Vec3::UnitZ())});
  }
  return traj;
}

}  // namespace inet
