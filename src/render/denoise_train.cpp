#include "render/denoise_train.h"

#include <torch/torch.h>
#include <torch/version.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/rng.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
constexpr uint32_t kTrainRngTag = 0x444e5354;  // "DNST"
/// Targets and scored values are clamped at this many times the frame scale m: a 128-spp target
/// holds single-sample fireflies of 10^4 m (sun glints found by one path), which would dominate
/// both the loss and the scores; real light above 64 m is rarer than 1 pixel in 10^4 (measured
/// on the training frames: the 99.99th percentile is at most 46 m).
constexpr float kClampScale = 64.f;

/// One training pair, whole frame, in torch layout.
struct PairFrame {
  std::string name;                  ///< "<input dir>/<file>"
  uint64_t bytes = 0, hash = 0;      ///< of the input file, for the record
  torch::Tensor features;            ///< F x H x W
  torch::Tensor candidates;          ///< K x 3 x H x W, C_k / m
  torch::Tensor afp;                 ///< 3 x H x W, max(footprint albedo, eps)
  torch::Tensor target;              ///< 3 x H x W, target reflected / m
  torch::Tensor mask;                ///< 1 x H x W, 1 on surface pixels of both
};

torch::Tensor chw(const ImageF& img) {
  torch::Tensor t = torch::from_blob(const_cast<float*>(img.data.data()),
                                     {img.height, img.width, img.channels}, torch::kFloat32);
  // clone: a permute that moves only size-1 dimensions counts as contiguous, and contiguous()
  // would then return a view of the caller's image
  return t.permute({2, 0, 1}).clone(at::MemoryFormat::Contiguous);
}

ImageF fromChw(const torch::Tensor& t3) {
  const torch::Tensor t = t3.detach().to(torch::kFloat32).permute({1, 2, 0}).contiguous();
  ImageF img(static_cast<int>(t.size(1)), static_cast<int>(t.size(0)),
             static_cast<int>(t.size(2)));
  std::memcpy(img.data.data(), t.data_ptr<float>(), sizeof(float) * img.data.size());
  return img;
}

std::vector<PairFrame> loadPairs(const std::vector<DenoiseTrainPairs>& pairs, float eps) {
  std::vector<PairFrame> out;
  for (const DenoiseTrainPairs& p : pairs) {
    for (const std::string& d : {p.input_dir, p.target_dir})
      if (!fs::is_directory(d)) throw InputError(d, "--pairs", "is not a folder");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(p.input_dir))
      if (e.path().extension() == ".exr" && fs::exists(fs::path(p.target_dir) / e.path().filename()))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    if (names.empty())
      throw InputError(p.input_dir, "--pairs",
                       "has no .exr file whose name is also in " + p.target_dir);
    for (const std::string& n : names) {
      const fs::path in_path = fs::path(p.input_dir) / n, ref_path = fs::path(p.target_dir) / n;
      const ImageF in = readExr(in_path, denoiserDumpChannels());
      const ImageF ref = readExr(ref_path, denoiserDumpChannels());
      if (in.width != ref.width || in.height != ref.height)
        throw InputError(ref_path.string(), "size", "differs from " + in_path.string());
      const DenoiserInput f = denoiserFeaturesFromDump(in, eps);
      PairFrame pf;
      pf.name = in_path.string();
      const std::string text = readTextFile(in_path);
      pf.bytes = text.size();
      pf.hash = stableHash(text);
      pf.features = chw(f.features);
      std::vector<torch::Tensor> cand;
      for (const ImageF& c : f.candidates) cand.push_back(chw(c));
      pf.candidates = torch::stack(cand);
      ImageF afp = channelRange(in, 6, 3), target = channelRange(ref, 0, 3);
      ImageF mask(in.width, in.height, 1);
      const float inv_m = 1.f / f.scale;
      for (size_t i = 0; i < in.pixelCount(); ++i) {
        bool ok = f.valid[i] != 0 && ref.data[i * 19 + 15] > 0.f;
        for (int c = 0; c < 3; ++c) {
          afp.data[3 * i + c] = std::max(afp.data[3 * i + c], eps);
          const float t = target.data[3 * i + c];
          ok = ok && std::isfinite(t);
          target.data[3 * i + c] =
              std::isfinite(t) ? std::min(std::max(t, 0.f) * inv_m, kClampScale) : 0.f;
        }
        mask.data[i] = ok ? 1.f : 0.f;
      }
      pf.afp = chw(afp);
      pf.target = chw(target);
      pf.mask = chw(mask);
      out.push_back(std::move(pf));
    }
  }
  return out;
}

/// The U-Net of neural_denoise.h in torch.
struct TorchNet {
  NeuralDenoiserConfig config;
  std::vector<torch::Tensor> p;  // weight, bias per convolution

  TorchNet(const NeuralDenoiser& net, bool grad) : config(net.config) {
    for (const ConvLayer& c : net.convs) {
      p.push_back(torch::from_blob(const_cast<float*>(c.weight.data()), {c.out, c.in, c.k, c.k},
                                   torch::kFloat32)
                      .clone()
                      .set_requires_grad(grad));
      p.push_back(torch::from_blob(const_cast<float*>(c.bias.data()), {c.out}, torch::kFloat32)
                      .clone()
                      .set_requires_grad(grad));
    }
  }
  void exportTo(NeuralDenoiser& net) const {
    for (size_t i = 0; i < net.convs.size(); ++i) {
      const torch::Tensor w = p[2 * i].detach().contiguous(), b = p[2 * i + 1].detach().contiguous();
      std::memcpy(net.convs[i].weight.data(), w.data_ptr<float>(), sizeof(float) * w.numel());
      std::memcpy(net.convs[i].bias.data(), b.data_ptr<float>(), sizeof(float) * b.numel());
    }
  }
  /// x: B x 13 x H x W -> B x 3 x H x W (the log1p residual).
  torch::Tensor forward(const torch::Tensor& x) const {
    const int L = static_cast<int>(config.channels.size());
    size_t k = 0;
    auto conv = [&](const torch::Tensor& h, bool act) {
      const torch::Tensor& w = p[2 * k];
      torch::Tensor y = torch::conv2d(h, w, p[2 * k + 1], 1, w.size(2) / 2);
      ++k;
      return act ? torch::leaky_relu(y, config.leak) : y;
    };
    std::vector<torch::Tensor> enc(L);
    for (int l = 0; l < L; ++l) {
      torch::Tensor h = conv(l == 0 ? x : torch::avg_pool2d(enc[l - 1], 2), true);
      enc[l] = conv(h, true);
    }
    torch::Tensor dec = enc[L - 1];
    for (int l = L - 2; l >= 0; --l) {
      torch::Tensor up = dec.repeat_interleave(2, 2).repeat_interleave(2, 3);
      dec = conv(torch::cat({up, enc[l]}, 1), true);
    }
    return conv(dec, false);
  }
};

/// The prediction y' (normalised units): softmax(8 tanh(logits / 8)) over the candidates, times
/// max(a_fp, eps). logits B x K x H x W, candidates B x K x 3 x H x W, afp B x 3 x H x W.
torch::Tensor predict(const torch::Tensor& logits, const torch::Tensor& candidates,
                      const torch::Tensor& afp) {
  const torch::Tensor w = torch::softmax(8.0 * torch::tanh(logits / 8.0), 1).unsqueeze(2);
  return (w * candidates).sum(1) * afp;
}

torch::Tensor relLoss(const torch::Tensor& pred, const torch::Tensor& target,
                      const torch::Tensor& mask, double floor) {
  const torch::Tensor err = (pred - target).pow(2) / (pred.detach().pow(2) + floor);
  return (err * mask).sum() / (3.0 * mask.sum().clamp_min(1.0));
}

/// Parts of the relative RMSE sqrt(mean (x - y)^2) / mean y over surface pixels: the sums of
/// (x - y)^2 and of y, and the count (per channel value).
struct RelParts {
  double sq = 0, sum = 0, n = 0;
  void add(const torch::Tensor& x, const torch::Tensor& y, const torch::Tensor& mask) {
    const torch::Tensor m = mask.expand_as(y);
    sq += ((x.clamp_max(kClampScale) - y).pow(2) * m).sum().item<double>();
    sum += (y * m).sum().item<double>();
    n += m.sum().item<double>();
  }
  double value() const { return n > 0 && sum > 0 ? std::sqrt(sq / n) / (sum / n) : 0.0; }
};

/// Pads C x H x W at the right and bottom to multiples of `m`.
torch::Tensor padTo(const torch::Tensor& t, int m) {
  const int64_t H = t.size(-2), W = t.size(-1);
  const int64_t ph = (m - H % m) % m, pw = (m - W % m) % m;
  return torch::constant_pad_nd(t, {0, pw, 0, ph});
}

DenoiseHoldoutScores scoreHoldout(const TorchNet& net, const NeuralDenoiser& cpp_net,
                                  const std::vector<PairFrame>& frames, double floor) {
  torch::NoGradGuard no_grad;
  DenoiseHoldoutScores s;
  s.frames = static_cast<int>(frames.size());
  if (frames.empty()) return s;
  double loss = 0;
  RelParts in_parts, at_parts, net_parts;
  const int m = 1 << (cpp_net.config.channels.size() - 1);
  for (const PairFrame& f : frames) {
    const int64_t H = f.features.size(1), W = f.features.size(2);
    const torch::Tensor x = padTo(f.features, m).unsqueeze(0);
    const torch::Tensor logits = net.forward(x).narrow(2, 0, H).narrow(3, 0, W);
    const torch::Tensor cand = f.candidates.unsqueeze(0), afp = f.afp.unsqueeze(0);
    const torch::Tensor pred = predict(logits, cand, afp);
    const torch::Tensor tgt = f.target.unsqueeze(0), mask = f.mask.unsqueeze(0);
    loss += relLoss(pred, tgt, mask, floor).item<double>();
    in_parts.add(cand.select(1, 0) * afp, tgt, mask);  // C_0: the input
    at_parts.add(cand.select(1, 1) * afp, tgt, mask);  // C_1: the à-trous filter
    net_parts.add(pred, tgt, mask);
  }
  s.loss = loss / static_cast<double>(frames.size());
  s.rel_rmse_input = in_parts.value();
  s.rel_rmse_atrous = at_parts.value();
  s.rel_rmse_network = net_parts.value();
  return s;
}

nlohmann::json filesJson(const std::vector<PairFrame>& frames) {
  nlohmann::json j = nlohmann::json::array();
  for (const PairFrame& f : frames)
    j.push_back({{"input", f.name}, {"bytes", f.bytes}, {"fnv1a64", fmt::format("{:016x}", f.hash)}});
  return j;
}

}  // namespace

void DenoiseTrainOptions::validate() const {
  config.validate("");
  if (train.empty()) throw InputError("", "--pairs", "needs at least one input:target pair");
  const int m = 1 << (config.channels.size() - 1);
  if (crop < m || crop % m != 0)
    throw InputError("", "--crop", fmt::format("must be a positive multiple of {}", m));
  if (steps < 1) throw InputError("", "--steps", "must be at least 1");
  if (batch < 1) throw InputError("", "--batch", "must be at least 1");
  if (!(lr > 0 && lr < 1)) throw InputError("", "--lr", "must be in (0, 1)");
  if (threads < 1) throw InputError("", "--threads", "must be at least 1");
}

ImageF torchNeuralDenoiserForward(const NeuralDenoiser& net, const ImageF& features) {
  torch::NoGradGuard no_grad;
  const TorchNet t(net, false);
  return fromChw(t.forward(chw(features).unsqueeze(0)).squeeze(0));
}

DenoiseTrainResult trainNeuralDenoiser(const DenoiseTrainOptions& opt,
                                       const std::function<void(int, int, double)>& progress) {
  opt.validate();
  const auto start = std::chrono::steady_clock::now();
  torch::set_num_threads(opt.threads);
  torch::manual_seed(opt.seed);
  const float eps = opt.config.albedo_epsilon;
  const std::vector<PairFrame> train = loadPairs(opt.train, eps);
  const std::vector<PairFrame> holdout = loadPairs(opt.holdout, eps);
  for (const PairFrame& f : train)
    if (f.features.size(1) < opt.crop || f.features.size(2) < opt.crop)
      throw InputError(f.name, "--crop", fmt::format("the frame is smaller than {} px", opt.crop));

  DenoiseTrainResult result;
  result.net = NeuralDenoiser::random(opt.config, opt.seed);
  TorchNet net(result.net, true);
  torch::optim::Adam adam(net.p, torch::optim::AdamOptions(opt.lr));
  std::vector<double> losses;
  for (int step = 0; step < opt.steps; ++step) {
    const double phase = static_cast<double>(step) / opt.steps;
    const double lr = opt.lr / 20 + (opt.lr - opt.lr / 20) * 0.5 * (1 + std::cos(std::numbers::pi * phase));
    for (auto& g : adam.param_groups()) static_cast<torch::optim::AdamOptions&>(g.options()).lr(lr);
    std::vector<torch::Tensor> xs, cs, as, ts, ms;
    for (int b = 0; b < opt.batch; ++b) {
      CounterRng rng(opt.seed, RngStream::Sensor, kTrainRngTag, static_cast<uint32_t>(step),
                     static_cast<uint32_t>(b));
      const PairFrame& f = train[rng.nextU32() % train.size()];
      const int64_t H = f.features.size(1), W = f.features.size(2);
      const int64_t y0 = rng.nextU32() % (H - opt.crop + 1), x0 = rng.nextU32() % (W - opt.crop + 1);
      const bool fx = rng.nextU32() & 1, fy = rng.nextU32() & 1;
      auto cut = [&](const torch::Tensor& t) {
        torch::Tensor c = t.narrow(1, y0, opt.crop).narrow(2, x0, opt.crop);
        if (fx) c = c.flip({2});
        if (fy) c = c.flip({1});
        return c;
      };
      torch::Tensor x = cut(f.features).clone();
      if (fx) x[9] = -x[9];   // normal x
      if (fy) x[10] = -x[10];  // normal y
      xs.push_back(x);
      torch::Tensor cc = f.candidates.narrow(2, y0, opt.crop).narrow(3, x0, opt.crop);
      if (fx) cc = cc.flip({3});
      if (fy) cc = cc.flip({2});
      cs.push_back(cc);
      as.push_back(cut(f.afp));
      ts.push_back(cut(f.target));
      ms.push_back(cut(f.mask));
    }
    const torch::Tensor x = torch::stack(xs), cand = torch::stack(cs), afp = torch::stack(as),
                        tgt = torch::stack(ts), mask = torch::stack(ms);
    const torch::Tensor loss =
        relLoss(predict(net.forward(x), cand, afp), tgt, mask, opt.loss_floor);
    adam.zero_grad();
    loss.backward();
    torch::nn::utils::clip_grad_norm_(net.p, 1.0);
    adam.step();
    losses.push_back(loss.item<double>());
    if (progress) progress(step + 1, opt.steps, losses.back());
  }
  net.exportTo(result.net);
  const size_t tail = std::max<size_t>(1, losses.size() / 10);
  for (size_t i = losses.size() - tail; i < losses.size(); ++i) result.final_train_loss += losses[i];
  result.final_train_loss /= static_cast<double>(tail);
  const TorchNet final_net(result.net, false);
  result.holdout = scoreHoldout(final_net, result.net, holdout, opt.loss_floor);

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json r;
  r["what"] = "learned denoiser (render/neural_denoise.h), trained by render/denoise_train.cpp";
  r["config"] = {{"channels", opt.config.channels},
                 {"leak", opt.config.leak},
                 {"albedo_epsilon", opt.config.albedo_epsilon}};
  r["parameters"] = result.net.parameterCount();
  r["settings"] = {{"steps", opt.steps}, {"batch", opt.batch}, {"crop", opt.crop},
                   {"lr", opt.lr},       {"seed", opt.seed},   {"threads", opt.threads},
                   {"loss", fmt::format("relative L2, denominator sg(pred)^2 + {}, Noise2Noise targets",
                                        opt.loss_floor)}};
  r["train_files"] = filesJson(train);
  r["holdout_files"] = filesJson(holdout);
  r["final_train_loss"] = result.final_train_loss;
  r["holdout"] = {{"frames", result.holdout.frames},
                  {"loss", result.holdout.loss},
                  {"rel_rmse_input", result.holdout.rel_rmse_input},
                  {"rel_rmse_atrous", result.holdout.rel_rmse_atrous},
                  {"rel_rmse_network", result.holdout.rel_rmse_network},
                  {"note", "against the held-out targets, whose own noise is included"}};
  nlohmann::json curve = nlohmann::json::array();
  const size_t every = std::max<size_t>(1, losses.size() / 50);
  for (size_t i = 0; i < losses.size(); i += every) {
    double s = 0;
    const size_t e = std::min(losses.size(), i + every);
    for (size_t j = i; j < e; ++j) s += losses[j];
    curve.push_back({{"step", e}, {"loss", s / static_cast<double>(e - i)}});
  }
  r["loss_curve"] = curve;
  r["torch"] = TORCH_VERSION;
  r["seconds"] = seconds;
  result.record_json = r.dump(2) + "\n";
  return result;
}

}  // namespace inet
