#include "builder/shards.h"

#include <archive.h>
#include <archive_entry.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "builder/unit_runner.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/stop.h"
#include "core/text.h"

namespace inet {

namespace fs = std::filesystem;

namespace {

constexpr int64_t kBlock = 512;
constexpr int64_t kTarEnd = 2 * kBlock;  // the end-of-archive marker: two zero blocks
const std::array<std::string, 3> kSplits = {"train", "validation", "test"};

int64_t padded(int64_t n) {
  return (n + kBlock - 1) / kBlock * kBlock;
}

int decimalDigits(int64_t n) {
  int d = 1;
  while (n >= 10) n /= 10, ++d;
  return d;
}

/// Bytes of the pax record "<length> <key>=<value>\n", whose length counts its own digits.
int64_t paxRecordBytes(size_t key_size, size_t value_size) {
  const int64_t rest = static_cast<int64_t>(key_size + value_size) + 3;  // ' ', '=', '\n'
  for (int d = 1;; ++d)
    if (decimalDigits(rest + d) == d) return rest + d;
}

/// Whether libarchive can store an ASCII path in the ustar header alone: at most 100
/// characters, or split at a '/' into a prefix of at most 155 and a non-empty rest of at most
/// 100 (archive_write_set_format_pax.c, the same search for the split).
bool fitsUstar(const std::string& p) {
  if (p.size() <= 100) return true;
  size_t slash = p.find('/', p.size() - 101);
  if (slash == 0) slash = p.find('/', 1);
  return slash != std::string::npos && slash + 1 < p.size() && slash <= 155;
}

bool keyChar(unsigned char c) {
  return std::isalnum(c) || c == '_' || c == '-' || c == '/';
}

/// Streams tar members through libarchive into a file, or into nothing when `file` is empty
/// (to learn the CRC-32 the bytes would have), counting bytes and the CRC-32 on the way.
class TarWriter {
 public:
  explicit TarWriter(const fs::path& file) : file_(file) {
    if (!file.empty()) {
      out_ = std::fopen(file.c_str(), "wb");
      if (!out_) fail("cannot create it: " + std::string(std::strerror(errno)));
      std::setvbuf(out_, nullptr, _IOFBF, 1 << 20);
    }
    a_ = archive_write_new();
    // restricted pax: plain ustar headers unless a name or size needs an extended header;
    // unblocked, so that nothing follows the end marker and the size is the members' sum
    if (archive_write_set_format_pax_restricted(a_) != ARCHIVE_OK ||
        archive_write_add_filter_none(a_) != ARCHIVE_OK ||
        archive_write_set_bytes_per_block(a_, 0) != ARCHIVE_OK ||
        archive_write_open(a_, this, nullptr, &TarWriter::write, nullptr) != ARCHIVE_OK)
      fail(archive_error_string(a_));
  }
  ~TarWriter() {
    if (a_) archive_write_free(a_);
    if (out_) std::fclose(out_);
  }
  TarWriter(const TarWriter&) = delete;
  TarWriter& operator=(const TarWriter&) = delete;

  /// One regular file: mode 0644, mtime 0, uid/gid 0, no user or group name.
  void add(const std::string& name, const char* data, size_t size) {
    archive_entry* e = archive_entry_new();
    archive_entry_set_pathname(e, name.c_str());
    archive_entry_set_filetype(e, AE_IFREG);
    archive_entry_set_perm(e, 0644);
    archive_entry_set_size(e, static_cast<la_int64_t>(size));
    archive_entry_set_mtime(e, 0, 0);
    const int r = archive_write_header(a_, e);
    archive_entry_free(e);
    if (r != ARCHIVE_OK) fail(name + ": " + archive_error_string(a_));
    while (size > 0) {
      const la_ssize_t n = archive_write_data(a_, data, size);
      if (n <= 0) fail(name + ": " + archive_error_string(a_));
      data += n;
      size -= static_cast<size_t>(n);
    }
    if (archive_write_finish_entry(a_) != ARCHIVE_OK) fail(name + ": " + archive_error_string(a_));
  }

  /// Writes the end marker and closes the file.
  void close() {
    if (archive_write_close(a_) != ARCHIVE_OK) fail(archive_error_string(a_));
    if (out_) {
      const bool bad = std::fflush(out_) != 0 || std::ferror(out_);
      const int closed = std::fclose(out_);
      out_ = nullptr;
      if (bad || closed != 0) fail("write failed (disk full?)");
    }
  }
  int64_t bytes() const { return bytes_; }
  uint32_t crc() const { return static_cast<uint32_t>(crc_); }

 private:
  static la_ssize_t write(archive* a, void* self_ptr, const void* buf, size_t n) {
    auto* self = static_cast<TarWriter*>(self_ptr);
    if (self->out_ && std::fwrite(buf, 1, n, self->out_) != n) {
      archive_set_error(a, errno, "%s", std::strerror(errno));
      return -1;
    }
    const auto* p = static_cast<const Bytef*>(buf);
    for (size_t left = n; left > 0;) {  // zlib's crc32 takes 32-bit lengths
      const uInt chunk = static_cast<uInt>(std::min<size_t>(left, 1u << 30));
      self->crc_ = crc32(self->crc_, p, chunk);
      p += chunk;
      left -= chunk;
    }
    self->bytes_ += static_cast<int64_t>(n);
    return static_cast<la_ssize_t>(n);
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(file_.empty() ? "tar" : file_.string(), "", why);
  }

  fs::path file_;
  FILE* out_ = nullptr;
  archive* a_ = nullptr;
  int64_t bytes_ = 0;
  uLong crc_ = crc32(0L, Z_NULL, 0);
};

struct SampleFile {
  std::string member;
  fs::path path;
  int64_t size = 0;
};

/// One manifest row as a sample: its key, the row's bytes and the selected files.
struct Sample {
  std::string split, key, row;
  std::vector<SampleFile> files;
  int64_t bytes = 0;  ///< tar bytes of all its members
};

/// Reads manifest.jsonl row by row, with the line number for messages.
class ManifestReader {
 public:
  ManifestReader(const fs::path& dir, const ShardOptions& opt)
      : file_(dir / "manifest.jsonl"), dir_(dir), opt_(opt) {
    std::error_code ec;
    if (!fs::is_regular_file(file_, ec))
      throw InputError(dir.string(), "manifest.jsonl",
                       "missing: the build is not complete (`interiornet dataset status " +
                           dir.string() + "` says what is left; a complete build writes it)");
    in_.open(file_, std::ios::binary);
    if (!in_) throw InputError(file_.string(), "", "cannot read it");
  }

  /// The next row as a sample, its files of the selected passes sized; false at the end.
  /// `seen` collects every pass key of the rows.
  bool next(Sample& s, std::set<std::string>* seen) {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++line_;
    const std::string where = fmt::format("line {}", line_);
    nlohmann::ordered_json row;
    try {
      row = nlohmann::ordered_json::parse(line);
    } catch (const nlohmann::json::exception&) {
      throw InputError(file_.string(), where, "not a JSON object");
    }
    auto field = [&](const char* k, auto check) -> const nlohmann::ordered_json& {
      if (!row.is_object() || !row.contains(k) || !check(row[k]))
        throw InputError(file_.string(), where, fmt::format("no valid \"{}\"", k));
      return row[k];
    };
    s.split = field("split", [](const auto& v) {
      return v.is_string() && std::count(kSplits.begin(), kSplits.end(), v) > 0;
    });
    const auto& folder = field("folder", [](const auto& v) { return v.is_string(); });
    const auto& frame = field("frame", [](const auto& v) { return v.is_number_unsigned(); });
    const auto& files = field("files", [](const auto& v) { return v.is_object(); });
    s.key = shardSampleKey(folder, frame.template get<int64_t>(), file_.string(), where);
    s.row = std::move(line);
    s.files.clear();
    s.bytes = tarMemberBytes(s.key + ".json", static_cast<int64_t>(s.row.size()));
    for (const auto& [pass, rel] : files.items()) {
      if (seen) seen->insert(pass);
      if (!selected(pass)) continue;
      s.files.push_back(sizedFile(s.key, pass, rel, where));
      s.bytes += tarMemberBytes(s.files.back().member, s.files.back().size);
    }
    return true;
  }
  const fs::path& file() const { return file_; }

 private:
  bool selected(const std::string& pass) const {
    return opt_.passes == std::vector<std::string>{"all"} ||
           std::find(opt_.passes.begin(), opt_.passes.end(), pass) != opt_.passes.end();
  }

  SampleFile sizedFile(const std::string& key, const std::string& pass,
                       const nlohmann::ordered_json& rel, const std::string& where) const {
    const std::string field = where + ", files." + pass;
    if (pass.empty() || pass[0] == '.' ||
        !std::all_of(pass.begin(), pass.end(), [](unsigned char c) {
          return std::isalnum(c) || c == '_' || c == '-' || c == '.';
        }))
      throw InputError(file_.string(), field, "not a pass key (letters, digits, '_', '-', '.')");
    const fs::path path = rel.is_string() ? fs::path(rel.get<std::string>()) : fs::path();
    // only files inside the build folder go into a shard
    const bool inside =
        !path.empty() && path.is_relative() &&
        std::none_of(path.begin(), path.end(), [](const fs::path& c) { return c == ".."; });
    if (!inside)
      throw InputError(file_.string(), field, "expected a path relative to the build folder");
    SampleFile f{shardMemberName(key, pass, path.string()), dir_ / path, 0};
    std::error_code ec;
    const uintmax_t size = fs::file_size(f.path, ec);
    if (ec)
      throw InputError(file_.string(), field,
                       path.generic_string() + " is missing in " + dir_.string() +
                           " (`interiornet dataset verify " + dir_.string() + "`)");
    f.size = static_cast<int64_t>(size);
    return f;
  }

  fs::path file_, dir_;
  const ShardOptions& opt_;
  std::ifstream in_;
  int64_t line_ = 0;
};

/// Reads every row once before anything is written: rows, keys, files and the pass names.
/// Returns the number of samples.
int64_t checkManifest(const fs::path& dir, const ShardOptions& opt) {
  ManifestReader reader(dir, opt);
  std::set<std::string> seen;
  std::map<std::string, std::string> last_key;  // per split: loaders group consecutive keys
  Sample s;
  int64_t rows = 0;
  while (reader.next(s, &seen)) {
    ++rows;
    std::string& last = last_key[s.split];
    if (s.key == last)
      throw InputError(reader.file().string(), fmt::format("line {}", rows),
                       "the key " + s.key + " of the row before: loaders would merge the two");
    last = s.key;
  }
  if (opt.passes != std::vector<std::string>{"all"})
    for (const std::string& p : opt.passes)
      if (!seen.count(p))
        throw InputError(dir.string(), "passes",
                         "no row has the pass key '" + p + "' (there are: " +
                             listNames({seen.begin(), seen.end()}, 40) + "; or all)");
  return rows;
}

/// Adds the samples' members to `tar`, reading each file; `done` after each sample.
void addSamples(TarWriter& tar, const std::vector<Sample>& samples, const fs::path& dir,
                const std::function<void()>& done) {
  std::string buf;
  for (const Sample& s : samples) {
    stopIfSignalled("while writing the shards of " + dir.string() +
                    " (their indexes are written last)");
    tar.add(s.key + ".json", s.row.data(), s.row.size());
    for (const SampleFile& f : s.files) {
      buf.resize(static_cast<size_t>(f.size));
      std::ifstream in(f.path, std::ios::binary);
      in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
      // a file that changed size since it was measured would move the shard bounds
      if (!in || in.gcount() != f.size || in.peek() != std::ifstream::traits_type::eof())
        throw InputError(f.path.string(), "",
                         fmt::format("unreadable, or changed while the shards were written (it "
                                     "had {} bytes)",
                                     f.size));
      tar.add(f.member, buf.data(), buf.size());
    }
    if (done) done();
  }
}

/// Shard records of an index from an earlier run (none when it is missing or unreadable).
std::vector<ShardRecord> readIndex(const fs::path& file) {
  std::vector<ShardRecord> out;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return out;
  try {
    const nlohmann::json j = nlohmann::json::parse(readTextFile(file));
    for (const auto& e : j.at("shardlist")) {
      ShardRecord r;
      r.url = e.at("url").get<std::string>();
      r.samples = e.at("nsamples").get<int64_t>();
      r.bytes = e.at("filesize").get<int64_t>();
      r.crc32 = static_cast<uint32_t>(std::stoul(e.at("crc32").get<std::string>(), nullptr, 16));
      r.first_key = e.at("first_key").get<std::string>();
      r.last_key = e.at("last_key").get<std::string>();
      out.push_back(std::move(r));
    }
  } catch (const std::exception&) {
    out.clear();  // then every shard is written again
  }
  return out;
}

/// The wids shard index: one line per shard, so that two indexes diff by shard.
std::string indexText(const std::string& split, const std::vector<ShardRecord>& shards,
                      const ShardOptions& opt) {
  using J = nlohmann::ordered_json;
  int64_t samples = 0, bytes = 0;
  for (const ShardRecord& r : shards) samples += r.samples, bytes += r.bytes;
  const J info = {{"format", "interiornet-shards"},
                  {"version", 1},
                  {"split", split},
                  {"max_bytes", opt.max_bytes},
                  {"passes", opt.passes},
                  {"samples", samples},
                  {"bytes", bytes}};
  std::string s = "{\n  \"__kind__\": \"wids-shard-index-v1\",\n  \"wids_version\": 1,\n";
  s += "  \"name\": " + J(opt.name + "-" + split).dump() + ",\n";
  s += "  \"interiornet\": " + info.dump() + ",\n  \"shardlist\": [\n";
  for (size_t i = 0; i < shards.size(); ++i) {
    const ShardRecord& r = shards[i];
    const J e = {{"url", r.url},
                 {"nsamples", r.samples},
                 {"filesize", r.bytes},
                 {"crc32", fmt::format("{:08x}", r.crc32)},
                 {"first_key", r.first_key},
                 {"last_key", r.last_key}};
    s += "    " + e.dump() + (i + 1 < shards.size() ? ",\n" : "\n");
  }
  return s + "  ]\n}\n";
}

/// Writes the shards of one pass over the manifest, split by split as their samples come.
class ShardSet {
 public:
  ShardSet(const fs::path& dir, const ShardOptions& opt, int64_t total)
      : dir_(dir), opt_(opt), bar_(total, "samples", opt.progress && total > 0) {
    for (const std::string& split : kSplits) old_[split] = readIndex(indexPath(split));
  }

  void add(Sample&& s) {
    Pending& p = pending_[s.split];
    if (!p.samples.empty() && p.bytes + s.bytes > opt_.max_bytes) flush(s.split);
    p.bytes += s.bytes;
    p.samples.push_back(std::move(s));
  }

  ShardReport finish() {
    for (const std::string& split : kSplits)
      if (!pending_[split].samples.empty()) flush(split);
    bar_.finish();
    for (const std::string& split : kSplits) {
      const std::vector<ShardRecord>& shards = report_.splits[split];
      if (!shards.empty()) writeTextAtomic(indexPath(split), indexText(split, shards, opt_));
      removeStale(split, shards.size());
      if (shards.empty()) report_.splits.erase(split);
    }
    return report_;
  }

  fs::path indexPath(const std::string& split) const { return dir_ / "shards" / (split + ".json"); }

 private:
  struct Pending {
    std::vector<Sample> samples;
    int64_t bytes = kTarEnd;
  };

  void flush(const std::string& split) {
    Pending& p = pending_[split];
    std::vector<ShardRecord>& shards = report_.splits[split];
    ShardRecord r;
    r.url = fmt::format("{}/{}-{:06d}.tar", split, split, shards.size());
    r.samples = static_cast<int64_t>(p.samples.size());
    r.bytes = p.bytes;
    r.first_key = p.samples.front().key;
    r.last_key = p.samples.back().key;
    const fs::path file = dir_ / "shards" / r.url;
    if (!reuse(split, shards.size(), file, p.samples, r)) {
      int64_t written = 0;
      writeFileAtomic(file, [&](const fs::path& tmp) {
        TarWriter tar(tmp);
        addSamples(tar, p.samples, dir_, [&] { bar_.update(++done_); });
        tar.close();
        written = tar.bytes();
        r.crc32 = tar.crc();
      });
      INET_CHECK_MSG(written == r.bytes, fmt::format("{}: {} bytes written, {} expected",
                                                     file.string(), written, r.bytes));
      report_.bytes_written += written;
    }
    report_.samples += r.samples;
    report_.bytes += r.bytes;
    shards.push_back(std::move(r));
    p = Pending{};
  }

  /// Whether the earlier run's shard `n` of `split` is what these samples give, byte for byte
  /// (its record, the file's size and CRC-32, and the CRC-32 of the bytes they would make).
  bool reuse(const std::string& split, size_t n, const fs::path& file,
             const std::vector<Sample>& samples, ShardRecord& r) {
    const std::vector<ShardRecord>& old = old_[split];
    if (n >= old.size()) return false;
    const ShardRecord& o = old[n];
    std::error_code ec;
    if (o.url != r.url || o.samples != r.samples || o.bytes != r.bytes ||
        o.first_key != r.first_key || o.last_key != r.last_key ||
        fs::file_size(file, ec) != static_cast<uintmax_t>(r.bytes) || ec)
      return false;
    TarWriter count_only({});
    addSamples(count_only, samples, dir_, nullptr);
    count_only.close();
    const std::string want = fmt::format("{:08x}:{}", o.crc32, o.bytes);
    if (count_only.crc() != o.crc32 || fileChecksum(file) != want) return false;
    r.crc32 = o.crc32;
    r.reused = true;
    done_ += r.samples;
    bar_.update(done_);
    return true;
  }

  /// Removes shards numbered `count` and up (an earlier run made more).
  void removeStale(const std::string& split, size_t count) const {
    const fs::path folder = dir_ / "shards" / split;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(folder, ec)) {
      const std::string name = e.path().filename().string();
      const std::string prefix = split + "-";
      if (name.size() != prefix.size() + 10 || name.rfind(prefix, 0) != 0 ||
          name.substr(name.size() - 4) != ".tar")
        continue;
      const std::string digits = name.substr(prefix.size(), 6);
      if (digits.find_first_not_of("0123456789") == std::string::npos &&
          std::stoul(digits) >= count)
        stale.push_back(e.path());
    }
    for (const fs::path& f : stale) fs::remove(f, ec);
  }

  fs::path dir_;
  const ShardOptions& opt_;
  ProgressBar bar_;
  int64_t done_ = 0;
  std::map<std::string, std::vector<ShardRecord>> old_;
  std::map<std::string, Pending> pending_;
  ShardReport report_;
};

}  // namespace

ShardOptions shardOptions(const DatasetSpec& spec) {
  ShardOptions o;
  o.name = spec.name;
  o.max_bytes = std::max<int64_t>(1, std::llround(spec.shards.max_mb * 1e6));
  o.passes = spec.shards.passes;
  return o;
}

std::string shardSampleKey(const std::string& folder, int64_t frame, const std::string& file,
                           const std::string& field) {
  const fs::path p = fs::path(folder).lexically_normal();
  std::vector<std::string> parts;
  for (const fs::path& c : p)
    if (!c.empty() && c != "/" && c != ".") parts.push_back(c.string());
  if (parts.size() < 2 || frame < 0)
    throw InputError(file, field,
                     "the folder '" + folder + "' does not name a layout and a sequence");
  const std::string key = fmt::format("{}/{}/{:06d}", parts[parts.size() - 2], parts.back(), frame);
  // WebDataset takes everything up to the first dot of the last component as the key
  if (!std::all_of(key.begin(), key.end(), [](unsigned char c) { return keyChar(c); }))
    throw InputError(
        file, field,
        "the sample key '" + key + "' may hold only letters, digits, '_', '-' and '/' (no dot)");
  return key;
}

std::string shardMemberName(const std::string& key, const std::string& pass_key,
                            const std::string& file) {
  std::string name = key + "." + pass_key;
  if (pass_key.find('.') == std::string::npos) name += fs::path(file).extension().string();
  return name;
}

int64_t tarMemberBytes(const std::string& name, int64_t size) {
  int64_t pax = 0;  // the extended header's records
  if (!fitsUstar(name)) pax += paxRecordBytes(4, name.size());
  if (size >= (int64_t{1} << 33))
    pax += paxRecordBytes(4, static_cast<size_t>(decimalDigits(size)));
  return kBlock + padded(size) + (pax > 0 ? kBlock + padded(pax) : 0);
}

ShardReport writeShards(const fs::path& dir, const ShardOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (opt.max_bytes < 1) throw InputError(dir.string(), "max_bytes", "must be >= 1");
  if (opt.passes.empty())
    throw InputError(dir.string(), "passes", "no pass key given (e.g. all, or cam0,depth0)");
  const int64_t total = checkManifest(dir, opt);
  removeStaleTemporaries(dir / "shards");
  ShardSet set(dir, opt, total);
  // from here until the new indexes are written, none describes shards being replaced
  std::error_code ec;
  for (const std::string& split : kSplits) fs::remove(set.indexPath(split), ec);
  ManifestReader reader(dir, opt);
  Sample s;
  while (reader.next(s, nullptr)) set.add(std::move(s));
  ShardReport report = set.finish();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace inet
