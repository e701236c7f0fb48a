// Issue 16: interiornet dataset plan | build | status | verify on a small plan (two procedural
// apartments with parametric furniture, a 4-frame sequence each in 2-frame units, their sparse
// views in three configurations, 48x36 at 1 spp). The same plan gives the same bytes whatever
// the threads or the interruptions (SIGKILL mid-unit, SIGTERM), the state agrees with the files
// (verify), a unit that fails is retried a bounded number of times with its error listed, and
// bad input is a one-line error.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "core/atomic_file.h"

namespace fs = std::filesystem;

namespace inet::test {
namespace {

const std::string kSpec = kTinyDatasetSpec;

/// Every file of a build folder but the job state (whose rows hold times).
std::map<std::string, std::string> buildTree(const fs::path& dir) {
  auto t = readTree(dir);
  for (auto it = t.begin(); it != t.end();)
    it = it->first.rfind("state.sqlite", 0) == 0 ? t.erase(it) : std::next(it);
  return t;
}

void expectSameTree(const std::map<std::string, std::string>& want, const fs::path& dir) {
  const auto got = buildTree(dir);
  EXPECT_EQ(got.size(), want.size()) << dir;
  for (const auto& [name, bytes] : want)
    EXPECT_TRUE(got.count(name) && got.at(name) == bytes) << name << " differs in " << dir;
}

size_t colourFrames(const fs::path& data) {
  size_t n = 0;
  std::error_code ec;
  if (!fs::exists(data, ec)) return 0;
  for (const auto& e : fs::recursive_directory_iterator(data, ec))
    n += e.path().extension() == ".png" && e.path().parent_path().parent_path().filename() == "cam0";
  return n;
}

/// Starts `interiornet args` and sends `sig` once `frames` colour frames exist under data;
/// returns the wait status.
int signalAfterFrames(const std::string& args, const fs::path& data, size_t frames, int sig) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = std::string("exec ") + INET_BINARY + " " + args + " >/dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (colourFrames(data) < frames && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

/// The mpirun command line of the tests: shared memory only (no network needed), as root too
/// (CI runs as root), more ranks than cores allowed. Empty when mpirun is not installed.
std::string mpirun(int ranks) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) return "";
  return "mpirun --allow-run-as-root --oversubscribe --mca btl self,vader -np " +
         std::to_string(ranks) + " ";
}

/// Starts `command` (a shell command line) and returns its pid.
pid_t spawnShell(const std::string& command) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec " + command + " >/dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

/// The pids of the ranks building `dir` (processes whose command line is this binary's build of
/// it, not mpirun's), in rank order (OMPI_COMM_WORLD_RANK from their environment).
std::vector<pid_t> rankPids(const std::string& dir) {
  std::map<int, pid_t> by_rank;
  const std::string want = std::string(INET_BINARY) + '\0' + "dataset" + '\0' + "build" + '\0' +
                           dir + '\0';
  std::error_code ec;  // processes come and go while we look
  for (const auto& e : fs::directory_iterator("/proc", ec)) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream cmdline(e.path() / "cmdline", std::ios::binary);
    const std::string args((std::istreambuf_iterator<char>(cmdline)), {});
    if (args.rfind(want, 0) != 0) continue;
    std::ifstream environ(e.path() / "environ", std::ios::binary);
    // a NUL in front, so that the first variable is found like the others
    const std::string env =
        std::string(1, '\0') + std::string((std::istreambuf_iterator<char>(environ)), {});
    const std::string key = std::string(1, '\0') + "OMPI_COMM_WORLD_RANK=";
    const size_t at = env.find(key);
    if (at == std::string::npos) continue;
    by_rank[std::atoi(env.c_str() + at + key.size())] = std::stoi(name);
  }
  std::vector<pid_t> pids;
  for (const auto& [rank, pid] : by_rank) pids.push_back(pid);
  return pids;
}

class CliDataset : public ::testing::Test {
 protected:
  /// One reference build, made by the first test of this process that needs it (ctest runs
  /// each test in its own process): plan and a local build with two threads.
  static void SetUpTestSuite() {
    shared_ = new TempDir("dataset_ref");
    writeFile(*shared_ / "tiny.yaml", kSpec);
  }
  static void TearDownTestSuite() {
    delete reference_;
    delete shared_;
  }
  static void buildReference() {
    if (reference_) return;
    const std::string ref = (*shared_ / "ref").string();
    plan_ = runInterinet("dataset plan " + (*shared_ / "tiny.yaml").string() + " --out " + ref);
    build_ = runInterinet("dataset build " + ref + " --no-progress --threads 2");
    reference_ = new std::map<std::string, std::string>(buildTree(ref));
    ASSERT_EQ(plan_.exit_code, 0) << plan_.err;
    ASSERT_EQ(build_.exit_code, 0) << build_.err;
  }
  static std::string spec() { return (*shared_ / "tiny.yaml").string(); }
  /// A new build folder with the reference's plan.
  std::string planned(const std::string& name) {
    const std::string out = (dir_ / name).string();
    const RunResult p = runInterinet("dataset plan " + spec() + " --out " + out);
    EXPECT_EQ(p.exit_code, 0) << p.err;
    return out;
  }
  static TempDir* shared_;
  static RunResult plan_, build_;
  static std::map<std::string, std::string>* reference_;
  TempDir dir_{"dataset"};
};
TempDir* CliDataset::shared_ = nullptr;
RunResult CliDataset::plan_, CliDataset::build_;
std::map<std::string, std::string>* CliDataset::reference_ = nullptr;

TEST_F(CliDataset, PlanBuildStatusAndVerify) {
  ASSERT_NO_FATAL_FAILURE(buildReference());
  EXPECT_NE(plan_.out.find("2 layouts, 2 sequences (8 frames), 6 sparse views, 5 work units"),
            std::string::npos)
      << plan_.out;
  EXPECT_NE(build_.out.find("5 done, 14 frames"), std::string::npos) << build_.out;
  // every sequence folder whole: indexes, boxes.json, imu0/, and the sparse views
  size_t sequences = 0, sparse = 0, boxes = 0, imu = 0;
  for (const auto& [name, bytes] : *reference_) {
    const fs::path p(name);
    sequences += p.filename() == "rgb.txt" && p.parent_path().filename() == "seq_000";
    sparse += p.filename() == "rgb.txt" &&
              p.parent_path().filename().string().rfind("sparse", 0) == 0;
    boxes += p.filename() == "boxes.json";
    imu += p.filename() == "sensor.yaml" && p.parent_path().filename() == "imu0";
  }
  EXPECT_EQ(sequences, 2u);
  EXPECT_EQ(sparse, 6u);
  EXPECT_EQ(boxes, 8u);
  EXPECT_EQ(imu, 2u);
  // the manifest: one row per frame and sparse view, in plan order, naming existing files
  ASSERT_TRUE(reference_->count("manifest.jsonl"));
  std::istringstream rows(reference_->at("manifest.jsonl"));
  std::string line;
  size_t n = 0, sparse_rows = 0;
  while (std::getline(rows, line)) {
    const nlohmann::json row = nlohmann::json::parse(line);
    ++n;
    sparse_rows += row["sequence"] == "sparse";
    for (const char* key : {"split", "subset", "layout", "configuration", "folder", "t_ns"})
      EXPECT_TRUE(row.contains(key)) << line;
    EXPECT_EQ(row["folder"].get<std::string>().rfind("data/" + row["split"].get<std::string>() +
                                                         "/" + row["subset"].get<std::string>(),
                                                     0),
              0u)
        << line;
    ASSERT_TRUE(row["files"].contains("cam0")) << line;
    // parametric furniture: no catalog piece to credit, but the instance image was looked at
    ASSERT_TRUE(row["files"].contains("label0_instance")) << line;
    EXPECT_EQ(row["assets"], nlohmann::json::array()) << line;
    for (const auto& [pass, path] : row["files"].items())
      EXPECT_TRUE(reference_->count(path.get<std::string>())) << pass << " " << path;
  }
  EXPECT_EQ(n, 14u);
  EXPECT_EQ(sparse_rows, 6u);
  // data/<split>/<subset>/<layout>/...
  for (const auto& [name, bytes] : *reference_) {
    if (name.rfind("data/", 0) != 0) continue;
    const std::string split = name.substr(5, name.find('/', 5) - 5);
    EXPECT_TRUE(split == "train" || split == "validation" || split == "test") << name;
    EXPECT_NE(name.find("/rooms_0"), std::string::npos) << name;
  }

  const std::string ref = (*shared_ / "ref").string();
  const RunResult status = runInterinet("dataset status " + ref);
  ASSERT_EQ(status.exit_code, 0) << status.err;
  EXPECT_NE(status.out.find("done            5 units         14 frames"), std::string::npos)
      << status.out;
  EXPECT_NE(status.out.find("rank 0 "), std::string::npos) << status.out;
  const RunResult json = runInterinet("dataset status --json " + ref);
  EXPECT_NE(json.out.find("\"done\": 5"), std::string::npos) << json.out;
  const RunResult verify = runInterinet("dataset verify " + ref);
  ASSERT_EQ(verify.exit_code, 0) << verify.err;
  EXPECT_NE(verify.out.find("of 5 done unit(s): all present"), std::string::npos) << verify.out;

  // verify finds a changed file and a missing one, naming them (in a copy)
  fs::copy(*shared_ / "ref", dir_ / "v", fs::copy_options::recursive);
  fs::path victim, gone;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "v" / "data"))
    if (e.path().extension() == ".png") (victim.empty() ? victim : gone) = e.path();
  {
    std::ofstream f(victim, std::ios::binary | std::ios::app);
    f << "x";
  }
  fs::remove(gone);
  const RunResult bad = runInterinet("dataset verify " + (dir_ / "v").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find(victim.filename().string() + ": checksum"), std::string::npos)
      << bad.err;
  EXPECT_NE(bad.err.find(gone.filename().string() + ": missing"), std::string::npos) << bad.err;
}

// SIGKILL mid-unit, then a rerun; SIGTERM (a scheduler's warning): exit 143 with no unit left
// running, then a rerun. Both end with the reference's bytes, and verify passes.
TEST_F(CliDataset, KilledOrStoppedBuildsResumeToTheSameBytes) {
  ASSERT_NO_FATAL_FAILURE(buildReference());
  const std::string c = planned("c");
  const int killed = signalAfterFrames("dataset build " + c + " --no-progress", dir_ / "c" / "data",
                                       3, SIGKILL);
  EXPECT_TRUE(WIFSIGNALED(killed));
  const RunResult after_kill = runInterinet("dataset status --json " + c);
  EXPECT_NE(after_kill.out.find("\"running\": 1"), std::string::npos) << after_kill.out;
  const RunResult resumed = runInterinet("dataset build " + c + " --no-progress");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("resuming: 1 unit(s)"), std::string::npos) << resumed.err;
  expectSameTree(*reference_, dir_ / "c");
  EXPECT_EQ(runInterinet("dataset verify " + c).exit_code, 0);

  const std::string d = planned("d");
  const int termed = signalAfterFrames("dataset build " + d + " --no-progress", dir_ / "d" / "data",
                                       1, SIGTERM);
  ASSERT_TRUE(WIFEXITED(termed));
  EXPECT_EQ(WEXITSTATUS(termed), 143);
  const nlohmann::json after_term =
      nlohmann::json::parse(runInterinet("dataset status --json " + d).out);
  EXPECT_EQ(after_term["units"]["running"].get<int>(), 0) << after_term.dump();
  EXPECT_GT(after_term["units"]["pending"].get<int>(), 0) << after_term.dump();
  ASSERT_EQ(runInterinet("dataset build " + d + " --no-progress").exit_code, 0);
  expectSameTree(*reference_, dir_ / "d");
}

// The MPI path for real: mpirun -np 1 (one thread) and -np 3 (a coordinator and two workers of
// one thread each) both end with the bytes of the threaded reference build, the -np 3 one after
// three SIGKILLs mid-build, each followed by a rerun: a worker (which takes the job down), the
// coordinator, and every process of the job at once.
TEST_F(CliDataset, MpiRanksGiveTheSameBytesAndSurviveAKilledRank) {
  if (mpirun(1).empty()) GTEST_SKIP() << "mpirun not found (Debian: openmpi-bin)";
  ASSERT_NO_FATAL_FAILURE(buildReference());
  const std::string one = planned("one");
  ASSERT_EQ(std::system((mpirun(1) + INET_BINARY + " dataset build " + one +
                         " --no-progress --threads 1 >/dev/null 2>&1")
                            .c_str()),
            0);
  expectSameTree(*reference_, dir_ / "one");

  const std::string three = planned("three");
  const std::string cmd =
      mpirun(3) + INET_BINARY + " dataset build " + three + " --no-progress --threads 1";
  // SIGKILL a worker, then the coordinator, then every process of the job (mpirun and the
  // ranks at once), each while units are in flight; each rerun goes on from the state
  const struct {
    const char* what;
    size_t frames;  // of 14 colour frames: the kill comes mid-build
  } kills[] = {{"worker", 3}, {"coordinator", 6}, {"job", 9}};
  for (const auto& k : kills) {
    const pid_t job = spawnShell(cmd);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (colourFrames(dir_ / "three" / "data") < k.frames &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const std::vector<pid_t> ranks = rankPids(three);
    ASSERT_EQ(ranks.size(), 3u) << k.what << ": the ranks of the job";
    if (std::string(k.what) == "worker") kill(ranks[1], SIGKILL);
    if (std::string(k.what) == "coordinator") kill(ranks[0], SIGKILL);
    if (std::string(k.what) == "job") {
      kill(job, SIGKILL);  // mpirun (the shell exec'd it)
      for (pid_t r : ranks) kill(r, SIGKILL);
    }
    int status = 0;
    waitpid(job, &status, 0);
    EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << k.what << ": the job went on without a rank";
    for (int i = 0; i < 200 && !rankPids(three).empty(); ++i)  // orphans of a killed mpirun
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(rankPids(three).empty()) << k.what << ": ranks outlived the job";
    // the job really was cut short: some units are not done
    const nlohmann::json mid =
        nlohmann::json::parse(runInterinet("dataset status --json " + three).out);
    EXPECT_LT(mid["units"]["done"].get<int>(), 5) << k.what << ": " << mid.dump();
  }
  ASSERT_EQ(std::system((cmd + " >/dev/null 2>&1").c_str()), 0);
  expectSameTree(*reference_, dir_ / "three");
  const RunResult status3 = runInterinet("dataset status " + three);
  EXPECT_NE(status3.out.find("rank 1 "), std::string::npos) << status3.out;
  EXPECT_NE(status3.out.find("rank 2 "), std::string::npos) << status3.out;
  EXPECT_EQ(runInterinet("dataset verify " + three).exit_code, 0);
}

TEST_F(CliDataset, AFailingUnitIsRetriedAndListedAndTheRestIsBuilt) {
  // a folder layout that is JSON but not a layout: its units fail, the apartment's do not
  writeFile(dir_ / "layouts" / "broken.json", R"({"rooms": [1, 2]})");
  std::string text = kSpec;
  text.replace(text.find("count: 2"), 8, "count: 1");
  const std::string layouts = "  procedural: {count: 1, rooms: [2, 3], furniture: parametric}\n";
  text.insert(text.find(layouts) + layouts.size(), "  folders: [layouts]\n");
  writeFile(dir_ / "mixed.yaml", text);
  const std::string out = (dir_ / "m").string();
  const RunResult plan = runInterinet("dataset plan " + (dir_ / "mixed.yaml").string() +
                                      " --out " + out);
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const RunResult build = runInterinet("dataset build " + out + " --no-progress --max-attempts 2");
  EXPECT_EQ(build.exit_code, 2) << build.err;
  EXPECT_NE(build.err.find("failed 2 time(s) each"), std::string::npos) << build.err;
  EXPECT_NE(build.err.find("attempt 2 of 2"), std::string::npos) << build.err;
  const RunResult status = runInterinet("dataset status " + out);
  EXPECT_NE(status.out.find("error    seq/file:layouts/broken.json"), std::string::npos)
      << status.out;
  EXPECT_NE(status.out.find("broken.json"), std::string::npos) << status.out;
  // the apartment's sequence is whole
  size_t whole = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "m" / "data"))
    whole += e.path().filename() == "rgb.txt" && e.path().parent_path().filename() == "seq_000";
  EXPECT_EQ(whole, 1u);
  EXPECT_EQ(runInterinet("dataset verify " + out).exit_code, 0);
}

TEST_F(CliDataset, BadInputIsAOneLineErrorAndWritesNothing) {
  writeFile(dir_ / "bad.yaml", "version: 1\nname: x\nlayouts: {procedural: {count: 1}}\nsequence: {}\n");
  const RunResult bad = runInterinet("dataset plan " + (dir_ / "bad.yaml").string() + " --out " +
                                     (dir_ / "x").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.yaml"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("sequence"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("line 4"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "x"));
  const RunResult none = runInterinet("dataset build " + (dir_ / "nowhere").string());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("no plan.json"), std::string::npos) << none.err;
  // a build folder belongs to its plan
  const std::string out = (dir_ / "p").string();
  ASSERT_EQ(runInterinet("dataset plan " + spec() + " --out " + out).exit_code, 0);
  // status reads the state and writes nothing (it may run on any host while a build runs)
  ASSERT_EQ(runInterinet("dataset status " + out).exit_code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "p" / "state.sqlite"));
  ASSERT_EQ(runInterinet("dataset build " + out + " --max-units 1 --no-progress").exit_code, 0);
  std::string other = kSpec;
  other.replace(other.find("seed: 3"), 7, "seed: 4");
  writeFile(dir_ / "other.yaml", other);
  const RunResult replan =
      runInterinet("dataset plan " + (dir_ / "other.yaml").string() + " --out " + out);
  EXPECT_EQ(replan.exit_code, 2);
  EXPECT_NE(replan.err.find("another plan"), std::string::npos) << replan.err;
}

}  // namespace
}  // namespace inet::test
