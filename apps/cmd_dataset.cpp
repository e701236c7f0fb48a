// interiornet dataset plan | build | status | verify (issue 16, docs/dataset.md): a dataset spec
// into a plan, the plan's work units into sequence folders, resumably, with the job state in
// SQLite. Thin over src/builder/.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "builder/dataset_build.h"
#include "builder/dataset_plan.h"
#include "builder/dataset_spec.h"
#include "builder/mpi_build.h"
#include "common.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "dataset/sequence_writer.h"

namespace inet::app {
namespace {

namespace fs = std::filesystem;

struct PlanArgs {
  std::string spec;
  std::string out;
};

void runPlan(const PlanArgs& a) {
  const DatasetSpec spec = parseDatasetSpec(a.spec);
  const DatasetPlan plan = makePlan(spec);
  const fs::path file = fs::path(a.out) / "plan.json";
  const std::string text = planText(plan);
  std::error_code ec;
  if (fs::exists(fs::path(a.out) / "state.sqlite", ec) && fs::exists(file, ec) &&
      readTextFile(file) != text)
    throw InputError(a.out, "--out",
                     "holds a build of another plan; plan a changed spec into a new folder");
  checkOutputFolder(a.out);
  writePlan(plan, file);
  const PlanCounts c = planCounts(plan);
  fmt::print("wrote {}: {} layouts, {} sequences ({} frames), {} sparse views, {} work units\n",
             file.string(), c.layouts, c.sequences, c.sequence_frames, c.sparse_views, c.units());
  fmt::print("{}", formatSplitStats(splitStats(plan)));
}

struct BuildArgs {
  std::string dir;
  int threads = 0;
  BuildOptions opt;
};

void runBuild(const BuildArgs& a) {
  installStopHandlers();
  if (a.opt.max_attempts < 1) throw InputError("", "--max-attempts", "must be >= 1");
  if (a.opt.max_units < 0) throw InputError("", "--max-units", "must be >= 0");
  ThreadLimit limit(a.threads);
  BuildReport r;
  if (launchedByMpi()) {
    int rank = 0, ranks = 1;
    r = buildMpi(a.dir, a.opt, &rank, &ranks);
    if (rank != 0) return;  // rank 0 speaks for the build
    fmt::print("{} rank(s): 1 coordinator, {} worker(s) x {} thread(s)\n", ranks,
               std::max(ranks - 1, 1), limit.threads());
  } else {
    BuildFolder folder(a.dir);
    r = buildLocal(folder, a.opt);
  }
  // the share of the workers' wall time not spent inside units: scheduling, waiting, idling
  const double worker_s = r.wall_s * r.workers;
  fmt::print("ran {} unit(s) in {:.1f} s ({:.1f} s in units over {} worker(s), {:.2f} % of their "
             "time outside units): {} done, {} frames\n",
             r.units_run, r.wall_s, r.unit_s, r.workers,
             worker_s > 0 ? 100.0 * std::max(0.0, worker_s - r.unit_s) / worker_s : 0.0,
             r.units_done, r.frames);
  if (r.unit_s > 0)
    fmt::print("in units: {:.1f} s setting up (scene, trajectory), {:.1f} s rendering and writing "
               "frames, {:.1f} s other (checksums, manifest)\n",
               r.setup_s, r.sequences_s, std::max(0.0, r.unit_s - r.setup_s - r.sequences_s));
  for (const auto& [rank, rss] : r.rss_kb) {
    if (rss.empty()) continue;
    // after the first unit, a tenth, half and all of them: flat once the caches are warm
    const size_t n = rss.size();
    fmt::print("rank {} resident memory after unit 1: {:.0f} MB, {}: {:.0f} MB, {}: {:.0f} MB, "
               "{}: {:.0f} MB; highest {:.0f} MB\n",
               rank, rss.front() / 1024.0, std::max<size_t>(1, n / 10),
               rss[std::max<size_t>(1, n / 10) - 1] / 1024.0, std::max<size_t>(1, n / 2),
               rss[std::max<size_t>(1, n / 2) - 1] / 1024.0, n, rss.back() / 1024.0,
               *std::max_element(rss.begin(), rss.end()) / 1024.0);
  }
  if (r.failed_total > 0)
    throw InputError(a.dir, "units",
                     fmt::format("{} unit(s) failed {} time(s) each; `interiornet dataset status "
                                 "{}` lists their errors, a rerun retries them",
                                 r.failed_total, a.opt.max_attempts, a.dir));
}

struct StatusArgs {
  std::string dir;
  bool json = false;
};

struct VerifyArgs {
  std::string dir;
};

void runVerify(const VerifyArgs& a) {
  const BuildFolder folder(a.dir, StateAccess::Read);
  const VerifyReport v = verifyBuild(folder);
  for (const std::string& p : v.problems) std::fprintf(stderr, "%s\n", p.c_str());
  if (!v.problems.empty())
    throw InputError(a.dir, "files",
                     fmt::format("{} of {} file(s) of {} done unit(s) do not match the state",
                                 v.problems.size(), v.files, v.units));
  fmt::print("verified {} file(s) of {} done unit(s): all present with their checksums\n",
             v.files, v.units);
}

}  // namespace

void registerDataset(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "dataset",
      "Build a dataset: a spec (docs/dataset.md) into a plan of layouts, sequences, sparse views "
      "and splits, then its work units into sequence folders, resumably; stats charts what a build "
      "holds (docs/dataset.md)");
  cmd->require_subcommand(1);

  auto plan = std::make_shared<PlanArgs>();
  auto* p = cmd->add_subcommand(
      "plan", "Read a dataset spec (YAML or JSON; docs/examples/dataset.yaml) and write its plan "
              "to OUT/plan.json: every layout with its split and subset, every sequence with its "
              "trajectory draws; the same spec gives the same plan");
  p->add_option("SPEC", plan->spec, "the dataset spec file")->required();
  p->add_option("--out", plan->out, "the build folder (created)")->required();
  p->callback([plan] { runPlan(*plan); });

  auto build = std::make_shared<BuildArgs>();
  auto* b = cmd->add_subcommand(
      "build", "Run the plan's pending work units into DIR/data (sequence frame ranges and "
               "batches of sparse views), recording each in DIR/state.sqlite; stop it at any "
               "time (SIGTERM, Ctrl-C, a kill) and rerun to finish the rest, with the same bytes. "
               "Under mpirun (mpirun -np N interiornet dataset build DIR) rank 0 hands units to "
               "ranks 1..N-1 as they free up (docs/cluster.md)");
  b->add_option("DIR", build->dir, "the build folder (with plan.json)")->required();
  b->add_option("--threads", build->threads,
                "worker threads, 0 = all cores (default 0); never changes the output");
  b->add_option("--max-attempts", build->opt.max_attempts,
                "runs of a failing unit before it is left failed (default 3)");
  b->add_option("--max-units", build->opt.max_units,
                "stop after running this many units (default 0 = all)");
  b->add_flag("--no-progress{false}", build->opt.progress, "do not draw the progress bar");
  b->callback([build] { runBuild(*build); });

  auto status = std::make_shared<StatusArgs>();
  auto* s = cmd->add_subcommand(
      "status", "Units and frames done, running, pending and failed; frames/s overall and per "
                "rank; ETA; the last errors");
  s->add_option("DIR", status->dir, "the build folder")->required();
  s->add_flag("--json", status->json, "as JSON");
  s->callback([status] {
    const BuildFolder folder(status->dir, StateAccess::Read);
    fmt::print("{}", status->json ? statusJson(folder) : statusText(folder));
  });

  auto verify = std::make_shared<VerifyArgs>();
  auto* v = cmd->add_subcommand(
      "verify", "Check that every done unit's files are present with the checksums recorded "
                "when they were written");
  v->add_option("DIR", verify->dir, "the build folder")->required();
  v->callback([verify] { runVerify(*verify); });
  registerDatasetStats(*cmd);
  registerDatasetShards(*cmd);
}

}  // namespace inet::app
