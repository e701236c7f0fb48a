#include "builder/build_state.h"

#include <sqlite3.h>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
namespace {

/// A prepared statement, finalised at scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql, const std::string& where) : where_(where) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw InputError(where, "", fmt::format("SQLite: {} ({})", sqlite3_errmsg(db), sql));
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& bind(int i, const std::string& v) {
    sqlite3_bind_text(stmt_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& bind(int i, int64_t v) {
    sqlite3_bind_int64(stmt_, i, v);
    return *this;
  }
  Statement& bind(int i, double v) {
    sqlite3_bind_double(stmt_, i, v);
    return *this;
  }
  /// Steps once: true with a row, false when done.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw InputError(where_, "",
                     fmt::format("SQLite: {}", sqlite3_errmsg(sqlite3_db_handle(stmt_))));
  }
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  int64_t integer(int col) const { return sqlite3_column_int64(stmt_, col); }
  double real(int col) const { return sqlite3_column_double(stmt_, col); }
  std::string text(int col) const {
    const auto* t = sqlite3_column_text(stmt_, col);
    return t ? std::string(reinterpret_cast<const char*>(t)) : std::string();
  }

 private:
  sqlite3_stmt* stmt_ = nullptr;
  std::string where_;
};

constexpr const char* kColumns =
    "ord, id, frames, state, rank, started, seconds, attempts, error, checksums";

UnitRecord recordOf(const Statement& s) {
  UnitRecord r;
  r.order = s.integer(0);
  r.id = s.text(1);
  r.frames = s.integer(2);
  r.state = static_cast<UnitState>(s.integer(3));
  r.rank = static_cast<int>(s.integer(4));
  r.started = s.real(5);
  r.seconds = s.real(6);
  r.attempts = static_cast<int>(s.integer(7));
  r.error = s.text(8);
  r.checksums = s.text(9);
  return r;
}

}  // namespace

const char* unitStateName(UnitState s) {
  switch (s) {
    case UnitState::Pending:
      return "pending";
    case UnitState::Running:
      return "running";
    case UnitState::Done:
      return "done";
    case UnitState::Failed:
      return "failed";
  }
  return "?";
}

BuildState::BuildState(const std::filesystem::path& db, bool read_only) : path_(db.string()) {
  std::error_code ec;
  // read-only and nothing built yet: an empty state in memory, never a file written
  const bool fresh = read_only && !std::filesystem::exists(db, ec);
  read_only_ = read_only && !fresh;
  const int flags = read_only_ ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  if (sqlite3_open_v2(fresh ? ":memory:" : path_.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw InputError(path_, "", "cannot open the build state: " + msg);
  }
  // One writer (the build); a reader (`dataset status` while a build runs) waits a little
  // rather than failing. Write-ahead logging keeps readers from blocking the writer.
  sqlite3_busy_timeout(db_, 10000);
  if (!read_only_) createSchema();
}

void BuildState::createSchema() {
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=NORMAL");
  exec("CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT)");
  exec(
      "CREATE TABLE IF NOT EXISTS units (ord INTEGER PRIMARY KEY, id TEXT UNIQUE NOT NULL, "
      "frames INTEGER, state INTEGER, rank INTEGER, started REAL, seconds REAL, "
      "attempts INTEGER, error TEXT, checksums TEXT)");
  exec("CREATE INDEX IF NOT EXISTS units_by_state ON units (state, ord)");
}

BuildState::~BuildState() {
  sqlite3_close(db_);
}

void BuildState::exec(const std::string& sql) const {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw InputError(path_, "", fmt::format("SQLite: {} ({})", msg, sql));
  }
}

void BuildState::sync(const std::vector<std::pair<std::string, int64_t>>& ids_and_frames,
                      const std::string& plan_checksum) {
  if (read_only_) {
    Statement get(db_, "SELECT value FROM meta WHERE key = 'plan'", path_);
    if (get.step() && get.text(0) != plan_checksum)
      throw InputError(path_, "plan", "this build folder was made from another plan");
    return;
  }
  exec("BEGIN IMMEDIATE");
  try {
    Statement get(db_, "SELECT value FROM meta WHERE key = 'plan'", path_);
    if (get.step()) {
      if (get.text(0) != plan_checksum)
        throw InputError(path_, "plan",
                         "this build folder was made from another plan (checksum " + get.text(0) +
                             ", the plan now " + plan_checksum +
                             "); build a changed plan into a new folder");
    } else {
      Statement put(db_, "INSERT INTO meta (key, value) VALUES ('plan', ?)", path_);
      put.bind(1, plan_checksum).step();
    }
    Statement count(db_, "SELECT COUNT(*) FROM units", path_);
    count.step();
    // a plan's units are fixed by the plan: rows exist for all of them or for none
    if (count.integer(0) == 0) {
      Statement ins(db_,
                    "INSERT INTO units (ord, id, frames, state, rank, started, seconds, "
                    "attempts, error, checksums) VALUES (?, ?, ?, 0, -1, 0, 0, 0, '', '')",
                    path_);
      for (size_t i = 0; i < ids_and_frames.size(); ++i) {
        ins.bind(1, static_cast<int64_t>(i))
            .bind(2, ids_and_frames[i].first)
            .bind(3, ids_and_frames[i].second)
            .step();
        ins.reset();
      }
    } else if (count.integer(0) != static_cast<int64_t>(ids_and_frames.size())) {
      throw InputError(
          path_, "units",
          fmt::format("holds {} units, the plan has {}", count.integer(0), ids_and_frames.size()));
    }
    exec("COMMIT");
  } catch (...) {
    exec("ROLLBACK");
    throw;
  }
}

std::vector<int64_t> BuildState::resetRunning() {
  std::vector<int64_t> orders;
  for (const UnitRecord& r : units(UnitState::Running)) orders.push_back(r.order);
  exec("UPDATE units SET state = 0, rank = -1, started = 0 WHERE state = 1");
  return orders;
}

int64_t BuildState::retryFailed(int max_attempts) {
  Statement s(db_, "UPDATE units SET state = 0 WHERE state = 3 AND attempts < ?", path_);
  s.bind(1, static_cast<int64_t>(max_attempts)).step();
  return sqlite3_changes(db_);
}

std::optional<UnitRecord> BuildState::claim(int rank, double now) {
  exec("BEGIN IMMEDIATE");
  try {
    Statement next(
        db_, fmt::format("SELECT {} FROM units WHERE state = 0 ORDER BY ord LIMIT 1", kColumns),
        path_);
    if (!next.step()) {
      exec("COMMIT");
      return std::nullopt;
    }
    UnitRecord r = recordOf(next);
    Statement run(db_, "UPDATE units SET state = 1, rank = ?, started = ? WHERE ord = ?", path_);
    run.bind(1, static_cast<int64_t>(rank)).bind(2, now).bind(3, r.order).step();
    exec("COMMIT");
    r.state = UnitState::Running;
    r.rank = rank;
    r.started = now;
    return r;
  } catch (...) {
    exec("ROLLBACK");
    throw;
  }
}

void BuildState::markDone(const std::string& id, double seconds, const std::string& checksums) {
  Statement s(db_,
              "UPDATE units SET state = 2, seconds = ?, checksums = ?, error = '' "
              "WHERE id = ?",
              path_);
  s.bind(1, seconds).bind(2, checksums).bind(3, id).step();
}

void BuildState::release(const std::string& id) {
  Statement s(db_, "UPDATE units SET state = 0, rank = -1, started = 0 WHERE id = ? AND state = 1",
              path_);
  s.bind(1, id).step();
}

void BuildState::markFailed(const std::string& id, const std::string& error, int max_attempts) {
  Statement s(db_,
              "UPDATE units SET attempts = attempts + 1, error = ?, rank = -1, "
              "state = CASE WHEN attempts + 1 < ? THEN 0 ELSE 3 END WHERE id = ?",
              path_);
  s.bind(1, error).bind(2, static_cast<int64_t>(max_attempts)).bind(3, id).step();
}

StateCounts BuildState::counts() const {
  StateCounts c;
  Statement s(db_, "SELECT state, COUNT(*), SUM(frames), SUM(seconds) FROM units GROUP BY state",
              path_);
  while (s.step()) {
    const int64_t st = s.integer(0);
    if (st < 0 || st > 3) continue;
    c.units[st] = s.integer(1);
    c.frames[st] = s.integer(2);
    if (st == static_cast<int64_t>(UnitState::Done)) c.done_seconds = s.real(3);
  }
  return c;
}

std::vector<UnitRecord> BuildState::units(std::optional<UnitState> state, int64_t limit) const {
  std::string sql = fmt::format("SELECT {} FROM units", kColumns);
  if (state) sql += fmt::format(" WHERE state = {}", static_cast<int>(*state));
  sql += " ORDER BY ord";
  if (limit > 0) sql += fmt::format(" LIMIT {}", limit);
  Statement s(db_, sql, path_);
  std::vector<UnitRecord> out;
  while (s.step()) out.push_back(recordOf(s));
  return out;
}

void BuildState::forEach(UnitState state, const std::function<void(const UnitRecord&)>& f) const {
  Statement s(db_, fmt::format("SELECT {} FROM units WHERE state = ? ORDER BY ord", kColumns),
              path_);
  s.bind(1, static_cast<int64_t>(state));
  while (s.step()) f(recordOf(s));
}

std::vector<UnitRecord> BuildState::withErrors() const {
  Statement s(db_, fmt::format("SELECT {} FROM units WHERE error != '' ORDER BY ord", kColumns),
              path_);
  std::vector<UnitRecord> out;
  while (s.step()) out.push_back(recordOf(s));
  return out;
}

std::optional<UnitRecord> BuildState::unit(const std::string& id) const {
  Statement s(db_, fmt::format("SELECT {} FROM units WHERE id = ?", kColumns), path_);
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return recordOf(s);
}

std::vector<BuildState::RankStats> BuildState::rankStats() const {
  Statement s(db_,
              "SELECT rank, COUNT(*), SUM(frames), SUM(seconds) FROM units WHERE state = 2 "
              "GROUP BY rank ORDER BY rank",
              path_);
  std::vector<RankStats> out;
  while (s.step())
    out.push_back({static_cast<int>(s.integer(0)), s.integer(1), s.integer(2), s.real(3)});
  return out;
}

}  // namespace inet
