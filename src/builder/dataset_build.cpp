#include "builder/dataset_build.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "builder/shards.h"
#include "builder/unit_runner.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/stop.h"

namespace inet {

namespace fs = std::filesystem;

namespace {

double nowSeconds() {
  using namespace std::chrono;
  return duration<double>(system_clock::now().time_since_epoch()).count();
}

double steadySeconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

BuildFolder::BuildFolder(const fs::path& root, StateAccess access) : root_(root) {
  const fs::path plan_file = root / "plan.json";
  std::error_code ec;
  if (!fs::is_regular_file(plan_file, ec))
    throw InputError(root.string(), "plan.json",
                     "not a build folder: no plan.json (make one with `interiornet dataset plan "
                     "SPEC --out " +
                         root.string() + "`)");
  plan_ = readPlan(plan_file);
  units_ = inet::units(plan_);
  if (access == StateAccess::None) return;
  state_ = std::make_unique<BuildState>(root / "state.sqlite", access == StateAccess::Read);
  std::vector<std::pair<std::string, int64_t>> rows;
  rows.reserve(units_.size());
  for (const WorkUnit& u : units_) rows.emplace_back(u.id, u.frames);
  state_->sync(rows, specChecksum(readTextFile(plan_file)));
}

namespace {

/// VmRSS of this process from /proc/self/status, in kB (0 where there is none).
int64_t residentKb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atoll(line.c_str() + 6);
  return 0;
}

/// The unit's position in the plan (`unit` is one of folder.units()).
int64_t unitOrder(const BuildFolder& folder, const WorkUnit& unit) {
  const int64_t order = static_cast<int64_t>(&unit - folder.units().data());
  INET_CHECK(order >= 0 && order < static_cast<int64_t>(folder.units().size()));
  return order;
}

}  // namespace

bool writeManifestIfComplete(const BuildFolder& folder) {
  const StateCounts c = folder.state().counts();
  if (c.units[static_cast<int>(UnitState::Done)] != c.total()) return false;
  for (size_t k = 0; k < folder.units().size(); ++k) {
    const fs::path rows = unitManifestPath(folder.root(), static_cast<int64_t>(k));
    std::error_code ec;
    if (!fs::is_regular_file(rows, ec)) {  // `dataset verify` names it
      std::fprintf(stderr, "warning: %s is missing: manifest.jsonl not written (dataset verify)\n",
                   rows.string().c_str());
      return false;
    }
  }
  // streamed unit by unit: the paper's 20M frames would be tens of GB of rows
  writeFileAtomic(folder.root() / "manifest.jsonl", [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    for (size_t k = 0; k < folder.units().size(); ++k) {
      const fs::path rows = unitManifestPath(folder.root(), static_cast<int64_t>(k));
      std::ifstream in(rows, std::ios::binary);
      if (fs::file_size(rows) > 0) out << in.rdbuf();  // (inserting nothing would set failbit)
    }
    if (!out) throw InputError(tmp.string(), "", "cannot write the manifest");
  });
  return true;
}

UnitResult runUnitCaught(const BuildFolder& folder, const WorkUnit& unit) {
  UnitResult r;
  const double t0 = steadySeconds();
  try {
    const UnitOutput out = runUnit(folder.plan(), unit, unitOrder(folder, unit), folder.root());
    r.text = out.checksums;
    r.setup_s = out.setup_s;
    r.sequences_s = out.sequences_s;
    r.kind = UnitResult::Kind::Done;
  } catch (const StopRequested& e) {
    r.kind = UnitResult::Kind::Stopped;
    r.text = e.what();
  } catch (const std::exception& e) {
    r.kind = UnitResult::Kind::Failed;
    r.text = e.what();
  }
  r.seconds = steadySeconds() - t0;
  r.rss_kb = residentKb();
  return r;
}

Coordinator::Coordinator(BuildFolder& folder, const BuildOptions& opt)
    : folder_(folder), opt_(opt), t0_(steadySeconds()) {
  BuildState& state = folder.state();
  const std::vector<int64_t> again = state.resetRunning();
  // nothing runs now: a temporary file in a folder of those units is a killed write
  std::set<fs::path> folders;
  for (const int64_t order : again) {
    const WorkUnit& u = folder.unit(order);
    for (int i = 0; i < u.layout_count; ++i)
      folders.insert(folder.root() / "data" /
                     layoutFolder(folder.plan().layouts.at(static_cast<size_t>(u.layout + i))));
  }
  if (!again.empty()) folders.insert(folder.root() / "manifest");
  size_t removed = 0;
  for (const fs::path& dir : folders) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
      if (e.is_regular_file(ec) && isTemporaryName(e.path().filename().string()))
        removed += fs::remove(e.path(), ec);
  }
  if (!again.empty())
    std::fprintf(stderr,
                 "resuming: %zu unit(s) a stopped build left running run again (%zu "
                 "half-written file(s) removed)\n",
                 again.size(), removed);
  const int64_t retried = state.retryFailed(opt.max_attempts);
  if (retried > 0)
    std::fprintf(stderr, "retrying %lld failed unit(s)\n", static_cast<long long>(retried));
  const StateCounts c = state.counts();
  frames_done_ = c.frames[static_cast<int>(UnitState::Done)];
  bar_ = std::make_unique<ProgressBar>(c.frames[0] + c.frames[1] + c.frames[2] + c.frames[3],
                                       "frames", opt.progress);
  bar_->update(frames_done_);
}

std::optional<int64_t> Coordinator::claim(int rank) {
  if (stopSignal() != 0 || (opt_.max_units > 0 && report_.units_run >= opt_.max_units))
    return std::nullopt;
  const std::optional<UnitRecord> r = folder_.state().claim(rank, nowSeconds());
  if (!r) return std::nullopt;
  ++report_.units_run;
  return r->order;
}

void Coordinator::record(int64_t order, int rank, const UnitResult& result) {
  const WorkUnit& unit = folder_.unit(order);
  BuildState& state = folder_.state();
  report_.unit_s += result.seconds;
  report_.setup_s += result.setup_s;
  report_.sequences_s += result.sequences_s;
  report_.rss_kb[rank].push_back(result.rss_kb);
  switch (result.kind) {
    case UnitResult::Kind::Done:
      state.markDone(unit.id, result.seconds, result.text);
      ++report_.units_done;
      report_.frames += unit.frames;
      frames_done_ += unit.frames;
      bar_->update(frames_done_);
      return;
    case UnitResult::Kind::Stopped:
      state.release(unit.id);  // not done: a rerun does it
      return;
    case UnitResult::Kind::Failed:
      break;
  }
  state.markFailed(unit.id, result.text, opt_.max_attempts);
  const auto after = state.unit(unit.id);
  std::fprintf(stderr, "unit %s failed on rank %d (attempt %d of %d): %s\n", unit.id.c_str(), rank,
               after ? after->attempts : 0, opt_.max_attempts, result.text.c_str());
  if (!after || after->state == UnitState::Failed) ++report_.units_failed;
}

BuildReport Coordinator::finish(int workers) {
  bar_->finish();
  // the shards hold the manifest's rows, so they follow it; a rerun of a complete build finds
  // them whole and rewrites none
  if (writeManifestIfComplete(folder_) && folder_.plan().spec.shards.enabled) {
    ShardOptions so = shardOptions(folder_.plan().spec);
    so.progress = opt_.progress;
    const ShardReport r = writeShards(folder_.root(), so);
    size_t shards = 0;
    for (const auto& [split, list] : r.splits) shards += list.size();
    std::fprintf(stderr,
                 "%zu shard(s) of %lld samples in %s: %.1f MB written, %.1f MB unchanged "
                 "(%.1f s)\n",
                 shards, static_cast<long long>(r.samples),
                 (folder_.root() / "shards").string().c_str(), r.bytes_written / 1e6,
                 (r.bytes - r.bytes_written) / 1e6, r.seconds);
  }
  const StateCounts c = folder_.state().counts();
  report_.pending_after = c.units[static_cast<int>(UnitState::Pending)];
  report_.failed_total = c.units[static_cast<int>(UnitState::Failed)];
  report_.wall_s = steadySeconds() - t0_;
  report_.workers = workers;
  return report_;
}

BuildReport buildLocal(BuildFolder& folder, const BuildOptions& opt) {
  Coordinator coordinator(folder, opt);
  while (const std::optional<int64_t> order = coordinator.claim(0))
    coordinator.record(*order, 0, runUnitCaught(folder, folder.unit(*order)));
  const BuildReport report = coordinator.finish(1);
  stopIfSignalled("between work units of " + folder.root().string());
  return report;
}

namespace {

struct StatusData {
  StateCounts counts;
  std::vector<BuildState::RankStats> ranks;
  double rate = 0.0;  ///< frames/s, summed over ranks
  double eta_s = 0.0;
  std::vector<UnitRecord> running, errors;
};

StatusData statusData(const BuildFolder& folder) {
  StatusData d;
  const BuildState& st = folder.state();
  d.counts = st.counts();
  d.ranks = st.rankStats();
  for (const auto& r : d.ranks)
    if (r.seconds > 0) d.rate += static_cast<double>(r.frames) / r.seconds;
  const int64_t left = d.counts.frames[0] + d.counts.frames[1];
  d.eta_s = d.rate > 0 ? static_cast<double>(left) / d.rate : 0.0;
  d.running = st.units(UnitState::Running);
  d.errors = st.withErrors();
  return d;
}

}  // namespace

std::string statusText(const BuildFolder& folder) {
  const StatusData d = statusData(folder);
  const PlanCounts pc = planCounts(folder.plan());
  std::string s = fmt::format(
      "dataset {} ({}): {} layouts, {} sequences, {} units, {} frames\n", folder.plan().spec.name,
      folder.root().string(), pc.layouts, pc.sequences, d.counts.total(),
      d.counts.frames[0] + d.counts.frames[1] + d.counts.frames[2] + d.counts.frames[3]);
  for (int k = 0; k < 4; ++k)
    s += fmt::format("  {:<8} {:>8} units {:>10} frames\n", unitStateName(UnitState(k)),
                     d.counts.units[k], d.counts.frames[k]);
  s += fmt::format("  speed    {:.2f} frames/s", d.rate);
  if (d.eta_s > 0) s += fmt::format(", ETA {}", formatDuration(d.eta_s));
  s += "\n";
  for (const auto& r : d.ranks)
    s += fmt::format("  rank {:<3} {:>6} units {:>8} frames {:>9.1f} s {:>7.2f} frames/s\n", r.rank,
                     r.units, r.frames, r.seconds,
                     r.seconds > 0 ? static_cast<double>(r.frames) / r.seconds : 0.0);
  for (const UnitRecord& u : d.running)
    s += fmt::format("  running  {} on rank {}\n", u.id, u.rank);
  const size_t shown = std::min<size_t>(5, d.errors.size());
  for (size_t i = d.errors.size() - shown; i < d.errors.size(); ++i)
    s += fmt::format("  error    {} ({} attempt(s), {}): {}\n", d.errors[i].id,
                     d.errors[i].attempts, unitStateName(d.errors[i].state), d.errors[i].error);
  return s;
}

std::string statusJson(const BuildFolder& folder) {
  const StatusData d = statusData(folder);
  nlohmann::ordered_json j;
  j["dataset"] = folder.plan().spec.name;
  for (int k = 0; k < 4; ++k) j["units"][unitStateName(UnitState(k))] = d.counts.units[k];
  for (int k = 0; k < 4; ++k) j["frames"][unitStateName(UnitState(k))] = d.counts.frames[k];
  j["frames_per_s"] = d.rate;
  j["eta_s"] = d.eta_s;
  j["ranks"] = nlohmann::ordered_json::array();
  for (const auto& r : d.ranks)
    j["ranks"].push_back(
        {{"rank", r.rank}, {"units", r.units}, {"frames", r.frames}, {"seconds", r.seconds}});
  j["running"] = nlohmann::ordered_json::array();
  for (const UnitRecord& u : d.running)
    j["running"].push_back({{"unit", u.id}, {"rank", u.rank}, {"started", u.started}});
  j["errors"] = nlohmann::ordered_json::array();
  for (const UnitRecord& u : d.errors)
    j["errors"].push_back({{"unit", u.id},
                           {"state", unitStateName(u.state)},
                           {"attempts", u.attempts},
                           {"error", u.error}});
  return j.dump(2) + "\n";
}

VerifyReport verifyBuild(const BuildFolder& folder) {
  VerifyReport v;
  folder.state().forEach(UnitState::Done, [&](const UnitRecord& u) {
    ++v.units;
    nlohmann::json sums;
    try {
      sums = nlohmann::json::parse(u.checksums);
    } catch (const nlohmann::json::exception&) {
      v.problems.push_back(u.id + ": its recorded checksums do not parse");
      return;
    }
    for (const auto& [rel, want] : sums.items()) {
      ++v.files;
      const fs::path f = folder.root() / rel;
      std::error_code ec;
      if (!fs::is_regular_file(f, ec)) {
        v.problems.push_back(rel + ": missing (unit " + u.id + ")");
        continue;
      }
      const std::string got = fileChecksum(f);
      if (got != want.get<std::string>())
        v.problems.push_back(fmt::format("{}: checksum {} where unit {} recorded {}", rel, got,
                                         u.id, want.get<std::string>()));
    }
  });
  return v;
}

}  // namespace inet
