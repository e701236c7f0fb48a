#pragma once
// Room shells exported as one object. SceneNet's layouts name the whole shell of a room "wall"
// (kitchen2: floor and ceiling are faces of wall.041), SceneNet v1 calls it "room_skeleton";
// labelled by name, the floor and the ceiling would be walls in the NYU40 ground truth. An
// object labelled wall is split into up to three objects of its own:
//  - floor:   its level triangles (normal within 18 degrees of the vertical, either way: a
//             shell modelled as an outward box has its floor facing down) whose lowest corner
//             lies within 0.3 m of the object's lowest point;
//  - ceiling: its other level triangles whose highest corner lies within 0.3 m of its top;
//  - wall:    everything else (window sills and the tops of low walls stay wall).
// A part is split out only with at least 0.5 m^2 of such triangles, and only from objects whose
// mesh no other object shares (an instanced wall would change everywhere).
#include <cstddef>

#include "scene/scene.h"

namespace inet {

/// Splits the floors and ceilings out of wall objects as above; the new objects take new
/// instance ids after the largest one. Returns how many wall objects were split.
size_t splitRoomShells(Scene& scene);

}  // namespace inet
