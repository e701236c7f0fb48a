#include "eval/eval_plot.h"

#include <fmt/format.h>

#include "core/plot.h"

namespace inet {
namespace {

const Rgb kGroundTruth{40, 40, 40};

double secondsSince(TimeNs t, TimeNs t0) {
  return 1e-9 * static_cast<double>(t - t0);
}

/// Error-over-time panel: one series plus its RMSE as a dashed horizontal line.
LinePlot errorPanel(const std::string& title, const std::string& y_label, std::vector<double> t_s,
                    std::vector<double> e, double rmse, Rgb colour) {
  LinePlot p;
  p.spec.title = title;
  p.spec.x_label = "time (s)";
  p.spec.y_label = y_label;
  p.spec.width = 700, p.spec.height = 600;
  const double t0 = t_s.empty() ? 0.0 : t_s.front(), t1 = t_s.empty() ? 1.0 : t_s.back();
  p.series.push_back({"error", std::move(t_s), std::move(e), colour});
  Series r{fmt::format("rmse {:.4g}", rmse), {t0, t1}, {rmse, rmse}, Rgb{214, 39, 40}};
  r.dashed = true;
  p.series.push_back(std::move(r));
  return p;
}

}  // namespace

void writeAtePlot(const std::filesystem::path& path, const Trajectory& gt, const Trajectory& est,
                  const AteResult& ate, const std::string& title) {
  LinePlot top;
  top.spec.title = title.empty() ? "trajectory (top view)" : title;
  top.spec.x_label = "x (m)";
  top.spec.y_label = "y (m)";
  top.spec.equal_aspect = true;
  top.spec.width = 800, top.spec.height = 600;
  Series g{"ground truth", {}, {}, kGroundTruth};
  for (const auto& p : gt.poses)
    g.x.push_back(p.T_world_camera.t.x()), g.y.push_back(p.T_world_camera.t.y());
  Series e{ate.align == AlignMode::None ? "estimate"
                                        : fmt::format("estimate ({})", alignModeName(ate.align)),
           {},
           {},
           paletteColour(0)};
  for (const auto& p : est.poses) {
    const Vec3 a = ate.alignment.apply(p.T_world_camera.t);
    e.x.push_back(a.x()), e.y.push_back(a.y());
  }
  top.series = {std::move(e), std::move(g)};  // ground truth drawn last, on top
  std::vector<double> t, err;
  const TimeNs t0 = gt.poses.front().t_ns;
  for (size_t k = 0; k < ate.matches.size(); ++k) {
    t.push_back(secondsSince(gt.poses[ate.matches[k].a].t_ns, t0));
    err.push_back(ate.translation_errors_m[k]);
  }
  LinePlot over_time = errorPanel("ATE over time", "translational error (m)", std::move(t),
                                  std::move(err), ate.translation_m.rmse, paletteColour(0));
  writeLinePlotRowPng(path, {top, over_time});
}

void writeRpePlot(const std::filesystem::path& path, const Trajectory& gt, const RpeResult& rpe,
                  const std::string& title) {
  std::vector<double> t;
  const TimeNs t0 = gt.poses.front().t_ns;
  for (auto [i, j] : rpe.pairs) t.push_back(secondsSince(gt.poses[rpe.matches[i].a].t_ns, t0));
  const std::string prefix = title.empty() ? "RPE" : title;
  writeLinePlotRowPng(
      path, {errorPanel(prefix + ": translation", "translational error (m)", t,
                        rpe.translation_errors_m, rpe.translation_m.rmse, paletteColour(0)),
             errorPanel(prefix + ": rotation", "rotational error (deg)", t, rpe.rotation_errors_deg,
                        rpe.rotation_deg.rmse, paletteColour(2))});
}

}  // namespace inet
