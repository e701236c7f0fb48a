#pragma once
// The kinds of procedural surface texture (issue 4): shared by the furniture library, which tags
// each part with the texture it should wear, and procedural_textures.h, which synthesises them.
namespace inet {

/// Which procedural texture a surface wears; None = plain colour.
enum class TextureKind { None, Wood, Fabric, Tiles, Marble, Carpet, Plaster, Leather, Metal };

/// Lower-case name of a kind ("none", "wood", ...), as used in file names and scene files.
inline const char* textureKindName(TextureKind kind) {
  switch (kind) {
    case TextureKind::None:
      return "none";
    case TextureKind::Wood:
      return "wood";
    case TextureKind::Fabric:
      return "fabric";
    case TextureKind::Tiles:
      return "tiles";
    case TextureKind::Marble:
      return "marble";
    case TextureKind::Carpet:
      return "carpet";
    case TextureKind::Plaster:
      return "plaster";
    case TextureKind::Leather:
      return "leather";
    case TextureKind::Metal:
      return "metal";
  }
  return "unknown";
}

}  // namespace inet
