// The learned denoiser's plain C++ side (render/neural_denoise.h): features, forward pass,
// weights file, determinism. The forward pass against LibTorch and training are in
// neural_denoise_torch_test.cpp.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/rng.h"
#include "render/neural_denoise.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

/// A frame of three surfaces (a bright wall, a dark floor, a sky strip without surface) with
/// noisy reflected light: reflected, variance, footprint albedo, albedo, normal, depth.
struct TestFrame {
  ImageF reflected, variance, afp, albedo, normal, depth;
  explicit TestFrame(int w = 40, int h = 32, uint64_t seed = 1)
      : reflected(w, h, 3), variance(w, h, 3), afp(w, h, 3), albedo(w, h, 3), normal(w, h, 3),
        depth(w, h, 1) {
    CounterRng rng(seed, RngStream::Sensor, 7, 0, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (y < 4) continue;  // sky: no surface
        const bool floor = y >= h / 2;
        const float a = floor ? 0.2f : 0.8f, light = floor ? 0.3f : 1.5f;
        for (int c = 0; c < 3; ++c) {
          albedo.at(x, y, c) = afp.at(x, y, c) = a;
          reflected.at(x, y, c) = a * light * static_cast<float>(1.0 + 0.4 * rng.normal());
          reflected.at(x, y, c) = std::max(reflected.at(x, y, c), 0.f);
          variance.at(x, y, c) = (0.4f * a * light) * (0.4f * a * light);
        }
        normal.at(x, y, floor ? 1 : 2) = -1.f;
        depth.at(x, y) = floor ? 1.5f + 0.01f * y : 3.f;
      }
  }
};

TEST(NeuralDenoiser, ShapesFollowTheConfig) {
  NeuralDenoiserConfig c;
  c.channels = {8, 12, 16};
  const std::vector<ConvLayer> s = NeuralDenoiser::shapes(c);
  ASSERT_EQ(s.size(), 3u * 2 + 2 + 1);
  EXPECT_EQ(s[0].in, kDenoiserFeatureCount);
  EXPECT_EQ(s[0].out, 8);
  EXPECT_EQ(s[2].in, 8);
  EXPECT_EQ(s[2].out, 12);
  EXPECT_EQ(s[6].in, 16 + 12);  // first decoder: up(enc_2) + enc_1
  EXPECT_EQ(s[7].in, 12 + 8);
  EXPECT_EQ(s[8].k, 1);
  EXPECT_EQ(s[8].out, kDenoiserCandidates);
}

TEST(NeuralDenoiser, FeaturesIgnoreTheExposureAndMarkSurfaces) {
  const TestFrame f;
  const DenoiserInput a =
      denoiserFeatures(f.reflected, f.variance, f.afp, f.albedo, f.normal, f.depth, 0.01f);
  ImageF r4 = f.reflected, v16 = f.variance;
  for (float& v : r4.data) v *= 4.f;
  for (float& v : v16.data) v *= 16.f;
  const DenoiserInput b = denoiserFeatures(r4, v16, f.afp, f.albedo, f.normal, f.depth, 0.01f);
  EXPECT_NEAR(b.scale / a.scale, 4.f, 1e-4f);
  ASSERT_EQ(a.features.data.size(), b.features.data.size());
  for (size_t i = 0; i < a.features.data.size(); ++i)
    EXPECT_NEAR(a.features.data[i], b.features.data[i], 1e-5f) << i;
  EXPECT_EQ(a.valid[0], 0);  // sky
  EXPECT_EQ(a.valid[static_cast<size_t>(10) * 40 + 3], 1);
  for (int c = 0; c < kDenoiserFeatureCount; ++c) EXPECT_EQ(a.features.at(0, 0, c), 0.f);
}

TEST(NeuralDenoiser, TheOutputIsTheChosenMixOfCandidates) {
  NeuralDenoiser net = NeuralDenoiser::random(NeuralDenoiserConfig{}, 3);
  ConvLayer& head = net.convs.back();
  const TestFrame f;
  const DenoiserInput in =
      denoiserFeatures(f.reflected, f.variance, f.afp, f.albedo, f.normal, f.depth, 0.01f);
  ASSERT_EQ(in.candidates.size(), static_cast<size_t>(kDenoiserCandidates));
  for (int pick = 0; pick < kDenoiserCandidates; ++pick) {
    // a head that only has a bias, +40 for candidate `pick` and -40 for the others: after the
    // soft bound (+-8) the others weigh e^-16 each, and the output is that candidate
    std::fill(head.weight.begin(), head.weight.end(), 0.f);
    std::fill(head.bias.begin(), head.bias.end(), -40.f);
    head.bias[pick] = 40.f;
    const ImageF out =
        neuralDenoise(net, f.reflected, f.variance, f.afp, f.albedo, f.normal, f.depth);
    for (size_t i = 0; i < out.pixelCount(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const float want = in.valid[i] ? in.candidates[pick].data[3 * i + c] * in.scale *
                                             std::max(f.afp.data[3 * i + c], 0.01f)
                                       : f.reflected.data[3 * i + c];
        ASSERT_NEAR(out.data[3 * i + c], want, 1e-5f * (1.f + want)) << pick << " " << i;
      }
    }
  }
  // C_0 is the input; the widest geometry-only candidate is nearly flat on the noisy wall
  double var0 = 0, var5 = 0, mean = 0;
  int n = 0;
  for (int y = 6; y < 14; ++y)
    for (int x = 4; x < 36; ++x) {
      const size_t i = static_cast<size_t>(y) * 40 + x;
      EXPECT_NEAR(in.candidates[0].data[3 * i] * in.scale * 0.8f, f.reflected.data[3 * i],
                  1e-5f);
      mean += in.candidates[5].data[3 * i];
      ++n;
    }
  mean /= n;
  for (int y = 6; y < 14; ++y)
    for (int x = 4; x < 36; ++x) {
      const size_t i = static_cast<size_t>(y) * 40 + x;
      var0 += std::pow(in.candidates[0].data[3 * i] - mean, 2);
      var5 += std::pow(in.candidates[5].data[3 * i] - mean, 2);
    }
  EXPECT_LT(var5, 0.02 * var0);
}

TEST(NeuralDenoiser, SameBytesOnAnyThreadCountAndOddSizes) {
  const NeuralDenoiser net = NeuralDenoiser::random(NeuralDenoiserConfig{}, 5);
  const TestFrame f(37, 29, 2);  // not a multiple of 8: padded and cropped
  ImageF one, many;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = neuralDenoise(net, f.reflected, f.variance, f.afp, f.albedo, f.normal, f.depth);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 4);
    many = neuralDenoise(net, f.reflected, f.variance, f.afp, f.albedo, f.normal, f.depth);
  }
  ASSERT_EQ(one.width, 37);
  ASSERT_EQ(one.height, 29);
  EXPECT_TRUE(one == many);
  // pixels without a surface keep their colour
  EXPECT_EQ(one.at(5, 1, 0), f.reflected.at(5, 1, 0));
}

TEST(NeuralDenoiser, WeightsRoundTripAndBadFilesAreOneLineErrors) {
  const fs::path dir = fs::temp_directory_path() / "inet_neural_denoise_test";
  fs::create_directories(dir);
  NeuralDenoiserConfig c;
  c.channels = {4, 6};
  const NeuralDenoiser net = NeuralDenoiser::random(c, 9);
  const std::string path = (dir / "net.bin").string();
  saveNeuralDenoiser(net, path);
  const NeuralDenoiser back = loadNeuralDenoiser(path);
  EXPECT_EQ(back.config.channels, c.channels);
  ASSERT_EQ(back.convs.size(), net.convs.size());
  for (size_t i = 0; i < net.convs.size(); ++i) {
    EXPECT_EQ(back.convs[i].weight, net.convs[i].weight);
    EXPECT_EQ(back.convs[i].bias, net.convs[i].bias);
  }
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto expectError = [&](const std::string& content, const std::string& field) {
    const std::string bad = (dir / "bad.bin").string();
    std::ofstream(bad, std::ios::binary) << content;
    try {
      loadNeuralDenoiser(bad);
      ADD_FAILURE() << "no error for field " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  expectError(bytes.substr(0, bytes.size() - 3), "conv5.bias");
  expectError("INETSTYL" + bytes.substr(8), "magic");
  expectError(bytes + "x", "tensors");
  expectError(bytes.substr(0, 20), "header");
  std::string nan = bytes;
  const uint32_t q = 0x7fc00000u;
  std::memcpy(&nan[nan.size() - 4], &q, 4);
  expectError(nan, "conv5.bias");
  EXPECT_THROW(loadNeuralDenoiser((dir / "missing.bin").string()), InputError);
  fs::remove_all(dir);
}

TEST(NeuralDenoiser, TheShippedWeightsLoad) {
  const std::string path = defaultNeuralDenoiserPath();
  ASSERT_TRUE(fs::exists(path)) << path;
  const NeuralDenoiser& net = defaultNeuralDenoiser();
  EXPECT_GT(net.parameterCount(), 1000u);
}

}  // namespace
}  // namespace inet
