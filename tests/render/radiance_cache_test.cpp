// The radiance cache (render/radiance_cache.h): a cell's mean is the mean of its records, the
// same in any order and split over any number of recorders; cells are told apart by position
// by the side a surface faces and by kind; a cell with too few records is not used; a lone bright
// record is left out. In a closed grey room lit by a lamp, paths that stop at the cache keep
// the mean within a few percent with less noise, with the same bytes on any thread count.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cstdio>
#include <random>

#include "render/radiance_cache.h"
#include "render/renderer.h"
#include "scene/primitives.h"
#include "image_stats.h"

namespace inet {
namespace {

using V = Eigen::Vector3f;
constexpr auto A = RadianceCache::Kind::PerAlbedo;

TEST(RadianceCache, AMeanIsItsRecordsWhateverTheirOrderAndRecorders) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 2.f);
  std::vector<V> values(300);
  for (V& v : values) v = V(u(rng), u(rng), u(rng));
  const V p(0.30f, 1.10f, 0.02f), up(0, 0, 1);
  RadianceCache one, many;
  RadianceCache::Recorder all(one);
  for (const V& v : values) all.record(p, up, A, v);
  one.merge(all);
  tbb::parallel_for(size_t{0}, values.size(), size_t{7}, [&](size_t i0) {
    RadianceCache::Recorder r(many);
    for (size_t i = std::min(values.size(), i0 + 7); i-- > i0;) r.record(p, up, A, values[i]);
    many.merge(r);
  });
  one.build();
  many.build();
  const V* a = one.lookup(p, up, A);
  const V* b = many.lookup(p + V(0.1f, 0.1f, 0.1f), V(0.1f, -0.2f, 0.9f), A);  // same cell, side
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(*a, *b);
  V mean = V::Zero();
  for (const V& v : values) mean += v;
  mean /= static_cast<float>(values.size());
  EXPECT_LT((*a - mean).cwiseAbs().maxCoeff(), 1e-5f);
  EXPECT_EQ(one.activeCells(), 1u);
  EXPECT_EQ(one.records(), values.size());
}

TEST(RadianceCache, CellsAreApartBySideAndPlaceAndNeedEnoughRecords) {
  RadianceCache::Config config;
  config.cell_m = 0.25f;
  config.min_records = 16;
  RadianceCache c(config);
  RadianceCache::Recorder r(c);
  const V p(1.01f, -0.40f, 2.49f);
  for (int i = 0; i < 16; ++i) {
    r.record(p, V(0, 0, -1), A, V(1, 1, 1));                // a ceiling, facing down
    r.record(p + V(0, 0, 0.005f), V(0, 0, 1), A, V(3, 3, 3));  // the floor above, facing up
    r.record(p + V(0.3f, 0, 0), V(0, 0, -1), A, V(5, 5, 5));  // the next cell along x
  }
  for (int i = 0; i < 15; ++i) r.record(V(-3, -3, 0), V(1, 0, 0), A, V(7, 7, 7));  // too few
  r.record(V(-3, -3, 0), V(1, 0, 0), A, V(-1, 0, 0));  // negative: dropped
  c.merge(r);
  c.build();
  EXPECT_EQ(c.activeCells(), 3u);
  ASSERT_NE(c.lookup(p, V(0, 0, -1), A), nullptr);
  EXPECT_FLOAT_EQ(c.lookup(p, V(0, 0, -1), A)->x(), 1.f);
  EXPECT_FLOAT_EQ(c.lookup(p, V(0, 0, 1), A)->x(), 3.f);
  EXPECT_FLOAT_EQ(c.lookup(p + V(0.3f, 0, 0), V(0, 0, -1), A)->x(), 5.f);
  EXPECT_EQ(c.lookup(V(-3, -3, 0), V(1, 0, 0), A), nullptr) << "15 records are under min_records";
  EXPECT_EQ(c.lookup(p, V(1, 0, 0), A), nullptr) << "nothing recorded facing +x there";
  EXPECT_EQ(c.lookup(p, V(0, 0, -1), RadianceCache::Kind::Radiance), nullptr)
      << "a rough non-Lambertian surface's radiance is kept apart from light per unit albedo";
}

TEST(RadianceCache, ALoneBrightRecordIsLeftOut) {
  RadianceCache c;
  RadianceCache::Recorder r(c);
  const V p(0.1f, 0.1f, 0.1f), n(0, 1, 0);
  for (int i = 0; i < 40; ++i) r.record(p, n, A, V(0.5f, 0.5f, 0.5f) * (1.f + 0.02f * i));
  r.record(p, n, A, V(1e4f, 1e4f, 1e4f));  // a caustic path
  c.merge(r);
  c.build();
  ASSERT_NE(c.lookup(p, n, A), nullptr);
  EXPECT_NEAR(c.lookup(p, n, A)->x(), 0.5f * 1.39f, 1e-4f);
  EXPECT_EQ(c.loneRecords(), 1u);
  // a bright record among others like it stays
  RadianceCache d;
  RadianceCache::Recorder s(d);
  for (int i = 0; i < 40; ++i) s.record(p, n, A, V(1, 1, 1) * static_cast<float>(i % 4 == 0 ? 8 : 1));
  d.merge(s);
  d.build();
  EXPECT_EQ(d.loneRecords(), 0u);
  EXPECT_FLOAT_EQ(d.lookup(p, n, A)->x(), (10 * 8 + 30) / 40.f);
}

// A closed grey room 4 x 3 x 2.5 m (albedo 0.7: much of its light has bounced more than twice)
// lit by a point lamp.
TEST(RadianceCache, CachedPathsKeepTheMeanWithLessNoiseAndTheSameBytesOnAnyThreadCount) {
  Scene s = test::closedGreyRoom(0.7f);
  Light lamp;
  lamp.name = "lamp";
  lamp.type = LightType::Point;
  lamp.position = Vec3(1.2, 0.8, 0.4);
  lamp.intensity = 3.f;
  s.lights = {lamp};
  Renderer r(s);
  const Pose pose = Pose::lookAt(Vec3(-1.6, -1.1, 1.4), Vec3(1, 1, 0.8), Vec3::UnitZ());
  auto render = [&](int spp, bool cached, uint64_t seed) {
    RenderOptions opt;
    opt.radiance_cache = cached;
    return test::renderSmallRgb(r, pose, opt, spp, seed, 8);
  };
  const ImageF reference = render(1024, false, 99);
  const auto [plain_mean, plain_err] = test::againstReference(render(16, false, 1), reference);
  const auto [cached_mean, cached_err] = test::againstReference(render(16, true, 1), reference);
  std::printf("16 spp: mean ratio plain %.4f, cached %.4f; relative RMSE plain %.4f, cached %.4f\n",
              plain_mean, cached_mean, plain_err, cached_err);
  EXPECT_NEAR(plain_mean, 1.0, 0.03);
  EXPECT_NEAR(cached_mean, 1.0, 0.03) << "the cache's bias";
  EXPECT_LT(cached_err, 0.75 * plain_err) << "measured 0.63x";
  const auto [one, two] = test::onOneAndTwoThreads([&] { return render(4, true, 3); });
  EXPECT_EQ(one.data, two.data);
  EXPECT_NE(one.data, render(4, false, 3).data) << "the cache must change the paths";
}

}  // namespace
}  // namespace inet
