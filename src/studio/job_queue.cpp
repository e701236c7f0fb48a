#include "studio/job_queue.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <random>

#include "core/error.h"

namespace inet::studio {

const char* jobStateName(JobState s) {
  switch (s) {
    case JobState::Pending:
      return "pending";
    case JobState::Running:
      return "running";
    case JobState::Done:
      return "done";
    case JobState::Failed:
      return "failed";
    case JobState::Cancelled:
      return "cancelled";
  }
  return "?";
}

nlohmann::json JobStatus::toJson(bool with_result) const {
  nlohmann::json j = {{"id", id},
                      {"kind", kind},
                      {"state", jobStateName(state)},
                      {"progress", progress},
                      {"message", message}};
  j["elapsed_ms"] = elapsed_ms;
  if (with_result && state == JobState::Done) j["result"] = result;
  if (state == JobState::Failed) j["error"] = error;
  return j;
}

struct JobQueue::Job {
  JobStatus status;
  Work work;
  bool cancel_requested = false;
};

/// The context of one running job: writes go to its status under the queue's lock.
class JobQueue::Context final : public JobContext {
 public:
  Context(JobQueue& q, Job& job) : q_(q), job_(job) {}
  void progress(double fraction, const std::string& message) override {
    std::lock_guard lock(q_.mutex_);
    job_.status.progress = std::clamp(fraction, 0.0, 1.0);
    job_.status.message = message;
  }
  bool cancelled() const override {
    std::lock_guard lock(q_.mutex_);
    return q_.stopping_ || job_.cancel_requested;
  }

 private:
  JobQueue& q_;
  Job& job_;
};

JobQueue::JobQueue(Options opt)
    : opt_(opt), start_ns_(std::chrono::steady_clock::now().time_since_epoch().count()) {
  INET_CHECK(opt_.workers >= 1 && opt_.max_stored >= 1);
  // ids need not be secret, only not repeat across restarts (a page polling an old id)
  id_salt_ = std::random_device{}();
  for (int i = 0; i < opt_.workers; ++i) workers_.emplace_back([this] { workerLoop(); });
}

JobQueue::~JobQueue() {
  shutdown();
}

int64_t JobQueue::nowMs() const {
  // + 1: a time of 0 means "not yet"
  return (std::chrono::steady_clock::now().time_since_epoch().count() - start_ns_) / 1'000'000 + 1;
}

std::optional<std::string> JobQueue::submit(const std::string& kind, Work work) {
  std::lock_guard lock(mutex_);
  if (stopping_) return std::nullopt;
  if (static_cast<int>(jobs_.size()) >= opt_.max_stored) {
    // forget the oldest finished job to make room
    auto it = std::find_if(order_.begin(), order_.end(), [&](const std::string& id) {
      const JobState s = jobs_.at(id)->status.state;
      return s == JobState::Done || s == JobState::Failed || s == JobState::Cancelled;
    });
    if (it == order_.end()) return std::nullopt;
    jobs_.erase(*it);
    order_.erase(it);
  }
  auto job = std::make_shared<Job>();
  job->status.id = fmt::format("{:08x}{:04x}", id_salt_ & 0xffffffffu, ++next_serial_);
  job->status.kind = kind;
  job->status.message = "waiting";
  job->status.created_ms = nowMs();
  job->work = std::move(work);
  jobs_[job->status.id] = job;
  order_.push_back(job->status.id);
  pending_.push_back(job);
  wake_.notify_one();
  return job->status.id;
}

JobStatus JobQueue::snapshot(const Job& job) const {
  JobStatus s = job.status;
  if (s.started_ms > 0) s.elapsed_ms = (s.finished_ms > 0 ? s.finished_ms : nowMs()) - s.started_ms;
  return s;
}

std::optional<JobStatus> JobQueue::status(const std::string& id) const {
  std::lock_guard lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  return snapshot(*it->second);
}

std::vector<JobStatus> JobQueue::list() const {
  std::lock_guard lock(mutex_);
  std::vector<JobStatus> out;
  for (const std::string& id : order_) {
    JobStatus s = snapshot(*jobs_.at(id));
    s.result = nullptr;
    out.push_back(std::move(s));
  }
  return out;
}

JobQueue::Cancel JobQueue::cancel(const std::string& id) {
  std::lock_guard lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return Cancel::NotFound;
  Job& job = *it->second;
  switch (job.status.state) {
    case JobState::Pending:
      pending_.erase(std::find(pending_.begin(), pending_.end(), it->second));
      job.status.state = JobState::Cancelled;
      job.status.message = "cancelled before it started";
      job.status.finished_ms = nowMs();
      job.work = nullptr;
      return Cancel::Removed;
    case JobState::Running:
      job.cancel_requested = true;
      job.status.message = "cancelling: " + job.status.message;
      return Cancel::Requested;
    default:
      return Cancel::Finished;
  }
}

int JobQueue::running() const {
  std::lock_guard lock(mutex_);
  return running_;
}

void JobQueue::workerLoop() {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !pending_.empty(); });
      if (stopping_) return;
      job = pending_.front();
      pending_.pop_front();
      job->status.state = JobState::Running;
      job->status.started_ms = nowMs();
      job->status.message = "running";
      ++running_;
    }
    Context ctx(*this, *job);
    nlohmann::json result, error;
    try {
      result = job->work(ctx);
    } catch (const InputError& e) {
      error = {{"error", e.what()}, {"file", e.file()}, {"field", e.field()}};
    } catch (const std::exception& e) {
      error = {{"error", e.what()}, {"file", ""}, {"field", ""}};
    }
    std::lock_guard lock(mutex_);
    --running_;
    job->status.finished_ms = nowMs();
    job->work = nullptr;  // what it captured is no longer needed
    if (job->cancel_requested && !error.is_null()) {
      job->status.state = JobState::Cancelled;
      job->status.message = "cancelled: " + error["error"].get<std::string>();
    } else if (error.is_null()) {
      job->status.state = JobState::Done;
      job->status.progress = 1.0;
      job->status.message = "done";
      job->status.result = std::move(result);
    } else {
      job->status.state = JobState::Failed;
      job->status.message = error["error"].get<std::string>();
      job->status.error = std::move(error);
    }
  }
}

void JobQueue::shutdown() {
  std::vector<std::thread> workers;
  {
    std::lock_guard lock(mutex_);
    workers.swap(workers_);
    stopping_ = true;
    for (auto& job : pending_) {
      job->status.state = JobState::Failed;
      job->status.message = "the server stopped before the job started";
      job->status.error = {{"error", job->status.message}, {"file", ""}, {"field", ""}};
      job->work = nullptr;
    }
    pending_.clear();
  }
  wake_.notify_all();
  for (std::thread& t : workers) t.join();
}

}  // namespace inet::studio
