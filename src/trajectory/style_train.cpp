#include "trajectory/style_train.h"

#include <torch/torch.h>
#include <torch/version.h>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/rng.h"

namespace inet {
namespace {

constexpr uint32_t kTrainRngTag = 0x54524e53;  // "TRNS"

torch::Tensor toTensor(const Eigen::MatrixXd& m, torch::Dtype dtype) {
  torch::Tensor t = torch::empty({m.rows(), m.cols()}, torch::kFloat64);
  auto acc = t.accessor<double, 2>();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) acc[r][c] = m(r, c);
  return t.to(dtype);
}

Eigen::MatrixXd toEigen(const torch::Tensor& t2) {
  torch::Tensor t = t2.detach().to(torch::kFloat64).contiguous();
  Eigen::MatrixXd m(t.size(0), t.size(1));
  auto acc = t.accessor<double, 2>();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) m(r, c) = acc[r][c];
  return m;
}

/// The network's parameters as torch tensors, in StyleModel::forEachTensor order.
struct TorchNet {
  StyleModelConfig config;
  std::vector<torch::Tensor> p;

  TorchNet(const StyleModel& model, torch::Dtype dtype, bool grad) : config(model.config) {
    StyleModel copy = model;
    copy.forEachTensor([&](const std::string&, Eigen::MatrixXd& m) {
      p.push_back(toTensor(m, dtype).set_requires_grad(grad));
    });
  }
  void exportTo(StyleModel& model) const {
    size_t i = 0;
    model.forEachTensor([&](const std::string&, Eigen::MatrixXd& m) { m = toEigen(p[i++]); });
  }
  /// x: B x 6 x T -> B x 12 x T (mean, clamped log_var).
  torch::Tensor forward(const torch::Tensor& x) const {
    auto lin = [](const torch::Tensor& w, const torch::Tensor& b, const torch::Tensor& h) {
      return torch::matmul(w, h) + b;  // b: rows x 1 broadcasts over time
    };
    const int64_t C = config.channels;
    size_t i = 0;
    torch::Tensor h = lin(p[0], p[1], x);
    i = 2;
    torch::Tensor s;
    for (int d : config.dilations) {
      const torch::Tensor w = torch::stack({p[i], p[i + 1]}, 2);  // 2C x C x 2: (past, now)
      const int64_t stride[] = {1}, padding[] = {0}, dilation[] = {d};
      torch::Tensor a = torch::conv1d(torch::constant_pad_nd(h, {d, 0}), w, p[i + 2].squeeze(1),
                                      at::IntArrayRef(stride), at::IntArrayRef(padding),
                                      at::IntArrayRef(dilation));
      torch::Tensor z = torch::tanh(a.narrow(1, 0, C)) * torch::sigmoid(a.narrow(1, C, C));
      h = h + lin(p[i + 3], p[i + 4], z);
      torch::Tensor sk = lin(p[i + 5], p[i + 6], z);
      s = s.defined() ? s + sk : sk;
      i += 7;
    }
    torch::Tensor h1 = torch::relu(lin(p[i], p[i + 1], torch::relu(s)));
    torch::Tensor o = lin(p[i + 2], p[i + 3], h1);
    torch::Tensor lv = torch::clamp(o.narrow(1, 6, 6), config.min_log_var, config.max_log_var);
    return torch::cat({o.narrow(1, 0, 6), lv}, 1);
  }
};

/// Mean Gaussian NLL of x[:, :, 1:] under the predictions o[:, :, :-1].
torch::Tensor nll(const torch::Tensor& o, const torch::Tensor& x) {
  const int64_t T = x.size(2);
  torch::Tensor mean = o.narrow(1, 0, 6).narrow(2, 0, T - 1);
  torch::Tensor lv = o.narrow(1, 6, 6).narrow(2, 0, T - 1);
  torch::Tensor y = x.narrow(2, 1, T - 1);
  return 0.5 * (lv + (y - mean).pow(2) * torch::exp(-lv) + std::log(2 * std::numbers::pi))
                   .mean();
}

struct DataFile {
  std::string name, role;
  uintmax_t bytes = 0;
  uint64_t hash = 0;
  int segments = 0, dropped_lines = 0;
  double seconds = 0;
  std::vector<Eigen::MatrixXd> residuals;  ///< 6 x T per piece, physical units
};

DataFile loadFile(const StyleTrainOptions& opt, const std::string& name, const std::string& role) {
  const std::string path = (std::filesystem::path(opt.data_dir) / name).string();
  DataFile f;
  f.name = name;
  f.role = role;
  const std::string text = readTextFile(path);
  f.bytes = text.size();
  f.hash = stableHash(text);
  for (const Trajectory& seg : loadMotionSegments(path, opt.config.rate_hz, {}, &f.dropped_lines)) {
    const std::vector<Vec6> r = styleResiduals(seg, opt.config);
    if (static_cast<int>(r.size()) < opt.window) continue;
    Eigen::MatrixXd m(6, r.size());
    for (size_t k = 0; k < r.size(); ++k) m.col(k) = r[k];
    f.residuals.push_back(m);
    f.seconds += r.size() / opt.config.rate_hz;
    ++f.segments;
  }
  if (f.segments == 0)
    throw InputError(path, "", "no clean piece as long as a training window");
  return f;
}

/// Horizontal and vertical RMS of v and w over the training residuals.
Vec6 measureScale(const std::vector<DataFile>& files) {
  double sum[4] = {0, 0, 0, 0};
  double n = 0;
  for (const DataFile& f : files) {
    if (f.role != "train") continue;
    for (const Eigen::MatrixXd& m : f.residuals) {
      sum[0] += m.topRows(2).squaredNorm() / 2;
      sum[1] += m.row(2).squaredNorm();
      sum[2] += m.middleRows(3, 2).squaredNorm() / 2;
      sum[3] += m.row(5).squaredNorm();
      n += m.cols();
    }
  }
  Vec6 s;
  s << std::sqrt(sum[0] / n), std::sqrt(sum[0] / n), std::sqrt(sum[1] / n),
      std::sqrt(sum[2] / n), std::sqrt(sum[2] / n), std::sqrt(sum[3] / n);
  return s;
}

/// Mean NLL over fixed non-overlapping windows of one role's files.
double evaluate(const TorchNet& net, const std::vector<DataFile>& files, const std::string& role,
                const Vec6& scale, int window) {
  torch::NoGradGuard no_grad;
  double sum = 0;
  int64_t count = 0;
  for (const DataFile& f : files) {
    if (f.role != role) continue;
    for (const Eigen::MatrixXd& m : f.residuals) {
      const Eigen::MatrixXd x = scale.cwiseInverse().asDiagonal() * m;
      for (Eigen::Index s = 0; s + window <= x.cols(); s += window) {
        torch::Tensor t = toTensor(x.middleCols(s, window), torch::kFloat32).unsqueeze(0);
        sum += nll(net.forward(t), t).item<double>();
        ++count;
      }
    }
  }
  return count > 0 ? sum / count : std::nan("");
}

}  // namespace

Eigen::MatrixXd torchStyleForward(const StyleModel& model, const Eigen::MatrixXd& x,
                                  bool double_precision) {
  torch::NoGradGuard no_grad;
  const torch::Dtype dt = double_precision ? torch::kFloat64 : torch::kFloat32;
  TorchNet net(model, dt, false);
  return toEigen(net.forward(toTensor(x, dt).unsqueeze(0)).squeeze(0));
}

StyleTrainResult trainStyleModel(const StyleTrainOptions& opt,
                                 const std::function<void(int, int, double)>& progress) {
  if (opt.train.empty()) throw InputError("", "--train", "needs at least one file");
  std::set<std::string> train_set(opt.train.begin(), opt.train.end());
  for (const std::string& h : opt.holdout)
    if (train_set.count(h)) throw InputError(h, "--holdout", "is also in --train");
  if (opt.epochs < 1 || opt.batch < 1 || opt.window < 16)
    throw InputError("", "--epochs", "epochs and batch must be >= 1, window >= 16");
  const auto start = std::chrono::steady_clock::now();
  torch::set_num_threads(opt.threads);
  torch::manual_seed(opt.seed);

  std::vector<DataFile> files;
  for (const std::string& n : opt.train) files.push_back(loadFile(opt, n, "train"));
  for (const std::string& n : opt.holdout) files.push_back(loadFile(opt, n, "holdout"));
  StyleTrainResult result;
  result.model = StyleModel::random(opt.config, opt.seed);
  result.model.scale = measureScale(files);
  const Vec6 inv = result.model.scale.cwiseInverse();
  std::vector<torch::Tensor> train;  // 6 x T normalised pieces
  std::vector<double> weight;        // sampling weight: the piece's window positions
  for (const DataFile& f : files)
    if (f.role == "train")
      for (const Eigen::MatrixXd& m : f.residuals) {
        train.push_back(toTensor(inv.asDiagonal() * m, torch::kFloat32));
        weight.push_back(static_cast<double>(m.cols() - opt.window + 1));
      }
  double total_weight = 0;
  for (double w : weight) total_weight += w;

  TorchNet net(result.model, torch::kFloat32, true);
  torch::optim::Adam adam(net.p, torch::optim::AdamOptions(opt.lr));
  const int steps_per_epoch = std::max(1, opt.windows_per_epoch / opt.batch);
  const int total_steps = steps_per_epoch * opt.epochs;
  nlohmann::json history = nlohmann::json::array();
  double epoch_loss = 0;
  for (int epoch = 0; epoch < opt.epochs; ++epoch) {
    epoch_loss = 0;
    for (int step = 0; step < steps_per_epoch; ++step) {
      const int global = epoch * steps_per_epoch + step;
      const double lr = opt.lr * (0.05 + 0.95 * 0.5 * (1 + std::cos(std::numbers::pi * global /
                                                                     total_steps)));
      for (auto& g : adam.param_groups()) g.options().set_lr(lr);
      std::vector<torch::Tensor> batch;
      for (int b = 0; b < opt.batch; ++b) {
        CounterRng rng(opt.seed, RngStream::Trajectory, kTrainRngTag, global, b);
        double pick = rng.uniformDouble() * total_weight;
        size_t s = 0;
        while (s + 1 < train.size() && pick >= weight[s]) pick -= weight[s++];
        const int64_t off = std::min<int64_t>(static_cast<int64_t>(pick),
                                              train[s].size(1) - opt.window);
        torch::Tensor w = train[s].narrow(1, off, opt.window).clone();
        const double yaw = rng.uniformDouble(0, 2 * std::numbers::pi);
        const double c = std::cos(yaw), sn = std::sin(yaw);
        for (int g = 0; g < 6; g += 3) {  // turn (x, y) of v and of w about z
          torch::Tensor x = w[g].clone(), y = w[g + 1].clone();
          w[g] = c * x - sn * y;
          w[g + 1] = sn * x + c * y;
        }
        batch.push_back(w);
      }
      torch::Tensor x = torch::stack(batch);
      adam.zero_grad();
      // noisy inputs, clean targets: robust to the model's own sampling noise when generating
      torch::Tensor x_in = opt.input_noise > 0 ? x + opt.input_noise * torch::randn_like(x) : x;
      torch::Tensor loss = nll(net.forward(x_in), x);
      loss.backward();
      torch::nn::utils::clip_grad_norm_(net.p, 1.0);
      adam.step();
      epoch_loss += loss.item<double>() / steps_per_epoch;
    }
    history.push_back(epoch_loss);
    if (progress) progress(epoch + 1, opt.epochs, epoch_loss);
  }
  net.exportTo(result.model);
  // report losses with the exported (double) model's float twin, the weights as shipped
  TorchNet final_net(result.model, torch::kFloat32, false);
  result.train_nll = evaluate(final_net, files, "train", result.model.scale, opt.window);
  result.holdout_nll = evaluate(final_net, files, "holdout", result.model.scale, opt.window);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json rec;
  rec["tool"] = "interiornet trajectory train-style";
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  rec["date"] = date;
  rec["torch_version"] = TORCH_VERSION;
  rec["data_dir"] = opt.data_dir;
  rec["data"] = nlohmann::json::array();
  for (const DataFile& f : files)
    rec["data"].push_back({{"file", f.name}, {"role", f.role}, {"bytes", f.bytes},
                           {"fnv1a64", fmt::format("{:016x}", f.hash)},
                           {"pieces", f.segments}, {"seconds_used", f.seconds},
                           {"dropped_lines", f.dropped_lines}});
  rec["split"] = {{"train", opt.train}, {"holdout", opt.holdout}};
  const MotionSegmentOptions seg;
  rec["preprocessing"] = {{"rate_hz", opt.config.rate_hz}, {"highpass_hz", opt.config.highpass_hz},
                          {"lowpass_hz", opt.config.lowpass_hz},
                          {"max_gap_s", seg.max_gap_s}, {"max_speed_mps", seg.max_speed_mps},
                          {"max_turn_rad_s", seg.max_turn_rad_s},
                          {"min_length_s", seg.min_length_s}, {"frame", "world, z up"}};
  rec["model"] = {{"channels", opt.config.channels}, {"skip_channels", opt.config.skip_channels},
                  {"head_channels", opt.config.head_channels},
                  {"dilations", opt.config.dilations},
                  {"receptive_field", opt.config.receptiveField()},
                  {"parameters", result.model.parameterCount()},
                  {"scale", std::vector<double>(result.model.scale.data(),
                                                result.model.scale.data() + 6)}};
  rec["training"] = {{"epochs", opt.epochs}, {"windows_per_epoch", opt.windows_per_epoch},
                     {"window", opt.window}, {"batch", opt.batch}, {"lr", opt.lr},
                     {"schedule", "cosine to lr/20"}, {"grad_clip", 1.0},
                     {"optimizer", "Adam"}, {"seed", opt.seed}, {"threads", opt.threads},
                     {"augmentation", "random yaw per window"},
                     {"input_noise", opt.input_noise},
                     {"seconds", seconds}, {"epoch_train_nll", history}};
  rec["losses"] = {{"metric", "mean Gaussian NLL per sample and channel (normalised units)"},
                   {"train_nll", result.train_nll}, {"holdout_nll", result.holdout_nll}};
  result.record_json = rec.dump(2) + "\n";
  return result;
}

}  // namespace inet
