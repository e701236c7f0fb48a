#pragma once
// Relative pose error (Sturm et al., IROS 2012; evo's `rpe`): for pairs (i, j) of associated
// poses a fixed "delta" apart, with ground truth Q and (aligned) estimate P,
//
//     E_ij = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j)
//
// translational error |trans(E_ij)| (metres) and rotational error angle(E_ij) (degrees). A rigid
// (SE(3)) alignment does not change it; Sim(3) does (it rescales the estimate), so monocular
// estimates are evaluated with --align sim3.
//
// Pairs are taken over the associated poses (index k = k-th match, in time order):
//  - frames:  j = i + delta;
//  - metres:  j = first index after i where the ground-truth path length from i reaches delta;
//  - seconds: j = first index after i where the ground-truth time from i reaches delta.
// By default the pairs are consecutive and disjoint (i_next = j, starting at 0, evo's default);
// all_pairs starts a pair at every i.
#include <string>
#include <utility>
#include <vector>

#include "eval/align.h"
#include "eval/associate.h"
#include "eval/error_stats.h"
#include "trajectory/trajectory.h"

namespace inet {

enum class DeltaUnit { Frames, Metres, Seconds };

/// "frames" (or "f"), "m", "s"; InputError naming `field` and listing the names otherwise.
DeltaUnit parseDeltaUnit(const std::string& name, const std::string& field = "--delta-unit");
const char* deltaUnitName(DeltaUnit unit);

struct RpeOptions {
  double delta = 1;  ///< a positive integer for frames, > 0 for metres and seconds
  DeltaUnit unit = DeltaUnit::Frames;
  bool all_pairs = false;
  AlignMode align = AlignMode::None;
  AssociationOptions association;  ///< offset is added to the estimate's stamps
};

struct RpeResult {
  Alignment alignment;
  size_t matched = 0;  ///< associated poses
  ErrorStats translation_m, rotation_deg;
  /// Pairs (i, j) as indices into `matches`; errors per pair.
  std::vector<std::pair<size_t, size_t>> pairs;
  std::vector<StampMatch> matches;  ///< a: ground-truth index, b: estimate index
  std::vector<double> translation_errors_m, rotation_errors_deg;
  std::string toString() const;
};

/// RPE of `est` against `gt`. InputError (file "") for a bad delta (field "--delta"), nothing
/// associated, or no pair `delta` apart (the message says how long the matched part is).
RpeResult computeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& opt = {});

}  // namespace inet
