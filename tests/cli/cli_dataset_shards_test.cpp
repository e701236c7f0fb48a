// Issue 16: WebDataset shards of a dataset build (docs/dataset.md "WebDataset shards"). A tiny
// spec with shards enabled and a small bound (two procedural apartments with parametric
// furniture, a 4-frame sequence each in 2-frame units, their sparse views, 48x36 at 1 spp):
// `dataset build` writes the shards after the manifest, every manifest row is one sample,
// Python's tarfile reads them, and `dataset shards` rewrites them with the same bytes, leaves
// whole ones alone, and refuses an incomplete build in one line.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "core/atomic_file.h"

namespace fs = std::filesystem;

namespace inet::test {
namespace {

const std::string kSpec = kTinyDatasetSpec + "shards: {enabled: true, max_mb: 0.15}\n";

std::map<std::string, std::string> shardTree(const fs::path& dir) {
  std::error_code ec;
  return fs::exists(dir / "shards", ec) ? readTree(dir / "shards")
                                        : std::map<std::string, std::string>{};
}

size_t lines(const std::string& text) {
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

/// Output of a shell command (stdout and stderr).
std::string shell(const std::string& cmd) {
  std::string out;
  if (FILE* p = popen((cmd + " 2>&1").c_str(), "r")) {
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    pclose(p);
  }
  return out;
}

/// Lists every shard of the indexes with Python's tarfile: "<samples> <members>".
const char* kPythonList = R"PY(
import json, os, sys, tarfile
d = sys.argv[1]
samples = members = 0
for split in ("train", "validation", "test"):
    index = os.path.join(d, "shards", split + ".json")
    if not os.path.exists(index):
        continue
    for entry in json.load(open(index))["shardlist"]:
        with tarfile.open(os.path.join(d, "shards", entry["url"])) as t:
            names = t.getnames()
        keys = [n for n in names if n.endswith(".json")]
        assert len(keys) == entry["nsamples"], entry
        samples += len(keys)
        members += len(names)
print(samples, members)
)PY";

TEST(CliDatasetShards, BuildWritesThemAndARerunGivesTheSameBytes) {
  TempDir dir("dataset_shards");
  writeFile(dir / "tiny.yaml", kSpec);
  const std::string ds = (dir / "ds").string();
  RunResult r = runInterinet("dataset plan " + (dir / "tiny.yaml").string() + " --out " + ds);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = runInterinet("dataset build " + ds + " --no-progress --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("shard(s) of 14 samples"), std::string::npos) << r.err;
  const size_t rows = lines(readTextFile(fs::path(ds) / "manifest.jsonl"));
  ASSERT_EQ(rows, 14u);  // 8 sequence frames, 6 sparse views

  // the indexes count every row once, over several shards per split
  size_t samples = 0, shards = 0;
  for (const char* split : {"train", "validation", "test"}) {
    const fs::path index = fs::path(ds) / "shards" / (std::string(split) + ".json");
    if (!fs::exists(index)) continue;
    const auto j = nlohmann::json::parse(readTextFile(index));
    EXPECT_EQ(j["__kind__"], "wids-shard-index-v1");
    for (const auto& e : j["shardlist"]) {
      samples += e["nsamples"].get<size_t>();
      ++shards;
      const fs::path tar = fs::path(ds) / "shards" / e["url"].get<std::string>();
      ASSERT_TRUE(fs::exists(tar)) << tar;
      EXPECT_EQ(fs::file_size(tar), e["filesize"].get<uintmax_t>());
    }
  }
  EXPECT_EQ(samples, rows);
  EXPECT_GE(shards, 4u);  // 0.15 MB holds two or three of these frames

  if (std::system("command -v python3 >/dev/null 2>&1") == 0) {
    writeFile(dir / "list.py", kPythonList);
    const std::string out = shell("python3 " + (dir / "list.py").string() + " " + ds);
    EXPECT_EQ(out.substr(0, out.find(' ')), std::to_string(rows)) << out;
  } else {
    std::printf("python3 is not installed: the shards are not listed by tarfile\n");
  }

  // on demand: a rerun leaves every shard as it is; from nothing, the same bytes again
  const auto built = shardTree(ds);
  r = runInterinet("dataset shards " + ds + " --no-progress");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("0.0 MB written"), std::string::npos) << r.out;
  EXPECT_EQ(shardTree(ds), built);
  fs::remove_all(fs::path(ds) / "shards");
  r = runInterinet("dataset shards " + ds + " --no-progress");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(shardTree(ds), built);

  // other settings: one shard per split with two passes; the extra shards go
  r = runInterinet("dataset shards " + ds + " --no-progress --max-mb 100 --passes cam0,depth0.exr");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto small = shardTree(ds);
  size_t tars = 0;
  for (const auto& [name, bytes] : small) {
    if (!name.ends_with(".tar")) continue;
    ++tars;
    EXPECT_NE(bytes.find(".cam0.png"), std::string::npos) << name;
    EXPECT_EQ(bytes.find(".label0_nyu.png"), std::string::npos) << name;
  }
  EXPECT_EQ(tars, r.out.find("validation:") != std::string::npos ? 2u : 1u) << r.out;

  r = runInterinet("dataset shards " + ds + " --passes cam0,depth9");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--passes: no row has the pass key 'depth9'"), std::string::npos) << r.err;
}

TEST(CliDatasetShards, AnIncompleteBuildIsRefused) {
  TempDir dir("dataset_shards_incomplete");
  writeFile(dir / "tiny.yaml", kSpec);
  const std::string ds = (dir / "ds").string();
  ASSERT_EQ(runInterinet("dataset plan " + (dir / "tiny.yaml").string() + " --out " + ds).exit_code,
            0);
  const RunResult r = runInterinet("dataset shards " + ds);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find(ds + ": manifest.jsonl: missing: the build is not complete"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(fs::path(ds) / "shards"));
  const RunResult none = runInterinet("dataset shards " + (dir / "nothing").string());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("no plan.json"), std::string::npos) << none.err;
}

}  // namespace
}  // namespace inet::test
