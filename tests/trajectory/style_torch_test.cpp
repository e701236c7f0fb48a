// The plain C++ style model inference (style_model.h) against LibTorch's forward pass
// (style_train.h), on random weights and on the shipped weights.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/rng.h"
#include "trajectory/style_model.h"
#include "trajectory/style_train.h"

namespace inet {
namespace {

Eigen::MatrixXd randomInput(uint64_t seed, int T) {
  Eigen::MatrixXd x(6, T);
  CounterRng rng(seed, RngStream::Trajectory, 99, 0, 0);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = rng.uniformDouble(-3, 3);
  return x;
}

/// max |a - b| / max |b|
double relativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

void expectEqualToTorch(const StyleModel& model, uint64_t seed) {
  const Eigen::MatrixXd x = randomInput(seed, 400);
  const Eigen::MatrixXd ours = model.forward(x);
  const Eigen::MatrixXd ref64 = torchStyleForward(model, x, true);
  const Eigen::MatrixXd ref32 = torchStyleForward(model, x, false);
  ASSERT_EQ(ours.rows(), 12);
  ASSERT_EQ(ours.cols(), 400);
  // element-wise relative to each value (floor 1e-3) against torch in double precision
  const double elem = ((ours - ref64).array().abs() /
                       ref64.array().abs().max(1e-3)).maxCoeff();
  EXPECT_LT(elem, 1e-5);
  EXPECT_LT(relativeError(ours, ref64), 1e-9);
  // torch in float32 (how it trains): equal to float rounding
  EXPECT_LT(relativeError(ours, ref32), 1e-5);
}

TEST(StyleTorch, ForwardEqualsLibTorchOnRandomWeights) {
  for (uint64_t seed : {1u, 2u, 3u}) expectEqualToTorch(StyleModel::random({}, seed), seed);
}

TEST(StyleTorch, ForwardEqualsLibTorchOnSmallConfig) {
  StyleModelConfig c;
  c.channels = 8;
  c.skip_channels = 5;
  c.head_channels = 7;
  c.dilations = {1, 3, 9};
  expectEqualToTorch(StyleModel::random(c, 5), 5);
}

TEST(StyleTorch, ForwardEqualsLibTorchOnShippedWeights) {
  if (!std::filesystem::exists(defaultStyleModelPath()))
    GTEST_SKIP() << "no shipped weights at " << defaultStyleModelPath();
  expectEqualToTorch(builtinStyleModel(), 11);
}

}  // namespace
}  // namespace inet
