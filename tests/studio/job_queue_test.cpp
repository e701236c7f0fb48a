// studio/job_queue.h: background jobs run on their own workers, report progress and failures,
// and the store stays bounded.
#include "studio/job_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include "core/error.h"

namespace inet::studio {
namespace {

using nlohmann::json;

/// Polls until the job leaves pending/running (or 10 s pass).
JobStatus waitFor(const JobQueue& q, const std::string& id) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (;;) {
    const JobStatus s = *q.status(id);
    if (s.state == JobState::Done || s.state == JobState::Failed ||
        s.state == JobState::Cancelled || std::chrono::steady_clock::now() > deadline)
      return s;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

TEST(JobQueue, RunsReportsProgressAndResults) {
  JobQueue q({1, 8});
  std::promise<void> go;
  std::shared_future<void> gate = go.get_future().share();
  const auto id = q.submit("test", [gate](JobContext& ctx) {
    ctx.progress(0.25, "a quarter");
    gate.wait();
    return json{{"answer", 42}};
  });
  ASSERT_TRUE(id);
  // running, at a quarter, until the gate opens
  for (int i = 0; i < 1000 && q.status(*id)->progress < 0.25; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  JobStatus s = *q.status(*id);
  EXPECT_EQ(s.state, JobState::Running);
  EXPECT_EQ(s.message, "a quarter");
  EXPECT_EQ(s.toJson()["state"], "running");
  EXPECT_FALSE(s.toJson().contains("result"));
  go.set_value();
  s = waitFor(q, *id);
  EXPECT_EQ(s.state, JobState::Done);
  EXPECT_EQ(s.progress, 1.0);
  EXPECT_EQ(s.toJson()["result"]["answer"], 42);
  EXPECT_FALSE(q.status("nope").has_value());
}

TEST(JobQueue, CancelStopsRunningAndRemovesPendingJobs) {
  JobQueue q({1, 8});
  std::atomic<bool> started{false};
  // runs until told to stop, as a sequence job does between frame ranges
  const auto running = q.submit("test", [&](JobContext& ctx) -> json {
    started = true;
    while (!ctx.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    throw InputError("", "", "stopped after 3 of 9 frames");
  });
  const auto pending = q.submit("test", [](JobContext&) { return json{{"ran", true}}; });
  ASSERT_TRUE(running && pending);
  while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(q.cancel(*pending), JobQueue::Cancel::Removed);
  EXPECT_EQ(q.status(*pending)->state, JobState::Cancelled);
  EXPECT_EQ(q.cancel(*running), JobQueue::Cancel::Requested);
  const JobStatus s = waitFor(q, *running);
  EXPECT_EQ(s.state, JobState::Cancelled);
  EXPECT_EQ(s.toJson()["state"], "cancelled");
  EXPECT_NE(s.message.find("stopped after 3 of 9 frames"), std::string::npos) << s.message;
  EXPECT_EQ(q.cancel(*running), JobQueue::Cancel::Finished);
  EXPECT_EQ(q.cancel("nope"), JobQueue::Cancel::NotFound);
  // the worker is free again
  const auto next = q.submit("test", [](JobContext&) { return json{{"ran", true}}; });
  EXPECT_EQ(waitFor(q, *next).state, JobState::Done);
}

TEST(JobQueue, FailuresCarryTheOneLineError) {
  JobQueue q({1, 8});
  const auto a = q.submit("test", [](JobContext&) -> json {
    throw InputError("layout.json", "free space", "no room for a camera");
  });
  const auto b = q.submit("test", [](JobContext&) -> json { throw std::runtime_error("boom"); });
  const JobStatus sa = waitFor(q, *a), sb = waitFor(q, *b);
  EXPECT_EQ(sa.state, JobState::Failed);
  EXPECT_EQ(sa.toJson()["error"], (json{{"error", "layout.json: free space: no room for a camera"},
                                        {"file", "layout.json"},
                                        {"field", "free space"}}));
  EXPECT_EQ(sb.message, "boom");
}

TEST(JobQueue, StoreIsBoundedAndForgetsFinishedJobsFirst) {
  JobQueue q({1, 3});
  std::promise<void> go;
  std::shared_future<void> gate = go.get_future().share();
  auto blocked = [gate](JobContext&) {
    gate.wait();
    return json();
  };
  const auto done = q.submit("quick", [](JobContext&) { return json(1); });
  ASSERT_EQ(waitFor(q, *done).state, JobState::Done);
  const auto r1 = q.submit("slow", blocked), r2 = q.submit("slow", blocked);
  ASSERT_TRUE(r1 && r2);
  // full (3 stored): the finished job makes room, then nothing does
  const auto r3 = q.submit("slow", blocked);
  ASSERT_TRUE(r3);
  EXPECT_FALSE(q.status(*done).has_value());
  EXPECT_FALSE(q.submit("slow", blocked).has_value());
  EXPECT_EQ(q.list().size(), 3u);
  for (int i = 0; i < 1000 && q.running() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(q.running(), 1);  // one worker: the others wait
  EXPECT_EQ(q.status(*r3)->state, JobState::Pending);
  go.set_value();
  EXPECT_EQ(waitFor(q, *r3).state, JobState::Done);
  EXPECT_TRUE(q.submit("again", [](JobContext&) { return json(); }).has_value());
}

TEST(JobQueue, ShutdownFailsPendingAndWaitsForRunning) {
  JobQueue q({1, 8});
  std::atomic<bool> saw_cancel{false};
  std::atomic<bool> started{false};
  const auto running = q.submit("loop", [&](JobContext& ctx) {
    started = true;
    while (!ctx.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    saw_cancel = true;
    return json("stopped early");
  });
  const auto pending = q.submit("never", [](JobContext&) { return json(); });
  while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  q.shutdown();
  EXPECT_TRUE(saw_cancel);
  EXPECT_EQ(q.status(*running)->state, JobState::Done);
  EXPECT_EQ(q.status(*pending)->state, JobState::Failed);
  EXPECT_FALSE(q.submit("late", [](JobContext&) { return json(); }).has_value());
  q.shutdown();  // idempotent
}

}  // namespace
}  // namespace inet::studio
