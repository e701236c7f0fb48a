#pragma once
// boxes.json: the 3D box of every object instance (scene/object_boxes.h) and, per frame, which
// instances the camera sees (pixel count and 2D box from the instance pass) with their boxes in
// that camera's frame. Format described in docs/output.md ("boxes.json").
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "scene/object_boxes.h"
#include "trajectory/trajectory.h"

namespace inet {

/// How much of one instance a frame shows.
struct InstanceVisibility {
  int instance = 0;
  int64_t pixels = 0;            ///< pixels whose instance id is this one
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< 2D box of those pixels, inclusive, pixel indices
};

/// The instances visible in an instance image (ids > 0), sorted by id.
std::vector<InstanceVisibility> instanceVisibility(const ImageU16& instance);

/// The boxes.json text (deterministic: same inputs, same bytes; lengths rounded to 1 um and
/// rotations to 1e-9). `frames[k]` is the camera pose of frame k, `visible[k]` its visibility;
/// scene time of frame k = frames[k].t_ns - frames[0].t_ns (as the renderer places moving
/// objects). Per frame, each visible instance gets its box in the camera frame (x right, y down,
/// z forward); moving instances also get their world box at that time.
std::string boxesJson(const Scene& scene, const std::vector<InstanceBox>& boxes,
                      const Trajectory& frames,
                      const std::vector<std::vector<InstanceVisibility>>& visible);

}  // namespace inet
