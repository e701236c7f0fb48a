#include "eval/feature_consistency.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <opencv2/features2d.hpp>

#include "core/error.h"
#include "eval/cv_image.h"
#include "eval/sequence_reader.h"
#include "scene/nyu40.h"

namespace inet {

FlowSampling parseFlowSampling(const std::string& name, const std::string& field) {
  if (name == "nearest") return FlowSampling::Nearest;
  if (name == "bilinear") return FlowSampling::Bilinear;
  throw InputError("", field, fmt::format("unknown '{}' (valid: nearest, bilinear)", name));
}

const char* flowSamplingName(FlowSampling s) {
  return s == FlowSampling::Nearest ? "nearest" : "bilinear";
}

std::vector<int> defaultFlatClasses() {
  std::vector<int> ids;
  for (const char* name : {"wall", "floor", "ceiling"}) {
    const std::optional<int> id = nyu40FromName(name);
    INET_CHECK(id.has_value());
    ids.push_back(*id);
  }
  return ids;
}

void FeatureOptions::validate() const {
  if (orb_features < 1 || orb_features > 1'000'000)
    throw InputError("", "features.orb_features",
                     fmt::format("must be in [1, 1000000], got {}", orb_features));
  if (!(max_error_px > 0) || !std::isfinite(max_error_px))
    throw InputError("", "features.max_error_px",
                     fmt::format("must be a positive number of pixels, got {}", max_error_px));
  if (stride < 1) throw InputError("", "features.stride", "must be at least 1");
  for (int c : flat_classes)
    if (c < 1 || c >= kNyu40Count)
      throw InputError("", "features.flat_classes",
                       fmt::format("{} is not an NYU40 class id (1..{})", c, kNyu40Count - 1));
}

std::string FeatureOptions::toString() const {
  return fmt::format(
      "FeatureOptions[orb_features={} max_error_px={} sampling={} flat_classes=[{}] stride={} "
      "max_pairs={}]",
      orb_features, max_error_px, flowSamplingName(sampling), fmt::join(flat_classes, ","), stride,
      max_pairs);
}

double MatchCounts::correctShare() const {
  return checked() ? static_cast<double>(correct) / static_cast<double>(checked()) : 0.0;
}

double MatchCounts::occludedShare() const {
  return matches ? static_cast<double>(occluded) / static_cast<double>(matches) : 0.0;
}

MatchCounts& MatchCounts::operator+=(const MatchCounts& o) {
  matches += o.matches;
  correct += o.correct;
  wrong += o.wrong;
  occluded += o.occluded;
  no_flow += o.no_flow;
  return *this;
}

MatchCounts MatchCounts::operator-(const MatchCounts& o) const {
  INET_CHECK(matches >= o.matches && correct >= o.correct && wrong >= o.wrong &&
             occluded >= o.occluded && no_flow >= o.no_flow);
  return {matches - o.matches, correct - o.correct, wrong - o.wrong, occluded - o.occluded,
          no_flow - o.no_flow};
}

std::string MatchCounts::toString() const {
  return fmt::format(
      "MatchCounts[matches={} correct={} wrong={} occluded={} no_flow={} share={:.4f}]", matches,
      correct, wrong, occluded, no_flow, correctShare());
}

namespace {

/// What the ground truth says at one keypoint of frame k.
struct FlowAt {
  bool known = false, occluded = false;
  double u = 0, v = 0;
};

FlowAt sampleFlow(const FlowField& f, double x, double y, FlowSampling sampling) {
  const int W = f.width(), H = f.height();
  const int xi = std::clamp(static_cast<int>(std::lround(x)), 0, W - 1);
  const int yi = std::clamp(static_cast<int>(std::lround(y)), 0, H - 1);
  FlowAt s;
  s.known = f.valid.at(xi, yi) != 0;
  s.occluded = !f.occluded.empty() && f.occluded.at(xi, yi) != 0;
  if (!s.known) return s;
  s.u = f.flow.at(xi, yi, 0);
  s.v = f.flow.at(xi, yi, 1);
  if (sampling == FlowSampling::Bilinear) {
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= W || y0 + 1 >= H) return s;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx)
        if (!f.valid.at(x0 + dx, y0 + dy)) return s;  // keep the nearest tap's flow
    const double ax = x - x0, ay = y - y0;
    for (int c = 0; c < 2; ++c) {
      auto tap = [&](int dx, int dy) {
        return static_cast<double>(f.flow.at(x0 + dx, y0 + dy, c));
      };
      const double top = (1 - ax) * tap(0, 0) + ax * tap(1, 0);
      const double bottom = (1 - ax) * tap(0, 1) + ax * tap(1, 1);
      (c == 0 ? s.u : s.v) = (1 - ay) * top + ay * bottom;
    }
  }
  return s;
}

bool onFlatClass(const ImageU8& labels, const cv::Point2f& p, const std::vector<int>& flat) {
  if (labels.empty()) return false;
  const int x = std::clamp(static_cast<int>(std::lround(p.x)), 0, labels.width - 1);
  const int y = std::clamp(static_cast<int>(std::lround(p.y)), 0, labels.height - 1);
  return std::find(flat.begin(), flat.end(), labels.at(x, y)) != flat.end();
}

}  // namespace

FramePairFeatures matchFramePair(const ImageU8& image_k, const ImageU8& image_next,
                                 const FlowField& flow_k, const ImageU8& labels_k,
                                 const FeatureOptions& opt) {
  const int W = flow_k.width(), H = flow_k.height();
  INET_CHECK(image_k.width == W && image_k.height == H);
  INET_CHECK(image_next.width == W && image_next.height == H);
  INET_CHECK(flow_k.valid.width == W && flow_k.valid.height == H);
  INET_CHECK(flow_k.occluded.empty() ||
             (flow_k.occluded.width == W && flow_k.occluded.height == H));
  INET_CHECK(labels_k.empty() || (labels_k.width == W && labels_k.height == H));

  const cv::Ptr<cv::ORB> orb = cv::ORB::create(opt.orb_features);
  std::vector<cv::KeyPoint> kp0, kp1;
  cv::Mat desc0, desc1;
  orb->detectAndCompute(cvimage::grey(image_k), cv::noArray(), kp0, desc0);
  orb->detectAndCompute(cvimage::grey(image_next), cv::noArray(), kp1, desc1);

  FramePairFeatures r;
  r.keypoints = kp0.size();
  r.keypoints_next = kp1.size();
  for (const cv::KeyPoint& kp : kp0)
    r.keypoints_flat += onFlatClass(labels_k, kp.pt, opt.flat_classes);
  if (desc0.empty() || desc1.empty()) return r;  // the matcher asserts on an empty side

  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_HAMMING, /*crossCheck=*/true).match(desc0, desc1, matches);
  const double max_err2 = opt.max_error_px * opt.max_error_px;
  for (const cv::DMatch& m : matches) {
    const cv::Point2f& a = kp0[m.queryIdx].pt;
    const cv::Point2f& b = kp1[m.trainIdx].pt;
    const FlowAt f = sampleFlow(flow_k, a.x, a.y, opt.sampling);
    MatchCounts one;
    one.matches = 1;
    if (!f.known) {
      one.no_flow = 1;
    } else if (f.occluded) {
      one.occluded = 1;
    } else {
      const double ex = b.x - (a.x + f.u), ey = b.y - (a.y + f.v);
      (ex * ex + ey * ey <= max_err2 ? one.correct : one.wrong) = 1;
    }
    r.all += one;
    if (onFlatClass(labels_k, a, opt.flat_classes)) r.flat += one;
  }
  return r;
}

FeatureConsistencyResult featureConsistency(const std::filesystem::path& sequence,
                                            const FeatureOptions& opt) {
  opt.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const SequenceReader seq(sequence);
  seq.requireFlow();
  FeatureConsistencyResult res;
  res.sequence = sequence.string();
  res.options = opt;
  res.frames = seq.frameCount();
  res.labels = seq.hasLabels();
  if (seq.frameCount() < 2)
    throw InputError((sequence / "cam0" / "data.csv").string(), "",
                     "one frame: the evaluation needs a pair of frames");
  size_t keypoints = 0, keypoints_flat = 0;
  for (size_t k = 0; k + 1 < seq.frameCount(); k += opt.stride) {
    if (opt.max_pairs && res.pairs.size() == opt.max_pairs) break;
    const ImageU8 labels = res.labels ? seq.labels(k) : ImageU8{};
    FramePairFeatures p =
        matchFramePair(seq.colour(k), seq.colour(k + 1), seq.flow(k), labels, opt);
    p.frame = k;
    p.t_ns = seq.frames()[k].t_ns;
    res.all += p.all;
    res.flat += p.flat;
    keypoints += p.keypoints;
    keypoints_flat += p.keypoints_flat;
    res.pairs.push_back(p);
  }
  const double n = static_cast<double>(res.pairs.size());
  res.keypoints_per_frame = keypoints / n;
  res.matches_per_pair = res.all.matches / n;
  res.flat_keypoint_share = keypoints ? static_cast<double>(keypoints_flat) / keypoints : 0.0;
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

std::string FeatureConsistencyResult::toString() const {
  return fmt::format(
      "FeatureConsistencyResult[{} pairs={} keypoints/frame={:.1f} matches/pair={:.1f} "
      "correct={:.4f} occluded={:.4f} flat keypoints={:.4f} flat correct={:.4f}]",
      sequence, pairs.size(), keypoints_per_frame, matches_per_pair, all.correctShare(),
      all.occludedShare(), flat_keypoint_share, flat.correctShare());
}

}  // namespace inet
