#pragma once
// What a surface sends on, region by region: a per-frame cache of the light leaving rough
// surfaces, so that a path can stop at its second rough vertex and take the rest of its light
// from the cache instead of from more bounces.
//
// Indoors much of a wall's light has bounced three times or more: the floor's sunlit patch
// lights the ceiling, which lights the wall. A path finds that light by going on bouncing, and
// each bounce past the second adds noise (apartment 3 at 16 spp: relative noise 0.64 with two
// bounces, 0.57 with three, 0.65 with eight, for 40 %, 62 % and all of the light). A sparse
// training pass of full paths through the frame's own view records, at the vertex after each
// path's first rough scattering, the light it gathered from there on divided by the
// throughput that reached it (and by the albedo there, on a Lambertian surface). Records are
// summed per world-space cell: a cubic grid cell, the axis the surface's side facing the path
// is closest to, and the kind of value. The frame's paths stop at that same vertex and take
// their cell's mean, the average of dozens to thousands of training paths, in place of more
// bounces. Training paths record where the frame's paths read, reached the same way, so a
// cell's mean is the mean over the points in it where those paths land and the blur does not
// move the expected light; what is left is the cell's noise, which every pixel of the frame
// shares. Read after the second rough scattering (the first design), a frame's mean moved by
// about 1 % between seeds at 2 training paths per pixel of every 2nd row and column, within
// 0.5 % at 8; read after the first, the paths keep less of their own light and 16 are used.
// Not unbiased for one frame, hence optional (RenderOptions::radiance_cache); the light the
// path gathers at its first rough vertex (direct light, photons, what its BSDF sample hits)
// stays exact.
//
// Hand-written because it is a table of sums: a hashed grid as in the radiance caches of
// real-time path tracers (e.g. SHaRC; Binder et al. 2019, "Massively parallel path space
// filtering"), kept per frame. Same bytes: each task sums its records in a map of its own, the
// maps' sums are integers (fixed point) merged under a lock, and integer sums commute, so the
// cache does not depend on the thread count or the order of tasks.
#include <Eigen/Core>
#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace inet {

class RadianceCache {
 public:
  struct Config {
    float cell_m = 0.25f;        ///< edge of a grid cell
    uint32_t min_records = 16;   ///< records of a cell before its mean is used
    /// Training: full paths per pixel of every 2nd row and column (at 16, a quarter of a 16-spp
    /// frame's paths), and the least number of training paths of a frame.
    int train_spp = 16;
    int train_min_paths = 1 << 15;
  };
  /// A record more than this many times brighter (luminance) than the mean of its cell's other
  /// records is left out of the mean: one caustic path (the sun through a mirror, 10^6 times a
  /// wall's light) would otherwise light a whole cell of the frame. Records are heavy-tailed
  /// (a vertex that connects to a sun photon): at 16x, 40 % of apartment 3's cells lost one and
  /// its walls came out 4 % dark, at 256x 1 %; at 4096x none of its records goes.
  static constexpr double kLoneRecordRatio = 4096.0;

  /// What a cell holds: the light a Lambertian surface sends on per unit albedo (so that the
  /// texture of the point read stays), or for other rough surfaces (a varnish, a metal, a
  /// curtain) the radiance itself, leaving toward the paths that reached it.
  enum class Kind : uint8_t { PerAlbedo, Radiance };

  /// A cell's sums, fixed point (value x 2^kFixedBits); `max` is its brightest record.
  struct Sums {
    uint64_t rgb[3] = {0, 0, 0};
    uint64_t max[3] = {0, 0, 0};
    uint64_t max_luma = 0;
    uint32_t count = 0;
  };

  /// Records of one task (not thread-safe), merged into a cache by RadianceCache::merge.
  class Recorder {
   public:
    explicit Recorder(const RadianceCache& cache) : cache_(&cache) {}
    /// `value` (finite, >= 0 per channel; others are dropped) of the `kind` a point p sent
    /// on, whose side facing the path has normal n.
    void record(const Eigen::Vector3f& p, const Eigen::Vector3f& n, Kind kind,
                const Eigen::Vector3f& value);

   private:
    friend class RadianceCache;
    const RadianceCache* cache_;
    std::unordered_map<uint64_t, Sums> sums_;
    size_t records_ = 0;
  };

  RadianceCache() : RadianceCache(Config{}) {}
  explicit RadianceCache(const Config& config);

  /// The key of p's cell on the side of normal n (the grid cell and n's nearest signed axis)
  /// for values of `kind`.
  uint64_t key(const Eigen::Vector3f& p, const Eigen::Vector3f& n, Kind kind) const;

  /// Adds a task's records (thread-safe; the result does not depend on the order of calls)
  /// and empties the recorder.
  void merge(Recorder& recorder);

  /// Ends training: fixes each cell's mean. Call once, before `lookup`.
  void build();

  /// The mean of the values of `kind` of (p, n)'s cell, or nullptr when the cell has fewer
  /// than Config::min_records records.
  const Eigen::Vector3f* lookup(const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                                Kind kind) const;

  /// Cells whose mean is used, after `build`; records merged (for tests and logs).
  size_t activeCells() const { return active_; }
  size_t records() const { return records_; }
  /// Records left out as lone bright ones (kLoneRecordRatio), after `build`.
  size_t loneRecords() const { return lone_; }
  const Config& config() const { return config_; }

 private:
  Config config_;
  float inv_cell_;
  std::mutex mutex_;
  std::unordered_map<uint64_t, Sums> sums_;
  // after build: open addressing, keys (0 = empty) and means
  std::vector<uint64_t> keys_;
  std::vector<Eigen::Vector3f> means_;
  uint64_t mask_ = 0;
  size_t active_ = 0, records_ = 0, lone_ = 0;
};

}  // namespace inet
