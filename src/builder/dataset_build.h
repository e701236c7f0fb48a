#pragma once
// `interiornet dataset build | status | verify` (issue 16) over a build folder (unit_runner.h):
// the coordinator that hands out a plan's work units and keeps the job state (build_state.h).
//
// A build is resumable at any moment: every file is written atomically, the state records a
// unit as done only after its files are whole (with their checksums), a unit a killed job left
// running is run again (the sequence pipeline skips its finished frames), and a failed unit is
// retried up to max_attempts times. The same plan gives the same bytes whatever the
// interruptions, the thread count or (with MPI) the rank count.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "builder/build_state.h"
#include "builder/dataset_plan.h"
#include "core/progress.h"

namespace inet {

struct BuildOptions {
  int max_attempts = 3;   ///< runs of a failing unit before it is left failed
  bool progress = true;   ///< a progress bar over the plan's frames
  int64_t max_units = 0;  ///< stop after running this many units (0 = all)
};

struct BuildReport {
  int64_t units_run = 0, units_done = 0, units_failed = 0;
  int64_t frames = 0;          ///< frames (and sparse views) of the units done now
  double wall_s = 0.0;         ///< wall time of the build
  double unit_s = 0.0;         ///< wall time inside units, summed over the workers
  int workers = 1;             ///< ranks that ran units (the rest of their time is overhead)
  double setup_s = 0.0;        ///< of unit_s: the pipeline before the first frame
  double sequences_s = 0.0;    ///< of unit_s: the pipeline rendering and writing frames
  /// Per rank that ran units: its resident memory after each of them, in the order run.
  std::map<int, std::vector<int64_t>> rss_kb;
  int64_t pending_after = 0;   ///< units still pending (max_units, or failures to retry)
  int64_t failed_total = 0;    ///< units failed for good, over the whole state
};

/// How a command uses the job state: a build writes it; status and verify only read it (from
/// any host, while a build runs); an MPI worker never opens it (only the coordinator does).
enum class StateAccess { Write, Read, None };

/// The plan and state of a build folder. Opens state.sqlite as `access` says (a build creates
/// it and syncs it with plan.json); InputError if the folder holds no plan.
class BuildFolder {
 public:
  explicit BuildFolder(const std::filesystem::path& root,
                       StateAccess access = StateAccess::Write);
  const std::filesystem::path& root() const { return root_; }
  const DatasetPlan& plan() const { return plan_; }
  const std::vector<WorkUnit>& units() const { return units_; }
  /// The unit of a state row (by its order).
  const WorkUnit& unit(int64_t order) const { return units_.at(static_cast<size_t>(order)); }
  bool hasState() const { return state_ != nullptr; }
  BuildState& state() { return *state_; }
  const BuildState& state() const { return *state_; }

 private:
  std::filesystem::path root_;
  DatasetPlan plan_;
  std::vector<WorkUnit> units_;
  std::unique_ptr<BuildState> state_;
};

/// What one unit did, as a rank reports it to the coordinator.
struct UnitResult {
  enum class Kind { Done, Failed, Stopped } kind = Kind::Done;
  double seconds = 0.0;
  double setup_s = 0.0, sequences_s = 0.0;  ///< of seconds: UnitOutput's
  int64_t rss_kb = 0;  ///< the rank's resident memory after the unit (VmRSS)
  std::string text;    ///< Done: the checksums; Failed: the error; Stopped: the message
};
/// Runs one unit and says how it went (never throws, but for a bug).
UnitResult runUnitCaught(const BuildFolder& folder, const WorkUnit& unit);

/// The one process that writes the job state, for the local build and for MPI's rank 0: hands
/// out units, records what the ranks report, keeps the progress bar and the report.
class Coordinator {
 public:
  /// Before any unit runs: units a killed build left running are pending again, and the
  /// temporary files they may have left half-written (in their layouts' folders and among the
  /// unit manifests) are removed, so a resumed build leaves no partial file; failed units with
  /// attempts left are pending again. Says what it did on stderr.
  Coordinator(BuildFolder& folder, const BuildOptions& opt);
  /// The next unit's order for `rank`, marked running; none when nothing is pending, after
  /// opt.max_units, or after a stop signal.
  std::optional<int64_t> claim(int rank);
  /// Records what `rank` reports of unit `order`.
  void record(int64_t order, int rank, const UnitResult& result);
  /// Writes manifest.jsonl when every unit is done; the report of the build so far.
  BuildReport finish(int workers);

 private:
  BuildFolder& folder_;
  BuildOptions opt_;
  BuildReport report_;
  double t0_ = 0.0;
  int64_t frames_done_ = 0;
  std::unique_ptr<ProgressBar> bar_;
};

/// Runs every pending unit of the build folder in this process (TBB threads inside each unit),
/// in plan order. A SIGTERM or SIGINT (core/stop.h) stops after the unit in flight reaches a
/// safe point: that unit goes back to pending and StopRequested propagates.
BuildReport buildLocal(BuildFolder& folder, const BuildOptions& opt);

/// When every unit is done: joins the units' manifest rows (unit_runner.h) in plan order into
/// manifest.jsonl (atomically). Returns whether it wrote it.
bool writeManifestIfComplete(const BuildFolder& folder);

/// `dataset status`: units and frames per state, frames/s overall and per rank, ETA, the last
/// errors. As text for the terminal, or as JSON.
std::string statusText(const BuildFolder& folder);
std::string statusJson(const BuildFolder& folder);

/// `dataset verify`: every done unit's files present with their recorded checksums.
struct VerifyReport {
  int64_t units = 0, files = 0;
  std::vector<std::string> problems;  ///< "<path>: missing" or "<path>: checksum ... != ..."
};
VerifyReport verifyBuild(const BuildFolder& folder);

}  // namespace inet
