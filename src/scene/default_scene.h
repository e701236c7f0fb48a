#pragma once
// The built-in default scene: one furnished 5 x 4 x 2.7 m living-bedroom, built in code so that
// `interiornet generate` needs no files. x in [0, 5], y in [0, 4], floor at z = 0, Z up.
// About 25 labelled instances (NYU40) made of shared box / cylinder / quad meshes and one analytic
// sphere, lit by an emissive ceiling panel, a window and a lamp shade.
#include "scene/scene.h"

namespace inet {

Scene makeDefaultScene();

}  // namespace inet
