// light.xml: every light type and area lights round-trip exactly; a setup switches lights and
// recolours emitters; malformed files give one-line errors naming file and attribute.
#include "scene/light_xml.h"

#include <gtest/gtest.h>

#include "core/atomic_file.h"
#include "scene/primitives.h"
#include "scene_test_util.h"

namespace inet {
namespace {

using test::TempDir;

Scene litScene() {
  Scene s;
  s.name = "lit";
  Mesh q = makePrimitive("quad", {}, "t", "q");
  q.id = "quad";
  s.meshes = {q};
  Material white, glow;
  white.id = "white";
  glow.id = "glow";
  glow.emission = Vec3f(3, 2.5f, 2);
  s.materials = {white, glow};
  Object floor = Object::make("floor", 0, 0, Mat4::Identity(), 2, 1);
  Object panel = Object::make("ceiling_light_1", 0, 1, Mat4::Identity(), 35, 2);
  panel.T_world_object(2, 3) = 2.5;
  Object panel2 = panel;
  panel2.name = "ceiling_light_2";
  panel2.instance = 3;
  s.objects = {floor, panel, panel2};
  Light point;
  point.name = "lamp_light";
  point.position = Vec3(1, 2, 1.2);
  point.intensity = 4.5f;
  point.temperature_k = 2700;
  point.max_distance = 6;
  point.radius = 0.025f;
  point.object = "floor";
  Light spot;
  spot.name = "spot";
  spot.type = LightType::Spot;
  spot.position = Vec3(0, 0, 2.4);
  spot.direction = Vec3(0, 0, -1);
  spot.cone_deg = 35;
  spot.falloff_deg = 7.5f;
  spot.color = Vec3f(1, 0.9f, 0.8f);
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Sun;
  sun.direction = Vec3(0.6, 0, -0.8);
  sun.intensity = 300;
  Light sky;
  sky.name = "sky";
  sky.type = LightType::Sky;
  sky.sky_model = SkyModel::Preetham;
  sky.direction = Vec3(0.6, 0, -0.8);
  sky.turbidity = 3.25f;
  sky.intensity = 20;
  sky.on = false;
  s.lights = {point, spot, sun, sky};
  return s;
}

TEST(LightXml, RoundTripsEveryLightAndAreaLights) {
  TempDir dir;
  Scene s = litScene();
  const std::string path = (dir.path() / "light.xml").string();
  saveLightXml(s, path);
  const LightSetup setup = loadLightXml(path);
  ASSERT_EQ(setup.lights.size(), 4u);
  Scene t = litScene();
  t.lights.clear();
  applyLightSetup(t, setup, path);
  test::expectScenesEqual(s, t);
  ASSERT_EQ(setup.areas.size(), 2u) << "one entry per emissive instance";
  EXPECT_EQ(setup.areas[0].object, "ceiling_light_1");
  EXPECT_EQ(setup.areas[0].radiance, Vec3f(3, 2.5f, 2));
  saveLightXml(t, (dir.path() / "again.xml").string());
  EXPECT_EQ(readTextFile(path), readTextFile((dir.path() / "again.xml").string()));
}

// An imported Mitsuba scene's envmap sky goes through light.xml (`vary lighting` wrote a file
// generate refused: "unknown sky model 'envmap'"): the image relative to the file's folder,
// the rotation exactly.
TEST(LightXml, EnvmapSkyRoundTripsWithItsImageAndRotation) {
  TempDir dir;
  const std::string image = dir.write("maps/sky.png", "not read here");
  Scene s = litScene();
  Light env;
  env.name = "envmap";
  env.type = LightType::Sky;
  env.sky_model = SkyModel::EnvMap;
  env.envmap = {"maps/sky.png", image};
  env.envmap_rotation = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  env.intensity = 2.5f;
  s.lights = {env};
  const std::string path = (dir.path() / "setups" / "light.xml").string();
  std::filesystem::create_directories(dir.path() / "setups");
  saveLightXml(s, path);
  EXPECT_NE(readTextFile(path).find("file=\"../maps/sky.png\""), std::string::npos)
      << readTextFile(path);
  const LightSetup setup = loadLightXml(path);
  ASSERT_EQ(setup.lights.size(), 1u);
  const Light& back = setup.lights[0];
  EXPECT_EQ(back.sky_model, SkyModel::EnvMap);
  EXPECT_TRUE(std::filesystem::equivalent(back.envmap.path, image));
  EXPECT_EQ(back.envmap_rotation, env.envmap_rotation);
  EXPECT_EQ(back.intensity, 2.5f);
  Scene t = litScene();
  applyLightSetup(t, setup, path);
  saveLightXml(t, (dir.path() / "setups" / "again.xml").string());
  EXPECT_EQ(readTextFile(path), readTextFile((dir.path() / "setups" / "again.xml").string()));
  // a missing image and a short rotation are named
  const std::string missing = dir.write(
      "setups/missing.xml",
      R"(<lights><light name="e" type="SkyLight" energy="1" model="envmap" file="nope.exr"/></lights>)");
  EXPECT_NE(test::errorOf([&] { (void)loadLightXml(missing); }).find("light[0].file: no such image"),
            std::string::npos);
  const std::string short_rot = dir.write(
      "setups/short.xml",
      R"(<lights><light name="e" type="SkyLight" energy="1" model="envmap" file="../maps/sky.png" )"
      R"(rotation="1 0 0 0 1 0 0 0"/></lights>)");
  EXPECT_NE(test::errorOf([&] { (void)loadLightXml(short_rot); }).find("light[0].rotation: expected 9"),
            std::string::npos);
}

// Names are the user's (an imported lamp's object name): quotes, ampersands, angle brackets and
// tabs were written raw, and the file did not read back.
TEST(LightXml, NamesWithXmlCharactersRoundTrip) {
  TempDir dir;
  Scene s = litScene();
  s.lights[0].name = "Lamp \"A\" & <co>\tdesk";
  s.lights[0].object = "floor";
  const std::string path = (dir.path() / "light.xml").string();
  saveLightXml(s, path);
  const LightSetup setup = loadLightXml(path);
  ASSERT_EQ(setup.lights.size(), 4u);
  EXPECT_EQ(setup.lights[0].name, "Lamp \"A\" & <co>\tdesk");
}

TEST(LightXml, SwitchesAndRecoloursOneEmitter) {
  TempDir dir;
  Scene s = litScene();
  LightSetup setup = lightSetupOf(s);
  setup.areas[1].on = false;                 // ceiling_light_2 off
  setup.areas[0].radiance = Vec3f(1, 1, 4);  // ceiling_light_1 bluish
  applyLightSetup(s, setup, "test");
  EXPECT_EQ(s.materials[s.objects[1].material].emission, Vec3f(1, 1, 4));
  EXPECT_FALSE(s.materials[s.objects[2].material].isEmissive());
  EXPECT_NE(s.objects[1].material, s.objects[2].material) << "each got its own copy";
  setup.areas.push_back({"chandelier", "", Vec3f::Ones(), true});
  EXPECT_THROW(applyLightSetup(s, setup, "test"), InputError);
}

// A lamp is several parts of one name (housing, trim, lens): only its lens glows, whether the
// light.xml names the part (as lightSetupOf writes it) or not (older files); a plain object
// named by an AreaLight glows whole; a part that does not exist is an error.
TEST(LightXml, OnlyTheGlowingPartOfALampGlows) {
  Scene s = litScene();
  Object housing = s.objects[1];
  housing.material = 0;
  housing.part = "can";
  s.objects[1].part = "lens";
  s.objects.push_back(housing);  // ceiling_light_1: lens (emissive) + can (white)
  auto glowing = [](const Scene& sc) {
    int n = 0;
    for (const Object& o : sc.objects) n += sc.materials[o.material].isEmissive();
    return n;
  };
  ASSERT_EQ(glowing(s), 2);
  LightSetup setup = lightSetupOf(s);
  ASSERT_EQ(setup.areas[0].part, "lens");
  // through the XML text and back: the part is kept
  const LightSetup reread = parseLightXml(lightXmlText(s, "mem.xml"), "mem.xml");
  EXPECT_EQ(reread.areas, setup.areas);
  Scene a = s;
  applyLightSetup(a, reread, "test");
  EXPECT_EQ(glowing(a), 2) << "the can must not glow";
  // an older file: no part, the lens dimmed
  LightSetup old = setup;
  for (AreaLightEntry& e : old.areas) e.part.clear();
  old.areas[0].radiance = Vec3f(1, 1, 1);
  Scene b = s;
  applyLightSetup(b, old, "test");
  EXPECT_EQ(glowing(b), 2);
  EXPECT_EQ(b.materials[b.objects[1].material].emission, Vec3f(1, 1, 1));
  // a plain object turned into a light glows whole
  LightSetup plain = setup;
  plain.areas.push_back({"floor", "", Vec3f(2, 2, 2), true});
  Scene c = s;
  applyLightSetup(c, plain, "test");
  EXPECT_EQ(glowing(c), 3);
  // a part that is not there
  LightSetup wrong = setup;
  wrong.areas[0].part = "bulb";
  Scene d = s;
  EXPECT_THROW(applyLightSetup(d, wrong, "test"), InputError);
}

TEST(LightXml, BrightnessScalesEnergyAndRadiance) {
  TempDir dir;
  const std::string path = dir.write(
      "b.xml",
      R"(<lights><light name="a" type="PointLight" energy="2" brightness="1.5" position="0 0 1"/>)"
      R"(<light type="AreaLight" object="lamp" radiance="1 2 3" brightness="0.5"/></lights>)");
  const LightSetup s = loadLightXml(path);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 3.f);
  ASSERT_EQ(s.areas.size(), 1u);
  EXPECT_EQ(s.areas[0].radiance, Vec3f(0.5f, 1.f, 1.5f));
}

TEST(LightXml, MalformedFilesNameFileAndAttribute) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"<lights><light", "malformed XML"},
      {"<lamps/>", "<lights>"},
      {"<lights><lamp/></lights>", "light[0]: unknown element <lamp>"},
      {R"(<lights><light name="a" type="LaserLight" energy="1"/></lights>)", "light[0].type"},
      {R"(<lights><light name="a" type="PointLight" energy="x" position="0 0 0"/></lights>)",
       "light[0].energy"},
      {R"(<lights><light name="a" type="PointLight" energy="1" position="0 0"/></lights>)",
       "light[0].position"},
      {R"(<lights><light name="a" type="PointLight" energy="1"/></lights>)",
       "light[0].position: missing attribute"},
      {R"(<lights><light type="AreaLight" object="x" radiance="1 -1 1"/></lights>)",
       "light[0].radiance"},
      {R"(<lights><light name="a" type="SunLight" energy="1" direction="0 0 -1" on="yes"/></lights>)",
       "light[0].on"},
      {R"(<lights><light name="a" type="SunLight" energy="1" direction="0 0 -1" brightness="-2"/></lights>)",
       "light[0].brightness"},
      // found by fuzz_light_xml: a colour beyond float's range was written back as inf
      {R"(<lights><light name="a" type="PointLight" energy="1" position="0 0 1" color="1 1e39 1"/></lights>)",
       "light[0].color: 1e+39 is beyond a 32-bit float's range"},
      {R"(<lights><light name="a" type="PointLight" energy="1e30" brightness="1e30" position="0 0 1"/></lights>)",
       "light[0].energy"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].first);
    const std::string path = dir.write("bad" + std::to_string(i) + ".xml", cases[i].first);
    const std::string msg = test::errorOf([&] { (void)loadLightXml(path); });
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(cases[i].second), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
  EXPECT_NE(test::errorOf([&] { (void)loadLightXml((dir.path() / "none.xml").string()); }), "");
}

}  // namespace
}  // namespace inet
