// Furniture library (issue 4): every category over many seeds, checked against the model-frame
// convention, hull coverage, the paper's physics ranges, NYU40 labels, materials and a few
// real-world dimension ranges.
#include "procedural/furniture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.h"
#include "scene/nyu40.h"
#include "scene/primitives.h"

namespace inet {
namespace {

constexpr int kSeeds = 50;
constexpr double kMm = 1e-3;

CounterRng rngFor(uint32_t item, uint32_t seed) {
  return CounterRng(0x5eedull + seed, RngStream::Layout, 0xF0, item, seed);
}

/// All categories x kSeeds models, built once.
const std::map<std::string, std::vector<FurnitureModel>>& allModels() {
  static const auto models = [] {
    std::map<std::string, std::vector<FurnitureModel>> m;
    const auto& cats = furnitureCategories();
    for (uint32_t c = 0; c < cats.size(); ++c)
      for (uint32_t s = 0; s < kSeeds; ++s) {
        CounterRng rng = rngFor(c, s);
        m[cats[c]].push_back(makeFurniture(cats[c], rng, "test"));
      }
    return m;
  }();
  return models;
}

/// Extreme points of a part's unit primitive in the model frame (the cylinder and sphere by
/// their bounding cube, which contains them).
std::vector<Vec3> corners(const FurniturePart& p) {
  std::vector<Vec3> out;
  const double hz = p.primitive == "quad" ? 0.0 : 0.5;
  for (int i = 0; i < 8; ++i) {
    const Vec3 c((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? hz : -hz);
    out.push_back((p.T_model_part * c.homogeneous()).head<3>());
  }
  return out;
}

Eigen::AlignedBox3d bounds(const FurniturePart& p) {
  Eigen::AlignedBox3d b;
  for (const auto& c : corners(p)) b.extend(c);
  return b;
}

/// Bounds of the first part whose name starts with `prefix` (all of them merged).
Eigen::AlignedBox3d partBox(const FurnitureModel& m, const std::string& prefix) {
  Eigen::AlignedBox3d b;
  for (const auto& p : m.parts)
    if (p.name.rfind(prefix, 0) == 0) b.extend(bounds(p));
  EXPECT_FALSE(b.isEmpty()) << m.category << " has no part " << prefix;
  return b;
}

/// Strictly inside the closed solid of a part (quads have no inside).
bool insidePart(const FurniturePart& p, const Vec3& x) {
  const Vec3 l = (p.T_model_part.inverse() * x.homogeneous()).head<3>();
  if (p.primitive == "box") return l.cwiseAbs().maxCoeff() < 0.5;
  if (p.primitive == "cylinder") return l.head<2>().norm() < 0.5 && std::abs(l.z()) < 0.5;
  if (p.primitive == "sphere") return l.norm() < 0.5;
  return false;
}

bool axisAligned(const FurniturePart& p) {
  const Mat3 L = p.T_model_part.block<3, 3>(0, 0);
  for (int c = 0; c < 3; ++c) {
    int nonzero = 0;
    for (int r = 0; r < 3; ++r) nonzero += std::abs(L(r, c)) > 1e-9;
    if (nonzero != 1) return false;
  }
  return true;
}

std::string where(const FurnitureModel& m, int seed) {
  return m.category + " seed " + std::to_string(seed);
}

TEST(Furniture, AtLeastFortyUniqueCategories) {
  const auto& cats = furnitureCategories();
  EXPECT_GE(cats.size(), 40u);
  EXPECT_EQ(std::set<std::string>(cats.begin(), cats.end()).size(), cats.size());
}

TEST(Furniture, EveryCategoryBuildsWithNamedValidParts) {
  const auto& prims = primitiveNames();
  for (const auto& [cat, models] : allModels())
    for (int s = 0; s < kSeeds; ++s) {
      const FurnitureModel& m = models[s];
      EXPECT_EQ(m.category, cat);
      ASSERT_FALSE(m.parts.empty()) << where(m, s);
      std::set<std::string> names;
      for (const auto& p : m.parts) {
        EXPECT_TRUE(names.insert(p.name).second) << where(m, s) << " repeats part " << p.name;
        EXPECT_NE(std::find(prims.begin(), prims.end(), p.primitive), prims.end()) << p.primitive;
        EXPECT_GE(p.material, 0);
        EXPECT_LT(p.material, static_cast<int>(m.materials.size()));
        EXPECT_TRUE(p.T_model_part.allFinite());
        EXPECT_GE(p.nyu40, 0);
        EXPECT_LE(p.nyu40, 40);
      }
    }
}

TEST(Furniture, PartsLieInsideSizeAndSizeIsTheirUnion) {
  for (const auto& [cat, models] : allModels())
    for (int s = 0; s < kSeeds; ++s) {
      const FurnitureModel& m = models[s];
      const Vec3 lo(-m.size.x() / 2, -m.size.y() / 2, 0),
          hi(m.size.x() / 2, m.size.y() / 2, m.size.z());
      Eigen::AlignedBox3d all;
      for (const auto& p : m.parts)
        for (const Vec3& c : corners(p)) {
          all.extend(c);
          EXPECT_TRUE((c.array() >= lo.array() - kMm).all() &&
                      (c.array() <= hi.array() + kMm).all())
              << where(m, s) << " part " << p.name << " corner " << c.transpose();
        }
      EXPECT_LT((all.min() - lo).cwiseAbs().maxCoeff(), kMm) << where(m, s);
      EXPECT_LT((all.max() - hi).cwiseAbs().maxCoeff(), kMm) << where(m, s);
      EXPECT_GT(m.size.minCoeff(), 0.0) << where(m, s);
    }
}

TEST(Furniture, HullsCoverEveryPart) {
  for (const auto& [cat, models] : allModels())
    for (int s = 0; s < kSeeds; ++s) {
      const FurnitureModel& m = models[s];
      ASSERT_FALSE(m.hulls.empty());
      EXPECT_LE(m.hulls.size(), m.parts.size());
      for (const auto& p : m.parts) {
        const Eigen::AlignedBox3d b = bounds(p);
        const bool covered = std::any_of(m.hulls.begin(), m.hulls.end(), [&](const auto& h) {
          return (b.min().array() >= h.min().array() - kMm).all() &&
                 (b.max().array() <= h.max().array() + kMm).all();
        });
        EXPECT_TRUE(covered) << where(m, s) << " part " << p.name;
      }
    }
}

TEST(Furniture, PartsDoNotInterpenetrate) {
  // Axis-aligned parts: their boxes may touch but not overlap by more than a few millimetres
  // (cylinders and spheres are judged by their bounding boxes, which contain them).
  for (const auto& [cat, models] : allModels())
    for (int s = 0; s < kSeeds; ++s) {
      const FurnitureModel& m = models[s];
      for (size_t i = 0; i < m.parts.size(); ++i)
        for (size_t j = i + 1; j < m.parts.size(); ++j) {
          if (!axisAligned(m.parts[i]) || !axisAligned(m.parts[j])) continue;
          const auto x = bounds(m.parts[i]).intersection(bounds(m.parts[j]));
          if (x.isEmpty()) continue;
          EXPECT_LE(x.sizes().minCoeff(), 3 * kMm)
              << where(m, s) << ": " << m.parts[i].name << " and " << m.parts[j].name;
        }
    }
}

TEST(Furniture, PhysicsInThePapersRanges) {
  for (const auto& [cat, models] : allModels())
    for (const auto& m : models) {
      EXPECT_GE(m.mass_kg, 0.05) << cat;
      EXPECT_LE(m.mass_kg, 45.0) << cat;
      EXPECT_GE(m.friction, 0.08) << cat;
      EXPECT_LE(m.friction, 0.27) << cat;
    }
  const auto& all = allModels();
  for (const char* c : {"bed_double", "wardrobe", "kitchen_counter", "refrigerator", "toilet",
                        "bathtub", "door", "window", "ceiling_light"})
    EXPECT_FALSE(all.at(c)[0].movable) << c;
  for (const char* c : {"dining_chair", "office_chair", "mug", "books", "pillow", "table_lamp"})
    EXPECT_TRUE(all.at(c)[0].movable) << c;
  // the heavy unmovable pieces are clamped at the top of the range
  EXPECT_EQ(all.at("refrigerator")[0].mass_kg, 45.0);
  EXPECT_LT(all.at("mug")[0].mass_kg, 1.0);
}

TEST(Furniture, Nyu40ClassesMatchCategories) {
  const std::map<std::string, std::string> expected = {{"bed_double", "bed"},
                                                       {"bed_single", "bed"},
                                                       {"nightstand", "night_stand"},
                                                       {"wardrobe", "cabinet"},
                                                       {"dresser", "dresser"},
                                                       {"desk", "desk"},
                                                       {"dining_chair", "chair"},
                                                       {"office_chair", "chair"},
                                                       {"dining_table", "table"},
                                                       {"sofa", "sofa"},
                                                       {"television", "television"},
                                                       {"bookshelf", "bookshelf"},
                                                       {"wall_shelf", "shelves"},
                                                       {"kitchen_counter", "counter"},
                                                       {"refrigerator", "refrigerator"},
                                                       {"toilet", "toilet"},
                                                       {"bathtub", "bathtub"},
                                                       {"bathroom_basin", "sink"},
                                                       {"mirror", "mirror"},
                                                       {"towel", "towel"},
                                                       {"floor_lamp", "lamp"},
                                                       {"ceiling_light", "lamp"},
                                                       {"rug", "floor_mat"},
                                                       {"curtain", "curtain"},
                                                       {"blinds", "blinds"},
                                                       {"picture", "picture"},
                                                       {"books", "books"},
                                                       {"box", "box"},
                                                       {"pillow", "pillow"},
                                                       {"clothes", "clothes"},
                                                       {"bag", "bag"},
                                                       {"door", "door"},
                                                       {"window", "window"},
                                                       {"whiteboard", "whiteboard"},
                                                       {"paper", "paper"},
                                                       {"shower_curtain", "shower curtain"}};
  const auto& all = allModels();
  for (const auto& [cat, cls] : expected) {
    ASSERT_TRUE(all.count(cat)) << cat;
    EXPECT_EQ(all.at(cat)[0].nyu40, *nyu40FromName(cls)) << cat;
  }
  std::set<int> covered;
  for (const auto& [cat, models] : all)
    for (const auto& m : models) {
      EXPECT_GE(m.nyu40, 1);
      EXPECT_LE(m.nyu40, 40);
      EXPECT_EQ(m.nyu40, models[0].nyu40) << cat << ": one class per category";
      covered.insert(m.nyu40);
      for (const auto& p : m.parts)
        if (p.nyu40 > 0) covered.insert(p.nyu40);
    }
  // every object class of NYU40 (all but wall, floor, ceiling and person) has a model
  for (int id = 3; id <= 40; ++id)
    if (id != 22 && id != 31) {
      EXPECT_TRUE(covered.count(id)) << nyu40Name(id);
    }
  // a kitchen sink counter is a counter whose basin is labelled sink
  const auto& sink = all.at("kitchen_sink_counter")[0];
  EXPECT_TRUE(std::any_of(sink.parts.begin(), sink.parts.end(),
                          [](const auto& p) { return p.nyu40 == *nyu40FromName("sink"); }));
}

TEST(Furniture, SameRngStateGivesTheSameModel) {
  const auto& cats = furnitureCategories();
  for (uint32_t c = 0; c < cats.size(); ++c) {
    CounterRng r1 = rngFor(c, 7), r2 = rngFor(c, 7);
    const FurnitureModel a = makeFurniture(cats[c], r1), b = makeFurniture(cats[c], r2);
    ASSERT_EQ(a.parts.size(), b.parts.size()) << cats[c];
    for (size_t i = 0; i < a.parts.size(); ++i) {
      EXPECT_EQ(a.parts[i].name, b.parts[i].name);
      EXPECT_EQ(a.parts[i].T_model_part, b.parts[i].T_model_part) << cats[c];
      EXPECT_EQ(a.parts[i].material, b.parts[i].material);
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i)
      EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.size, b.size);
    EXPECT_EQ(a.mass_kg, b.mass_kg);
    EXPECT_EQ(a.friction, b.friction);
    EXPECT_EQ(a.hulls.size(), b.hulls.size());
    EXPECT_EQ(a.light.has_value(), b.light.has_value());
    EXPECT_EQ(a.toString(), b.toString());
  }
  // and different seeds give different pieces
  const auto& sofas = allModels().at("sofa");
  EXPECT_NE(sofas[0].size, sofas[1].size);
}

TEST(Furniture, KeyDimensionsInRealWorldRanges) {
  const auto& all = allModels();
  auto in = [](double v, double lo, double hi) { return v >= lo - kMm && v <= hi + kMm; };
  for (int s = 0; s < kSeeds; ++s) {
    const auto mattress = partBox(all.at("bed_double")[s], "mattress");
    EXPECT_TRUE(in(mattress.sizes().x(), 1.4, 1.8)) << mattress.sizes().x();
    EXPECT_TRUE(in(mattress.sizes().y(), 1.9, 2.1)) << mattress.sizes().y();
    EXPECT_TRUE(in(mattress.max().z(), 0.45, 0.6)) << mattress.max().z();
    EXPECT_TRUE(in(all.at("bed_double")[s].size.x(), 1.4, 1.9));
    EXPECT_TRUE(in(partBox(all.at("bed_single")[s], "mattress").sizes().x(), 0.8, 1.0));
    EXPECT_TRUE(in(partBox(all.at("dining_chair")[s], "seat").max().z(), 0.43, 0.48));
    EXPECT_TRUE(in(partBox(all.at("office_chair")[s], "seat").max().z(), 0.42, 0.52));
    const FurnitureModel& desk = all.at("desk")[s];
    EXPECT_TRUE(in(partBox(desk, "top").max().z(), 0.72, 0.76));
    EXPECT_TRUE(in(desk.size.x(), 1.0, 1.6) && in(desk.size.y(), 0.6, 0.8)) << desk.toString();
    const auto leaf = partBox(all.at("door")[s], "leaf");
    EXPECT_TRUE(in(leaf.sizes().x(), 0.8, 0.9)) << leaf.sizes().x();
    EXPECT_TRUE(in(leaf.max().z(), 2.0, 2.1)) << leaf.max().z();
    const FurnitureModel& sofa = all.at("sofa")[s];
    EXPECT_TRUE(in(sofa.size.x(), 1.6, 2.4) && in(sofa.size.y(), 0.8, 1.0) &&
                in(sofa.size.z(), 0.75, 0.9))
        << sofa.toString();
    const FurnitureModel& fridge = all.at("refrigerator")[s];
    EXPECT_TRUE(in(fridge.size.x(), 0.55, 0.7) && in(fridge.size.z(), 1.7, 2.0));
    EXPECT_TRUE(in(partBox(all.at("kitchen_counter")[s], "countertop").max().z(), 0.88, 0.92));
    EXPECT_TRUE(in(partBox(all.at("dining_table")[s], "top").max().z(), 0.73, 0.77));
  }
}

TEST(Furniture, FrontFacesMinusY) {
  const auto& all = allModels();
  for (int s = 0; s < kSeeds; ++s) {
    EXPECT_GT(partBox(all.at("sofa")[s], "back").center().y(), 0.0);
    EXPECT_GT(partBox(all.at("dining_chair")[s], "backrest").center().y(), 0.0);
    EXPECT_GT(partBox(all.at("office_chair")[s], "back").center().y(), 0.0);
    EXPECT_GT(partBox(all.at("bed_double")[s], "headboard").center().y(), 0.0);
    const FurnitureModel& tv = all.at("television")[s];
    EXPECT_LT(partBox(tv, "screen").center().y(), partBox(tv, "panel").center().y());
  }
}

TEST(Furniture, LampsEmitLightFromOutsideTheirParts) {
  const int lamp = *nyu40FromName("lamp");
  for (const auto& [cat, models] : allModels())
    for (int s = 0; s < kSeeds; ++s) {
      const FurnitureModel& m = models[s];
      const bool emissive = std::any_of(m.parts.begin(), m.parts.end(), [&](const auto& p) {
        return m.materials[p.material].emission.maxCoeff() > 0.f;
      });
      if (m.nyu40 == lamp) {
        EXPECT_TRUE(m.light || emissive) << where(m, s);
      }
      if (!m.light) continue;
      EXPECT_EQ(m.nyu40, lamp) << where(m, s);
      const LightSpec& l = *m.light;
      EXPECT_GT(l.intensity_w_sr, 0.f);
      EXPECT_NEAR(l.direction.norm(), 1.0, 1e-9);
      EXPECT_TRUE(l.temperature_k >= 1000.f && l.temperature_k <= 40000.f);
      if (l.type == LightType::Spot) {
        EXPECT_TRUE(l.cone_deg > 0.f && l.cone_deg < 90.f);
      }
      EXPECT_TRUE(
          (l.position.array() >= Vec3(-m.size.x() / 2, -m.size.y() / 2, 0).array()).all() &&
          (l.position.array() <= Vec3(m.size.x() / 2, m.size.y() / 2, m.size.z()).array()).all())
          << where(m, s);
      for (const auto& p : m.parts)
        EXPECT_FALSE(insidePart(p, l.position)) << where(m, s) << ": light inside " << p.name;
    }
  // ceiling emitters shine downwards (quads emit along their normal)
  for (const auto& m : allModels().at("ceiling_light"))
    for (const auto& p : m.parts)
      if (p.primitive == "quad" && m.materials[p.material].emission.maxCoeff() > 0.f) {
        EXPECT_LT((p.T_model_part.block<3, 3>(0, 0) * Vec3::UnitZ()).z(), 0.0) << p.name;
      }
  for (const char* c : {"floor_lamp", "table_lamp", "pendant_light"})
    EXPECT_TRUE(allModels().at(c)[0].light) << c;
}

TEST(Furniture, MaterialsAreValidAndNamesIdentifySpecs) {
  std::map<std::string, MaterialSpec> by_name;
  std::set<MaterialType> types;
  std::set<TextureKind> textures;
  for (const auto& [cat, models] : allModels()) {
    std::set<std::string> variants;
    for (const auto& m : models) {
      std::string set;
      for (const auto& mat : m.materials) {
        set += mat.name + ",";
        types.insert(mat.type);
        textures.insert(mat.texture);
        EXPECT_FALSE(mat.name.empty());
        EXPECT_TRUE(mat.albedo.minCoeff() >= 0.f && mat.albedo.maxCoeff() <= 1.f) << mat.name;
        EXPECT_TRUE(mat.transmittance.minCoeff() >= 0.f && mat.transmittance.maxCoeff() <= 1.f);
        EXPECT_TRUE(mat.roughness >= 0.f && mat.roughness <= 1.f) << mat.name;
        EXPECT_TRUE(mat.ior >= 1.f && mat.ior <= 4.f);
        EXPECT_GE(mat.emission.minCoeff(), 0.f);
        EXPECT_GT(mat.texture_scale_m, 0.f);
        if (mat.type == MaterialType::Translucent) {
          EXPECT_LE((mat.albedo + mat.transmittance).maxCoeff(), 1.f) << mat.name;
        }
        if (mat.type == MaterialType::Conductor) {
          EXPECT_NE(std::find(metalNames().begin(), metalNames().end(), mat.metal),
                    metalNames().end())
              << mat.name;
        }
        auto [it, fresh] = by_name.emplace(mat.name, mat);
        if (!fresh) {  // equal names, equal specs
          const MaterialSpec& o = it->second;
          EXPECT_TRUE(o.type == mat.type && o.albedo == mat.albedo &&
                      o.roughness == mat.roughness && o.metal == mat.metal &&
                      o.transmittance == mat.transmittance && o.emission == mat.emission &&
                      o.texture == mat.texture && o.texture_scale_m == mat.texture_scale_m)
              << mat.name;
        }
      }
      std::set<std::string> names;
      for (const auto& mat : m.materials) EXPECT_TRUE(names.insert(mat.name).second) << mat.name;
      variants.insert(set);
    }
    if (cat != "paper") {
      EXPECT_GE(variants.size(), 3u) << cat << ": material variants";
    }
  }
  EXPECT_EQ(types.size(), 6u) << "all material families in use";
  for (TextureKind k :
       {TextureKind::Wood, TextureKind::Fabric, TextureKind::Tiles, TextureKind::Marble,
        TextureKind::Carpet, TextureKind::Plaster, TextureKind::Leather, TextureKind::Metal})
    EXPECT_TRUE(textures.count(k)) << textureKindName(k);
}

TEST(Furniture, PlacementMountAndSupportsAreConsistent) {
  using P = FurnitureModel::Placement;
  for (const auto& [cat, models] : allModels())
    for (const auto& m : models) {
      if (m.placement == P::Wall) {
        EXPECT_GT(m.mount_height, 0.0) << cat;
      }
      if (m.placement == P::Floor || m.placement == P::OnSurface || m.placement == P::Ceiling) {
        EXPECT_EQ(m.mount_height, 0.0) << cat;
      }
      EXPECT_EQ(m.is_support, !m.support_heights.empty()) << cat;
      EXPECT_TRUE(std::is_sorted(m.support_heights.begin(), m.support_heights.end())) << cat;
      for (double h : m.support_heights) {
        EXPECT_GT(h, 0.0) << cat;
        EXPECT_LE(h, m.size.z() + kMm) << cat;
      }
    }
  const auto& all = allModels();
  for (const char* c : {"desk", "dining_table", "coffee_table", "side_table", "nightstand",
                        "kitchen_counter", "bookshelf", "tv_stand", "dresser", "wall_shelf"})
    EXPECT_TRUE(all.at(c)[0].is_support) << c;
  EXPECT_EQ(all.at("ceiling_light")[0].placement, P::Ceiling);
  EXPECT_EQ(all.at("door")[0].placement, P::InWall);
  EXPECT_EQ(all.at("door")[0].mount_height, 0.0);
  EXPECT_GT(all.at("window")[0].mount_height, 0.5);
  EXPECT_EQ(all.at("picture")[0].placement, P::Wall);
  // the desk's top surface is a support height
  const FurnitureModel& desk = all.at("desk")[0];
  EXPECT_NEAR(desk.support_heights.back(), partBox(desk, "top").max().z(), 1e-9);
}

TEST(Furniture, SizeHintFixesNominalDimensions) {
  CounterRng rng = rngFor(1, 1);
  FurnitureSizeHint hint;
  hint.width = 1.234;
  hint.height = 2.0;
  const FurnitureModel w = makeFurnitureSized("wardrobe", hint, rng);
  EXPECT_NEAR(w.size.x(), 1.234, 1e-9);
  EXPECT_NEAR(w.size.z(), 2.0, 1e-9);
  FurnitureSizeHint opening;  // doors and windows fill the wall opening, frame included
  opening.width = 0.95;
  opening.height = 2.15;
  const FurnitureModel d = makeFurnitureSized("door", opening, rng);
  EXPECT_NEAR(d.size.x(), 0.95, 1e-9);
  EXPECT_NEAR(d.size.z(), 2.15, 1e-9);

  FurnitureSizeHint bad;
  bad.width = 0.3;
  try {
    makeFurnitureSized("mug", bad, rng, "plan.json");
    FAIL() << "a mug has no adjustable width";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "size_hint.width");
    EXPECT_NE(std::string(e.what()).find("mug"), std::string::npos);
  }
  bad.width = -1.0;
  EXPECT_THROW(makeFurnitureSized("wardrobe", bad, rng), InputError);
}

TEST(Furniture, UnknownCategoryIsAnInputErrorListingTheValidNames) {
  CounterRng rng = rngFor(0, 0);
  try {
    makeFurniture("hovercraft", rng, "layout.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "layout.json");
    EXPECT_EQ(e.field(), "category");
    const std::string msg = e.what();
    EXPECT_NE(msg.find("hovercraft"), std::string::npos) << msg;
    EXPECT_NE(msg.find("sofa"), std::string::npos) << msg;
    EXPECT_NE(msg.find("bed_double"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace inet
