// Generated apartments: the acceptance checks on many seeds (every room reachable from
// the front door through free floor, no two pieces' hulls interpenetrating by more than 1 cm,
// every piece inside its room, at least 60 % free floor per room), determinism, round trips of
// layout.json and light.xml, and that the scene builds and renders.
#include "procedural/apartment.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <set>

#include "../temp_dir.h"
#include "core/atomic_file.h"
#include "core/image_io.h"
#include "core/rng.h"
#include "render/renderer.h"
#include "scene/layout_json.h"
#include "scene/layout_stats.h"
#include "scene/light_xml.h"
#include "apartment_checks.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

using test::TempDir;
using test::checkApartment;

Apartment build(uint64_t seed, const fs::path& dir, const fs::path& textures = {}) {
  ApartmentOptions opt;
  opt.seed = seed;
  opt.texture_size = 64;
  return makeApartment(opt, dir, textures.empty() ? dir / "textures" : textures);
}

// The 1,000 layouts from seeds 0..999 (textures shared, as `layout generate --count`
// writes them).
TEST(Apartment, AcceptanceChecksOnAThousandSeeds) {
  TempDir dir;
  for (uint64_t seed = 0; seed < 1000; ++seed) {
    SCOPED_TRACE(seed);
    Apartment apt = build(seed, dir.path() / std::to_string(seed), dir.path() / "textures");
    checkApartment(apt);
    if (HasFailure()) break;
  }
}

TEST(Apartment, DeterministicAndRoundTrips) {
  TempDir a, b;
  Apartment x = build(7, a.path()), y = build(7, b.path());
  const std::string path = (a.path() / "layout.json").string();
  saveLayout(x.scene, path);
  saveLayout(y.scene, (b.path() / "layout.json").string());
  EXPECT_EQ(readTextFile(path), readTextFile((b.path() / "layout.json").string()))
      << "same seed, same bytes";
  Scene loaded = loadLayout(path);
  EXPECT_EQ(layoutToJson(loaded), readTextFile(path)) << "layout.json round-trips exactly";
  // light.xml round trip
  const std::string lx = (a.path() / "light.xml").string();
  saveLightXml(x.scene, lx);
  LightSetup setup = loadLightXml(lx);
  EXPECT_EQ(setup.lights.size(), x.scene.lights.size());
  Scene copy = loaded;
  applyLightSetup(copy, setup, lx);
  saveLightXml(copy, (a.path() / "again.xml").string());
  EXPECT_EQ(readTextFile(lx), readTextFile((a.path() / "again.xml").string()));
  // a different seed differs
  TempDir c;
  Apartment z = build(8, c.path());
  EXPECT_NE(layoutToJson(z.scene), layoutToJson(x.scene));
}

TEST(Apartment, BuildsAndRendersWithLabels) {
  TempDir dir;
  Apartment apt = build(3, dir.path());
  Renderer r(apt.scene);
  // a camera in the middle of the first room, 1.5 m up, looking along the longer side
  const Room& room = apt.scene.rooms[0];
  Eigen::AlignedBox2d b;
  for (const auto& p : room.outline) b.extend(p);
  const Eigen::Vector2d c = b.center();
  const Vec3 eye(c.x(), c.y(), 1.5), target(b.max().x(), c.y(), 1.0);
  const CameraIntrinsics K = CameraIntrinsics::centred(64, 48, 40);
  RenderOptions opt;
  opt.spp = 4;
  opt.passes = static_cast<PassMask>(Pass::Rgb) | static_cast<PassMask>(Pass::Label) |
               static_cast<PassMask>(Pass::Instance);
  Frame f;
  r.render(K, Pose::lookAt(eye, target, Vec3::UnitZ()), opt, 0, f);
  std::set<int> labels;
  for (uint8_t v : f.label.data) labels.insert(v);
  EXPECT_TRUE(labels.count(1)) << "walls in view";
  EXPECT_EQ(labels.count(0), 0u) << "a closed apartment: every pixel hits something";
  double mean = 0;
  for (float v : f.rgb.data) mean += v;
  EXPECT_GT(mean / f.rgb.data.size(), 0.0) << "lit";
}

}  // namespace
}  // namespace inet

namespace inet {
namespace {

/// Mean luminance of the material colours (MaterialSpec albedo: a texture's mean colour) of
/// 200 pieces of each of a few categories in `style`.
double styleLuminance(DecorStyle style) {
  double sum = 0;
  int n = 0;
  for (const char* category : {"sofa", "wardrobe", "dining_table", "bookshelf", "armchair"})
    for (uint32_t i = 0; i < 200; ++i) {
      CounterRng rng(5, RngStream::Layout, 9, i, 0);
      FurnitureSizeHint hint;
      hint.style = style;
      for (const MaterialSpec& m : makeFurnitureSized(category, hint, rng).materials) {
        sum += 0.2126 * m.albedo.x() + 0.7152 * m.albedo.y() + 0.0722 * m.albedo.z();
        ++n;
      }
    }
  return sum / n;
}

// A style changes materials, not placement: same pieces in the same places, lighter materials
// for scandinavian than for classic over several seeds, and "any" is the unstyled generator.
TEST(Apartment, DecorationStylesChangeMaterialsNotPlacement) {
  TempDir dir("apartment_style");
  for (uint64_t seed : {1u, 2u, 3u, 4u}) {
    ApartmentOptions opt;
    opt.seed = seed;
    opt.texture_size = 64;
    opt.style = DecorStyle::Scandinavian;
    Apartment a = makeApartment(opt, dir.path(), dir.path() / "textures");
    opt.style = DecorStyle::Classic;
    Apartment b = makeApartment(opt, dir.path(), dir.path() / "textures");
    ASSERT_EQ(a.pieces.size(), b.pieces.size()) << "seed " << seed;
    for (size_t i = 0; i < a.pieces.size(); ++i)
      EXPECT_EQ(a.pieces[i].category, b.pieces[i].category) << "seed " << seed << " piece " << i;
  }
  const double any = styleLuminance(DecorStyle::Any);
  const double scandinavian = styleLuminance(DecorStyle::Scandinavian);
  const double classic = styleLuminance(DecorStyle::Classic);
  std::printf("mean material luminance: any %.3f, scandinavian %.3f, classic %.3f\n", any,
              scandinavian, classic);
  EXPECT_GT(scandinavian, 1.3 * classic);
  EXPECT_GT(scandinavian, any);
  EXPECT_LT(classic, any);
  EXPECT_EQ(parseDecorStyle("industrial"), DecorStyle::Industrial);
  EXPECT_THROW(parseDecorStyle("baroque"), InputError);
  // weights: a dark warm wood suits classic more than scandinavian, a light ash the reverse
  MaterialSpec walnut, ash;
  walnut.albedo = {0.20f, 0.12f, 0.07f};
  ash.albedo = {0.72f, 0.66f, 0.56f};
  EXPECT_GT(styleWeight(DecorStyle::Classic, walnut), styleWeight(DecorStyle::Scandinavian, walnut));
  EXPECT_GT(styleWeight(DecorStyle::Scandinavian, ash), styleWeight(DecorStyle::Classic, ash));
  EXPECT_EQ(styleWeight(DecorStyle::Any, ash), 1.0);
}

TEST(LayoutStats, CountsRoomsObjectsCategoriesAndWritesCharts) {
  TempDir dir;
  LayoutStats stats;
  std::map<std::string, size_t> kinds;
  size_t rooms = 0;
  for (uint64_t seed = 0; seed < 5; ++seed) {
    Apartment apt = build(seed, dir.path() / std::to_string(seed), dir.path() / "textures");
    stats.add(apt.scene);
    rooms += apt.scene.rooms.size();
    std::set<int> seen;
    for (const Object& o : apt.scene.objects)
      if (o.kind == "sofa" && seen.insert(o.instance).second) ++kinds["sofa"];
  }
  EXPECT_EQ(stats.layouts, 5u);
  size_t counted = 0;
  for (const auto& [k, n] : stats.room_types) counted += n;
  EXPECT_EQ(counted, rooms);
  EXPECT_EQ(stats.categories["sofa"], kinds["sofa"]) << "instances, not parts";
  EXPECT_EQ(stats.categories.count("wall"), 0u) << "the shell is not furniture";
  stats.write((dir.path() / "stats").string());
  for (const char* f : {"rooms_per_layout.csv", "objects_per_layout.csv", "categories.csv",
                        "room_types.csv", "categories.png", "rooms_per_layout.png",
                        "objects_per_layout.png", "room_types.png"})
    EXPECT_TRUE(fs::exists(dir.path() / "stats" / f)) << f;
  // one horizontal bar per room type: the chart grows with the number of rows
  ImageU8 png = readPng8((dir.path() / "stats" / "room_types.png").string());
  EXPECT_EQ(png.width, 900);
  EXPECT_EQ(png.height, std::max<int>(400, 60 + 22 * static_cast<int>(stats.room_types.size())));
}

}  // namespace
}  // namespace inet
