#pragma once
// Figures of an evaluation, as PNG (core/plot.h): what a reviewer looks at before the numbers.
#include <filesystem>
#include <string>

#include "eval/ate.h"
#include "eval/rpe.h"
#include "trajectory/trajectory.h"

namespace inet {

/// Two panels side by side: a top-down x-y view (equal aspect) of the ground truth and the
/// aligned estimate (every estimate pose, matched or not), and the translational ATE over
/// time (seconds from the first ground-truth pose) with its RMSE as a dashed line.
void writeAtePlot(const std::filesystem::path& path, const Trajectory& gt, const Trajectory& est,
                  const AteResult& ate, const std::string& title);

/// Two panels: translational and rotational RPE over time (at the first pose of each pair).
void writeRpePlot(const std::filesystem::path& path, const Trajectory& gt, const RpeResult& rpe,
                  const std::string& title);

}  // namespace inet
