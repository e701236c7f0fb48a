// eval/feature_consistency and eval/sequence_reader: ORB matches checked against a flow whose
// truth is known by construction (an image and its copy shifted by whole pixels), each rule of
// the classification on its own (tolerance, occlusion, no flow, flat classes), the reader's
// error messages, and the measurement on a generated sequence with its mutations (a flow moved
// by 5 px, images under strong noise).
#include "eval/feature_consistency.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "../expect_input_error.h"
#include "core/atomic_file.h"
#include "core/rng.h"
#include "eval/sequence_reader.h"
#include "generated_sequence.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

constexpr int kW = 320, kH = 240;
constexpr int kShiftX = 5, kShiftY = 3;  // frame k+1 = frame k moved right and down

/// Floor division, so that the texture continues past the left and top edges.
int floorDiv(int a, int b) {
  return a >= 0 ? a / b : (a - b + 1) / b;
}

/// Value noise: random grey on a grid of `cell` px, bilinear in between.
double valueNoise(int x, int y, int cell) {
  const int gx = floorDiv(x, cell), gy = floorDiv(y, cell);
  const double fx = double(x - gx * cell) / cell, fy = double(y - gy * cell) / cell;
  auto v = [cell](int i, int j) {
    CounterRng rng(11, RngStream::Sensor, static_cast<uint32_t>(i + 100000),
                   static_cast<uint32_t>(j + 100000), static_cast<uint32_t>(cell));
    return static_cast<double>(rng.nextU32() & 0xff);
  };
  return (1 - fy) * ((1 - fx) * v(gx, gy) + fx * v(gx + 1, gy)) +
         fy * ((1 - fx) * v(gx, gy + 1) + fx * v(gx + 1, gy + 1));
}

/// A smooth random texture (three octaves of value noise, 16, 8 and 4 px) moved by whole
/// pixels, as 8-bit colour with R = G = B: plenty of distinct ORB corners at every scale.
/// (Square blocks of random grey gave look-alike corners and 20 % false matches.)
ImageU8 textureImage(int shift_x, int shift_y) {
  ImageU8 img(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int sx = x - shift_x, sy = y - shift_y;
      const double v =
          0.5 * valueNoise(sx, sy, 16) + 0.3 * valueNoise(sx, sy, 8) + 0.2 * valueNoise(sx, sy, 4);
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<uint8_t>(v);
    }
  return img;
}

/// The exact flow of the shift (plus an error): constant, valid everywhere, occluded where the
/// pixel leaves the image.
FlowField shiftFlow(float error_u = 0, float error_v = 0) {
  FlowField f;
  f.flow = ImageF(kW, kH, 2);
  f.valid = ImageU8(kW, kH, 1, 1);
  f.occluded = ImageU8(kW, kH, 1, 0);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      f.flow.at(x, y, 0) = kShiftX + error_u;
      f.flow.at(x, y, 1) = kShiftY + error_v;
      f.occluded.at(x, y) = x + kShiftX >= kW || y + kShiftY >= kH;
    }
  return f;
}

struct ShiftedPair : ::testing::Test {
  const ImageU8 a = textureImage(0, 0);
  const ImageU8 b = textureImage(kShiftX, kShiftY);
};

TEST_F(ShiftedPair, ExactFlowMakesNearlyEveryMatchCorrect) {
  const FramePairFeatures r = matchFramePair(a, b, shiftFlow(), {});
  // measured: 847 keypoints, 664 matches, 98 % correct. The rest are ORB's own error: a
  // keypoint of pyramid level L sits on that level's pixel grid, 1.2^L px apart at full size,
  // so a shift that is whole at level 0 is not at level L (errors of 3-7 px there)
  EXPECT_GT(r.keypoints, 700u);
  EXPECT_GT(r.all.matches, 500u);
  EXPECT_EQ(r.all.matches, r.all.correct + r.all.wrong + r.all.occluded + r.all.no_flow);
  EXPECT_EQ(r.all.no_flow, 0u);
  EXPECT_GT(r.all.correctShare(), 0.95) << r.all.toString();
  EXPECT_EQ(r.keypoints_flat, 0u);  // no labels: nothing is flat
  EXPECT_EQ(r.flat.matches, 0u);
}

TEST_F(ShiftedPair, FlowWrongByFivePixelsMakesNearlyNoMatchCorrect) {
  const FramePairFeatures exact = matchFramePair(a, b, shiftFlow(), {});
  const FramePairFeatures r = matchFramePair(a, b, shiftFlow(5, 0), {});
  EXPECT_EQ(r.all.matches, exact.all.matches);  // the same matches, judged differently
  EXPECT_LT(r.all.correctShare(), 0.02) << r.all.toString();
}

TEST_F(ShiftedPair, ToleranceIsTheLargestEndpointError) {
  // a frame matched with itself: every match joins a keypoint to itself (Hamming distance 0),
  // so a flow of (1.5, 2) puts every match exactly 2.5 px from where the flow points
  FlowField off = shiftFlow(1.5f - kShiftX, 2.0f - kShiftY);
  std::fill(off.occluded.data.begin(), off.occluded.data.end(), 0);
  FeatureOptions loose, tight;
  loose.max_error_px = 2.501;
  tight.max_error_px = 2.499;
  const FramePairFeatures l = matchFramePair(a, a, off, {}, loose);
  const FramePairFeatures t = matchFramePair(a, a, off, {}, tight);
  EXPECT_GT(l.all.matches, 700u);
  EXPECT_EQ(l.all.correct, l.all.matches) << l.all.toString();
  EXPECT_EQ(t.all.wrong, t.all.matches) << t.all.toString();
  // the bound itself counts as correct: an error of exactly 3 px (3.0f is exact)
  const FramePairFeatures edge = matchFramePair(a, a, shiftFlow(-kShiftX + 3.0f, -kShiftY), {});
  EXPECT_EQ(edge.all.correct + edge.all.occluded, edge.all.matches);
}

TEST_F(ShiftedPair, OccludedAndUnknownFlowAreCountedApart) {
  FlowField hidden = shiftFlow();
  std::fill(hidden.occluded.data.begin(), hidden.occluded.data.end(), 1);
  const FramePairFeatures h = matchFramePair(a, b, hidden, {});
  EXPECT_GT(h.all.matches, 0u);
  EXPECT_EQ(h.all.occluded, h.all.matches);
  EXPECT_EQ(h.all.checked(), 0u);
  EXPECT_EQ(h.all.correctShare(), 0.0);
  EXPECT_EQ(h.all.occludedShare(), 1.0);

  FlowField unknown = shiftFlow();
  std::fill(unknown.valid.data.begin(), unknown.valid.data.end(), 0);
  const FramePairFeatures u = matchFramePair(a, b, unknown, {});
  EXPECT_EQ(u.all.no_flow, u.all.matches);
}

TEST_F(ShiftedPair, FlatClassesComeFromTheLabelsOfFrameK) {
  const std::vector<int> flat = defaultFlatClasses();
  EXPECT_EQ(flat, (std::vector<int>{1, 2, 22}));  // NYU40 wall, floor, ceiling
  ImageU8 labels(kW, kH, 1, 5);                   // chair
  const FramePairFeatures none = matchFramePair(a, b, shiftFlow(), labels);
  EXPECT_EQ(none.keypoints_flat, 0u);
  std::fill(labels.data.begin(), labels.data.end(), 22);  // ceiling
  const FramePairFeatures all = matchFramePair(a, b, shiftFlow(), labels);
  EXPECT_EQ(all.keypoints_flat, all.keypoints);
  EXPECT_EQ(all.flat.matches, all.all.matches);
  EXPECT_EQ(all.flat.correct, all.all.correct);
  // left half wall: the flat keypoints are those left of the middle
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) labels.at(x, y) = x < kW / 2 ? 1 : 5;
  const FramePairFeatures half = matchFramePair(a, b, shiftFlow(), labels);
  EXPECT_GT(half.keypoints_flat, half.keypoints / 4);
  EXPECT_LT(half.keypoints_flat, 3 * half.keypoints / 4);
  EXPECT_GT(half.flat.matches, 0u);
  EXPECT_LT(half.flat.matches, half.all.matches);
}

TEST_F(ShiftedPair, BilinearSamplingAgreesOnAConstantFlow) {
  FeatureOptions bilinear;
  bilinear.sampling = FlowSampling::Bilinear;
  const FramePairFeatures n = matchFramePair(a, b, shiftFlow(), {});
  const FramePairFeatures l = matchFramePair(a, b, shiftFlow(), {}, bilinear);
  EXPECT_EQ(l.all.correct, n.all.correct);
  EXPECT_EQ(l.all.wrong, n.all.wrong);
}

TEST(FeatureOptions, BadValuesAndNamesAreInputErrors) {
  FeatureOptions o;
  o.max_error_px = 0;
  EXPECT_EQ(test::expectInputError([&] { o.validate(); }).field(), "features.max_error_px");
  o = {};
  o.flat_classes = {41};
  EXPECT_EQ(test::expectInputError([&] { o.validate(); }).field(), "features.flat_classes");
  const InputError e = test::expectInputError([] { parseFlowSampling("cubic"); });
  EXPECT_NE(std::string(e.what()).find("nearest, bilinear"), std::string::npos) << e.what();
}

// ---- the reader's errors ---------------------------------------------------------------------

const char* kMeta = R"({"meta_format_version": 1, "camera": {"width": 4, "height": 3,
  "lens": "pinhole", "renderer": {"fx": 4.0, "fy": 4.0, "cx": 2.0, "cy": 1.5}}})";

TEST(SequenceReader, MissingFolderNamesIt) {
  const InputError e = test::expectInputError([] { SequenceReader r("/nonexistent/seq_000"); });
  EXPECT_EQ(e.file(), "/nonexistent/seq_000");
  EXPECT_NE(e.problem().find("not found"), std::string::npos);
  const InputError f = test::expectInputError([] { featureConsistency("/nonexistent/seq_000"); });
  EXPECT_EQ(f.file(), "/nonexistent/seq_000");
}

TEST(SequenceReader, MetaAndCsvErrorsNameFileAndField) {
  test::TempDir dir("eval_reader");
  const fs::path seq = dir / "seq";
  fs::create_directories(seq);
  InputError e = test::expectInputError([&] { SequenceReader r(seq); });
  EXPECT_EQ(e.file(), (seq / "meta.json").string());

  std::string meta = kMeta;
  meta.replace(meta.find("\"fx\": 4.0, "), 11, "");
  writeTextAtomic(seq / "meta.json", meta);
  e = test::expectInputError([&] { SequenceReader r(seq); });
  EXPECT_EQ(e.file(), (seq / "meta.json").string());
  EXPECT_EQ(e.field(), "camera.renderer.fx");

  writeTextAtomic(seq / "meta.json", kMeta);
  e = test::expectInputError([&] { SequenceReader r(seq); });
  EXPECT_EQ(e.file(), (seq / "cam0" / "data.csv").string());

  writeTextAtomic(seq / "cam0" / "data.csv",
                  "#timestamp [ns],filename\n0000000000000000000,0000000000000000000.png\n"
                  "40000000 0000000000040000000.png\n");
  e = test::expectInputError([&] { SequenceReader r(seq); });
  EXPECT_EQ(e.file(), (seq / "cam0" / "data.csv").string());
  EXPECT_EQ(e.field(), "line 3");

  writeTextAtomic(seq / "cam0" / "data.csv",
                  "#timestamp [ns],filename\n0000000000000000000,0000000000000000000.png\n"
                  "0000000000040000000,0000000000040000000.png\n");
  const SequenceReader r(seq);
  EXPECT_EQ(r.frameCount(), 2u);
  EXPECT_EQ(r.frames()[1].t_ns, 40'000'000);
  EXPECT_DOUBLE_EQ(r.intrinsics().cxOpenCV(), 1.5);
  e = test::expectInputError([&] { r.requireFlow(); });
  EXPECT_EQ(e.file(), (seq / "flow0" / "data.csv").string());
  e = test::expectInputError([&] { r.colour(1); });
  EXPECT_EQ(e.file(), (seq / "cam0" / "data" / "0000000000040000000.png").string());
  e = test::expectInputError([&] { featureConsistency(seq); });
  EXPECT_EQ(e.file(), (seq / "flow0" / "data.csv").string());
}

// ---- a generated sequence --------------------------------------------------------------------

TEST(FeatureConsistency, GeneratedRoomAndItsMutations) {
  test::TempDir dir("eval_features");
  const fs::path seq = test::generateRoom(dir / "out");
  const FeatureConsistencyResult clean = featureConsistency(seq);
  ASSERT_EQ(clean.pairs.size(), static_cast<size_t>(test::kSeqFrames - 1));
  EXPECT_TRUE(clean.labels);
  // measured: 163 keypoints per frame, 99 matches per pair, 0.923 correct, 7 % of the
  // keypoints on wall/floor/ceiling
  EXPECT_GT(clean.keypoints_per_frame, 100);
  EXPECT_GT(clean.matches_per_pair, 50);
  EXPECT_GT(clean.all.correctShare(), 0.85) << clean.toString();
  EXPECT_EQ(clean.all.no_flow, 0u);  // the closed room has a surface behind every pixel
  EXPECT_GT(clean.flat_keypoint_share, 0.0);
  EXPECT_LT(clean.flat_keypoint_share, 0.5);

  // the same run gives the same numbers
  const FeatureConsistencyResult again = featureConsistency(seq);
  EXPECT_EQ(again.all.correct, clean.all.correct);
  EXPECT_EQ(again.all.matches, clean.all.matches);

  // stride and limit pick the pairs
  FeatureOptions some;
  some.stride = 2;
  some.max_pairs = 2;
  const FeatureConsistencyResult picked = featureConsistency(seq, some);
  ASSERT_EQ(picked.pairs.size(), 2u);
  EXPECT_EQ(picked.pairs[1].frame, 2u);
  EXPECT_EQ(picked.pairs[1].all.correct, clean.pairs[2].all.correct);

  // a flow 5 px off: the matches stay, nearly none is correct any more (measured 0.009)
  const fs::path shifted = dir / "shifted";
  fs::copy(seq, shifted, fs::copy_options::recursive);
  test::shiftFlowFiles(shifted, 5, 0);
  const FeatureConsistencyResult bad_flow = featureConsistency(shifted);
  EXPECT_EQ(bad_flow.all.matches, clean.all.matches);
  EXPECT_LT(bad_flow.all.correctShare(), 0.05) << bad_flow.toString();

  // strong per-pixel noise (+-80 codes): ORB finds corners in the noise, on the flat walls
  // too, and about half of the matches are wrong (measured: 618 keypoints per frame, 31 % of
  // them flat, 0.47 correct)
  const fs::path noisy = dir / "noisy";
  fs::copy(seq, noisy, fs::copy_options::recursive);
  test::addImageNoise(noisy, 80);
  const FeatureConsistencyResult noise = featureConsistency(noisy);
  EXPECT_LT(noise.all.correctShare(), clean.all.correctShare() - 0.3) << noise.toString();
  EXPECT_GT(noise.flat_keypoint_share, 2 * clean.flat_keypoint_share) << noise.toString();
}

}  // namespace
}  // namespace inet
