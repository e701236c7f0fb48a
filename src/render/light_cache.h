#pragma once
// What each light actually delivers, region by region: a per-frame cache that makes the light
// pick of next-event estimation (lights.h) aware of visibility.
//
// The pick is proportional to the light each source could give a receiver if nothing were in
// the way. Indoors by day that estimate is ruled by the sun (350 W/m^2), hidden from nearly
// every receiver: in a procedural apartment it took about 70 % of the light samples while the
// sky through the windows, which lights the walls, got a quarter, half of those through the
// panes. A short training pass of each frame records, per world-space cell and per light, the
// share of its shadow rays that got through (the transmittance, 0 when blocked or when the
// light is behind the surface); the pick then weighs each light's estimate by that share,
// never below kFloor, so every light that could light a receiver keeps a probability and the
// estimate stays unbiased.
//
// Hand-written because it is a table of counters: a hashed uniform grid (as in the
// many-light caches of production renderers, e.g. Vevoda et al. 2018, "Bayesian online
// regression for adaptive direct illumination sampling", reduced here to a ratio per cell).
// Same bytes: counts and sums are integers added atomically, which commute, so the cache does
// not depend on the thread count or the order of tiles.
#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace inet {

class LightCache {
 public:
  /// Lights the cache follows, by SceneLights::cacheSlot (analytic lights first; the rest keep
  /// their plain estimate): as many as a pick point caches.
  static constexpr int kLights = 16;
  /// Least factor a light's estimate is weighed by: a light whose every training shadow ray was
  /// blocked still gets a tenth of its plain share.
  static constexpr float kFloor = 0.1f;
  /// Training shadow rays of a light in a cell before its share is trusted.
  static constexpr uint32_t kMinTrials = 16;

  struct Config {
    float cell_m = 0.5f;  ///< edge of a grid cell
    int table_bits = 14;  ///< 2^bits hashed cells (cells that collide share their counts)
  };

  LightCache() : LightCache(Config{}) {}
  explicit LightCache(const Config& config);

  /// Training: a shadow ray from a receiver at `p` toward pick entry `light` carried
  /// `transmittance` (in [0, 1]; 0 when blocked or the light is behind the surface).
  /// Thread-safe; the result does not depend on the order of calls.
  void record(const Eigen::Vector3f& p, int light, float transmittance);

  /// Ends training: fixes each cell's factors. Call once, before `factors`.
  void build();

  /// The factors of the cell of p, kLights of them (1 where training gave too little), or
  /// nullptr where no light of the cell was trained (every factor 1).
  const float* factors(const Eigen::Vector3f& p) const;

  /// Cells with at least one trained factor, after `build` (for tests and logs).
  int activeCells() const { return active_; }

 private:
  uint32_t slot(const Eigen::Vector3f& p) const;

  Config config_;
  float inv_cell_;
  uint32_t mask_;
  // per slot and light: trials, and the transmittances' sum x 2^16
  std::unique_ptr<std::atomic<uint32_t>[]> trials_;
  std::unique_ptr<std::atomic<uint64_t>[]> sums_;
  std::vector<int32_t> table_of_slot_;  // -1: every factor 1
  std::vector<float> tables_;           // kLights per trained cell
  int active_ = 0;
};

}  // namespace inet
