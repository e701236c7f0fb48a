#pragma once
// The passes (channels) a frame can carry, as one table: per pass its command-line name, pixel
// layout, who makes it, whether it is exact, the Frame member that holds it and what it is
// derived from. Everything else about passes is read from this table: the masks, passName and
// parsePassList here, the writer's shape checks and member lookups (dataset/), and what the
// sensor stage must have rendered for a derived pass (pipeline/sensor_outputs.h).
//
// Adding a pass: one enumerator (the next bit), one Frame member, one row below (in bit order;
// static_asserts check it), its encoder in a format writer, and, for a derived pass, its
// computation in the sensor stage.
#include <array>
#include <bit>
#include <cstdint>
#include <string>

#include "render/frame.h"

namespace inet {

/// One frame channel. The bit of the pass in row i of kPassTable is 1 << i.
enum class Pass : uint32_t {
  Rgb = 1u << 0,
  DepthZ = 1u << 1,
  DepthRay = 1u << 2,
  Normal = 1u << 3,
  Label = 1u << 4,
  Instance = 1u << 5,
  Albedo = 1u << 6,
  Shading = 1u << 7,
  DepthNoisy = 1u << 8,
  Flow = 1u << 9,
  FlowBackward = 1u << 10,
};

constexpr PassMask bit(Pass p) {
  return static_cast<PassMask>(p);
}
/// The set of the given passes.
template <typename... P>
constexpr PassMask passMask(P... p) {
  return (PassMask{0} | ... | bit(p));
}
constexpr bool has(PassMask m, Pass p) {
  return (m & bit(p)) != 0;
}

/// How one pixel of a pass is stored in its Frame member.
enum class PixelType {
  Float,  ///< ImageF, `channels` floats
  U8,     ///< ImageU8, one byte
  U16,    ///< ImageU16, one 16-bit value
  Flow,   ///< FlowField: flow (2 floats), valid and occluded masks (1 byte each)
};

/// Who makes a pass.
enum class PassSource {
  PathTracer,   ///< the renderer's path tracer (Monte Carlo: noisy, filtered)
  CentreRay,    ///< the renderer's ray through the pixel centre (exact, never filtered)
  SensorStage,  ///< derived after rendering by the sensor stage (pipeline/sensor_outputs.h)
                ///< from the passes in PassInfo::needs
};

/// Which neighbouring frame a pass needs: a frame without it has no such pass.
enum class Neighbour { None, Next, Previous };

/// Where a pass lives in Frame: exactly the member of its pixel type is set.
struct FrameMember {
  ImageF Frame::*f = nullptr;
  ImageU8 Frame::*u8 = nullptr;
  ImageU16 Frame::*u16 = nullptr;
  FlowField Frame::*flow = nullptr;
};

/// Which camera a derived pass can be made for.
enum PassLimit : uint32_t {
  kAnyCamera = 0,
  kPinholeOnly = 1u << 0,        ///< --lens pinhole
  kGlobalShutterOnly = 1u << 1,  ///< no rolling shutter (--readout-ms 0)
};

struct PassInfo {
  Pass pass;
  const char* name;  ///< command-line name (--passes), also in meta.json and encoder keys
  int channels;      ///< per pixel (Flow: of the flow image)
  PixelType pixel;
  PassSource source;
  bool exact;  ///< ground truth (one value per pixel, never filtered or noisy)
  FrameMember member;
  /// What it is made from besides the scene: for a SensorStage pass the passes the renderer
  /// must make (DepthZ there means the lens's depth: DepthRay for a lens without z-depth,
  /// see lensDepthPasses); for Shading the path tracer's inputs.
  PassMask needs;
  Neighbour neighbour;
  uint32_t limits;  ///< PassLimit bits
  const char* description;
};

// clang-format off
inline constexpr PassInfo kPassTable[] = {
    {Pass::Rgb, "rgb", 3, PixelType::Float, PassSource::PathTracer, false, {.f = &Frame::rgb},
     0, Neighbour::None, kAnyCamera,
     "linear RGB radiance, path traced"},
    {Pass::DepthZ, "depth", 1, PixelType::Float, PassSource::CentreRay, true,
     {.f = &Frame::depth_z}, 0, Neighbour::None, kAnyCamera,
     "z-depth along the optical axis, metres, 0 = no surface"},
    {Pass::DepthRay, "ray_depth", 1, PixelType::Float, PassSource::CentreRay, true,
     {.f = &Frame::depth_ray}, 0, Neighbour::None, kAnyCamera,
     "Euclidean distance camera centre -> surface (the paper's depth), metres"},
    {Pass::Normal, "normal", 3, PixelType::Float, PassSource::CentreRay, true,
     {.f = &Frame::normal}, 0, Neighbour::None, kAnyCamera,
     "unit surface normal in the camera frame, facing the camera"},
    {Pass::Label, "label", 1, PixelType::U8, PassSource::CentreRay, true,
     {.u8 = &Frame::label}, 0, Neighbour::None, kAnyCamera,
     "NYU40 class id, 0 = void"},
    {Pass::Instance, "instance", 1, PixelType::U16, PassSource::CentreRay, true,
     {.u16 = &Frame::instance}, 0, Neighbour::None, kAnyCamera,
     "instance id, 0 = none"},
    {Pass::Albedo, "albedo", 3, PixelType::Float, PassSource::CentreRay, true,
     {.f = &Frame::albedo}, 0, Neighbour::None, kAnyCamera,
     "linear diffuse reflectance (\"pure texture\")"},
    {Pass::Shading, "shading", 3, PixelType::Float, PassSource::PathTracer, false,
     {.f = &Frame::shading}, passMask(Pass::Rgb, Pass::Albedo), Neighbour::None, kAnyCamera,
     "illumination only: rgb / albedo per channel (the paper's shading RGB variation)"},
    {Pass::DepthNoisy, "depth_noisy", 1, PixelType::Float, PassSource::SensorStage, false,
     {.f = &Frame::depth_noisy}, passMask(Pass::DepthZ, Pass::Normal), Neighbour::None,
     kPinholeOnly,
     "Kinect-like z-depth (sensors/depth_noise.h), metres, 0 = no return"},
    {Pass::Flow, "flow", 2, PixelType::Flow, PassSource::SensorStage, true,
     {.flow = &Frame::flow}, passMask(Pass::DepthZ, Pass::Instance), Neighbour::Next,
     kGlobalShutterOnly,
     "forward optical flow to the next frame, pixels (sensors/optical_flow.h)"},
    {Pass::FlowBackward, "flow_bwd", 2, PixelType::Flow, PassSource::SensorStage, true,
     {.flow = &Frame::flow_bwd}, passMask(Pass::DepthZ, Pass::Instance), Neighbour::Previous,
     kGlobalShutterOnly,
     "backward optical flow to the previous frame, pixels"},
};
// clang-format on

inline constexpr size_t kPassCount = std::size(kPassTable);

namespace detail {
constexpr bool passTableConsistent() {
  for (size_t i = 0; i < kPassCount; ++i) {
    const PassInfo& p = kPassTable[i];
    if (bit(p.pass) != PassMask{1} << i) return false;  // row i holds bit i
    const int set = (p.member.f != nullptr) + (p.member.u8 != nullptr) +
                    (p.member.u16 != nullptr) + (p.member.flow != nullptr);
    const bool right = (p.pixel == PixelType::Float && p.member.f) ||
                       (p.pixel == PixelType::U8 && p.member.u8) ||
                       (p.pixel == PixelType::U16 && p.member.u16) ||
                       (p.pixel == PixelType::Flow && p.member.flow);
    if (set != 1 || !right) return false;
    if (p.source == PassSource::CentreRay && !p.exact) return false;
    if (p.needs & ~((PassMask{1} << kPassCount) - 1)) return false;
  }
  return true;
}
template <typename Pred>
constexpr PassMask passesWhere(Pred pred) {
  PassMask m = 0;
  for (const PassInfo& p : kPassTable)
    if (pred(p)) m |= bit(p.pass);
  return m;
}
}  // namespace detail
static_assert(detail::passTableConsistent(),
              "kPassTable: row i must hold the pass with bit 1 << i and the member of its pixel "
              "type; centre-ray passes are exact");

/// The row of a pass.
constexpr const PassInfo& passInfo(Pass p) {
  return kPassTable[std::countr_zero(bit(p))];
}

/// Every pass, the derived ones included.
inline constexpr PassMask kAllPasses = detail::passesWhere([](const PassInfo&) { return true; });
/// What the renderer makes: the path tracer's passes and the exact ground truth.
inline constexpr PassMask kRenderPasses =
    detail::passesWhere([](const PassInfo& p) { return p.source != PassSource::SensorStage; });
/// The exact passes of one ray through each pixel centre.
inline constexpr PassMask kGroundTruthPasses =
    detail::passesWhere([](const PassInfo& p) { return p.source == PassSource::CentreRay; });
/// Passes only a pinhole camera / a global shutter can have.
inline constexpr PassMask kPinholeOnlyPasses =
    detail::passesWhere([](const PassInfo& p) { return (p.limits & kPinholeOnly) != 0; });
inline constexpr PassMask kGlobalShutterOnlyPasses =
    detail::passesWhere([](const PassInfo& p) { return (p.limits & kGlobalShutterOnly) != 0; });

/// `passes` with z-depth read as the lens's depth: DepthZ becomes DepthRay when `z_depth` is
/// false (fisheye and panorama have no z-depth, render/lens.h groundTruthDepthKind).
constexpr PassMask lensDepthPasses(PassMask passes, bool z_depth) {
  if (z_depth || !has(passes, Pass::DepthZ)) return passes;
  return (passes & ~bit(Pass::DepthZ)) | bit(Pass::DepthRay);
}

/// What the renderer must make so that the sensor stage can derive the SensorStage passes of
/// `passes`: their `needs`, with the lens's depth (lensDepthPasses).
constexpr PassMask neededForDerived(PassMask passes, bool z_depth) {
  PassMask r = 0;
  for (const PassInfo& p : kPassTable)
    if (p.source == PassSource::SensorStage && has(passes, p.pass))
      r |= lensDepthPasses(p.needs, z_depth);
  return r;
}

// Defined in render/frame.cpp.
/// Name of a pass as used on the command line ("rgb", "depth", "ray_depth", ...).
std::string passName(Pass p);
/// Parses "rgb,depth,..." or "all" into a mask; throws InputError(where, "--passes", ...).
PassMask parsePassList(const std::string& list, const std::string& where);

/// The float image of a Float pass (a pass of another pixel type is a bug and aborts).
const ImageF& floatImage(const Frame& f, Pass p);
/// The flow field of a Flow pass (a pass of another pixel type is a bug and aborts).
const FlowField& flowField(const Frame& f, Pass p);

}  // namespace inet
