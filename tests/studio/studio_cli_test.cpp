// `interiornet studio` end to end: the real binary on a free port (--port 0, the port read from
// the URL it prints), its placeholder page and /api/health, and a clean exit on SIGTERM; its
// one-line errors and its help.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <thread>

#include "../cli/cli_util.h"

extern char** environ;

namespace inet::test {
namespace {

using Clock = std::chrono::steady_clock;

/// The studio as a child process, its stdout on a pipe.
class StudioProcess {
 public:
  explicit StudioProcess(const std::vector<std::string>& args) {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe");
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    std::vector<std::string> argv_s = {INET_BINARY, "studio"};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& s : argv_s) argv.push_back(s.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, INET_BINARY, &fa, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
    ::close(fds[1]);
    out_fd_ = fds[0];
  }
  ~StudioProcess() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    ::close(out_fd_);
  }
  /// Reads stdout until `pattern` matches a line or `timeout_s` passes; returns the match.
  std::smatch waitForLine(const std::regex& pattern, double timeout_s) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    std::smatch m;
    while (Clock::now() < deadline) {
      size_t nl;
      while ((nl = buffer_.find('\n')) != std::string::npos) {
        line_ = buffer_.substr(0, nl);
        buffer_.erase(0, nl + 1);
        all_ += line_ + "\n";
        if (std::regex_search(line_, m, pattern)) return m;
      }
      pollfd p{out_fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) > 0) {
        char buf[4096];
        const ssize_t n = ::read(out_fd_, buf, sizeof buf);
        if (n <= 0) break;
        buffer_.append(buf, static_cast<size_t>(n));
      }
    }
    return m;
  }
  /// Waits up to `timeout_s` for the exit; the exit code, or -1 if still running.
  int waitExit(double timeout_s) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (Clock::now() < deadline) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
  }
  pid_t pid() const { return pid_; }
  const std::string& output() const { return all_; }

 private:
  pid_t pid_ = -1;
  int out_fd_ = -1;
  bool exited_ = false;
  std::string buffer_, line_, all_;
};

/// VmRSS of process `pid` in KiB.
long rssKibOf(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      long v = 0;
      in >> v;
      return v;
    }
    std::getline(in, key);
  }
  return -1;
}

/// `n` clients, each on its own thread and connection, post a 250-frame preview at once;
/// returns how many got their poses.
int concurrentPreviews(int port, const std::string& token, int n, int round) {
  std::atomic<int> ok{0};
  std::vector<std::thread> clients;
  for (int i = 0; i < n; ++i)
    clients.emplace_back([&, i] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(60, 0);
      c.set_bearer_token_auth(token);
      const nlohmann::json body = {{"frames", 250}, {"seed", round * 1000 + i}};
      auto r = c.Post("/api/trajectory/preview", body.dump(), "application/json");
      if (r && r->status == 200 && nlohmann::json::parse(r->body)["poses"].size() == 250) ++ok;
    });
  for (std::thread& t : clients) t.join();
  return ok;
}

TEST(StudioCli, ServesOnAFreePortAndStopsCleanlyOnSigterm) {
  StudioProcess studio({"--layout", "builtin:room", "--port", "0"});
  ASSERT_GT(studio.pid(), 0);
  const std::smatch m = studio.waitForLine(
      std::regex(R"(serving http://127\.0\.0\.1:(\d+)/\?token=([0-9a-f]{32}) )"), 60.0);
  ASSERT_FALSE(m.empty()) << "no URL printed; stdout so far:\n" << studio.output();
  const int port = std::stoi(m[1].str());
  const std::string token = m[2].str();
  ASSERT_GT(port, 0);
  httplib::Client c("127.0.0.1", port);
  // a random access token: nothing without it
  auto r = c.Get("/api/health");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  EXPECT_EQ(c.Get("/")->status, 401);
  c.set_bearer_token_auth(token);
  r = c.Get("/api/health");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(nlohmann::json::parse(r->body)["status"], "ok");
  r = c.Get("/");  // the page the build bundled (or studio/web/unbuilt without node_modules)
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("interiornet studio"), std::string::npos);
  r = c.Get("/api/layout");
  ASSERT_TRUE(r);
  EXPECT_EQ(nlohmann::json::parse(r->body)["source"], "builtin:room");

  // the server process's own memory under rounds of 50 concurrent previews
  const long rss_start = rssKibOf(studio.pid());
  std::vector<long> rss;
  for (int round = 0; round < 4; ++round) {
    EXPECT_EQ(concurrentPreviews(port, token, 50, round), 50) << "round " << round + 1;
    rss.push_back(rssKibOf(studio.pid()));
  }
  std::cout << "studio e2e: server VmRSS " << rss_start << " KiB after start, after each round of "
            << "50 concurrent previews:";
  for (long k : rss) std::cout << " " << k;
  std::cout << " KiB\n";
  // the first round pays for the worker threads and glibc's per-thread malloc arenas (~42 MiB
  // here; with MALLOC_ARENA_MAX=2 it is ~9 MiB); later rounds add ~2 MiB each until the arenas
  // are all made (measured over 12 rounds: +60 MiB, then flat), not per request
  EXPECT_LT(rss.back() - rss_start, 96 * 1024);
  EXPECT_LT(rss.back() - rss[0], 32 * 1024);

  const auto t0 = Clock::now();
  ASSERT_EQ(::kill(studio.pid(), SIGTERM), 0);
  const int code = studio.waitExit(10.0);
  const double stop_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  EXPECT_EQ(code, 0);
  EXPECT_FALSE(studio.waitForLine(std::regex("stopped by SIGTERM"), 2.0).empty())
      << studio.output();
  std::cout << "studio e2e: port " << port << ", SIGTERM to exit " << stop_ms << " ms\n";
  // the port is free again
  EXPECT_FALSE(httplib::Client("127.0.0.1", port).Get("/api/health"));
}

TEST(StudioCli, RefusesANonLoopbackHostWithOneLine) {
  const RunResult r = runInterinet("studio --layout builtin:room --host 0.0.0.0 --port 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error: --host: '0.0.0.0' is not a loopback address"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--allow-remote"), std::string::npos);
  const RunResult d = runInterinet("studio --layout builtin:room --port 0 --data nonsense");
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("error: --data: 'nonsense' is not NAME=DIR"), std::string::npos) << d.err;
  const RunResult t = runInterinet("studio --layout builtin:room --port 0 --tls-cert cert.pem");
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_NE(t.err.find("error: --tls-key: HTTPS needs both --tls-cert and --tls-key"),
            std::string::npos)
      << t.err;
}

TEST(StudioCli, HelpExplainsTheTunnel) {
  const RunResult r = runInterinet("studio --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("ssh -L 8080:localhost:8080"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--allow-remote"), std::string::npos);
  EXPECT_NE(r.out.find("--port"), std::string::npos);
  EXPECT_NE(r.out.find("--tls-cert"), std::string::npos);
}

}  // namespace
}  // namespace inet::test
