#pragma once
// Background jobs of the studio: work that takes longer than a request should (a trajectory
// now; preview renders and whole sequences later) runs on a few worker threads of its own while
// the page polls GET /api/jobs/<id> for its state and progress.
//
// Bounded on both sides: at most `workers` jobs run at once, and at most `max_stored` jobs are
// kept (pending, running or finished). When the store is full the oldest finished job is
// forgotten; when every stored job is still unfinished, submit() refuses (the server answers
// 503) rather than queueing without end.
#include <nlohmann/json.hpp>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace inet::studio {

enum class JobState { Pending, Running, Done, Failed, Cancelled };
/// "pending", "running", "done", "failed", "cancelled".
const char* jobStateName(JobState s);

/// A job's state as the API reports it.
struct JobStatus {
  std::string id;
  std::string kind;  ///< what it does ("trajectory")
  JobState state = JobState::Pending;
  double progress = 0.0;  ///< 0..1
  std::string message;    ///< what it is doing, or why it failed (one line)
  nlohmann::json result;  ///< set when done
  nlohmann::json error;   ///< set when failed: {"error", "file", "field"}
  int64_t created_ms = 0, started_ms = 0,
          finished_ms = 0;  ///< since the queue started, 0 = not yet
  int64_t elapsed_ms = 0;   ///< running time so far (when the status was taken)
  /// {"id", "kind", "state", "progress", "message", "elapsed_ms", "result"/"error"}.
  nlohmann::json toJson(bool with_result = true) const;
};

/// What a running job may tell the queue; thread-safe.
class JobContext {
 public:
  /// Sets the progress (clamped to 0..1) and the message shown with it.
  virtual void progress(double fraction, const std::string& message) = 0;
  /// True once the job is cancelled or the queue is shutting down: long work should stop at its
  /// next safe point (return or throw; either way the job ends "cancelled" when it was
  /// cancelled).
  virtual bool cancelled() const = 0;

 protected:
  ~JobContext() = default;
};

class JobQueue {
 public:
  /// The work: returns the result JSON; an InputError or other exception fails the job with
  /// its message.
  using Work = std::function<nlohmann::json(JobContext&)>;
  struct Options {
    int workers = 1;      ///< jobs running at once
    int max_stored = 64;  ///< jobs remembered (finished ones are forgotten oldest first)
  };

  explicit JobQueue(Options opt);
  ~JobQueue();  ///< shutdown()
  JobQueue(const JobQueue&) = delete;
  JobQueue& operator=(const JobQueue&) = delete;

  /// Queues `work`; returns its id, or nullopt when max_stored unfinished jobs are stored.
  std::optional<std::string> submit(const std::string& kind, Work work);
  std::optional<JobStatus> status(const std::string& id) const;
  /// What cancel() did: nothing (no such job, or it has finished), removed a pending job, or
  /// asked a running one to stop (JobContext::cancelled(); it ends "cancelled" when it does).
  enum class Cancel { NotFound, Finished, Removed, Requested };
  Cancel cancel(const std::string& id);
  /// Every stored job, oldest first, without results.
  std::vector<JobStatus> list() const;
  /// Pending jobs fail ("the server stopped"); running ones are told (cancelled()) and waited
  /// for. Idempotent.
  void shutdown();
  int running() const;

 private:
  struct Job;
  class Context;
  void workerLoop();
  int64_t nowMs() const;
  JobStatus snapshot(const Job& job) const;  ///< under mutex_

  Options opt_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::deque<std::string> order_;  ///< ids, oldest first
  std::deque<std::shared_ptr<Job>> pending_;
  std::vector<std::thread> workers_;
  bool stopping_ = false;
  int running_ = 0;
  uint64_t next_serial_ = 0;
  uint64_t id_salt_ = 0;
  const int64_t start_ns_;
};

}  // namespace inet::studio
