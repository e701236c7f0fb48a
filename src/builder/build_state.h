#pragma once
// The job state of `interiornet dataset build` (issue 16) in SQLite: one row per work unit,
// pending / running (rank, start) / done (seconds, checksums of its files) / failed (attempts,
// last error). One process writes it: the coordinator (the build's rank 0, or the only process),
// never the workers, so the database never has many writers on a shared filesystem. Every
// change is a transaction, so a job killed at any moment leaves a consistent database; a rerun
// puts the units the killed job left running back to pending (resetRunning) and goes on.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;

namespace inet {

enum class UnitState { Pending = 0, Running = 1, Done = 2, Failed = 3 };
/// "pending", "running", "done", "failed".
const char* unitStateName(UnitState s);

/// One unit's row.
struct UnitRecord {
  int64_t order = 0;  ///< position in units(plan): units are handed out in this order
  std::string id;
  int64_t frames = 0;
  UnitState state = UnitState::Pending;
  int rank = -1;               ///< running: the rank working on it
  double started = 0.0;        ///< running: seconds since the epoch
  double seconds = 0.0;        ///< done: wall time of the unit on its rank
  int attempts = 0;            ///< failed runs so far
  std::string error;           ///< the last failure's message
  std::string checksums;       ///< done: JSON object {relative path: "crc32:size"}
};

struct StateCounts {
  int64_t units[4] = {0, 0, 0, 0};   ///< by UnitState
  int64_t frames[4] = {0, 0, 0, 0};  ///< by UnitState
  double done_seconds = 0.0;         ///< sum of the done units' seconds
  int64_t total() const { return units[0] + units[1] + units[2] + units[3]; }
};

class BuildState {
 public:
  /// Opens or creates the database (InputError naming it when it cannot). Read-only: opens it
  /// without writing (`status`, `verify`, from any host while a build runs); a database that
  /// does not exist yet is then an empty one in memory (nothing built).
  explicit BuildState(const std::filesystem::path& db, bool read_only = false);
  ~BuildState();
  BuildState(const BuildState&) = delete;
  BuildState& operator=(const BuildState&) = delete;

  /// Adds the units not in the database yet as pending, in one transaction; existing rows keep
  /// their state (read-only: only checks that the database belongs to the plan). `plan_checksum` is stored and must match on later syncs (InputError
  /// otherwise: a build folder belongs to one plan).
  void sync(const std::vector<std::pair<std::string, int64_t>>& ids_and_frames,
            const std::string& plan_checksum);
  /// Units a killed job left running become pending again; returns their orders.
  std::vector<int64_t> resetRunning();
  /// Failed units with fewer than `max_attempts` attempts become pending again; returns how many.
  int64_t retryFailed(int max_attempts);
  /// The first pending unit in order, marked running on `rank`; none when nothing is pending.
  std::optional<UnitRecord> claim(int rank, double now);
  void markDone(const std::string& id, double seconds, const std::string& checksums);
  /// A running unit goes back to pending without counting an attempt (its rank was stopped).
  void release(const std::string& id);
  /// Counts an attempt; the unit goes back to pending while attempts < max_attempts, else to
  /// failed.
  void markFailed(const std::string& id, const std::string& error, int max_attempts);

  StateCounts counts() const;
  /// Rows in a state, in order (all when state is empty), at most `limit` (0 = all).
  std::vector<UnitRecord> units(std::optional<UnitState> state, int64_t limit = 0) const;
  /// Calls `f` with every row in a state, in order, one at a time (a million done units'
  /// checksums do not fit in memory at once).
  void forEach(UnitState state, const std::function<void(const UnitRecord&)>& f) const;
  /// The rows with an error (failed, or pending after a failed attempt), in order.
  std::vector<UnitRecord> withErrors() const;
  std::optional<UnitRecord> unit(const std::string& id) const;
  /// Done units' seconds and frames per rank that ran them: rank, units, frames, seconds.
  struct RankStats {
    int rank = 0;
    int64_t units = 0, frames = 0;
    double seconds = 0.0;
  };
  std::vector<RankStats> rankStats() const;

 private:
  void exec(const std::string& sql) const;
  void createSchema();
  sqlite3* db_ = nullptr;
  bool read_only_ = false;
  std::string path_;
};

}  // namespace inet
