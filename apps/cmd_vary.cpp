// interiornet vary lighting: new lighting configurations (light.xml) of a layout
// (variation/lighting.h): random within documented ranges, a time of day, or lights switched by
// name.
#include <cstdio>
#include <memory>
#include <sstream>

#include <fmt/format.h>

#include "common.h"
#include "core/error.h"
#include "dataset/sequence_writer.h"
#include "scene/light_xml.h"
#include "core/atomic_file.h"
#include "scene/layout_json.h"
#include "variation/lighting.h"
#include "variation/rearrange.h"

namespace inet::app {
namespace {

struct VaryLightingArgs {
  SceneSource scene;
  std::string mode = "random";
  std::string out;
  RandomLightingOptions random;
  SunTime when;
  std::string date = "2026-06-21", time = "12:00";
  std::string on, off;
};

std::vector<std::string> names(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  for (std::string s; std::getline(ss, s, ',');)
    if (!s.empty()) out.push_back(s);
  return out;
}

void parseDateTime(VaryLightingArgs& a) {
  char dash1 = 0, dash2 = 0, colon = 0, extra = 0;
  int minute = 0, hour = 0;
  if (std::sscanf(a.date.c_str(), "%d%c%d%c%d%c", &a.when.year, &dash1, &a.when.month, &dash2,
                  &a.when.day, &extra) != 5 ||
      dash1 != '-' || dash2 != '-')
    throw InputError("", "--date", "expected YYYY-MM-DD, got '" + a.date + "'");
  if (std::sscanf(a.time.c_str(), "%d%c%d%c", &hour, &colon, &minute, &extra) != 3 ||
      colon != ':' || minute < 0 || minute > 59)
    throw InputError("", "--time", "expected HH:MM, got '" + a.time + "'");
  a.when.hour = hour + minute / 60.0;
}

/// Switches the lights named in `on` / `off` (analytic lights by name, area lights by object).
void switchByName(LightSetup& s, const std::string& list, bool on, const std::string& flag) {
  for (const std::string& n : names(list)) {
    bool found = false;
    for (Light& l : s.lights)
      if (l.name == n || (!l.object.empty() && l.object == n)) l.on = on, found = true;
    for (AreaLightEntry& e : s.areas)
      if (e.object == n) e.on = on, found = true;
    if (!found) throw InputError("", flag, "the layout has no light or emissive object '" + n + "'");
  }
}

void runVaryLighting(VaryLightingArgs a) {
  if (a.out.empty()) throw InputError("", "--out", "give the light.xml to write");
  Scene scene = a.scene.load();
  LightSetup setup = lightSetupOf(scene);
  if (a.mode == "random") {
    setup = randomLighting(setup, a.random);
  } else if (a.mode == "time-of-day") {
    parseDateTime(a);
    setup = timeOfDayLighting(setup, a.when);
    const SunAngles sun = sunPosition(a.when);
    std::fprintf(stderr, "sun: elevation %.2f deg, azimuth %.2f deg (from north through east)\n",
                 sun.elevation * 180 / M_PI, sun.azimuth * 180 / M_PI);
  } else if (a.mode != "manual") {
    throw InputError("", "--mode", "must be random, time-of-day or manual, not '" + a.mode + "'");
  }
  switchByName(setup, a.off, false, "--off");
  switchByName(setup, a.on, true, "--on");
  checkOutputFolder(std::filesystem::path(a.out).parent_path().empty()
                        ? std::filesystem::path(".")
                        : std::filesystem::path(a.out).parent_path());
  applyLightSetup(scene, setup, a.out);
  saveLightXml(scene, a.out);
  size_t lit = 0, total = setup.lights.size() + setup.areas.size();
  for (const Light& l : setup.lights) lit += l.on;
  for (const AreaLightEntry& e : setup.areas) lit += e.on;
  std::printf("wrote %s (%zu of %zu lights on)\n", a.out.c_str(), lit, total);
}

struct VaryRearrangeArgs {
  SceneSource scene;
  RearrangeOptions opt;
  std::string out;
};

/// Texture and mesh-file paths of `s` (relative to `from`, the input layout's folder) made
/// relative to `to`, where the new layout goes, so that it keeps working there.
void relocate(Scene& s, const std::filesystem::path& from, const std::filesystem::path& to) {
  namespace fs = std::filesystem;
  auto move = [&](std::string& file) {
    if (file.empty()) return;
    const fs::path p = fs::path(file).is_absolute() ? fs::path(file) : from / file;
    file = fs::proximate(fs::absolute(p), to).generic_string();
  };
  for (Material& m : s.materials)
    for (TextureRef* t : {&m.albedo_texture, &m.roughness_texture, &m.normal_texture})
      if (!t->empty()) t->file = fs::proximate(fs::absolute(t->path), to).generic_string();
  for (Mesh& m : s.meshes)
    if (m.source.kind == MeshSource::Kind::File) move(m.source.file);
}

void runVaryRearrange(const VaryRearrangeArgs& a) {
  namespace fs = std::filesystem;
  a.opt.validate("vary rearrange");
  if (a.scene.isDefault()) throw InputError("", "--layout", "give the layout to rearrange");
  if (a.out.empty()) throw InputError("", "--out", "give the folder to write");
  const Scene scene = a.scene.load();
  checkOutputFolder(a.out);
  RearrangeLog log;
  Scene moved = rearrange(scene, a.opt, &log);
  const int lights = moveBoundLights(scene, moved);
  const fs::path dir = a.out;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(a.out, "--out", "cannot create folder: " + ec.message());
  relocate(moved, fs::absolute(fs::path(a.scene.path)).parent_path(), fs::absolute(dir));
  writeTextAtomic(dir / "rearrange_log.json", log.toJson());
  saveLightXml(moved, (dir / "light.xml").string());
  saveLayout(moved, (dir / "layout.json").string());  // last: its presence means done
  std::printf(
      "rearranged %s: pushed %d of %d movable instances (%.0f %%), %d moved, %d lights carried "
      "along; %.1f s simulated in %.0f ms; wrote %s/{layout.json, light.xml, "
      "rearrange_log.json}\n",
      scene.name.c_str(), log.selected, log.movable, 100 * log.share, log.moved, lights,
      log.sim_time_s, log.wall_ms, a.out.c_str());
  if (!log.ok())
    std::fprintf(stderr, "warning: the settled layout failed a check; see rearrange_log.json\n");
}

}  // namespace

void registerVary(CLI::App& app) {
  auto* vary = app.add_subcommand(
      "vary",
      "Scene variants of a layout: lighting configurations (light.xml) and physics-based "
      "rearrangement");
  vary->require_subcommand(1);
  auto* cmd = vary->add_subcommand(
      "lighting",
      "Write a new lighting configuration of a layout as light.xml (use it with --lights): "
      "random (each lamp on with --on-probability, brightness and colour temperature drawn in "
      "range), time-of-day (sun and daylight sky placed by date, time and latitude; lamps on "
      "after dusk) or manual (only --on/--off)");
  auto a = std::make_shared<VaryLightingArgs>();
  addSceneFlags(*cmd, a->scene);
  cmd->add_option("--mode", a->mode, "random, time-of-day or manual (default random)");
  cmd->add_option("--seed", a->random.seed, "random mode: seed (default 0)");
  cmd->add_option("--on-probability", a->random.on_probability,
                  "random mode: chance each light is on (default 0.7; one stays on)");
  cmd->add_option("--min-temperature", a->random.min_temperature_k,
                  "random mode: colour temperature range, kelvin (default 2700..6500)");
  cmd->add_option("--max-temperature", a->random.max_temperature_k, "");
  cmd->add_option("--min-brightness", a->random.min_brightness,
                  "random mode: factor on each light's energy (default 0.5..1.5)");
  cmd->add_option("--max-brightness", a->random.max_brightness, "");
  cmd->add_option("--date", a->date, "time-of-day: YYYY-MM-DD (default 2026-06-21)");
  cmd->add_option("--time", a->time, "time-of-day: local clock HH:MM (default 12:00)");
  cmd->add_option("--latitude", a->when.latitude_deg, "time-of-day: degrees north (default 51.5)");
  cmd->add_option("--longitude", a->when.longitude_deg, "time-of-day: degrees east (default 0)");
  cmd->add_option("--utc-offset", a->when.utc_offset_h,
                  "time-of-day: the clock's offset from UTC, hours (default 0)");
  cmd->add_option("--north", a->when.north_deg,
                  "time-of-day: the layout's north, degrees counter-clockwise from world +y "
                  "(default 0)");
  cmd->add_option("--on", a->on, "comma list of lights (or emissive objects) to switch on");
  cmd->add_option("--off", a->off, "comma list of lights (or emissive objects) to switch off");
  cmd->add_option("--out", a->out, "the light.xml to write")->required();
  cmd->callback([a] { runVaryLighting(*a); });

  auto* re = vary->add_subcommand(
      "rearrange",
      "Move things as daily life does (Bullet physics): push a random 5-45 % of the movable "
      "objects with a horizontal acceleration of 0.5-2 m/s^2 for 0.5 s, let everything settle "
      "(10 s at most; what rests on a pushed piece rides along or falls); writes OUT/layout.json, "
      "OUT/light.xml (lamps' lights moved with them) and OUT/rearrange_log.json");
  auto r = std::make_shared<VaryRearrangeArgs>();
  addSceneFlags(*re, r->scene);
  re->add_option("--seed", r->opt.seed, "seed (default 0)");
  re->add_option("--min-share", r->opt.min_share, "share of movable objects pushed, from (0.05)");
  re->add_option("--max-share", r->opt.max_share, "... to (0.45)");
  re->add_option("--min-accel", r->opt.min_accel, "push acceleration in m/s^2, from (0.5)");
  re->add_option("--max-accel", r->opt.max_accel, "... to (2)");
  re->add_option("--duration", r->opt.duration_s, "simulated seconds at most (default 10)");
  re->add_option("--out", r->out, "output folder")->required();
  re->callback([r] { runVaryRearrange(*r); });
}

}  // namespace inet::app
