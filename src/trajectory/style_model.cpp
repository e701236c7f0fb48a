#include "trajectory/style_model.h"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "core/atomic_file.h"
#include "core/weights_file.h"
#include "core/error.h"
#include "core/rng.h"
#include "trajectory/formats.h"
#include "trajectory/spectrum.h"

namespace inet {
namespace {

constexpr char kMagic[8] = {'I', 'N', 'E', 'T', 'S', 'T', 'Y', 'L'};
constexpr uint32_t kFormatVersion = 1;
constexpr uint32_t kStyleRngTag = 0x57594c45;  // "STYLE": the style's Philox sub-stream

nlohmann::json configToJson(const StyleModelConfig& c) {
  return {{"rate_hz", c.rate_hz},           {"highpass_hz", c.highpass_hz}, {"lowpass_hz", c.lowpass_hz},
          {"channels", c.channels},         {"skip_channels", c.skip_channels},
          {"head_channels", c.head_channels}, {"dilations", c.dilations},
          {"min_log_var", c.min_log_var},   {"max_log_var", c.max_log_var}};
}

StyleModelConfig configFromJson(const nlohmann::json& j) {
  StyleModelConfig c;
  c.rate_hz = j.at("rate_hz").get<double>();
  c.highpass_hz = j.at("highpass_hz").get<double>();
  c.lowpass_hz = j.at("lowpass_hz").get<double>();
  c.channels = j.at("channels").get<int>();
  c.skip_channels = j.at("skip_channels").get<int>();
  c.head_channels = j.at("head_channels").get<int>();
  c.dilations = j.at("dilations").get<std::vector<int>>();
  c.min_log_var = j.at("min_log_var").get<double>();
  c.max_log_var = j.at("max_log_var").get<double>();
  return c;
}

Eigen::VectorXd sigmoid(const Eigen::VectorXd& a) {
  return (1.0 + (-a.array()).exp()).inverse().matrix();
}

/// Head: (mean, clamped log_var) from the summed skip activations.
template <class S>
auto head(const StyleModel& m, const S& s) {
  Eigen::MatrixXd h1 = ((m.head1_w * s.cwiseMax(0.0)).colwise() + m.head1_b).cwiseMax(0.0);
  Eigen::MatrixXd o = (m.head2_w * h1).colwise() + m.head2_b;
  o.bottomRows(6) = o.bottomRows(6).cwiseMax(m.config.min_log_var).cwiseMin(m.config.max_log_var);
  return o;
}

}  // namespace

int StyleModelConfig::receptiveField() const {
  int rf = 1;
  for (int d : dilations) rf += d;
  return rf;
}

void StyleModel::forEachTensor(
    const std::function<void(const std::string&, Eigen::MatrixXd&)>& f) {
  auto vec = [&](const std::string& name, Eigen::VectorXd& v) {
    Eigen::MatrixXd m = v;
    f(name, m);
    v = m.col(0);
  };
  f("in_w", in_w);
  vec("in_b", in_b);
  for (size_t l = 0; l < layers.size(); ++l) {
    std::string p = "l";  // (not "l" + to_string: GCC 12 -Wrestrict false positive)
    p += std::to_string(l);
    p += ".";
    StyleLayer& L = layers[l];
    f(p + "past", L.past);
    f(p + "now", L.now);
    vec(p + "b", L.b);
    f(p + "res_w", L.res_w);
    vec(p + "res_b", L.res_b);
    f(p + "skip_w", L.skip_w);
    vec(p + "skip_b", L.skip_b);
  }
  f("head1_w", head1_w);
  vec("head1_b", head1_b);
  f("head2_w", head2_w);
  vec("head2_b", head2_b);
}

StyleModel StyleModel::random(const StyleModelConfig& config, uint64_t seed) {
  StyleModel m;
  m.config = config;
  const int C = config.channels, S = config.skip_channels, H = config.head_channels;
  m.in_w.resize(C, 6);
  m.in_b.resize(C);
  for (int d : config.dilations) {
    StyleLayer L;
    L.dilation = d;
    L.past.resize(2 * C, C);
    L.now.resize(2 * C, C);
    L.b.resize(2 * C);
    L.res_w.resize(C, C);
    L.res_b.resize(C);
    L.skip_w.resize(S, C);
    L.skip_b.resize(S);
    m.layers.push_back(L);
  }
  m.head1_w.resize(H, S);
  m.head1_b.resize(H);
  m.head2_w.resize(12, H);
  m.head2_b.resize(12);
  uint32_t index = 0;
  int fan_in = 6;
  m.forEachTensor([&](const std::string& name, Eigen::MatrixXd& t) {
    // a bias shares its weight's fan-in; a kernel-2 convolution has 2 C inputs
    if (t.cols() > 1) fan_in = name.ends_with("past") || name.ends_with("now") ? 2 * C : t.cols();
    CounterRng rng(seed, RngStream::Trajectory, kStyleRngTag + 1, index++, 0);
    const double bound = 1.0 / std::sqrt(static_cast<double>(fan_in));
    for (Eigen::Index i = 0; i < t.size(); ++i) t.data()[i] = rng.uniformDouble(-bound, bound);
  });
  return m;
}

size_t StyleModel::parameterCount() const {
  size_t n = 0;
  StyleModel copy = *this;
  copy.forEachTensor([&](const std::string&, Eigen::MatrixXd& t) { n += t.size(); });
  return n;
}

Eigen::MatrixXd StyleModel::forward(const Eigen::MatrixXd& x) const {
  INET_CHECK(x.rows() == 6);
  const Eigen::Index T = x.cols(), C = config.channels;
  Eigen::MatrixXd h = (in_w * x).colwise() + in_b;
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(config.skip_channels, T);
  for (const StyleLayer& L : layers) {
    Eigen::MatrixXd shifted = Eigen::MatrixXd::Zero(C, T);
    if (T > L.dilation) shifted.rightCols(T - L.dilation) = h.leftCols(T - L.dilation);
    Eigen::MatrixXd a = ((L.past * shifted + L.now * h).colwise() + L.b);
    Eigen::MatrixXd z = a.topRows(C).array().tanh() *
                        (1.0 + (-a.bottomRows(C).array()).exp()).inverse();
    h += (L.res_w * z).colwise() + L.res_b;
    s += (L.skip_w * z).colwise() + L.skip_b;
  }
  return head(*this, s);
}

StyleStream::StyleStream(const StyleModel& model) : m_(model) {
  for (const StyleLayer& L : model.layers) {
    hist_.push_back(Eigen::MatrixXd::Zero(model.config.channels, L.dilation));
    head_.push_back(0);
  }
}

Eigen::Matrix<double, 12, 1> StyleStream::push(const Vec6& x) {
  const int C = m_.config.channels;
  h_ = m_.in_w * x + m_.in_b;
  s_.setZero(m_.config.skip_channels);
  for (size_t l = 0; l < m_.layers.size(); ++l) {
    const StyleLayer& L = m_.layers[l];
    auto past = hist_[l].col(head_[l]);  // h_l[t - d]: written d pushes ago (zero before)
    a_.noalias() = L.past * past;
    a_.noalias() += L.now * h_;
    a_ += L.b;
    past = h_;
    head_[l] = (head_[l] + 1) % L.dilation;
    z_ = a_.head(C).array().tanh() * sigmoid(a_.tail(C)).array();
    h_.noalias() += L.res_w * z_;
    h_ += L.res_b;
    s_.noalias() += L.skip_w * z_;
    s_ += L.skip_b;
  }
  return head(m_, s_);
}

void saveStyleModel(const StyleModel& model, const std::string& path) {
  StyleModel copy = model;
  nlohmann::json header{{"config", configToJson(model.config)}, {"tensors", nlohmann::json::array()}};
  header["scale"] = std::vector<double>(model.scale.data(), model.scale.data() + 6);
  std::vector<float> data;
  copy.forEachTensor([&](const std::string& name, Eigen::MatrixXd& t) {
    header["tensors"].push_back({{"name", name}, {"rows", t.rows()}, {"cols", t.cols()}});
    for (Eigen::Index r = 0; r < t.rows(); ++r)
      for (Eigen::Index c = 0; c < t.cols(); ++c) data.push_back(static_cast<float>(t(r, c)));
  });
  writeTextAtomic(path, encodeWeightsFile(std::string(kMagic, 8), kFormatVersion, header.dump(), data));
}

StyleModel loadStyleModel(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the style model weights");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  WeightsFileReader file(std::move(bytes), path, std::string(kMagic, 8), kFormatVersion,
                         "a style model weights file");
  nlohmann::json header;
  StyleModel m;
  try {
    header = nlohmann::json::parse(file.header());
    m = StyleModel::random(configFromJson(header.at("config")), 0);
    const auto scale = header.at("scale").get<std::vector<double>>();
    if (scale.size() != 6) throw InputError(path, "scale", "needs 6 values");
    for (int i = 0; i < 6; ++i) m.scale[i] = scale[i];
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "header", e.what());
  }
  size_t index = 0;
  m.forEachTensor([&](const std::string& name, Eigen::MatrixXd& t) {
    const auto& spec = header["tensors"];
    if (index >= spec.size() || spec[index].value("name", "") != name ||
        spec[index].value("rows", -1) != t.rows() || spec[index].value("cols", -1) != t.cols())
      throw InputError(path, "tensors", "tensor " + std::to_string(index) + " is not " + name +
                                            " of " + std::to_string(t.rows()) + " x " +
                                            std::to_string(t.cols()));
    ++index;
    const std::vector<float> v = file.readFloats(static_cast<size_t>(t.size()), name);
    for (Eigen::Index r = 0; r < t.rows(); ++r)
      for (Eigen::Index c = 0; c < t.cols(); ++c) t(r, c) = v[r * t.cols() + c];
  });
  file.finish();
  return m;
}

std::string defaultStyleModelPath() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("INET_STYLE_MODEL"); env != nullptr && *env != '\0')
    return env;
  const fs::path source = INET_STYLE_MODEL_SOURCE_PATH;
  std::error_code ec;
  if (fs::exists(source, ec)) return source.string();
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed =
        exe.parent_path().parent_path() / "share/interiornet/style" / source.filename();
    if (fs::exists(installed, ec)) return installed.string();
  }
  return source.string();  // loading then names the expected file
}

const StyleModel& builtinStyleModel() {
  static const StyleModel model = loadStyleModel(defaultStyleModelPath());
  return model;
}

// ---- data ----

std::vector<Trajectory> loadMotionSegments(const std::string& path, double rate_hz,
                                           const MotionSegmentOptions& opt, int* dropped_lines) {
  // drop lines whose time does not increase (fr2_desk repeats a stamp), then parse strictly
  const std::string text = readTextFile(path);
  const bool seconds = detectTrajectoryFormat(path, text) == TrajectoryFormat::Tum;
  std::istringstream lines(text);
  std::string line, kept;
  TimeNs last = std::numeric_limits<TimeNs>::min();
  int dropped = 0;
  while (std::getline(lines, line)) {
    const size_t b = line.find_first_not_of(" \t");
    if (b != std::string::npos && line[b] != '#') {
      const std::string first = line.substr(b, line.find_first_of(" \t,", b) - b);
      TimeNs t = 0;
      bool ok = seconds && parseSecondsToNs(first, t);
      if (!seconds) {
        try {
          t = std::stoll(first);
          ok = true;
        } catch (const std::exception&) {
        }
      }
      if (ok && t <= last) {
        ++dropped;
        continue;
      }
      if (ok) last = t;
    }
    kept += line + "\n";
  }
  if (dropped_lines != nullptr) *dropped_lines = dropped;
  const Trajectory all = parseTrajectory(kept, path, detectTrajectoryFormat(path, kept));
  std::vector<Trajectory> out;
  Trajectory piece;
  auto flush = [&] {
    if (piece.size() >= 2 && 1e-9 * static_cast<double>(piece.poses.back().t_ns -
                                                         piece.poses.front().t_ns) >=
                                 opt.min_length_s)
      out.push_back(resampleUniform(piece, rate_hz));
    piece.poses.clear();
  };
  for (const TimedPose& p : all.poses) {
    if (!piece.empty()) {
      const TimedPose& q = piece.poses.back();
      const double dt = 1e-9 * static_cast<double>(p.t_ns - q.t_ns);
      const double speed = (p.T_world_camera.t - q.T_world_camera.t).norm() / dt;
      const double turn = p.T_world_camera.q.angularDistance(q.T_world_camera.q) / dt;
      if (dt > opt.max_gap_s || speed > opt.max_speed_mps || turn > opt.max_turn_rad_s) flush();
    }
    piece.poses.push_back(p);
  }
  flush();
  return out;
}

std::vector<double> gaussianLowPass(double cutoff_hz, double rate_hz) {
  const double sigma = std::sqrt(std::log(2.0)) / (2 * std::numbers::pi * cutoff_hz) * rate_hz;
  const int half = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> kernel(2 * half + 1);
  double sum = 0;
  for (int i = -half; i <= half; ++i) sum += kernel[i + half] = std::exp(-0.5 * i * i / (sigma * sigma));
  for (double& k : kernel) k /= sum;
  return kernel;
}

std::vector<Vec6> styleResiduals(const Trajectory& uniform, const StyleModelConfig& config) {
  const MotionSeries m = motionSeries(uniform, config.rate_hz);
  const std::vector<double> lo = gaussianLowPass(config.highpass_hz, config.rate_hz);
  const std::vector<double> hi = config.lowpass_hz > 0
                                     ? gaussianLowPass(config.lowpass_hz, config.rate_hz)
                                     : std::vector<double>{1.0};
  const int half = static_cast<int>(lo.size() / 2), half_hi = static_cast<int>(hi.size() / 2);
  auto filter = [&](const std::vector<double>& kernel, int h, int k) {
    Vec6 out = Vec6::Zero();
    for (int i = -h; i <= h; ++i) {
      out.head<3>() += kernel[i + h] * m.v_world[k + i];
      out.tail<3>() += kernel[i + h] * m.w_world[k + i];
    }
    return out;
  };
  std::vector<Vec6> out;
  const int n = static_cast<int>(m.v_world.size());
  for (int k = half; k + half < n; ++k) out.push_back(filter(hi, half_hi, k) - filter(lo, half, k));
  return out;
}

// ---- styling ----

namespace {

/// Uniform Catmull-Rom through samples y (extended linearly at the ends) at fractional index u.
template <class V>
V catmullRom(const std::vector<V>& y, double u) {
  const int n = static_cast<int>(y.size());
  const int k = std::clamp(static_cast<int>(std::floor(u)), 0, n - 1);
  const double f = std::clamp(u - k, 0.0, 1.0);
  auto at = [&](int i) -> V {  // linear extrapolation past the ends
    if (n < 2) return y[0];
    if (i < 0) return y[0] + i * (y[1] - y[0]);
    if (i > n - 1) return y[n - 1] + (i - n + 1) * (y[n - 1] - y[n - 2]);
    return y[i];
  };
  const V p0 = at(k - 1), p1 = at(k), p2 = at(k + 1), p3 = at(k + 2);
  return 0.5 * ((2 * p1) + (-p0 + p2) * f + (2 * p0 - 5 * p1 + 4 * p2 - p3) * f * f +
                (-p0 + 3 * p1 - 3 * p2 + p3) * f * f * f);
}

Quat expQuat(const Vec3& phi) {
  const double a = phi.norm();
  if (a < 1e-12) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(a, phi / a));
}

/// The base sampled on the style grid t0 + k dt (linear positions, slerp rotations).
std::vector<Pose> baseOnGrid(const Trajectory& base, int n, double rate) {
  std::vector<Pose> out(n);
  size_t j = 0;
  const TimeNs t0 = base.poses.front().t_ns;
  for (int k = 0; k < n; ++k) {
    const TimeNs t = t0 + std::llround(k * 1e9 / rate);
    while (j + 2 < base.size() && base.poses[j + 1].t_ns <= t) ++j;
    const Pose& a = base.poses[j].T_world_camera;
    const Pose& b = base.poses[j + 1].T_world_camera;
    // f > 1 extrapolates the last step linearly (the grid ends up to 2 samples past the base)
    const double f = std::max(0.0, static_cast<double>(t - base.poses[j].t_ns) /
                                       static_cast<double>(base.poses[j + 1].t_ns -
                                                           base.poses[j].t_ns));
    out[k] = Pose{a.q.slerp(f, b.q), (1 - f) * a.t + f * b.t};
  }
  return out;
}

/// Per grid sample, the world-frame corrections that take the base to its Gaussian low-pass
/// (config.highpass_hz): position LP(p) - p and rotation Log(LP(R) R^T), where LP(R)_k =
/// R_k Exp(sum_i g_i Log(R_k^T R_{k+i})) (a weighted mean in the tangent space at R_k; the
/// kernel is cut at 3 sigma; the ends use an odd extension).
void lowPassCorrections(const std::vector<Pose>& grid, const StyleModelConfig& config,
                        std::vector<Vec3>& dp, std::vector<Vec3>& dr) {
  const int n = static_cast<int>(grid.size());
  const std::vector<double> g = gaussianLowPass(config.highpass_hz, config.rate_hz);
  const int half = static_cast<int>(g.size() / 2);
  dp.assign(n, Vec3::Zero());
  dr.assign(n, Vec3::Zero());
  // beyond the ends the samples are mirrored through the end point (odd extension), so a
  // steady motion is its own low-pass all the way to the ends
  auto mirror = [n](int j, int& end) {
    end = j < 0 ? 0 : n - 1;
    return std::clamp(j < 0 ? -j : 2 * (n - 1) - j, 0, n - 1);
  };
  for (int k = 0; k < n; ++k) {
    const Quat qk_inv = grid[k].q.conjugate();
    auto log_at = [&](int j) {
      const Eigen::AngleAxisd aa(qk_inv * grid[j].q);
      return Vec3(aa.angle() * aa.axis());
    };
    Vec3 p = Vec3::Zero(), r = Vec3::Zero();
    for (int i = -half; i <= half; ++i) {
      const int j = k + i;
      const double w = g[i + half];
      if (j >= 0 && j < n) {
        p += w * grid[j].t;
        r += w * log_at(j);
      } else {
        int end = 0;
        const int m = mirror(j, end);
        p += w * (2 * grid[end].t - grid[m].t);
        r += w * (2 * log_at(end) - log_at(m));
      }
    }
    dp[k] = p - grid[k].t;
    dr[k] = grid[k].q * r;  // body-frame tangent -> world frame
  }
}

}  // namespace

Trajectory applyStyle(const Trajectory& base_dense, const StyleModel& model, uint64_t seed,
                      const std::function<bool(const Vec3&)>& is_free,
                      const StyleOptions& options) {
  if (base_dense.size() < 2) return base_dense;
  const double rate = model.config.rate_hz, dt = 1.0 / rate;
  const double kappa = 2 * std::numbers::pi * options.pull_back_hz;
  const TimeNs t0 = base_dense.poses.front().t_ns;
  const double span_s = 1e-9 * static_cast<double>(base_dense.poses.back().t_ns - t0);
  const int n = static_cast<int>(std::floor(span_s * rate)) + 3;  // Catmull-Rom needs k + 2
  const std::vector<Pose> grid = baseOnGrid(base_dense, n, rate);
  std::vector<Vec3> c_pos(n, Vec3::Zero()), c_rot(n, Vec3::Zero());
  if (options.replace_base_jitter) lowPassCorrections(grid, model.config, c_pos, c_rot);
  std::vector<Vec3> d_grid(n), phi_grid(n);
  StyleStream stream(model);
  Vec6 x = Vec6::Zero();
  Vec3 d = Vec3::Zero(), phi = Vec3::Zero();
  for (int step = 0; step < options.warmup_steps + n; ++step) {
    const Eigen::Matrix<double, 12, 1> o = stream.push(x);
    CounterRng rng(seed, RngStream::Trajectory, kStyleRngTag, static_cast<uint32_t>(step), 0);
    for (int c = 0; c < 6; ++c)
      x[c] = o[c] + options.temperature * std::exp(0.5 * o[6 + c]) * rng.normal();
    const Vec6 r = x.cwiseProduct(model.scale) * options.strength;
    d += dt * (r.head<3>() - kappa * d);
    phi += dt * (r.tail<3>() - kappa * phi);
    if (step >= options.warmup_steps) {
      d_grid[step - options.warmup_steps] = c_pos[step - options.warmup_steps] + d;
      phi_grid[step - options.warmup_steps] = phi;
    }
  }
  // The collision force, smooth so that it adds no acceleration spikes: per grid sample the
  // largest free fraction of the offset (1, 3/4, 1/2, 1/4, 0), eroded (minimum over +-W) and
  // then blurred over the same support, which keeps every fraction at or below its raw value.
  std::vector<double> frac(n), eroded(n);
  for (int k = 0; k < n; ++k) {
    frac[k] = 1.0;
    while (frac[k] > 0 && !is_free(grid[k].t + frac[k] * d_grid[k])) frac[k] -= 0.25;
    frac[k] = std::max(frac[k], 0.0);
  }
  const int W = static_cast<int>(std::lround(0.25 * rate));
  for (int k = 0; k < n; ++k) {
    eroded[k] = 1.0;
    for (int i = std::max(0, k - W); i <= std::min(n - 1, k + W); ++i)
      eroded[k] = std::min(eroded[k], frac[i]);
  }
  for (int k = 0; k < n; ++k) {
    double sum = 0, wsum = 0;
    for (int i = std::max(0, k - W); i <= std::min(n - 1, k + W); ++i) {
      const double u = (i - k) / (0.4 * W), w = std::exp(-0.5 * u * u);
      sum += w * eroded[i];
      wsum += w;
    }
    d_grid[k] *= sum / wsum;
  }
  // Styled poses on the grid, then interpolated to the base's times: with
  // replace_base_jitter only the grid poses count (the base's own motion between grid samples
  // is above the band and is replaced too); otherwise the offsets ride on every base pose.
  std::vector<Vec3> pos(n);
  std::vector<Eigen::Vector4d> rot(n);
  for (int k = 0; k < n; ++k) {
    pos[k] = grid[k].t + d_grid[k];
    rot[k] = (expQuat(phi_grid[k]) * expQuat(c_rot[k]) * grid[k].q).coeffs();
    if (k > 0 && rot[k].dot(rot[k - 1]) < 0) rot[k] = -rot[k];
  }
  Trajectory out = base_dense;
  for (TimedPose& p : out.poses) {
    const double u = 1e-9 * static_cast<double>(p.t_ns - t0) * rate;
    const Vec3 base = p.T_world_camera.t;
    Vec3 off = options.replace_base_jitter ? Vec3(catmullRom(pos, u) - base)
                                           : catmullRom(d_grid, u);
    for (int tries = 0; !is_free(base + off) && tries <= 4; ++tries)
      off = tries == 4 ? Vec3::Zero() : Vec3(0.5 * off);
    p.T_world_camera.t = base + off;
    if (options.replace_base_jitter) {
      p.T_world_camera.q.coeffs() = catmullRom(rot, u).normalized();
    } else {
      p.T_world_camera.q = (expQuat(catmullRom(phi_grid, u)) * p.T_world_camera.q).normalized();
    }
  }
  return out;
}

}  // namespace inet
