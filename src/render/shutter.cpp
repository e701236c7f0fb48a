#include "render/shutter.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace inet {
namespace {

// Limits keep readout * row within int64 for any image height up to 2^20 rows.
constexpr TimeNs kMaxShutterNs = 100'000'000'000;  // 100 s
constexpr int kMaxRows = 1 << 20;

}  // namespace

void Shutter::validate(const std::string& where) const {
  if (exposure_ns < 0 || exposure_ns > kMaxShutterNs)
    throw InputError(where, "exposure_ns", fmt::format("{} is outside 0..1e11 ns", exposure_ns));
  if (readout_ns < 0 || readout_ns > kMaxShutterNs)
    throw InputError(where, "readout_ns", fmt::format("{} is outside 0..1e11 ns", readout_ns));
}

std::string Shutter::toString() const {
  return fmt::format("Shutter[{} exposure_ns={} readout_ns={}]", global() ? "global" : "rolling",
                     exposure_ns, readout_ns);
}

TimeNs rowStart(const Shutter& s, TimeNs frame_t_ns, int row, int height) {
  INET_CHECK_MSG(row >= 0 && row < height && height <= kMaxRows,
                 fmt::format("row {} of height {}", row, height));
  INET_CHECK(s.readout_ns >= 0 && s.readout_ns <= kMaxShutterNs);
  if (height == 1) return frame_t_ns;
  // readout * row / (height - 1), rounded to nearest in exact integer arithmetic
  const TimeNs den = height - 1;
  return frame_t_ns + (2 * s.readout_ns * row + den) / (2 * den);
}

TimeNs sampleTime(const Shutter& s, TimeNs frame_t_ns, int row, int height, float u) {
  INET_CHECK(s.exposure_ns >= 0 && s.exposure_ns <= kMaxShutterNs);
  return rowStart(s, frame_t_ns, row, height) +
         std::llround(static_cast<double>(u) * static_cast<double>(s.exposure_ns));
}

TimeNs groundTruthTime(const Shutter& s, TimeNs frame_t_ns, int row, int height) {
  return rowStart(s, frame_t_ns, row, height) + s.exposure_ns / 2;
}

TimeNs frameCentreTime(const Shutter& s, TimeNs frame_t_ns) {
  return frame_t_ns + (s.readout_ns + s.exposure_ns) / 2;
}

}  // namespace inet
