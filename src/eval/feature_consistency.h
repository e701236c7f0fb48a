#pragma once
// How well a feature-based SLAM front end can work on a sequence: ORB features matched between
// consecutive frames and every match checked against the exact forward flow (issue 14).
//
// Per frame pair (k, k+1): cv::ORB::create(orb_features) (OpenCV's defaults otherwise: scale
// 1.2, 8 levels, FAST threshold 20, edge threshold 31) on the grey image of each frame
// (cvtColor RGB2GRAY of the stored sRGB codes), brute-force Hamming matching with cross-check
// (a pair is kept only when each descriptor is the other's nearest). A match from keypoint x_k
// to x_k+1 is then, with f the flow of frame k sampled at x_k:
//
//     no_flow   f is unknown there (no surface: a window to the sky, a hole in the scene);
//     occluded  the occlusion mask says x_k's point is hidden in frame k+1 or leaves its image;
//     correct   otherwise, when || x_k+1 - (x_k + f) || <= max_error_px;
//     wrong     otherwise.
//
// correctShare() = correct / (correct + wrong): the share of the matches that the ground truth
// can judge. Occluded and no-flow matches are reported beside it, not counted as wrong, because
// the flow cannot say where their point went. Keypoint and flow positions share OpenCV's pixel
// convention (centres at integers; the flow is a difference of positions, so convention-free).
// ORB scales a keypoint found on pyramid level L by 1.2^L without the half-pixel shift, which
// biases x_k and x_k+1 alike by under 1.3 px; their difference, which is what is checked, keeps
// well under the 3 px default.
//
// "Flat" keypoints are those whose pixel in frame k carries one of `flat_classes` in label0
// (NYU40 wall, floor and ceiling by default): the large untextured surfaces where real scenes
// give few and unreliable corners and synthetic ones may give many (texture noise, path-tracing
// noise). Their share of all keypoints and their own correct share are reported separately.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/pose.h"
#include "render/frame.h"

namespace inet {

/// Where in the flow image a keypoint's flow is read.
enum class FlowSampling {
  /// the pixel whose centre is nearest: keypoints sit on corners, which are often depth edges,
  /// where a bilinear blend mixes two surfaces' flows into a flow of neither
  Nearest,
  /// bilinear between the four surrounding centres when all four have flow, else nearest
  Bilinear,
};

/// "nearest" or "bilinear"; InputError naming `field` and listing both otherwise.
FlowSampling parseFlowSampling(const std::string& name, const std::string& field = "--sampling");
const char* flowSamplingName(FlowSampling s);

/// NYU40 wall, floor and ceiling (ids 1, 2, 22), looked up by name in scene/nyu40.h.
std::vector<int> defaultFlatClasses();

struct FeatureOptions {
  int orb_features = 1000;    ///< cv::ORB::create(nfeatures)
  double max_error_px = 3.0;  ///< largest endpoint error of a correct match, pixels
  FlowSampling sampling = FlowSampling::Nearest;
  std::vector<int> flat_classes = defaultFlatClasses();  ///< NYU40 ids
  size_t stride = 1;     ///< evaluate the pairs (k, k+1) for k = 0, stride, 2 stride, ...
  size_t max_pairs = 0;  ///< at most this many pairs; 0 = all
  /// InputError naming the option (field "features.<name>") for a value out of range.
  void validate() const;
  std::string toString() const;
};

/// Matches of one pair (or a sum over pairs), by what the ground truth says about them.
struct MatchCounts {
  size_t matches = 0;  ///< cross-checked matches = correct + wrong + occluded + no_flow
  size_t correct = 0, wrong = 0, occluded = 0, no_flow = 0;
  size_t checked() const { return correct + wrong; }
  /// correct / checked(); 0 when no match could be checked.
  double correctShare() const;
  /// occluded / matches; 0 without matches.
  double occludedShare() const;
  MatchCounts& operator+=(const MatchCounts& o);
  MatchCounts operator-(const MatchCounts& o) const;
  std::string toString() const;
};

/// One frame pair (k, k+1).
struct FramePairFeatures {
  size_t frame = 0;  ///< k
  TimeNs t_ns = 0;   ///< frame k's stamp
  size_t keypoints = 0, keypoints_next = 0;
  size_t keypoints_flat = 0;  ///< of frame k's, on a flat class (0 without labels)
  MatchCounts all;
  MatchCounts flat;  ///< the matches whose frame-k keypoint is on a flat class
};

/// Features of frames k and k+1 checked against frame k's forward flow. `labels` (NYU40, frame
/// k) may be empty: then nothing counts as flat. Images are 8-bit grey or sRGB colour of one
/// size, that of the flow.
FramePairFeatures matchFramePair(const ImageU8& image_k, const ImageU8& image_next,
                                 const FlowField& flow_k, const ImageU8& labels_k,
                                 const FeatureOptions& opt = {});

struct FeatureConsistencyResult {
  std::string sequence;  ///< the folder
  FeatureOptions options;
  size_t frames = 0;    ///< in the sequence
  bool labels = false;  ///< label0 was there: the flat figures mean something
  std::vector<FramePairFeatures> pairs;
  MatchCounts all, flat;           ///< sums over the pairs
  double keypoints_per_frame = 0;  ///< mean of frame k's keypoints over the pairs
  double matches_per_pair = 0;
  double flat_keypoint_share = 0;  ///< flat keypoints / keypoints, frames k of the pairs
  double seconds = 0;              ///< wall time, reading included
  std::string toString() const;
};

/// matchFramePair over the sequence folder's pairs (eval/sequence_reader.h; InputError naming
/// the file for a missing folder, meta.json field, flow0 or image). Deterministic: ORB and the
/// matcher draw no random numbers.
FeatureConsistencyResult featureConsistency(const std::filesystem::path& sequence,
                                            const FeatureOptions& opt = {});

}  // namespace inet
