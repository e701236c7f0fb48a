#pragma once
// A smooth, collision-free camera path through the built-in default room (default_scene.h), used
// until the trajectory stage (issue 5) generates paths for any layout. The camera circles an
// ellipse around the room centre at about 1.45 m, looking across the room centre and slightly down
// at the furniture; one loop takes 16 s.
#include "trajectory/trajectory.h"

namespace inet {

/// `frames` poses at `fps`, the first at t0_ns.
Trajectory builtinTrajectory(int frames, double fps, TimeNs t0_ns = 0);

}  // namespace inet
