// Acceptance of the learned style (issue 5, item 3; docs/style.md): on real hand-held
// sequences the model never saw (the record's held-out list), the power spectra of angular
// velocity and of linear acceleration in 1-12 Hz of styled base trajectories are closer to the
// real ones than the unstyled base trajectories are, by at least 2x in log-spectral distance.
// All series are sampled at the model rate (100 Hz) from the Catmull-Rom interpolant of their
// poses (spectrum.h). Base trajectories: hand-held type, apartments 0-2, fixed seeds.
//
// Set INET_STYLE_PLOTS=<folder> to also write style_spectra.png and style_segment.png there.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "../temp_dir.h"
#include "core/atomic_file.h"
#include "core/plot.h"
#include "procedural/apartment.h"
#include "trajectory/free_space.h"
#include "trajectory/random_trajectory.h"
#include "trajectory/spectrum.h"
#include "trajectory/style_model.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

constexpr double kRate = 100.0;
constexpr int kSegment = 256;  // 2.56 s Welch segments: 0.39 Hz bins, 29 of them in 1-12 Hz
constexpr double kLo = 1.0, kHi = 12.0;

struct Spectra {
  WelchPsd w{kRate, kSegment}, a{kRate, kSegment};
  void add(const Trajectory& uniform) {
    const MotionSeries m = motionSeries(uniform, kRate);
    w.add(m.w_world);
    a.add(m.a_world);
  }
};

Series spectrumSeries(const Spectrum& s, const std::string& label, Rgb colour) {
  Series out{label, {}, {}, colour};
  for (size_t i = 0; i < s.freq_hz.size(); ++i)
    if (s.freq_hz[i] >= 0.3) {
      out.x.push_back(s.freq_hz[i]);
      out.y.push_back(s.psd[i]);
    }
  return out;
}

LinePlot spectrumPanel(const std::string& title, const std::string& unit, const Spectrum& real,
                       const Spectrum& base, const Spectrum& styled, double lsd_base,
                       double lsd_styled) {
  LinePlot p;
  p.spec.title = title;
  p.spec.x_label = "frequency (Hz); band 1-12 Hz between the grey lines";
  p.spec.y_label = "PSD (" + unit + ")";
  p.spec.log_x = p.spec.log_y = true;
  p.spec.width = 760;
  p.spec.height = 560;
  p.series.push_back(spectrumSeries(real, "real, held out", Rgb{0, 0, 0}));
  p.series.push_back(spectrumSeries(
      base, "base (LSD " + std::to_string(lsd_base).substr(0, 4) + " dB)", paletteColour(0)));
  p.series.push_back(spectrumSeries(
      styled, "styled (LSD " + std::to_string(lsd_styled).substr(0, 4) + " dB)",
      paletteColour(3)));
  double lo = 1e300, hi = 0;
  for (const Series& s : p.series)
    for (double y : s.y)
      if (y > 0) lo = std::min(lo, y), hi = std::max(hi, y);
  for (double f : {kLo, kHi})
    p.series.push_back(Series{"", {f, f}, {lo, hi}, Rgb{170, 170, 170}, Series::Style::Line,
                              1.0, 2.0, true});
  return p;
}

void writeSegmentPlot(const fs::path& png, const Trajectory& base, const Trajectory& styled) {
  std::vector<LinePlot> panels(2);
  const char* axis[3] = {"x", "y", "z"};
  panels[0].spec.title = "5 s of a base trajectory and its styled version";
  panels[0].spec.y_label = "position minus start (m)";
  panels[1].spec.title = "angular speed";
  panels[1].spec.y_label = "|w| (rad/s)";
  for (auto& p : panels) p.spec.x_label = "time (s)", p.spec.width = 760, p.spec.height = 500;
  const size_t k0 = 2000, k1 = std::min(base.size(), k0 + 1000);  // 10 s .. 15 s at 200 Hz
  const Vec3 p0 = base.poses[k0].T_world_camera.t;
  for (int c = 0; c < 3; ++c) {
    Series b{std::string("base ") + axis[c] + " (dashed)", {}, {}, paletteColour(c)};
    Series s{std::string("styled ") + axis[c], {}, {}, paletteColour(c)};
    b.dashed = true;
    for (size_t k = k0; k < k1; ++k) {
      const double t = 1e-9 * static_cast<double>(base.poses[k].t_ns - base.poses[0].t_ns);
      b.x.push_back(t);
      b.y.push_back(base.poses[k].T_world_camera.t[c] - p0[c]);
      s.x.push_back(t);
      s.y.push_back(styled.poses[k].T_world_camera.t[c] - p0[c]);
    }
    panels[0].series.push_back(b);
    panels[0].series.push_back(s);
  }
  for (int which = 0; which < 2; ++which) {
    const Trajectory& tr = which == 0 ? base : styled;
    Series s{which == 0 ? "base" : "styled", {}, {}, paletteColour(which == 0 ? 0 : 3)};
    for (size_t k = k0; k + 1 < k1; ++k) {
      const Eigen::AngleAxisd aa(tr.poses[k + 1].T_world_camera.q *
                                 tr.poses[k].T_world_camera.q.conjugate());
      s.x.push_back(1e-9 * static_cast<double>(tr.poses[k].t_ns - tr.poses[0].t_ns));
      s.y.push_back(aa.angle() * 200.0);
    }
    panels[1].series.push_back(s);
  }
  writeLinePlotRowPng(png, panels);
}

TEST(StyleAcceptance, StyledSpectraAreTwiceCloserToHeldOutRealThanBase) {
  const fs::path data = fs::path(INET_SHARED_DIR) / "data/trajectories";
  if (!fs::is_directory(data)) GTEST_SKIP() << "no real trajectories at " << data;
  const fs::path record_path = fs::path(defaultStyleModelPath()).parent_path() /
                               "handheld_wavenet_record.json";
  if (!fs::exists(defaultStyleModelPath()) || !fs::exists(record_path))
    GTEST_SKIP() << "no shipped style model at " << defaultStyleModelPath();
  const StyleModel& model = builtinStyleModel();
  ASSERT_EQ(model.config.rate_hz, kRate);
  const auto record = nlohmann::json::parse(readTextFile(record_path));

  // INET_STYLE_SPLIT=train compares with the training sequences instead (for calibrating the
  // sampling temperature on training data only; the acceptance is on the held-out ones)
  const char* split_env = std::getenv("INET_STYLE_SPLIT");
  const std::string split = split_env != nullptr && *split_env != '\0' ? split_env : "holdout";
  StyleOptions style;
  if (const char* t = std::getenv("INET_STYLE_TEMPERATURE")) style.temperature = std::atof(t);
  Spectra real, base, styled;
  for (const std::string& name : record.at("split").at(split).get<std::vector<std::string>>())
    for (const Trajectory& seg : loadMotionSegments((data / name).string(), kRate)) real.add(seg);
  ASSERT_GT(real.w.segments(), 100);

  test::TempDir dir("style_acceptance");
  Trajectory plot_base, plot_styled;
  for (uint64_t layout = 0; layout < 3; ++layout) {
    ApartmentOptions aopt;
    aopt.seed = layout;
    aopt.texture_size = 64;
    const Apartment apt = makeApartment(aopt, dir.path(), dir.path() / "textures");
    const FreeSpace space(apt.scene);
    for (int n = 0; n < 3; ++n) {
      RandomTrajectoryOptions opt;
      opt.type = MotionType::HandHeld;
      opt.seed = 7000 + layout * 10 + n;
      opt.frames = 750;  // 30 s at 25 Hz
      const RandomTrajectory traj = generateRandomTrajectory(space, opt);
      auto is_free = [&](const Vec3& p) { return space.hasClearance(p, opt.clearance); };
      const Trajectory st = applyStyle(traj.dense, model, opt.seed, is_free, style);
      ASSERT_EQ(st.size(), traj.dense.size());
      for (const TimedPose& p : st.poses) ASSERT_TRUE(is_free(p.T_world_camera.t));
      base.add(resampleUniform(traj.dense, kRate));
      styled.add(resampleUniform(st, kRate));
      if (layout == 0 && n == 0) plot_base = traj.dense, plot_styled = st;
    }
  }
  const Spectrum r_w = real.w.result(), r_a = real.a.result();
  const Spectrum b_w = base.w.result(), b_a = base.a.result();
  const Spectrum s_w = styled.w.result(), s_a = styled.a.result();
  const double lsd_bw = logSpectralDistanceDb(b_w, r_w, kLo, kHi);
  const double lsd_sw = logSpectralDistanceDb(s_w, r_w, kLo, kHi);
  const double lsd_ba = logSpectralDistanceDb(b_a, r_a, kLo, kHi);
  const double lsd_sa = logSpectralDistanceDb(s_a, r_a, kLo, kHi);
  std::printf("log-spectral distance to held-out real, 1-12 Hz (dB):\n"
              "  angular velocity:    base %.2f  styled %.2f  (ratio %.1f)\n"
              "  linear acceleration: base %.2f  styled %.2f  (ratio %.1f)\n",
              lsd_bw, lsd_sw, lsd_bw / lsd_sw, lsd_ba, lsd_sa, lsd_ba / lsd_sa);
  EXPECT_LE(2 * lsd_sw, lsd_bw);
  EXPECT_LE(2 * lsd_sa, lsd_ba);

  if (const char* out = std::getenv("INET_STYLE_PLOTS"); out != nullptr && *out != '\0') {
    writeLinePlotRowPng(
        fs::path(out) / "style_spectra.png",
        {spectrumPanel("angular velocity (trace of per-axis PSDs)", "(rad/s)^2/Hz", r_w, b_w,
                       s_w, lsd_bw, lsd_sw),
         spectrumPanel("linear acceleration (trace of per-axis PSDs)", "(m/s^2)^2/Hz", r_a,
                       b_a, s_a, lsd_ba, lsd_sa)});
    writeSegmentPlot(fs::path(out) / "style_segment.png", plot_base, plot_styled);
  }
}

}  // namespace
}  // namespace inet
