// The learned denoiser against LibTorch: the plain C++ forward pass (neural_denoise.h) equals
// torch's (denoise_train.h), and training on synthetic noisy / clean pairs learns to remove
// noise the way the shipped network is trained to.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/image_io.h"
#include "core/rng.h"
#include "render/denoise_train.h"
#include "render/neural_denoise.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

/// A synthetic dump (render/neural_denoise.h denoiserDump): two walls and a floor with smooth
/// light, noisy reflected colour with relative noise `noise`, seeded per frame and `stream`.
ImageF syntheticDump(int w, int h, uint32_t frame, uint32_t stream, float noise) {
  ImageF d(w, h, 19);
  CounterRng layout(42, RngStream::Sensor, 11, frame, 0);
  const float split = w * (0.3f + 0.4f * layout.uniform()), horizon = h * (0.5f + 0.2f * layout.uniform());
  const float a_left = 0.2f + 0.7f * layout.uniform(), a_right = 0.2f + 0.7f * layout.uniform();
  const float a_floor = 0.1f + 0.5f * layout.uniform();
  const float sun = 0.5f + 3.f * layout.uniform();
  CounterRng rng(42, RngStream::Sensor, 12 + stream, frame, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = d.pixel(x, y);
      const bool floor = y > horizon, left = x < split;
      const float a = floor ? a_floor : left ? a_left : a_right;
      const float light = floor ? sun * (0.5f + 0.5f * x / w) : left ? 1.f : 0.6f + 0.4f * y / h;
      const float nx = floor ? 0.f : left ? 0.7f : -0.7f, ny = floor ? -1.f : 0.f,
                  nz = floor ? 0.f : -0.7f;
      const float mean = a * light;
      for (int c = 0; c < 3; ++c) {
        const float tint = 1.f + 0.1f * c;
        p[c] = std::max(0.f, mean * tint * static_cast<float>(1.0 + noise * rng.normal()));
        p[3 + c] = (noise * mean * tint) * (noise * mean * tint);
        p[6 + c] = p[9 + c] = a * tint;
        p[16 + c] = 0.f;
      }
      p[12] = nx;
      p[13] = ny;
      p[14] = nz;
      p[15] = floor ? 1.f + 2.f * (h - y) / h : 3.f;
    }
  return d;
}

TEST(NeuralDenoiserTorch, PlainForwardPassEqualsTorch) {
  NeuralDenoiserConfig c;
  for (int levels : {1, 2, 4}) {
    c.channels = std::vector<int>{16, 24, 32, 32};
    c.channels.resize(levels);
    NeuralDenoiser net = NeuralDenoiser::random(c, 7 + levels);
    std::vector<float>& head = net.convs.back().weight;  // random() starts it at zero
    for (size_t j = 0; j < head.size(); ++j) head[j] = 0.2f * std::sin(1.7f * static_cast<float>(j));
    const DenoiserInput in = denoiserFeaturesFromDump(syntheticDump(48, 40, 1, 0, 0.5f), 0.01f);
    const ImageF ours = runNeuralDenoiser(net, in.features);
    const ImageF ref = torchNeuralDenoiserForward(net, in.features);
    ASSERT_EQ(ours.width, ref.width);
    ASSERT_EQ(ours.channels, kDenoiserCandidates);
    float worst = 0, scale = 0;
    for (size_t i = 0; i < ours.data.size(); ++i) {
      worst = std::max(worst, std::abs(ours.data[i] - ref.data[i]));
      scale = std::max(scale, std::abs(ref.data[i]));
    }
    EXPECT_GT(scale, 0.01f);
    EXPECT_LT(worst, 2e-5f * scale) << levels << " levels";
  }
}

TEST(NeuralDenoiserTorch, TrainingOnNoisyTargetsRemovesNoise) {
  const fs::path dir = fs::temp_directory_path() / "inet_denoise_train_test";
  fs::remove_all(dir);
  auto write = [&](const std::string& set, uint32_t frame, uint32_t stream, float noise) {
    writeExr(dir / set / (std::to_string(frame) + ".exr"), syntheticDump(64, 48, frame, stream, noise),
             denoiserDumpChannels());
  };
  // inputs at 40 % noise; targets independent at 15 % (Noise2Noise: never clean)
  for (uint32_t f = 0; f < 6; ++f) {
    write("train_in", f, 0, 0.4f);
    write("train_ref", f, 1, 0.15f);
  }
  for (uint32_t f = 100; f < 102; ++f) {
    write("hold_in", f, 0, 0.4f);
    write("hold_ref", f, 1, 0.f);
  }
  DenoiseTrainOptions opt;
  opt.train = {{(dir / "train_in").string(), (dir / "train_ref").string()}};
  opt.holdout = {{(dir / "hold_in").string(), (dir / "hold_ref").string()}};
  opt.config.channels = {8, 12, 16};
  opt.steps = 800;
  opt.batch = 4;
  opt.crop = 32;
  opt.lr = 5e-3;
  opt.threads = 2;
  const DenoiseTrainResult r = trainNeuralDenoiser(opt);
  EXPECT_EQ(r.holdout.frames, 2);
  EXPECT_NEAR(r.holdout.rel_rmse_input, 0.4, 0.05);
  // the network removes most of the noise on frames it never saw, and beats the identity by far
  EXPECT_LT(r.holdout.rel_rmse_network, 0.5 * r.holdout.rel_rmse_input)
      << "atrous " << r.holdout.rel_rmse_atrous;
  // and at least as well as the best fixed filter among its candidates, the à-trous one
  EXPECT_LT(r.holdout.rel_rmse_network, r.holdout.rel_rmse_atrous)
      << "input " << r.holdout.rel_rmse_input;
  EXPECT_NE(r.record_json.find("holdout_files"), std::string::npos);
  // bad input names the field
  DenoiseTrainOptions bad = opt;
  bad.crop = 30;
  EXPECT_THROW(trainNeuralDenoiser(bad), InputError);
  bad = opt;
  bad.train = {{(dir / "train_in").string(), (dir / "hold_ref").string()}};  // no common file
  EXPECT_THROW(trainNeuralDenoiser(bad), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace inet
