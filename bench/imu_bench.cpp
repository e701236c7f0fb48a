// IMU generation speed (issue 6 acceptance: 60 s at 800 Hz in under 50 ms).
//   BM_ImuFromSpline    ideal samples + Kalibr noise from a ready spline (48 001 samples)
//   BM_ImuFromPoses     the whole simulateImu: spline fit to 60 s of 200 Hz poses (50 ms knots
//                       by default, or every pose with 5 ms knots) + sampling + noise
//   BM_ImuCsv           formatting the three CSV files' text (not the disk write)
//   BM_SplineFit        PoseSpline::fit alone on 100 s of 200 Hz poses (issue 13: well under a
//                       second), default 50 ms knots and 5 ms knots (every pose a knot)
// Input: the analytic wandering and turning camera of tests/sensors/motion.h (copied here so
// the benchmark does not depend on test headers).
#include <benchmark/benchmark.h>

#include <cmath>

#include "sensors/imu.h"
#include "sensors/imu_io.h"

namespace inet {
namespace {

Trajectory poses200Hz(double seconds) {
  Trajectory traj;
  Mat3 base;
  base.col(0) = Vec3(0, -1, 0);
  base.col(1) = Vec3(0, 0, -1);
  base.col(2) = Vec3(1, 0, 0);
  for (int k = 0; k <= static_cast<int>(seconds * 200); ++k) {
    const double t = k / 200.0;
    const Quat q = Quat(Eigen::AngleAxisd(1.3 * t, Vec3::UnitZ())) *
                   Quat(Eigen::AngleAxisd(0.2 * std::sin(1.7 * t), Vec3::UnitY())) * Quat(base);
    const Vec3 p(0.5 * std::sin(1.1 * t), 0.4 * std::cos(0.7 * t), 1.5 + 0.1 * std::sin(2 * t));
    traj.poses.push_back({TimeNs{k} * 5'000'000, Pose{q.normalized(), p}});
  }
  return traj;
}

void BM_ImuFromSpline(benchmark::State& state) {
  const Trajectory traj = poses200Hz(60.0);
  PoseSpline spline(0, 1, std::vector<Vec3>(4), std::vector<Quat>(4, Quat::Identity()));
  ImuOptions opt;  // 800 Hz, EuRoC noise
  simulateImu(traj, opt, {}, &spline);
  for (auto _ : state) {
    ImuSequence seq;
    seq.ideal = sampleIdealImu(spline, opt);
    addImuNoise(seq.ideal, opt.noise, opt.rate_hz, opt.seed, seq.measured, seq.bias);
    benchmark::DoNotOptimize(seq.measured.data());
    state.counters["samples"] = static_cast<double>(seq.measured.size());
  }
}
BENCHMARK(BM_ImuFromSpline)->Unit(benchmark::kMillisecond);

void BM_ImuFromPoses(benchmark::State& state) {
  const Trajectory traj = poses200Hz(60.0);
  SplineFitOptions fit;
  fit.knot_spacing_ns = state.range(0) * 1'000'000;
  for (auto _ : state) {
    const ImuSequence seq = simulateImu(traj, ImuOptions{}, fit);
    benchmark::DoNotOptimize(seq.measured.data());
  }
}
BENCHMARK(BM_ImuFromPoses)->Arg(0)->Arg(5)->ArgName("knot_ms")->Unit(benchmark::kMillisecond);

void BM_SplineFit(benchmark::State& state) {
  const Trajectory traj = poses200Hz(100.0);
  SplineFitOptions fit;
  fit.knot_spacing_ns = state.range(0) * 1'000'000;
  for (auto _ : state) {
    const PoseSpline spline = PoseSpline::fit(traj, fit);
    benchmark::DoNotOptimize(spline.numControls());
  }
  SplineFitReport rep;
  PoseSpline::fit(traj, fit, &rep);
  state.counters["poses"] = static_cast<double>(traj.size());
  state.counters["gauss_newton"] = rep.rotation_iterations;
}
BENCHMARK(BM_SplineFit)->Arg(0)->Arg(5)->ArgName("knot_ms")->Unit(benchmark::kMillisecond);

void BM_ImuCsv(benchmark::State& state) {
  const ImuSequence seq = simulateImu(poses200Hz(60.0), ImuOptions{});
  for (auto _ : state) {
    std::string a = formatImuCsv(seq.measured), b = formatImuCsv(seq.ideal),
                c = formatImuBiasCsv(seq.measured, seq.bias);
    benchmark::DoNotOptimize(a.data());
    benchmark::DoNotOptimize(b.data());
    benchmark::DoNotOptimize(c.data());
  }
}
BENCHMARK(BM_ImuCsv)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace inet

BENCHMARK_MAIN();
