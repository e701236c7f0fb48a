#include "sensors/event_sim.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/color.h"
#include "core/error.h"
#include "core/rng.h"

namespace inet {
namespace {

constexpr int64_t kNoEvent = std::numeric_limits<int64_t>::min();
constexpr double kTolerance = 1e-6;                 // ESIM: no events for |L_k - L_{k-1}| <= 1e-6
constexpr double kShotNoiseIntensityFactor = 0.25;  // v2e SHOT_NOISE_INTEN_FACTOR

bool eventLess(const Event& a, const Event& b) {
  if (a.t_ns != b.t_ns) return a.t_ns < b.t_ns;
  if (a.y != b.y) return a.y < b.y;
  if (a.x != b.x) return a.x < b.x;
  return a.p < b.p;
}

}  // namespace

std::string Event::toString() const {
  return fmt::format("Event(t_ns={}, x={}, y={}, p={})", t_ns, x, y, p);
}

void EventOptions::validate(const std::string& source) const {
  auto need = [&](bool ok, const char* field, const std::string& what) {
    if (!ok) throw InputError(source, field, what);
  };
  auto threshold = [&](double c, const char* field) {
    need(std::isfinite(c) && c >= kMinContrastThreshold && c <= 10, field,
         fmt::format("contrast threshold {} must be in [{}, 10] (log units; typical 0.1-0.5)", c,
                     kMinContrastThreshold));
  };
  threshold(c_pos, "--contrast-pos");
  threshold(c_neg, "--contrast-neg");
  need(std::isfinite(sigma_c) && sigma_c >= 0 && sigma_c <= 1, "--contrast-sigma",
       fmt::format("{} must be in [0, 1] (log units)", sigma_c));
  need(refractory_ns >= 0, "--refractory-ns", fmt::format("{} must be >= 0", refractory_ns));
  need(std::isfinite(log_eps) && log_eps > 0 && log_eps <= 1, "--log-eps",
       fmt::format("{} must be in (0, 1]", log_eps));
  need(std::isfinite(threshold_spread) && threshold_spread >= 0 && threshold_spread <= 1,
       "--threshold-spread", fmt::format("{} must be in [0, 1] (log units)", threshold_spread));
  need(std::isfinite(leak_rate_hz) && leak_rate_hz >= 0, "--leak-rate-hz",
       fmt::format("{} must be finite and >= 0", leak_rate_hz));
  need(std::isfinite(shot_noise_rate_hz) && shot_noise_rate_hz >= 0, "--shot-noise-rate-hz",
       fmt::format("{} must be finite and >= 0", shot_noise_rate_hz));
}

std::string EventOptions::toString() const {
  return fmt::format(
      "EventOptions(c_pos={}, c_neg={}, sigma_c={}, refractory_ns={}, log_eps={}, seed={}, "
      "threshold_spread={}, leak_rate_hz={}, shot_noise_rate_hz={})",
      c_pos, c_neg, sigma_c, refractory_ns, log_eps, seed, threshold_spread, leak_rate_hz,
      shot_noise_rate_hz);
}

double logIntensity(float linear_luminance, double eps) {
  const double i = linear_luminance;
  return std::log(eps + (i > 0 ? i : (std::isnan(i) ? i : 0.0)));
}

namespace {

/// Per pixel f(luminance) of a 1-, 3- or 4-channel linear image, into one channel.
template <class F>
ImageF mapLuminance(const ImageF& linear, F f) {
  INET_CHECK_MSG(linear.channels == 1 || linear.channels == 3 || linear.channels == 4,
                 fmt::format("{} channels (1, 3 or 4 expected)", linear.channels));
  ImageF out(linear.width, linear.height, 1);
  tbb::parallel_for(tbb::blocked_range<int>(0, linear.height, 8), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < linear.width; ++x) {
        const float* c = linear.pixel(x, y);
        out.at(x, y) = f(linear.channels == 1 ? c[0] : luminance(Eigen::Map<const Eigen::Vector3f>(c)));
      }
  });
  return out;
}

}  // namespace

ImageF luminanceImage(const ImageF& linear, double scale) {
  return mapLuminance(linear, [scale](float y) { return static_cast<float>(scale * y); });
}

ImageF logIntensityImage(const ImageF& linear, double eps) {
  return mapLuminance(linear,
                      [eps](float y) { return static_cast<float>(logIntensity(y, eps)); });
}

// ---------------------------------------------------------------------------------------------

struct EventSimulator::Interval {
  int64_t t0_ns, t1_ns;
  double dt_s;
  uint32_t index;  // k - 1 for the interval ending at sample k
};

EventSimulator::EventSimulator(int width, int height, const EventOptions& opts)
    : width_(width), height_(height), opts_(opts) {
  opts_.validate();
  if (width < 1 || height < 1 || width > 65535 || height > 65535)
    throw InputError("", "resolution",
                     fmt::format("{}x{}: width and height must be in [1, 65535]", width, height));
  const size_t n = static_cast<size_t>(width) * height;
  prev_.assign(n, 0.0);
  ref_.assign(n, 0.0);
  leak_.assign(n, 0.0);
  t_last_.assign(n, kNoEvent);
  crossings_.assign(n, 0);
  next_on_.assign(n, 0.0);
  next_off_.assign(n, 0.0);
  rows_.resize(static_cast<size_t>(height));
  if (opts_.threshold_spread > 0) {
    theta_on_.resize(n);
    theta_off_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      CounterRng rng(opts_.seed, RngStream::Sensor, static_cast<uint32_t>(i), 0, kEventPixelRngTag);
      double z_on, z_off;
      rng.normalPair(z_on, z_off);
      theta_on_[i] = static_cast<float>(
          std::max(opts_.c_pos + opts_.threshold_spread * z_on, kMinContrastThreshold));
      theta_off_[i] = static_cast<float>(
          std::max(opts_.c_neg + opts_.threshold_spread * z_off, kMinContrastThreshold));
    }
  }
}

void EventSimulator::drawThresholds(size_t i) {
  const int x = static_cast<int>(i % width_), y = static_cast<int>(i / width_);
  double on = pixelThreshold(x, y, 1), off = pixelThreshold(x, y, 0);
  if (opts_.sigma_c > 0) {
    CounterRng rng(opts_.seed, RngStream::Sensor, static_cast<uint32_t>(i), crossings_[i],
                   kEventThresholdRngTag);
    double z_on, z_off;
    rng.normalPair(z_on, z_off);
    on += opts_.sigma_c * z_on;
    off += opts_.sigma_c * z_off;
  }
  next_on_[i] = std::max(on, kMinContrastThreshold);
  next_off_[i] = std::max(off, kMinContrastThreshold);
}

double EventSimulator::pixelThreshold(int x, int y, int p) const {
  const size_t i = static_cast<size_t>(y) * width_ + x;
  if (theta_on_.empty()) return p ? opts_.c_pos : opts_.c_neg;
  return p ? theta_on_[i] : theta_off_[i];
}

double EventSimulator::reference(int x, int y) const {
  const size_t i = static_cast<size_t>(y) * width_ + x;
  return ref_[i] - leak_[i];
}

ImageF EventSimulator::referenceImage() const {
  ImageF out(width_, height_, 1);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) out.at(x, y) = static_cast<float>(reference(x, y));
  return out;
}

void EventSimulator::processRow(int y, const ImageF& L, const Interval& iv,
                                std::vector<Event>& row_out) {
  row_out.clear();
  const double dt_ns = static_cast<double>(iv.t1_ns - iv.t0_ns);
  const bool shot = opts_.shot_noise_rate_hz > 0;
  for (int x = 0; x < width_; ++x) {
    const size_t i = static_cast<size_t>(y) * width_ + x;
    const double theta_on = pixelThreshold(x, y, 1), theta_off = pixelThreshold(x, y, 0);
    // The leak lowers the reference at a constant rate; raising the signal instead keeps the
    // interpolated crossing times exact.
    if (opts_.leak_rate_hz > 0) leak_[i] += opts_.leak_rate_hz * theta_on * iv.dt_s;
    const double prev = prev_[i];
    const double cur = static_cast<double>(L.at(x, y)) + leak_[i];
    CounterRng rng(opts_.seed, RngStream::Sensor, static_cast<uint32_t>(i), iv.index, kEventRngTag);
    const size_t first = row_out.size();
    // ESIM skips |change| <= 1e-6; with the leak the change includes the leak, which can be
    // below that at every one of many short intervals and must still add up.
    const double change = cur - prev;
    if (opts_.leak_rate_hz > 0 ? change != 0 : std::abs(change) > kTolerance) {
      const int pol = cur >= prev ? 1 : -1;
      // ESIM also requires the level to lie strictly past prev. A level at or before prev can
      // only come from a threshold redrawn smaller than the last one; ESIM then emits nothing
      // and the pixel stays blocked while L keeps going the same way. It fires at t0 + 1 ns here.
      double level = ref_[i];
      for (;;) {
        // the pixel's threshold for its next crossing, drawn when it last crossed
        level += pol * (pol > 0 ? next_on_[i] : next_off_[i]);
        if (pol > 0 ? level > cur : level < cur) break;
        int64_t t = iv.t0_ns + std::llround((level - prev) / (cur - prev) * dt_ns);
        t = std::clamp(t, iv.t0_ns + 1, iv.t1_ns);
        if (t_last_[i] == kNoEvent || t - t_last_[i] >= opts_.refractory_ns) {
          row_out.push_back({t, static_cast<uint16_t>(x), static_cast<uint16_t>(y),
                             static_cast<uint8_t>(pol > 0)});
          t_last_[i] = t;
        }
        ref_[i] = level;  // ESIM moves the reference even for a dropped event
        ++crossings_[i];
        drawThresholds(i);
      }
    }
    if (shot) {
      const double lin =
          std::clamp(std::exp(static_cast<double>(L.at(x, y))) - opts_.log_eps, 0.0, 1.0);
      const double inten01 = (255.0 * lin + 20.0) / 275.0;
      const double f =
          opts_.shot_noise_rate_hz / 2 * iv.dt_s * ((kShotNoiseIntensityFactor - 1) * inten01 + 1);
      const double p_on = std::min(f * opts_.c_pos / theta_on, 0.5);
      const double p_off = std::min(f * opts_.c_neg / theta_off, 0.5);
      const double u = rng.uniformDouble();
      const int pol = u >= 1 - p_on ? 1 : (u < p_off ? -1 : 0);
      if (pol != 0) {
        const int64_t t =
            iv.t0_ns + 1 + static_cast<int64_t>(rng.uniformDouble() * static_cast<double>(dt_ns));
        bool keep = t_last_[i] == kNoEvent || t - t_last_[i] >= opts_.refractory_ns;
        for (size_t j = first; j < row_out.size() && keep; ++j)
          keep = std::abs(row_out[j].t_ns - t) >= opts_.refractory_ns;
        if (keep) {
          row_out.push_back({t, static_cast<uint16_t>(x), static_cast<uint16_t>(y),
                             static_cast<uint8_t>(pol > 0)});
          t_last_[i] = std::max(t_last_[i], t);
          ref_[i] = cur;  // the pixel resets to the current level
        }
      }
    }
    prev_[i] = cur;
  }
}

size_t EventSimulator::addSample(int64_t t_ns, const ImageF& log_intensity, std::vector<Event>& out,
                                 const std::string& source) {
  INET_CHECK_MSG(log_intensity.width == width_ && log_intensity.height == height_ &&
                     log_intensity.channels == 1,
                 fmt::format("sample is {}x{}x{}, simulator {}x{}x1", log_intensity.width,
                             log_intensity.height, log_intensity.channels, width_, height_));
  if (samples_ > 0 && t_ns <= t_prev_)
    throw InputError(
        source, "t_ns",
        fmt::format("sample times must strictly increase: {} ns after {} ns", t_ns, t_prev_));
  // Reject non-finite input before touching any state (a NaN would silently mute a pixel).
  for (size_t i = 0; i < log_intensity.data.size(); ++i)
    if (!std::isfinite(log_intensity.data[i]))
      throw InputError(source, "log intensity",
                       fmt::format("pixel ({}, {}) is {} at t = {} ns", i % width_, i / width_,
                                   log_intensity.data[i], t_ns));
  last_ = log_intensity;
  if (samples_++ == 0) {
    for (size_t i = 0; i < prev_.size(); ++i) {
      if (opts_.leak_rate_hz > 0) {  // random initial leak phase in [0, theta_on)
        CounterRng rng(opts_.seed, RngStream::Sensor, static_cast<uint32_t>(i), 1,
                       kEventPixelRngTag);
        leak_[i] = rng.uniformDouble() *
                   pixelThreshold(static_cast<int>(i % width_), static_cast<int>(i / width_), 1);
      }
      prev_[i] = static_cast<double>(log_intensity.data[i]) + leak_[i];
      ref_[i] = static_cast<double>(log_intensity.data[i]);
      drawThresholds(i);
    }
    t_prev_ = t_ns;
    return 0;
  }
  const Interval iv{t_prev_, t_ns, static_cast<double>(t_ns - t_prev_) * 1e-9,
                    static_cast<uint32_t>(samples_ - 2)};
  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 4), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      processRow(y, log_intensity, iv, rows_[static_cast<size_t>(y)]);
  });
  t_prev_ = t_ns;
  // Rows are concatenated in order and sorted by a total order on event values: the result
  // does not depend on how rows were split among threads.
  const size_t start = out.size();
  size_t total = 0;
  for (const auto& r : rows_) total += r.size();
  if (out.capacity() < start + total)  // grow geometrically: an exact reserve copies every call
    out.reserve(std::max(start + total, 2 * out.capacity()));
  for (const auto& r : rows_) out.insert(out.end(), r.begin(), r.end());
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end(), eventLess);
  return total;
}

// ---------------------------------------------------------------------------------------------

ImageF reconstructLogIntensity(const std::vector<Event>& events, const ImageF& initial_log,
                               double c_pos, double c_neg) {
  INET_CHECK(initial_log.channels == 1);
  std::vector<double> acc(initial_log.data.begin(), initial_log.data.end());
  for (const Event& e : events) {
    if (e.x >= initial_log.width || e.y >= initial_log.height)
      throw InputError("", "events",
                       fmt::format("{} lies outside the {}x{} image", e.toString(),
                                   initial_log.width, initial_log.height));
    acc[initial_log.index(e.x, e.y)] += e.p ? c_pos : -c_neg;
  }
  ImageF out(initial_log.width, initial_log.height, 1);
  for (size_t i = 0; i < acc.size(); ++i) out.data[i] = static_cast<float>(acc[i]);
  return out;
}

void AdaptiveSamplingOptions::validate(const std::string& source) const {
  if (!(std::isfinite(lambda) && lambda > 0))
    throw InputError(source, "--adaptive-lambda", fmt::format("{} must be > 0", lambda));
  if (min_dt_ns < 1)
    throw InputError(source, "--min-dt-ns", fmt::format("{} must be >= 1 ns", min_dt_ns));
  if (!(std::isfinite(min_rate_hz) && min_rate_hz > 0 && 1e9 / min_rate_hz >= min_dt_ns))
    throw InputError(
        source, "--min-rate-hz",
        fmt::format("{} must be > 0 with 1 / rate >= min dt ({} ns)", min_rate_hz, min_dt_ns));
}

std::string AdaptiveSamplingOptions::toString() const {
  return fmt::format("AdaptiveSamplingOptions(mode={}, lambda={}, min_dt_ns={}, min_rate_hz={})",
                     mode == Mode::Brightness ? "brightness" : "flow", lambda, min_dt_ns,
                     min_rate_hz);
}

double logIntensityRate(const ImageF& L_prev, int64_t t_prev_ns, const ImageF& L_cur,
                        int64_t t_cur_ns, double quantile) {
  INET_CHECK(t_cur_ns > t_prev_ns);
  INET_CHECK(L_prev.channels == 1 && L_cur.channels == 1 && L_prev.width == L_cur.width &&
             L_prev.height == L_cur.height && !L_cur.data.empty());
  INET_CHECK(quantile > 0 && quantile <= 1);
  std::vector<double> diff(L_cur.data.size());
  for (size_t i = 0; i < diff.size(); ++i)
    diff[i] = std::abs(static_cast<double>(L_cur.data[i]) - L_prev.data[i]);
  const size_t q = std::min(diff.size() - 1, static_cast<size_t>(quantile * diff.size()));
  std::nth_element(diff.begin(), diff.begin() + q, diff.end());
  return diff[q] / (static_cast<double>(t_cur_ns - t_prev_ns) * 1e-9);
}

int64_t nextSampleInterval(double max_speed, const AdaptiveSamplingOptions& opts) {
  const double max_dt_ns = 1e9 / opts.min_rate_hz;
  if (std::isnan(max_speed)) return opts.min_dt_ns;  // unknown: sample densely
  if (!(max_speed > 0)) return static_cast<int64_t>(max_dt_ns);
  const double dt_ns = opts.lambda / max_speed * 1e9;
  return static_cast<int64_t>(std::clamp(dt_ns, static_cast<double>(opts.min_dt_ns), max_dt_ns));
}

}  // namespace inet
