// The light cache (render/light_cache.h): its factors are the trained share of each light's
// shadow rays that got through, floored, the same in any order of records; light picks that
// use it keep their pdfs consistent (sample against environmentRadiance / trianglePdf); and in
// a closed room with a lamp inside and the sun on its roof, cached picks keep the mean and cut
// the noise, with the same bytes on any thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "render/light_cache.h"
#include "render/lights.h"
#include "render/renderer.h"
#include "scene/primitives.h"
#include "emissive_quad.h"
#include "image_stats.h"

namespace inet {
namespace {

TEST(LightCache, FactorsAreTheSharesThatGotThroughFlooredAndOrderFree) {
  const Eigen::Vector3f p(0.2f, 0.3f, 1.1f), q(3.2f, 0.3f, 1.1f), r(-5.f, 2.f, 0.4f);
  std::vector<std::pair<int, float>> recs;
  for (int i = 0; i < 100; ++i) {
    recs.push_back({0, i < 25 ? 1.f : 0.f});  // light 0: a quarter get through
    recs.push_back({1, 0.f});                 // light 1: always blocked
    recs.push_back({2, 0.5f});                // light 2: through a pane of transmittance 0.5
  }
  for (uint32_t i = 0; i + 1 < LightCache::kMinTrials; ++i) recs.push_back({3, 0.f});  // too few
  LightCache forward, backward;
  for (const auto& [light, t] : recs) forward.record(p, light, t);
  {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    tbb::parallel_for(size_t{0}, recs.size(), [&](size_t i) {
      const auto& [light, t] = recs[recs.size() - 1 - i];
      backward.record(p, light, t);
    });
  }
  forward.record(r, 40, 1.f);  // beyond kLights: ignored
  forward.build();
  backward.build();
  EXPECT_EQ(forward.activeCells(), 1);
  const float* f = forward.factors(p);
  ASSERT_NE(f, nullptr);
  EXPECT_FLOAT_EQ(f[0], 0.25f);
  EXPECT_FLOAT_EQ(f[1], LightCache::kFloor);
  EXPECT_FLOAT_EQ(f[2], 0.5f);
  EXPECT_FLOAT_EQ(f[3], 1.f) << "under kMinTrials a light keeps its plain estimate";
  EXPECT_FLOAT_EQ(f[5], 1.f);
  EXPECT_EQ(forward.factors(q), nullptr) << "an untrained cell changes nothing";
  EXPECT_EQ(forward.factors(r), nullptr);
  const float* b = backward.factors(p);
  ASSERT_NE(b, nullptr);
  for (int k = 0; k < LightCache::kLights; ++k) EXPECT_EQ(f[k], b[k]);
}

// A sun, a sky, a point lamp and an emissive quad; a cache that learned the sun and the sky
// blocked around the receivers. Picks move to the lamp and the quad, and every light sample's
// pdf is what environmentRadiance and trianglePdf give the same direction at that pick point.
TEST(LightCache, CachedPicksShiftToWhatGetsThroughWithConsistentPdfs) {
  Scene s;
  Light lamp, sun, sky;
  lamp.name = "lamp";
  lamp.type = LightType::Point;
  lamp.position = Vec3(1, 1, 2);
  lamp.intensity = 5.f;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(0.3, 0.2, -1).normalized();
  sun.intensity = 350.f;
  sky.name = "sky";
  sky.type = LightType::Sky;
  sky.intensity = 30.f;
  s.lights = {lamp, sun, sky};
  const SceneLights lights(s, test::emissiveQuad(0));
  ASSERT_EQ(lights.pickCount(), 4u);  // the quad, then lamp, sun, sky
  const std::vector<Vec3f> receivers = {Vec3f(1.2f, 1.1f, 0.3f), Vec3f(2.1f, 2.2f, 1.0f)};
  LightCache cache;
  for (const Vec3f& p : receivers)
    for (int i = 0; i < 64; ++i) {
      cache.record(p, lights.cacheSlot(2), 0.f);                      // the sun: blocked
      cache.record(p, lights.cacheSlot(3), i % 8 == 0 ? 1.f : 0.f);  // the sky: 1 in 8
      cache.record(p, lights.cacheSlot(1), 1.f);                      // the lamp: clear
    }
  cache.build();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(0.f, 1.f);
  for (const Vec3f& p : receivers) {
    const SceneLights::PickPoint plain = lights.pickAt(p), cached = lights.pickAt(p, &cache);
    // the pick probabilities at the cached point, from how often `sample` picks each entry
    std::vector<int> picks(4, 0);
    int skies = 0, triangles = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      LightSample ls;
      if (!lights.sample(cached, U(rng), {U(rng), U(rng)}, ls)) continue;
      ASSERT_GE(ls.pick, 0);
      ++picks[static_cast<size_t>(ls.pick)];
      // (a sun's own direction can round to just outside its disk: its pdf is not compared)
      if (ls.delta || ls.pick == 2) continue;
      float pdf = 0.f;
      if (std::isinf(ls.dist)) {
        lights.environmentRadiance(ls.wi, &cached, pdf);
        ++skies;
      } else {
        const size_t tri = test::emissiveQuadTriangle(p, ls.wi);
        pdf = lights.trianglePdf(tri, cached, ls.dist, ls.wi.z());  // normal . (-wi)
        ++triangles;
      }
      ASSERT_NEAR(pdf / ls.pdf, 1.f, 1e-3f) << "pick " << ls.pick;
    }
    EXPECT_GT(skies, 0);
    EXPECT_GT(triangles, 0);
    // each entry's share is its plain share times its factor, renormalised: the quad (never
    // trained) 1, the lamp 1, the sun kFloor, the sky 1/8
    const double f[4] = {1.0, 1.0, LightCache::kFloor, 0.125};
    double norm = 0;
    for (size_t k = 0; k < 4; ++k) norm += f[k] * lights.pickProbability(p, k);
    for (size_t k = 0; k < 4; ++k) {
      const double expected = f[k] * lights.pickProbability(p, k) / norm;
      EXPECT_NEAR(picks[k] / static_cast<double>(n), expected, 0.01) << "entry " << k;
    }
    EXPECT_NEAR(cached.total / plain.total, norm, 1e-4);
    EXPECT_GT(lights.pickProbability(p, 2), 0.45) << "the sun rules the plain pick";
    EXPECT_GT(picks[1], 4.0 * lights.pickProbability(p, 1) * n)
        << "the lamp, whose rays get through, gets the picks the sun and the sky lost";
    EXPECT_GT(picks[2], 0) << "a blocked light keeps a share (kFloor): unbiased";
  }
}

// A closed grey room 4 x 3 x 2.5 m with a point lamp inside and a bright sun above the roof:
// the plain pick spends most shadow rays on the sun, which never gets in.
TEST(LightCache, CachedPicksKeepTheMeanWithLessNoiseAndTheSameBytesOnAnyThreadCount) {
  Scene s = test::closedGreyRoom(0.6f);
  Light lamp, sun;
  lamp.name = "lamp";
  lamp.type = LightType::Point;
  lamp.position = Vec3(0.8, 0.5, 2.0);
  lamp.intensity = 3.f;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(0.2, 0.1, -1).normalized();
  sun.intensity = 350.f;
  s.lights = {lamp, sun};
  Renderer r(s);
  const Pose pose = Pose::lookAt(Vec3(-1.6, -1.1, 1.4), Vec3(1, 1, 0.8), Vec3::UnitZ());
  auto render = [&](int spp, bool cached, uint64_t seed) {
    RenderOptions opt;
    opt.light_cache = cached;
    return test::renderSmallRgb(r, pose, opt, spp, seed);
  };
  const ImageF reference = render(1024, false, 99);
  const auto [plain_mean, plain_err] = test::againstReference(render(16, false, 1), reference);
  const auto [cached_mean, cached_err] = test::againstReference(render(16, true, 1), reference);
  EXPECT_NEAR(plain_mean, 1.0, 0.1);
  EXPECT_NEAR(cached_mean, 1.0, 0.03);
  EXPECT_LT(cached_err, 0.7 * plain_err) << "cached " << cached_err << ", plain " << plain_err;
  std::printf("relative RMSE at 16 spp: plain %.4f, cached %.4f\n", plain_err, cached_err);
  // unbiased: many cached samples converge on the plain reference
  EXPECT_NEAR(test::againstReference(render(256, true, 7), reference).mean_ratio, 1.0, 0.01);
  const auto [one, two] = test::onOneAndTwoThreads([&] { return render(4, true, 3); });
  EXPECT_EQ(one.data, two.data);
  EXPECT_NE(one.data, render(4, false, 3).data) << "the cache must change the picks";
}

}  // namespace
}  // namespace inet
