#include "render/light_cache.h"

#include <algorithm>
#include <cmath>

#include "render/sampler.h"

namespace inet {
namespace {

constexpr int kFixedBits = 16;  // transmittance sums hold t x 2^16

}  // namespace

LightCache::LightCache(const Config& config)
    : config_(config),
      inv_cell_(1.f / config.cell_m),
      mask_((1u << config.table_bits) - 1u),
      trials_(new std::atomic<uint32_t>[static_cast<size_t>(kLights) << config.table_bits]),
      sums_(new std::atomic<uint64_t>[static_cast<size_t>(kLights) << config.table_bits]) {
  const size_t n = static_cast<size_t>(kLights) << config.table_bits;
  for (size_t i = 0; i < n; ++i) {
    trials_[i].store(0, std::memory_order_relaxed);
    sums_[i].store(0, std::memory_order_relaxed);
  }
}

uint32_t LightCache::slot(const Eigen::Vector3f& p) const {
  auto cellIndex = [&](float x) {
    return static_cast<uint32_t>(static_cast<int32_t>(std::floor(x * inv_cell_)));
  };
  return sobol_detail::hash4(0, cellIndex(p.x()), cellIndex(p.y()), cellIndex(p.z())) & mask_;
}

void LightCache::record(const Eigen::Vector3f& p, int light, float transmittance) {
  if (light < 0 || light >= kLights) return;
  const size_t i = static_cast<size_t>(slot(p)) * kLights + static_cast<size_t>(light);
  trials_[i].fetch_add(1u, std::memory_order_relaxed);
  const float t = std::clamp(transmittance, 0.f, 1.f);  // NaN becomes 0
  if (t > 0.f)
    sums_[i].fetch_add(static_cast<uint64_t>(std::ldexp(t, kFixedBits) + 0.5f),
                       std::memory_order_relaxed);
}

void LightCache::build() {
  const size_t slots = size_t{1} << config_.table_bits;
  table_of_slot_.assign(slots, -1);
  tables_.clear();
  for (size_t s = 0; s < slots; ++s) {
    float f[kLights];
    bool trained = false;
    for (int k = 0; k < kLights; ++k) {
      const size_t i = s * kLights + static_cast<size_t>(k);
      const uint32_t n = trials_[i].load(std::memory_order_relaxed);
      f[k] = 1.f;
      if (n < kMinTrials) continue;
      const double share = std::ldexp(static_cast<double>(sums_[i].load(std::memory_order_relaxed)),
                                      -kFixedBits) / n;
      f[k] = std::max(kFloor, static_cast<float>(share));
      trained = true;
    }
    if (!trained) continue;
    table_of_slot_[s] = static_cast<int32_t>(tables_.size() / kLights);
    tables_.insert(tables_.end(), f, f + kLights);
  }
  active_ = static_cast<int>(tables_.size() / kLights);
}

const float* LightCache::factors(const Eigen::Vector3f& p) const {
  if (tables_.empty()) return nullptr;
  const int32_t t = table_of_slot_[slot(p)];
  return t < 0 ? nullptr : &tables_[static_cast<size_t>(t) * kLights];
}

}  // namespace inet
