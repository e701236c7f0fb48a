#pragma once
// The learned trajectory style (paper section 6.2, docs/style.md): a WaveNet (van den Oord et
// al. 2016) that takes a window of past hand-held velocity residuals and predicts the next one
// as a Gaussian, sampled autoregressively on top of a smooth base trajectory.
//
// Features. A real or base trajectory is resampled at config.rate_hz (100 Hz: the rate of the
// TUM RGB-D ground truth, the slowest hand-held source) through the Catmull-Rom interpolant of
// trajectory/spectrum.h. Per sample, the world-frame linear velocity v and angular velocity w
// (spectrum.h's central differences) are band-passed as the difference of two Gaussian
// low-passes, r = LP_lowpass_hz(v, w) - LP_highpass_hz(v, w) (-3 dB at 25 Hz and at 0.4 Hz;
// sigma_t = sqrt(ln 2) / (2 pi f)): the hand-held part of the motion (steps, sway, tremor)
// without the path, which the base trajectory supplies, and without most of the mocap noise
// (position noise of ~0.3 mm becomes velocity noise that an autoregressive model cannot tell
// from motion, and would integrate into a random walk when generating). World frame (z up)
// rather than body frame because world angular velocity does not depend on which frame rides on
// the body (camera in TUM RGB-D, IMU in TUM-VI), and the walking bounce is vertical whatever the
// camera's attitude; training rotates every window by a random yaw, so the model has no
// preferred horizontal direction. Normalised: r_n = r / scale, one scale for horizontal and one
// for vertical components of v and of w (so yaw rotations commute with normalisation).
//
// Network (all convolutions causal, zero history before the first sample):
//   h_0 = W_in x + b_in                                    (1x1, 6 -> C)
//   for each dilation d_l (kernel 2):
//     a   = W_past h_l[t - d_l] + W_now h_l[t] + b          (C -> 2C)
//     z   = tanh(a[0:C]) * sigmoid(a[C:2C])                 (gated activation)
//     h_{l+1} = h_l + W_res z + b_res;  s += W_skip z + b_skip
//   o = W_2 relu(W_1 relu(s) + b_1) + b_2                   (12 outputs)
//   mean = o[0:6], log_var = clamp(o[6:12], min_log_var, max_log_var)
// Output t is the distribution of x[t + 1] given x[0..t]. Receptive field 1 + sum(d_l) samples.
//
// Weights file (.bin, little-endian): 8 bytes "INETSTYL", uint32 format version (1), uint32
// header length n, n bytes of JSON header {"config": {...}, "scale": [6], "tensors": [{"name",
// "rows", "cols"}...]}, then each tensor's rows x cols float32 values, row-major, in header
// order. Names: in_w, in_b, then per layer l: l{l}.past, l{l}.now, l{l}.b, l{l}.res_w,
// l{l}.res_b, l{l}.skip_w, l{l}.skip_b, then head1_w, head1_b, head2_w, head2_b (biases are
// rows x 1). Convolution taps: torch's weight[:, :, 0] is "past", [:, :, 1] is "now".
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "trajectory/trajectory.h"

namespace inet {

using Vec6 = Eigen::Matrix<double, 6, 1>;

struct StyleModelConfig {
  double rate_hz = 100.0;     ///< sample rate of the features and of generation
  double highpass_hz = 0.4;   ///< the residual keeps motion above this (-3 dB)
  double lowpass_hz = 25.0;   ///< ... and below this (-3 dB; mocap noise); <= 0: no low-pass
  int channels = 32;          ///< residual channels C
  int skip_channels = 32;     ///< skip channels S
  int head_channels = 32;     ///< hidden width of the output head H
  std::vector<int> dilations = {1, 2, 4, 8, 16, 32, 64};
  double min_log_var = -12.0, max_log_var = 4.0;  ///< clamp of the predicted log-variance
  int receptiveField() const;
};

struct StyleLayer {
  int dilation = 1;
  Eigen::MatrixXd past, now;  ///< 2C x C
  Eigen::VectorXd b;          ///< 2C
  Eigen::MatrixXd res_w;      ///< C x C
  Eigen::VectorXd res_b;
  Eigen::MatrixXd skip_w;     ///< S x C
  Eigen::VectorXd skip_b;
};

/// The network's weights and normalisation, in double precision.
struct StyleModel {
  StyleModelConfig config;
  Vec6 scale = Vec6::Ones();  ///< residual units per normalised unit (m/s x3, rad/s x3)
  Eigen::MatrixXd in_w;       ///< C x 6
  Eigen::VectorXd in_b;
  std::vector<StyleLayer> layers;
  Eigen::MatrixXd head1_w, head2_w;  ///< H x S, 12 x H
  Eigen::VectorXd head1_b, head2_b;

  /// Weights drawn from U(-1/sqrt(fan_in), 1/sqrt(fan_in)) (torch's default) with a
  /// counter-based generator: for tests and as the training's starting point.
  static StyleModel random(const StyleModelConfig& config, uint64_t seed);
  /// The whole network over a normalised input sequence x (6 x T): returns 12 x T, column t
  /// = (mean, log_var) of x[t + 1].
  Eigen::MatrixXd forward(const Eigen::MatrixXd& x) const;
  size_t parameterCount() const;
  /// Visits every tensor in file order with its name (biases as rows x 1 matrices).
  void forEachTensor(const std::function<void(const std::string&, Eigen::MatrixXd&)>& f);
};

/// The same network one sample at a time, keeping per-layer histories (fast WaveNet
/// generation, Paine et al. 2016): after push(x[0..t]) output() equals forward(x).col(t).
class StyleStream {
 public:
  explicit StyleStream(const StyleModel& model);
  /// Feeds x[t] (normalised) and returns (mean, log_var) of x[t + 1].
  Eigen::Matrix<double, 12, 1> push(const Vec6& x);

 private:
  const StyleModel& m_;
  std::vector<Eigen::MatrixXd> hist_;  ///< per layer: C x dilation ring of past inputs
  std::vector<int> head_;              ///< per layer: ring position of h[t - d]
  Eigen::VectorXd h_, a_, z_, s_;
};

/// Reads a weights file (format above). Throws InputError naming the file for a wrong magic,
/// version, header or size.
StyleModel loadStyleModel(const std::string& path);
/// Writes it (atomically).
void saveStyleModel(const StyleModel& model, const std::string& path);
/// The shipped hand-held model: $INET_STYLE_MODEL if set, else data/style/handheld_wavenet.bin
/// of the source tree this was built from, else <executable>/../share/interiornet/style/....
std::string defaultStyleModelPath();
/// loadStyleModel(defaultStyleModelPath()), loaded once (thread-safe). Throws InputError.
const StyleModel& builtinStyleModel();

/// How real data is cut into clean pieces before resampling.
struct MotionSegmentOptions {
  double max_gap_s = 0.05;        ///< a longer time step splits the sequence
  double max_speed_mps = 4.0;     ///< a step implying more splits it (mocap glitches)
  double max_turn_rad_s = 15.0;   ///< same for rotation
  double min_length_s = 5.0;      ///< shorter pieces are dropped
};
/// Reads a TUM (.txt) or EuRoC/TUM-VI (.csv) trajectory, tolerating lines whose time does not
/// increase (they are dropped; counted in *dropped_lines), cuts it into clean pieces and
/// resamples each at rate_hz. Throws InputError for unreadable files.
std::vector<Trajectory> loadMotionSegments(const std::string& path, double rate_hz,
                                           const MotionSegmentOptions& opt = {},
                                           int* dropped_lines = nullptr);
/// Normalised Gaussian taps at rate_hz with its -3 dB point at cutoff_hz (sigma_t =
/// sqrt(ln 2) / (2 pi cutoff_hz)), cut at 3 sigma.
std::vector<double> gaussianLowPass(double cutoff_hz, double rate_hz);
/// Residual features of one uniformly sampled piece (at config.rate_hz), in physical units;
/// the low-pass's edge samples (3 sigma at each end) are trimmed.
std::vector<Vec6> styleResiduals(const Trajectory& uniform, const StyleModelConfig& config);

struct StyleOptions {
  double strength = 1.0;       ///< scales the generated residual velocities
  /// Scales the sampled standard deviation (sampling temperature); 1 samples the model as
  /// trained.
  double temperature = 1.0;
  double pull_back_hz = 0.1;   ///< leak rate of the offsets towards the base (1/s = 2 pi f)
  int warmup_steps = 256;      ///< samples generated and discarded before the first pose
  /// Replace the base's own motion above config.highpass_hz (the band the model generates)
  /// instead of adding to it: the base supplies the path, the model all the hand-held motion.
  bool replace_base_jitter = true;
};

/// Styles a base trajectory (any rate; the 200 Hz dense poses are meant). Residuals r_k are
/// sampled at the model rate (Philox stream keyed by seed and k, after warmup_steps discarded
/// ones), then integrated into a world-frame position offset d and rotation offset phi with a
/// leak towards the base:
///   d_{k+1} = d_k + dt (strength r_v,k - kappa d_k),   phi likewise with r_w,
///   kappa = 2 pi pull_back_hz.
/// With replace_base_jitter the offsets are taken from the base's low-pass (the same Gaussian
/// as the features' high-pass, computed on the model-rate grid, odd extension at the ends), so
/// the base keeps the path and the model supplies all motion above highpass_hz; otherwise they
/// are added to the base. Styled pose = (Exp(phi) Exp(c_R) R_base, p_base + c_p + d), with
/// (c_p, c_R) the base's low-pass corrections (zero without replace_base_jitter).
/// The force of the collision model: whenever p_base + c_p + d_k is not free (is_free false),
/// d_k is halved until it is (at most 8 times, then 0), and the state continues from there.
/// The offsets are interpolated (Catmull-Rom) to the base's times; an output position that is
/// not free is pulled back to 1/2, 1/4 ... of its offset and finally onto the base pose, so no
/// sample leaves free space if the base does not. Deterministic in (base, model, seed, options).
Trajectory applyStyle(const Trajectory& base_dense, const StyleModel& model, uint64_t seed,
                      const std::function<bool(const Vec3&)>& is_free,
                      const StyleOptions& options);
inline Trajectory applyStyle(const Trajectory& base_dense, const StyleModel& model,
                             uint64_t seed, const std::function<bool(const Vec3&)>& is_free,
                             double strength = 1.0) {
  StyleOptions o;
  o.strength = strength;
  return applyStyle(base_dense, model, seed, is_free, o);
}

}  // namespace inet
