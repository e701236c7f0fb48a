#pragma once
// Procedural surface textures for furniture and rooms (issue 4): wood grain, fabric weave, tiles,
// marble, carpet, painted plaster, leather and brushed metal, as image sets a material reads with
// render/texture.h (albedo sRGB-encoded, roughness and normal maps linear, repeat wrapping).
//
// Every image tiles seamlessly: all patterns are built from periodic noise (periodic_noise.h) and
// from grids whose cell counts divide the texture, so the last column meets the first as any two
// neighbouring columns do. Features are defined in uv units, so the same (kind, colour, seed) at
// sizes 256 and 512 shows the same pattern at two resolutions.
//
// Colour: each kind builds a linear modulation m(x) around 1 (per channel); the albedo is
// s_c * mean_albedo_c * m_c(x), clamped to [0, 1] and encoded with the exact sRGB OETF, with the
// per-channel scale s_c solved so that the mean of the DECODED linear albedo equals mean_albedo
// (within 0.5% where clamping allows; a request near 1 on a patterned kind saturates).
//
// Normal maps: from a height field h in uv units (fraction of the texture width), by central
// differences with wrap-around: n = normalize(-dh/du, -dh/dv, 1) with u right and v up (OpenGL
// convention, +Y = up in the image), stored as round(255 * (n + 1) / 2).
//
// Random numbers: CounterRng(seed, RngStream::Layout, kTextureTag, kind * 256 + field, 0), one
// stream per noise field, so adding a field to one kind never changes another kind.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "core/image.h"
#include "procedural/texture_kind.h"

namespace inet {

/// The images a material needs.
struct TextureSet {
  ImageU8 albedo;     ///< 3 channels, sRGB-encoded, seamless (tiles with repeat wrapping)
  ImageU8 roughness;  ///< 1 channel, linear perceptual roughness value * 255 (or empty)
  ImageU8 normal;     ///< 3 channels, linear tangent-space normal map, OpenGL +Y (or empty)
};

/// Typical (mean) perceptual roughness of a kind's roughness map; 1 for None (no map).
/// Wood 0.5, fabric 0.85, tiles 0.2 (glossy tiles, rough grout), marble 0.2, carpet 0.95,
/// plaster 0.7, leather 0.5, metal 0.3.
float typicalRoughness(TextureKind kind);

/// A seamless texture of `kind` whose albedo's mean LINEAR colour is `mean_albedo` (within ~2%),
/// `size` x `size` texels, deterministic in `seed`. Looks:
///  - Wood: 4 planks along u, each of 2 boards, with ring grain (dark late-wood lines) distorted
///    by noise, fine fibres; faint grain relief and thin recessed plank seams.
///  - Fabric: plain weave of 64 x 64 threads (4 texels each at size 256) with per-thread tone.
///  - Tiles: 4 x 4 square tiles with darker recessed grout, per-tile colour variation.
///  - Marble: light cloudy base with turbulence-distorted veins; no normal map (polished).
///  - Carpet: soft high-frequency fibre noise with tuft mottling.
///  - Plaster: painted wall, subtle low-contrast noise and faint roller bumps.
///  - Leather: cellular grain (raised cells, darker creases).
///  - Metal: brushed streaks along u.
///  - None: a uniform albedo (the nearest sRGB code; mean within 8-bit quantisation), no maps.
/// Errors: InputError for a size that is not a power of two in [64, 1024] or a mean_albedo
/// component outside [0, 1] (or NaN).
TextureSet makeTexture(TextureKind kind, const Eigen::Vector3f& mean_albedo, uint64_t seed,
                       int size = 256);

/// Writes the set as <stem>_albedo.png, <stem>_roughness.png, <stem>_normal.png into `dir`
/// (created if missing; each file atomic, deterministic bytes), returning the three paths in that
/// order ("" for an empty image, which writes nothing).
std::array<std::string, 3> writeTexture(const TextureSet& t, const std::filesystem::path& dir,
                                        const std::string& stem);

}  // namespace inet
