#include "scene/nyu40.h"

#include <array>
#include <cctype>
#include <cmath>

namespace inet {
namespace {
// Order and spelling follow the NYU40 list in ../shared/data/labels (BlenderProc's nyu_idset.csv).
constexpr std::array<std::string_view, kNyu40Count> kNames = {
    "void",       "wall",    "floor",       "cabinet",        "bed",
    "chair",      "sofa",    "table",       "door",           "window",
    "bookshelf",  "picture", "counter",     "blinds",         "desk",
    "shelves",    "curtain", "dresser",     "pillow",         "mirror",
    "floor_mat",  "clothes", "ceiling",     "books",          "refridgerator",
    "television", "paper",   "towel",       "shower_curtain", "box",
    "whiteboard", "person",  "night_stand", "toilet",         "sink",
    "lamp",       "bathtub", "bag",         "otherstructure", "otherfurniture",
    "otherprop"};

std::string normalise(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == ' ' || c == '_' || c == '-') continue;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}
}  // namespace

std::string_view nyu40Name(int id) {
  if (id < 0 || id >= kNyu40Count) return {};
  return kNames[id];
}

std::optional<int> nyu40FromName(std::string_view name) {
  std::string key = normalise(name);
  if (key == "refrigerator" || key == "fridge") return 24;
  if (key == "tv") return 25;
  if (key == "unlabelled" || key == "unlabeled") return 0;
  for (int i = 0; i < kNyu40Count; ++i) {
    if (normalise(kNames[i]) == key) return i;
  }
  return std::nullopt;
}

void nyu40Color(int id, unsigned char rgb[3]) {
  if (id <= 0) {
    rgb[0] = rgb[1] = rgb[2] = 0;
    return;
  }
  // golden-ratio hue walk: neighbouring ids get well separated colours
  double h = std::fmod(id * 0.618033988749895, 1.0) * 6.0;
  double s = 0.65 + 0.35 * ((id * 7) % 3) / 2.0, v = 0.95 - 0.25 * ((id * 5) % 2);
  int sector = static_cast<int>(h);
  double f = h - sector, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = 0, g = 0, b = 0;
  switch (sector % 6) {
    case 0:
      r = v;
      g = t;
      b = p;
      break;
    case 1:
      r = q;
      g = v;
      b = p;
      break;
    case 2:
      r = p;
      g = v;
      b = t;
      break;
    case 3:
      r = p;
      g = q;
      b = v;
      break;
    case 4:
      r = t;
      g = p;
      b = v;
      break;
    default:
      r = v;
      g = p;
      b = q;
      break;
  }
  rgb[0] = static_cast<unsigned char>(r * 255 + 0.5);
  rgb[1] = static_cast<unsigned char>(g * 255 + 0.5);
  rgb[2] = static_cast<unsigned char>(b * 255 + 0.5);
}

}  // namespace inet
