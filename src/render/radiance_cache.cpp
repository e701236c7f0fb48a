#include "render/radiance_cache.h"

#include <algorithm>
#include <cmath>

namespace inet {
namespace {

constexpr int kFixedBits = 20;        // sums hold value x 2^20
constexpr float kMaxValue = 1.6e7f;   // a channel above this is clamped (2^44 fixed): 2^20
                                      // such records still fit in 64 bits
constexpr uint64_t kUsed = 1ull << 63;  // set in every key, so 0 marks an empty slot

uint64_t mix(uint64_t x) {  // splitmix64's finaliser
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

uint64_t fixedLuma(const uint64_t rgb[3]) {  // Rec. 709 weights in 1/1024ths
  return rgb[0] * 218 + rgb[1] * 732 + rgb[2] * 74;
}

// a > b in the order that picks a cell's brightest record (ties by channels: commutative)
bool brighter(uint64_t luma_a, const uint64_t a[3], uint64_t luma_b, const uint64_t b[3]) {
  if (luma_a != luma_b) return luma_a > luma_b;
  return std::lexicographical_compare(b, b + 3, a, a + 3);
}

void add(RadianceCache::Sums& into, const RadianceCache::Sums& s) {
  for (int c = 0; c < 3; ++c) into.rgb[c] += s.rgb[c];
  into.count += s.count;
  if (brighter(s.max_luma, s.max, into.max_luma, into.max)) {
    std::copy(s.max, s.max + 3, into.max);
    into.max_luma = s.max_luma;
  }
}

}  // namespace

RadianceCache::RadianceCache(const Config& config)
    : config_(config), inv_cell_(1.f / config.cell_m) {}

uint64_t RadianceCache::key(const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                           Kind kind) const {
  auto cell = [&](float x) {
    // 19 bits per axis: +-2^18 cells (65 km at 25 cm) around the origin
    const auto i = static_cast<int64_t>(std::floor(x * inv_cell_));
    return static_cast<uint64_t>(i + (int64_t{1} << 18)) & 0x7FFFFu;
  };
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(n[a]) > std::fabs(n[axis])) axis = a;
  const uint64_t side = static_cast<uint64_t>(axis * 2 + (n[axis] < 0.f ? 1 : 0)) +
                        (kind == Kind::Radiance ? 6u : 0u);
  return kUsed | (side << 57) | (cell(p.x()) << 38) | (cell(p.y()) << 19) | cell(p.z());
}

void RadianceCache::Recorder::record(const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                                     Kind kind, const Eigen::Vector3f& value) {
  Sums s;
  for (int c = 0; c < 3; ++c) {
    if (!(value[c] >= 0.f) || !std::isfinite(value[c])) return;
    s.rgb[c] = s.max[c] =
        static_cast<uint64_t>(std::ldexp(std::min(value[c], kMaxValue), kFixedBits) + 0.5f);
  }
  s.max_luma = fixedLuma(s.rgb);
  s.count = 1;
  add(sums_[cache_->key(p, n, kind)], s);
  ++records_;
}

void RadianceCache::merge(Recorder& recorder) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [k, s] : recorder.sums_) add(sums_[k], s);
  records_ += recorder.records_;
  recorder.sums_.clear();
  recorder.records_ = 0;
}

void RadianceCache::build() {
  size_t used = 0;
  for (const auto& [k, s] : sums_) used += s.count >= config_.min_records;
  size_t capacity = 16;
  while (capacity < 2 * used) capacity *= 2;
  keys_.assign(capacity, 0);
  means_.assign(capacity, Eigen::Vector3f::Zero());
  mask_ = capacity - 1;
  active_ = lone_ = 0;
  for (const auto& [k, s] : sums_) {
    if (s.count < config_.min_records) continue;
    // the brightest record, when it is a lone one, is left out
    uint64_t rgb[3] = {s.rgb[0], s.rgb[1], s.rgb[2]};
    uint32_t n = s.count;
    const uint64_t others[3] = {rgb[0] - s.max[0], rgb[1] - s.max[1], rgb[2] - s.max[2]};
    if (static_cast<double>(s.max_luma) * (n - 1) >
        kLoneRecordRatio * static_cast<double>(fixedLuma(others))) {
      std::copy(others, others + 3, rgb);
      --n;
      ++lone_;
    }
    Eigen::Vector3f mean;
    for (int c = 0; c < 3; ++c)
      mean[c] = static_cast<float>(std::ldexp(static_cast<double>(rgb[c]), -kFixedBits) / n);
    uint64_t slot = mix(k) & mask_;
    while (keys_[slot] != 0) slot = (slot + 1) & mask_;
    keys_[slot] = k;
    means_[slot] = mean;
    ++active_;
  }
  sums_.clear();
}

const Eigen::Vector3f* RadianceCache::lookup(const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                                             Kind kind) const {
  if (active_ == 0) return nullptr;
  const uint64_t k = key(p, n, kind);
  for (uint64_t slot = mix(k) & mask_;; slot = (slot + 1) & mask_) {
    if (keys_[slot] == k) return &means_[slot];
    if (keys_[slot] == 0) return nullptr;
  }
}

}  // namespace inet
