#pragma once
// Built-in parametric meshes, all centred at the origin in a unit-sized box so that an object's
// transform carries its real size:
//   box       unit cube [-0.5, 0.5]^3, 12 triangles, outward winding
//   cylinder  radius 0.5, height 1 along z, centred; param "segments" (3..256, default 24)
//   fold      one fold of cloth, y = cos(2 pi (x + 1/2)) / 2 for x, z in [-0.5, 0.5], one
//             two-sided surface with smooth normals; param "segments" (2..256, default 16).
//             Folds side by side along x join with continuous normals (curtain panels)
//   quad      unit square [-0.5, 0.5]^2 in the z = 0 plane, geometric normal +z
//   sphere    analytic sphere (not tessellated); param "radius" (> 0, default 0.5)
#include <map>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet {

/// Names accepted by makePrimitive, for error messages.
const std::vector<std::string>& primitiveNames();

/// Builds the primitive `name` with `params`. Unknown names or parameters and out-of-range values
/// throw InputError(where, field, ...), where `field` names the offending key.
Mesh makePrimitive(const std::string& name, const std::map<std::string, double>& params,
                   const std::string& where, const std::string& field);

}  // namespace inet
