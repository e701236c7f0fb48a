// Sweet Home 3D's Home.xml (src/assets/sh3d_home.h) and the geometry made from it
// (sh3d_import.h: walls, joins, arcs, cut-outs, rooms through GEOS): arbitrary bytes either
// parse and convert or throw InputError. Furniture other than doors and windows is dropped.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "assets/sh3d_home.h"
#include "assets/sh3d_import.h"
#include "core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  inet::Sh3dHome home;
  try {
    home = inet::parseHomeXml(text, "fuzz.sh3d");
  } catch (const inet::InputError&) {
    return 0;
  }
  // keep the doors and windows (their cut-outs shape the walls, before any model is read: the
  // missing archive then ends the conversion with an InputError)
  std::vector<inet::Sh3dPiece> openings;
  for (auto& p : home.pieces)
    if (p.kind == inet::Sh3dPieceKind::DoorOrWindow) openings.push_back(p);
  home.pieces = openings;
  try {
    inet::Sh3dImportOptions opt;
    inet::sh3dToScene(home, opt);
  } catch (const inet::InputError&) {
  }
  return 0;
}
