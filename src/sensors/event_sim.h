#pragma once
// Event camera (DVS) simulation from sampled log intensity, after ESIM (Rebecq, Gehrig &
// Scaramuzza, "ESIM: an Open Event Camera Simulator", CoRL 2018; rpg_esim
// esim/src/event_simulator.cpp) with optional v2e-style noise (Hu, Liu & Delbruck, CVPR-W 2021;
// v2ecore/emulator_utils.py). SENSORS.md section 3.
//
// Brightness L = ln(eps + I), I linear luminance in [0, 1] (logIntensity). Per pixel, with the
// reference level L_ref set to L_0 at the first sample (which emits nothing), each interval
// (t_{k-1}, L_{k-1}) -> (t_k, L_k) with |L_k - L_{k-1}| > 1e-6 does:
//     p = sign(L_k - L_{k-1});  repeat { C = the pixel's current threshold of polarity p;
//     x = L_ref + p C; stop if x is past L_k; t = t_{k-1} + (x -
//     L_{k-1}) / (L_k - L_{k-1}) (t_k - t_{k-1}) (rounded to the nearest ns, then clamped to
//     [t_{k-1} + 1 ns, t_k]); emit (t, x, y, p) unless t - t_last < refractory; L_ref = x (also
//     when the event is dropped, as ESIM does); draw the pixel's next thresholds }.
// A pixel's thresholds are C_on = theta_on + N(0, sigma_c) and C_off = theta_off + N(0, sigma_c),
// clamped >= 0.01, drawn at the start and again after each of its crossings: the comparator
// noise of one reset holds until the next event.
// theta_p = c_pos or c_neg, or a fixed per-pixel value N(c_p, threshold_spread) (v2e).
// The events of one interval are sorted by (t, y, x, p); every one lies in (t_{k-1}, t_k], so
// successive calls append a globally sorted stream.
//
// Differences from ESIM:
//  - ESIM redraws C per pixel per sampling interval, and uses that one draw for every crossing
//    of the interval. Both make the output depend on how finely the simulator samples, which is
//    an artefact of the simulation, not of the sensor: more intervals mean more redraws, a
//    smaller effective threshold and more events (+10 % at 0.5-3 ms steps on a smooth random
//    video), and n crossings in one interval share one error, so the nominal-C reconstruction
//    drifts by n sigma instead of sqrt(n) sigma. Here a threshold is drawn per crossing and held
//    until that crossing fires, whatever the sampling (keyed by the pixel's crossing count).
//  - ESIM also stops when x is not strictly past L_{k-1}, which can only happen with a threshold
//    that changed between intervals; with thresholds held per crossing it does not arise, but
//    such a level would fire at t_{k-1} + 1 ns rather than block the pixel.
//    With sigma_c = 0 (or a constant threshold) both rules give the same events as ESIM.
//  - below ESIM's resolution: L and the crossing arithmetic are double (ESIM: float); the time
//    is rounded to the nearest ns (ESIM truncates), then kept > t_{k-1}.
//
// Optional noise (v2e's "noisy" mode; all 0 = off = pure ESIM):
//  - leak: the reference sinks at leak_rate_hz * theta_on per second (v2e
//    subtract_leak_current), so a static pixel fires ON events at leak_rate_hz. Implemented as
//    the equivalent rising offset on the signal (crossing times stay exact; the 1e-6 tolerance
//    is then dropped, as the leak of one short interval can be below it); each pixel starts at
//    a random phase in [0, theta_on) so that leak events of a uniform scene are not synchronous
//    (our choice).
//  - shot noise: per interval, ON with probability r/2 dt f theta_nominal/theta_on, OFF with
//    r/2 dt f theta_nominal/theta_off, f = 1 - 0.75 I01 with I01 = (255 I + 20) / 275 (v2e
//    generate_shot_noise, SHOT_NOISE_INTEN_FACTOR 0.25); at a uniform time in the interval,
//    subject to the refractory period. A shot event resets the pixel's reference to the current
//    level, as a real pixel's reset does (v2e shifts it by +-theta instead).
//
// Randomness: CounterRng(seed, RngStream::Sensor, pixel = y * width + x, crossing count,
// kEventThresholdRngTag) for the thresholds, CounterRng(seed, RngStream::Sensor, pixel,
// interval k - 1, kEventRngTag) per pixel and interval (shot noise) and
// CounterRng(seed, RngStream::Sensor, pixel, 0 or 1, kEventPixelRngTag) for the fixed per-pixel
// thresholds (0) and leak phase (1), so the output is a pure function of (seed, samples)
// whatever the thread count.
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace inet {

/// Third counter word of the per-interval event streams (ASCII "EVS"), apart from kImuRngTag,
/// kSensorNoiseTag and kDepthNoiseRngTag.
constexpr uint32_t kEventRngTag = 0x455653u;
/// Third counter word of the fixed per-pixel event values (ASCII "EVP").
constexpr uint32_t kEventPixelRngTag = 0x455650u;
/// Third counter word of the per-crossing threshold draws (ASCII "EVT").
constexpr uint32_t kEventThresholdRngTag = 0x455654u;
/// Smallest contrast threshold used (log units); keeps the crossing loop finite (SENSORS.md 3).
constexpr double kMinContrastThreshold = 0.01;

/// One event: time (int64 ns, the sample clock), pixel column x and row y (0-based, origin top
/// left) and polarity p (1 = ON, brighter; 0 = OFF, darker). 16 bytes.
struct Event {
  int64_t t_ns = 0;
  uint16_t x = 0;
  uint16_t y = 0;
  uint8_t p = 0;
  bool operator==(const Event&) const = default;
  std::string toString() const;
};

struct EventOptions {
  /// Nominal ON / OFF contrast thresholds, log-intensity units (ESIM Cp, Cm). 0.2 like v2e's
  /// default (ESIM's flag default 1.0 is far above real sensors' 0.1-0.5).
  double c_pos = 0.2;
  double c_neg = 0.2;
  /// Std of the threshold noise, drawn per pixel per crossing (ESIM's sigma_Cp = sigma_Cm
  /// default 0.021; ESIM draws it per sampling interval, see the header comment).
  double sigma_c = 0.021;
  /// Events of a pixel closer than this to its previous event are dropped, ns (ESIM default 0;
  /// v2e 0.5 ms).
  int64_t refractory_ns = 0;
  /// eps of L = ln(eps + I) (ESIM log_eps).
  double log_eps = 1e-3;
  uint64_t seed = 0;
  /// v2e noise, 0 = off: std of the fixed per-pixel thresholds around c_pos / c_neg (v2e
  /// sigma_thres 0.03), leak event rate per pixel (v2e 0.01 Hz when on; some configs 0.1-0.2)
  /// and shot-noise event rate per pixel at zero intensity (v2e 0.001 Hz; 1-5 Hz in low light).
  double threshold_spread = 0.0;
  double leak_rate_hz = 0.0;
  double shot_noise_rate_hz = 0.0;

  /// Throws InputError(source, "--contrast-pos" / "--contrast-neg" / "--contrast-sigma" /
  /// "--refractory-ns" / "--log-eps" / "--threshold-spread" / "--leak-rate-hz" /
  /// "--shot-noise-rate-hz", ...) for non-finite or impossible values (thresholds < 0.01 or >
  /// 10, negative sigmas, rates or refractory, eps outside (0, 1]).
  void validate(const std::string& source = "") const;
  std::string toString() const;
};

/// L = ln(eps + max(I, 0)) for a linear luminance I (1 = white). NaN stays NaN.
double logIntensity(float linear_luminance, double eps);

/// One-channel log-intensity image of a linear image: 1 channel = luminance itself, 3 or 4
/// (alpha ignored) = Rec. 709 / sRGB-primaries luminance Y = 0.2126 R + 0.7152 G + 0.0722 B.
/// The input must be LINEAR (not gamma encoded) with 1 = white: divide 8-bit data by 255.
ImageF logIntensityImage(const ImageF& linear, double eps);
/// One-channel luminance (as logIntensityImage reads it) of a 1-, 3- or 4-channel linear image,
/// times `scale`.
ImageF luminanceImage(const ImageF& linear, double scale = 1.0);

/// Stateful per-pixel simulator: feed log-intensity samples in increasing time order.
/// Not thread-safe itself; addSample parallelises over rows internally (TBB).
class EventSimulator {
 public:
  /// width, height in [1, 65535] (x, y are uint16). Throws InputError as opts.validate().
  EventSimulator(int width, int height, const EventOptions& opts);

  /// Adds the sample L(t_ns) (1-channel log intensity, width x height) and appends the events
  /// of the interval since the previous sample to `out`, sorted by (t, y, x, p), all in
  /// (t_prev, t_ns]. The first call only initialises (no events). Returns the number appended.
  /// Throws InputError(source, "t_ns", ...) unless t_ns > the previous sample's time, and
  /// InputError(source, "log intensity", "pixel (x, y) ...") for a non-finite value (the state
  /// is then unchanged). Aborts (INET_CHECK) on a size mismatch, a programming error.
  size_t addSample(int64_t t_ns, const ImageF& log_intensity, std::vector<Event>& out,
                   const std::string& source = "");

  bool initialized() const { return samples_ > 0; }
  /// Number of samples added so far (the interval index of the next call is samples - 1).
  uint64_t sampleCount() const { return samples_; }
  /// Time of the latest sample, ns (undefined before the first).
  int64_t lastTime() const { return t_prev_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const EventOptions& options() const { return opts_; }

  /// L_ref of pixel (x, y) in log-intensity units: the level of its last crossing (or L_0).
  /// With leak on, the leak accumulated so far is subtracted (the sunk reference).
  double reference(int x, int y) const;
  /// reference() of every pixel as an image.
  ImageF referenceImage() const;
  /// The latest sample as given.
  const ImageF& lastLogIntensity() const { return last_; }
  /// Fixed threshold theta_p of pixel (x, y) for p = 1 (ON) or 0 (OFF): c_pos / c_neg, or the
  /// pixel's draw when threshold_spread > 0 (before the per-interval sigma_c noise).
  double pixelThreshold(int x, int y, int p) const;

 private:
  struct Interval;
  void processRow(int y, const ImageF& L, const Interval& iv, std::vector<Event>& row_out);
  /// Draws pixel i's thresholds for its next crossing (after crossing number crossings_[i]).
  void drawThresholds(size_t i);

  int width_, height_;
  EventOptions opts_;
  uint64_t samples_ = 0;
  int64_t t_prev_ = 0;
  ImageF last_;
  // per pixel, row-major
  std::vector<double> prev_;                 // L + leak offset at the previous sample
  std::vector<double> ref_;                  // L_ref in the same (offset) coordinates
  std::vector<double> leak_;                 // accumulated leak offset (0 without leak)
  std::vector<int64_t> t_last_;              // last emitted event, INT64_MIN = none yet
  std::vector<float> theta_on_, theta_off_;  // empty unless threshold_spread > 0
  std::vector<uint32_t> crossings_;          // crossings so far (keys the threshold draws)
  std::vector<double> next_on_, next_off_;   // thresholds of the next ON / OFF crossing
  std::vector<std::vector<Event>> rows_;     // scratch, one per row
};

/// L_0 + c_pos N_on - c_neg N_off per pixel: the log intensity that `events` imply when
/// starting from `initial_log` (1 channel), i.e. the ESIM reference level for sigma_c = 0.
/// Throws InputError("", "events", ...) for an event outside the image.
ImageF reconstructLogIntensity(const std::vector<Event>& events, const ImageF& initial_log,
                               double c_pos, double c_neg);

/// ESIM's adaptive sampling (DataProviderOnlineMoving3DCameraRig, flags
/// simulation_adaptive_sampling_method / _lambda): the next sample comes after
///     brightness mode: dt = lambda / max_x |dL/dt|   (lambda in log units, <= C)
///     flow mode:       dt = lambda / max_x |flow|    (lambda in pixels, flow in px/s)
/// clamped to [min_dt_ns, 1 / min_rate_hz] (ESIM: "never slower than the minimum frame rate";
/// the floor is ours, so that a flash or a renderer glitch cannot stall a run).
struct AdaptiveSamplingOptions {
  enum class Mode { Brightness, Flow };
  Mode mode = Mode::Brightness;
  double lambda = 0.5;          ///< ESIM simulation_adaptive_sampling_lambda
  int64_t min_dt_ns = 100'000;  ///< 0.1 ms (10 kHz at most)
  double min_rate_hz = 30.0;    ///< ESIM simulation_minimum_framerate
  /// Throws InputError(source, "--adaptive-lambda" / "--min-dt-ns" / "--min-rate-hz", ...).
  void validate(const std::string& source = "") const;
  std::string toString() const;
};

/// |L_cur - L_prev| / (t_cur - t_prev) in 1/s (brightness-mode input, estimated from the last
/// two samples) at the given quantile over pixels: 1 = the maximum (ESIM); below 1 ignores the
/// few pixels with the largest change (e.g. the Monte Carlo error of a rendered image). Requires
/// t_cur > t_prev and equal, non-empty 1-channel sizes.
double logIntensityRate(const ImageF& L_prev, int64_t t_prev_ns, const ImageF& L_cur,
                        int64_t t_cur_ns, double quantile = 1.0);

/// The next sampling interval in ns for `max_speed`: max |dL/dt| in 1/s (Mode::Brightness) or
/// the largest optical-flow magnitude in px/s (Mode::Flow). Speed 0 -> 1 / min_rate_hz; NaN
/// (unknown) -> min_dt_ns.
int64_t nextSampleInterval(double max_speed, const AdaptiveSamplingOptions& opts);

}  // namespace inet
