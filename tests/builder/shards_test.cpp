// WebDataset shards of a build folder (builder/shards.h) from a synthetic build written here (a
// manifest.jsonl and small files): keys and member names, the tar size model, grouping by key
// in manifest order, the size bound, byte-identical reruns, the wids index, reuse and clean-up
// on a rerun, and the errors. The shards are read back by Python's tarfile (and by webdataset
// when it is installed), which checks every member against the file it came from.
#include "builder/shards.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../expect_input_error.h"
#include "../temp_dir.h"
#include "builder/unit_runner.h"
#include "core/atomic_file.h"

namespace inet {
namespace {

namespace fs = std::filesystem;
using test::expectInputError;
using test::TempDir;

/// `size` bytes that differ from file to file (a simple LCG keyed by `seed`).
std::string bytesOf(size_t size, uint32_t seed) {
  std::string s(size, '\0');
  for (char& c : s) {
    seed = seed * 1664525u + 1013904223u;
    c = static_cast<char>(seed >> 24);
  }
  return s;
}

/// A build folder with a manifest in the form unit_runner.cpp writes, and its files.
class SyntheticBuild {
 public:
  SyntheticBuild() : dir_("shards") {}
  const fs::path& path() const { return dir_.path(); }

  /// Frames [0, frames) of one sequence folder, with files of the given sizes by pass key.
  void sequence(const std::string& split, const std::string& layout, const std::string& seq,
                int frames, const std::map<std::string, size_t>& sizes) {
    const std::string folder = "data/" + split + "/rooms_02/" + layout + "/" + seq;
    for (int f = 0; f < frames; ++f) {
      const int64_t t_ns = 40'000'000LL * f;
      nlohmann::ordered_json row = {{"split", split},
                                    {"subset", "rooms_02"},
                                    {"layout", layout},
                                    {"configuration", "original"},
                                    {"sequence", seq},
                                    {"folder", folder},
                                    {"trajectory", "hand-held"},
                                    {"frame", f},
                                    {"t_ns", t_ns}};
      nlohmann::ordered_json files = nlohmann::ordered_json::object();
      // the manifest's key order (unit_runner.cpp): the sequence's file order, not sorted
      for (const char* pass : {"cam0", "depth0.exr", "label0_nyu", "flow0.flo"}) {
        if (!sizes.count(pass)) continue;
        const std::string p = pass;
        const std::string dot = p.find('.') == std::string::npos ? "" : p.substr(p.find('.'));
        const std::string stem = p.substr(0, p.find('.'));
        const std::string name = fmt::format("{:019d}{}", t_ns, dot.empty() ? ".png" : dot);
        const std::string rel = folder + "/" + stem + "/data/" + name;
        dir_.write(rel,
                   bytesOf(sizes.at(pass), static_cast<uint32_t>(rows_.size() * 31 + rel.size())));
        files[pass] = rel;
      }
      row["files"] = files;
      rows_.push_back(row.dump());
    }
  }
  void writeManifest() const {
    std::string text;
    for (const std::string& r : rows_) text += r + "\n";
    dir_.write("manifest.jsonl", text);
  }
  const std::vector<std::string>& rows() const { return rows_; }

 private:
  TempDir dir_;
  std::vector<std::string> rows_;
};

const std::map<std::string, size_t> kFrame = {
    {"cam0", 3000}, {"depth0.exr", 1500}, {"label0_nyu", 200}, {"flow0.flo", 800}};

/// Three sequences in two splits (interleaved, as the plan orders layouts), one frame larger
/// than the bound, and a test-split layout whose long name needs pax headers.
void fillBuild(SyntheticBuild& b) {
  b.sequence("train", "procedural_1", "seq_000", 6, kFrame);
  b.sequence("validation", "procedural_2", "seq_000", 3, kFrame);
  b.sequence("train", "procedural_3", "seq_000_lighting_7", 2, kFrame);
  b.sequence("train", "procedural_3", "sparse", 1, {{"cam0", 30000}});  // > the bound
  b.sequence("test", "file_" + std::string(160, 'x'), "seq_000", 2, kFrame);
  b.writeManifest();
}

constexpr int64_t kMaxBytes = 20000;

std::map<std::string, std::string> shardFiles(const fs::path& dir) {
  std::map<std::string, std::string> out;
  std::error_code ec;
  if (!fs::exists(dir / "shards", ec)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir / "shards"))
    if (e.is_regular_file())
      out[e.path().lexically_relative(dir).generic_string()] = readTextFile(e.path());
  return out;
}

ShardOptions options(int64_t max_bytes = kMaxBytes) {
  ShardOptions o;
  o.name = "synthetic";
  o.max_bytes = max_bytes;
  return o;
}

TEST(Shards, KeysAndMemberNames) {
  EXPECT_EQ(shardSampleKey("data/train/rooms_02/procedural_12/seq_000_lighting_5", 42, "m", "f"),
            "procedural_12/seq_000_lighting_5/000042");
  EXPECT_EQ(shardSampleKey("data/test/rooms_01/file_a/sparse_rearranged_3", 1234567, "m", "f"),
            "file_a/sparse_rearranged_3/1234567");
  // a dot would end the key early in every WebDataset loader
  const InputError e = expectInputError(
      [] { shardSampleKey("data/train/r/lay.out/seq_000", 1, "m.jsonl", "line 3"); });
  EXPECT_EQ(e.file(), "m.jsonl");
  EXPECT_EQ(e.field(), "line 3");
  EXPECT_NE(e.problem().find("lay.out/seq_000/000001"), std::string::npos) << e.what();
  expectInputError([] { shardSampleKey("seq_000", 1, "m", "f"); });
  EXPECT_EQ(shardMemberName("k/s/000001", "cam0", "a/cam0/data/1.png"), "k/s/000001.cam0.png");
  EXPECT_EQ(shardMemberName("k/s/000001", "depth0.exr", "a/depth0/data/1.exr"),
            "k/s/000001.depth0.exr");
  EXPECT_EQ(shardMemberName("k/s/000001", "label0_nyu", "a/label0/data/1_nyu.png"),
            "k/s/000001.label0_nyu.png");
}

TEST(Shards, TarSizeModel) {
  // header block + data in whole blocks
  EXPECT_EQ(tarMemberBytes("a.json", 0), 512);
  EXPECT_EQ(tarMemberBytes("a.json", 1), 1024);
  EXPECT_EQ(tarMemberBytes("a.json", 512), 1024);
  EXPECT_EQ(tarMemberBytes("a.json", 513), 1536);
  // 100 characters fit the ustar name field; 150 split at a '/' into prefix and name
  EXPECT_EQ(tarMemberBytes(std::string(100, 'n'), 10), 1024);
  EXPECT_EQ(tarMemberBytes(std::string(120, 'p') + "/" + std::string(29, 'n'), 10), 1024);
  // no usable '/': a pax header, "160 path=<150 chars>\n" (3 + 1 + 5 + 150 + 1 = 160 bytes)
  // in one block, with its own header block
  EXPECT_EQ(tarMemberBytes(std::string(150, 'n'), 10), 512 + 512 + 1024);
  // 8 GiB and up: a "size" record too
  EXPECT_EQ(tarMemberBytes("a", int64_t{1} << 33), 512 + 512 + 512 + (int64_t{1} << 33));
}

TEST(Shards, GroupedBoundedIndexedAndDeterministic) {
  SyntheticBuild b;
  fillBuild(b);
  const ShardReport r = writeShards(b.path(), options());
  EXPECT_EQ(r.samples, static_cast<int64_t>(b.rows().size()));
  ASSERT_EQ(r.splits.size(), 3u);
  // samples in manifest order per split, concatenated over the shards
  std::map<std::string, std::vector<std::string>> want_keys;
  for (const std::string& line : b.rows()) {
    const auto row = nlohmann::json::parse(line);
    const std::string folder = row["folder"];
    const fs::path p(folder);
    want_keys[row["split"]].push_back(fmt::format("{}/{}/{:06d}",
                                                  p.parent_path().filename().string(),
                                                  p.filename().string(), row["frame"].get<int>()));
  }
  for (const auto& [split, shards] : r.splits) {
    const auto index = nlohmann::json::parse(readTextFile(b.path() / "shards" / (split + ".json")));
    EXPECT_EQ(index["__kind__"], "wids-shard-index-v1");
    EXPECT_EQ(index["wids_version"], 1);
    EXPECT_EQ(index["name"], "synthetic-" + split);
    ASSERT_EQ(index["shardlist"].size(), shards.size());
    size_t k = 0;
    for (size_t i = 0; i < shards.size(); ++i) {
      const auto& e = index["shardlist"][i];
      EXPECT_EQ(e["url"], fmt::format("{}/{}-{:06d}.tar", split, split, i));
      const fs::path file = b.path() / "shards" / e["url"].get<std::string>();
      EXPECT_EQ(e["filesize"].get<int64_t>(), static_cast<int64_t>(fs::file_size(file)));
      EXPECT_EQ(fmt::format("{}:{}", e["crc32"].get<std::string>(), fs::file_size(file)),
                fileChecksum(file));
      const int64_t n = e["nsamples"];
      // the bound holds but for a shard of one sample larger than it
      EXPECT_TRUE(e["filesize"].get<int64_t>() <= kMaxBytes || n == 1) << file;
      EXPECT_EQ(e["first_key"], want_keys[split].at(k));
      EXPECT_EQ(e["last_key"], want_keys[split].at(k + static_cast<size_t>(n) - 1));
      k += static_cast<size_t>(n);
    }
    EXPECT_EQ(k, want_keys[split].size()) << split;
  }
  EXPECT_GE(r.splits.at("train").size(), 4u);  // 8 samples of ~8 kB (one of 31 kB) in 20 kB
  // a fresh write, and a write in another folder, give the same bytes
  const auto first = shardFiles(b.path());
  fs::remove_all(b.path() / "shards");
  writeShards(b.path(), options());
  EXPECT_EQ(shardFiles(b.path()), first);
  TempDir copy("shards_copy");
  fs::copy(b.path(), copy.path(), fs::copy_options::recursive);
  fs::remove_all(copy / "shards");
  writeShards(copy.path(), options());
  EXPECT_EQ(shardFiles(copy.path()), first);
}

TEST(Shards, RerunReusesWholeShardsAndRewritesChangedOnes) {
  SyntheticBuild b;
  fillBuild(b);
  writeShards(b.path(), options());
  const auto first = shardFiles(b.path());
  const ShardReport again = writeShards(b.path(), options());
  EXPECT_EQ(again.bytes_written, 0);
  EXPECT_EQ(shardFiles(b.path()), first);
  // a changed file of the same size: only its shard is written again
  const auto row = nlohmann::json::parse(b.rows().at(3));  // train, 4th sample
  const fs::path changed = b.path() / row["files"]["cam0"].get<std::string>();
  std::string bytes = readTextFile(changed);
  bytes[100] ^= 0x5a;
  writeTextAtomic(changed, bytes);
  const ShardReport third = writeShards(b.path(), options());
  int rewritten = 0;
  for (const auto& [split, shards] : third.splits)
    for (const ShardRecord& s : shards) {
      rewritten += !s.reused;
      if (!s.reused) {
        EXPECT_EQ(s.first_key.substr(0, 12), "procedural_1") << s.url;
      }
    }
  EXPECT_EQ(rewritten, 1);
  EXPECT_GT(third.bytes_written, 0);
  // fewer, larger shards: the extra ones of the earlier run go
  const ShardReport one = writeShards(b.path(), options(1'000'000));
  EXPECT_EQ(one.splits.at("train").size(), 1u);
  size_t tars = 0;
  for (const auto& [name, data] : shardFiles(b.path())) tars += name.ends_with(".tar");
  EXPECT_EQ(tars, 3u);
}

TEST(Shards, PassSelection) {
  SyntheticBuild b;
  fillBuild(b);
  ShardOptions o = options();
  o.passes = {"cam0", "depth0.exr"};
  const ShardReport r = writeShards(b.path(), o);
  EXPECT_EQ(r.samples, static_cast<int64_t>(b.rows().size()));
  const std::string tar = readTextFile(b.path() / "shards/validation/validation-000000.tar");
  EXPECT_NE(tar.find("procedural_2/seq_000/000000.cam0.png"), std::string::npos);
  EXPECT_NE(tar.find("procedural_2/seq_000/000000.depth0.exr"), std::string::npos);
  EXPECT_EQ(tar.find(".label0_nyu.png"), std::string::npos);
  EXPECT_EQ(tar.find(".flow0.flo"), std::string::npos);
  o.passes = {"cam0", "depth9"};
  const InputError e = expectInputError([&] { writeShards(b.path(), o); });
  EXPECT_EQ(e.field(), "passes");
  EXPECT_NE(e.problem().find("'depth9'"), std::string::npos) << e.what();
  EXPECT_NE(e.problem().find("label0_nyu"), std::string::npos) << e.what();  // what there is
}

TEST(Shards, ErrorsNameTheFolderAndWriteNothing) {
  SyntheticBuild b;
  b.sequence("train", "procedural_1", "seq_000", 2, kFrame);
  // no manifest.jsonl: the build is not complete
  InputError e = expectInputError([&] { writeShards(b.path(), options()); });
  EXPECT_EQ(e.file(), b.path().string());
  EXPECT_EQ(e.field(), "manifest.jsonl");
  EXPECT_NE(e.problem().find("not complete"), std::string::npos) << e.what();
  // a listed file that is missing (in the last row: nothing is written before the check ends)
  b.writeManifest();
  const auto row = nlohmann::json::parse(b.rows().back());
  fs::remove(b.path() / row["files"]["depth0.exr"].get<std::string>());
  e = expectInputError([&] { writeShards(b.path(), options()); });
  EXPECT_EQ(e.file(), (b.path() / "manifest.jsonl").string());
  EXPECT_EQ(e.field(), "line 2, files.depth0.exr");
  EXPECT_NE(e.problem().find("is missing in " + b.path().string()), std::string::npos) << e.what();
  EXPECT_FALSE(fs::exists(b.path() / "shards"));
  // a row that is not JSON
  writeTextAtomic(b.path() / "manifest.jsonl", b.rows().front() + "\n{not json\n");
  e = expectInputError([&] { writeShards(b.path(), options()); });
  EXPECT_EQ(e.field(), "line 2");
  // a path out of the build folder
  TempDir other("shards_out");
  other.write(
      "manifest.jsonl",
      R"({"split":"train","folder":"data/train/r/l/s","frame":0,"files":{"cam0":"../x.png"}})"
      "\n");
  e = expectInputError([&] { writeShards(other.path(), options()); });
  EXPECT_EQ(e.field(), "line 1, files.cam0");
}

/// Python's tarfile reads every shard: members, order, headers and contents against the build.
const char* kPythonCheck = R"PY(
import json, os, sys, tarfile
d, max_bytes = sys.argv[1], int(sys.argv[2])
rows = [json.loads(l) for l in open(os.path.join(d, "manifest.jsonl"))]
def key_of(r):
    parts = r["folder"].split("/")
    return "%s/%s/%06d" % (parts[-2], parts[-1], r["frame"])
total, urls, longest = 0, [], 0
for split in ("train", "validation", "test"):
    want = [r for r in rows if r["split"] == split]
    index = json.load(open(os.path.join(d, "shards", split + ".json")))
    assert index["__kind__"] == "wids-shard-index-v1" and index["wids_version"] == 1
    got, sizes = [], []
    for entry in index["shardlist"]:
        path = os.path.join(d, "shards", entry["url"])
        urls.append(path)
        starts = []
        with tarfile.open(path) as t:
            members = t.getmembers()
            for m in members:
                assert m.isfile() and m.mtime == 0 and m.uid == 0 and m.gid == 0, m.name
                assert m.uname == "" and m.gname == "" and m.mode == 0o644, m.name
                longest = max(longest, len(m.name))
            i = 0
            while i < len(members):
                m = members[i]
                head, _, last = m.name.rpartition("/")
                key = (head + "/" if head else "") + last.split(".", 1)[0]
                assert last.split(".", 1)[1] == "json", m.name
                row = json.loads(t.extractfile(m).read())
                assert key == key_of(row), (key, row)
                starts.append(m.offset)
                got.append(key)
                i += 1
                for pk, rel in row["files"].items():
                    ext = "" if "." in pk else os.path.splitext(rel)[1]
                    f = members[i]
                    assert f.name == key + "." + pk + ext, (f.name, pk)
                    assert t.extractfile(f).read() == open(os.path.join(d, rel), "rb").read()
                    i += 1
            end = members[-1].offset_data + (members[-1].size + 511) // 512 * 512
        size = os.path.getsize(path)
        assert size == end + 1024 and size == entry["filesize"], path
        assert size <= max_bytes or len(starts) == 1, path
        sizes.append((size, [b - a for a, b in zip(starts, starts[1:] + [end])]))
        assert entry["nsamples"] == len(starts)
    # a shard closes only before a sample that would take it over the bound
    for (size, _), (_, nxt) in zip(sizes, sizes[1:]):
        assert size + nxt[0] > max_bytes, (size, nxt[0])
    assert got == [key_of(r) for r in want], split
    total += len(got)
assert longest > 180  # the long layout (a 165-character folder) needed pax headers
print("OK", total)
try:
    import webdataset as wds
except ImportError:
    print("NOTE webdataset is not installed: read with tarfile only")
else:
    keys = [s["__key__"] for s in wds.WebDataset(urls, shardshuffle=False)]
    assert keys == [key_of(r) for s in ("train", "validation", "test") for r in rows
                    if r["split"] == s], keys
    print("OK webdataset", len(keys))
)PY";

TEST(Shards, PythonTarfileReadsThem) {
  if (std::system("command -v python3 >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3 is not installed: the shards are not read back by Python";
  SyntheticBuild b;
  fillBuild(b);
  writeShards(b.path(), options());
  TempDir py("shards_py");
  const std::string script = py.write("check.py", kPythonCheck);
  const std::string cmd =
      fmt::format("python3 {} {} {} 2>&1", script, b.path().string(), kMaxBytes);
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    pclose(p);
  }
  EXPECT_NE(out.find(fmt::format("OK {}", b.rows().size())), std::string::npos) << out;
  if (out.find("NOTE") != std::string::npos) std::printf("%s", out.c_str());
}

}  // namespace
}  // namespace inet
