#pragma once
// Checks shared by the estimator tests (light cache, radiance cache, sun photons): an image
// against a reference, the same render on 1 and 2 threads, and a closed grey room to render.
#include <tbb/global_control.h>

#include <cmath>
#include <utility>

#include "core/image.h"
#include "render/renderer.h"
#include "scene/primitives.h"

namespace inet::test {

struct AgainstReference {
  double mean_ratio = 0;  ///< image mean / reference mean
  double rel_rmse = 0;    ///< RMSE / reference mean
};

inline AgainstReference againstReference(const ImageF& img, const ImageF& ref) {
  double sum = 0, ref_sum = 0, se = 0;
  for (size_t i = 0; i < img.data.size(); ++i) {
    sum += img.data[i];
    ref_sum += ref.data[i];
    se += (img.data[i] - ref.data[i]) * (img.data[i] - ref.data[i]);
  }
  const double n = static_cast<double>(img.data.size());
  return {sum / ref_sum, std::sqrt(se / n) / (ref_sum / n)};
}

/// The RGB pass of a 48 x 36 view (focal 40 px) from `pose`: `options` (its estimators) with
/// the given samples, seed and bounces.
inline ImageF renderSmallRgb(const Renderer& r, const Pose& pose, RenderOptions options, int spp,
                             uint64_t seed, int bounces = 4) {
  options.spp = spp;
  options.max_bounces = bounces;
  options.seed = seed;
  options.passes = static_cast<PassMask>(Pass::Rgb);
  Frame f;
  r.render(CameraIntrinsics::centred(48, 36, 40), pose, options, 0, f);
  return f.rgb;
}

/// A closed room 4 x 3 x 2.5 m (x in [-2, 2], y in [-1.5, 1.5], z in [0, 2.5]) of one grey
/// plaster of the given albedo, its faces turned inward; no lights.
inline Scene closedGreyRoom(float albedo) {
  Scene s;
  Mesh box = makePrimitive("box", {}, "test", "box");
  for (Tri& t : box.triangles) std::swap(t[1], t[2]);
  box.source.kind = MeshSource::Kind::Inline;
  box.id = "inward_box";
  s.meshes = {box};
  Material m;
  m.id = "plaster";
  m.albedo = Vec3f::Constant(albedo);
  s.materials = {m};
  s.objects = {Object::make(
      "room", 0, 0,
      (Eigen::Translation3d(0, 0, 1.25) * Eigen::Scaling(Vec3(4, 3, 2.5))).matrix(), 1, 1)};
  return s;
}

/// render() run with at most 1 and at most 2 threads.
template <class Render>
std::pair<ImageF, ImageF> onOneAndTwoThreads(Render render) {
  std::pair<ImageF, ImageF> out;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    out.first = render();
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    out.second = render();
  }
  return out;
}

}  // namespace inet::test
