#include "sensors/event_io.h"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "core/error.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

constexpr size_t kTextBufferBytes = size_t{1} << 20;
constexpr uint64_t kMaxMsToIdx = 100'000'000;  // 27.8 h after t0: 800 MB of index

int64_t floorDiv(int64_t a, int64_t b) {
  const int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

/// "<path>.tmp-<pid>", the temporary name of core/atomic_file.h.
fs::path temporaryFor(const fs::path& path) {
  fs::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  return tmp;
}

void createParent(const fs::path& path) {
  if (!path.has_parent_path()) return;
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec)
    throw InputError(path.parent_path().string(), "", "cannot create folder: " + ec.message());
}

/// width and height are both 0 (unknown) or both in [1, 65536].
void checkSize(const fs::path& path, int width, int height) {
  const bool unknown = width == 0 && height == 0;
  if (!unknown && (width < 1 || height < 1 || width > 65536 || height > 65536))
    throw InputError(path.string(), "width/height",
                     fmt::format("{}x{}: both 0 (unknown) or both in [1, 65536]", width, height));
}

void renameIntoPlace(const fs::path& tmp, const fs::path& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(path.string(), "", "cannot rename temporary into place: " + ec.message());
  }
}

// --- text ---------------------------------------------------------------------------------------

/// Writes the decimal digits of v at p; returns the end.
char* putUint(char* p, uint64_t v) {
  char tmp[20];
  int n = 0;
  do {
    tmp[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0);
  while (n > 0) *p++ = tmp[--n];
  return p;
}

/// Appends "t x y p\n" with t = (t_ns - t0_ns) s printed exactly from the integer ns.
void appendLine(std::string& out, const Event& e, int64_t t0_ns) {
  char buf[64];  // at most 1 + 20 + 1 + 9 + 3 * 6 + 2 = 51 characters
  char* p = buf;
  const int64_t rel = e.t_ns - t0_ns;
  const uint64_t mag = rel < 0 ? 0 - static_cast<uint64_t>(rel) : static_cast<uint64_t>(rel);
  if (rel < 0) *p++ = '-';
  p = putUint(p, mag / 1'000'000'000u);
  *p++ = '.';
  uint64_t frac = mag % 1'000'000'000u;
  for (int d = 8; d >= 0; --d, frac /= 10) p[d] = static_cast<char>('0' + frac % 10);
  p += 9;
  *p++ = ' ';
  p = putUint(p, e.x);
  *p++ = ' ';
  p = putUint(p, e.y);
  *p++ = ' ';
  *p++ = e.p ? '1' : '0';
  *p++ = '\n';
  out.append(buf, p);
}

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

/// Seconds as text -> ns. Plain decimals are converted exactly (rounded half up at the 10th
/// decimal); exponent forms go through double (exact to ~1e-16 relative).
bool parseSecondsNs(std::string_view s, int64_t& ns) {
  if (s.empty()) return false;
  if (s.find_first_of("eE") != std::string_view::npos) {
    double v = 0;
    const auto r = std::from_chars(s.data() + (s[0] == '+'), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v) ||
        std::abs(v) > 9.2e9)
      return false;
    ns = std::llround(v * 1e9);
    return true;
  }
  size_t i = 0;
  const bool neg = s[0] == '-';
  if (s[0] == '-' || s[0] == '+') ++i;
  int64_t whole = 0;
  size_t digits = 0;
  for (; i < s.size() && isDigit(s[i]); ++i, ++digits)
    if (__builtin_mul_overflow(whole, 10, &whole) ||
        __builtin_add_overflow(whole, s[i] - '0', &whole))
      return false;
  int64_t frac = 0;
  int frac_digits = 0;
  bool round_up = false;
  if (i < s.size() && s[i] == '.') {
    for (++i; i < s.size() && isDigit(s[i]); ++i, ++digits) {
      if (frac_digits < 9) frac = frac * 10 + (s[i] - '0');
      if (frac_digits == 9) round_up = s[i] >= '5';
      ++frac_digits;
    }
  }
  if (i != s.size() || digits == 0) return false;
  for (int d = std::min(frac_digits, 9); d < 9; ++d) frac *= 10;
  if (__builtin_mul_overflow(whole, 1'000'000'000, &ns) ||
      __builtin_add_overflow(ns, frac + (round_up ? 1 : 0), &ns))
    return false;
  if (neg) ns = -ns;
  return true;
}

template <class T>
bool parseInt(std::string_view s, T& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

/// Line-by-line parser shared by the file and in-memory readers.
class TextParser {
 public:
  TextParser(std::string source, int64_t t0_ns) : source_(std::move(source)), t0_ns_(t0_ns) {}

  void line(std::string_view text) {
    ++line_no_;
    if (!text.empty() && text.back() == '\n') text.remove_suffix(1);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    const size_t first_char = text.find_first_not_of(" \t");
    if (first_char == std::string_view::npos || text[first_char] == '#') return;  // blank, comment
    std::string_view tok[5];
    int n = 0;
    for (size_t i = 0; i < text.size();) {
      if (text[i] == ' ' || text[i] == '\t') {
        ++i;
        continue;
      }
      const size_t j = std::min(text.find_first_of(" \t", i), text.size());
      if (n == 5) return fail("more than 4 columns: '" + std::string(text) + "'");
      tok[n++] = text.substr(i, j - i);
      i = j;
    }
    const bool first = !seen_data_;
    seen_data_ = true;
    if (n == 2 && first) return header(tok[0], tok[1]);
    if (n != 4) return fail(fmt::format("expected 't x y p' (4 columns), got '{}'", text));
    Event e;
    int64_t rel = 0;
    if (!parseSecondsNs(tok[0], rel) || __builtin_add_overflow(rel, t0_ns_, &e.t_ns))
      return fail("time is not a number of seconds in range: '" + std::string(tok[0]) + "'");
    if (!parseInt(tok[1], e.x) || !parseInt(tok[2], e.y))
      return fail(fmt::format("x, y must be integers in [0, 65535]: '{}', '{}'", tok[1], tok[2]));
    if (out_.width > 0 && (e.x >= out_.width || e.y >= out_.height))
      return fail(fmt::format("pixel ({}, {}) outside the {}x{} of the header line", e.x, e.y,
                              out_.width, out_.height));
    if (tok[3] == "1") {
      e.p = 1;
    } else if (tok[3] == "0" || tok[3] == "-1") {
      e.p = 0;
    } else {
      return fail("polarity must be 0 or 1 (or -1 for OFF): '" + std::string(tok[3]) + "'");
    }
    out_.events.push_back(e);
  }

  EventFile take() { return std::move(out_); }

 private:
  void header(std::string_view w, std::string_view h) {
    if (!parseInt(w, out_.width) || !parseInt(h, out_.height) || out_.width < 1 ||
        out_.height < 1 || out_.width > 65536 || out_.height > 65536)
      fail(fmt::format("the E2VID header line 'W H' needs two sizes in [1, 65536], got '{} {}'", w,
                       h));
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(source_, fmt::format("line {}", line_no_), problem);
  }

  std::string source_;
  int64_t t0_ns_;
  int line_no_ = 0;
  bool seen_data_ = false;
  EventFile out_;
};

}  // namespace

// --- RPG text writer ----------------------------------------------------------------------------

std::string formatEventLine(const Event& e, int64_t t0_ns) {
  std::string s;
  appendLine(s, e, t0_ns);
  return s;
}

EventTextWriter::EventTextWriter(const fs::path& path, int64_t t0_ns, int width, int height)
    : path_(path), tmp_(temporaryFor(path)), t0_ns_(t0_ns) {
  checkSize(path_, width, height);
  createParent(path_);
  file_ = std::fopen(tmp_.c_str(), "wb");
  if (!file_)
    throw InputError(path_.string(), "", std::string("cannot write: ") + std::strerror(errno));
  buf_.reserve(kTextBufferBytes + 64);
  if (width > 0) buf_ += fmt::format("{} {}\n", width, height);
}

EventTextWriter::~EventTextWriter() {
  if (!file_) return;
  std::fclose(file_);
  std::error_code ec;
  fs::remove(tmp_, ec);
}

void EventTextWriter::flushBuffer() {
  if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), file_) != buf_.size())
    throw InputError(path_.string(), "", std::string("write failed: ") + std::strerror(errno));
  buf_.clear();
}

void EventTextWriter::write(std::span<const Event> events) {
  INET_CHECK_MSG(file_ != nullptr, "write after close");
  for (const Event& e : events) {
    appendLine(buf_, e, t0_ns_);
    if (buf_.size() >= kTextBufferBytes) flushBuffer();
  }
  count_ += events.size();
}

void EventTextWriter::close() {
  INET_CHECK_MSG(file_ != nullptr, "close twice");
  flushBuffer();
  const bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!ok || !closed) {
    std::error_code ec;
    fs::remove(tmp_, ec);
    throw InputError(path_.string(), "", "write failed (disk full?)");
  }
  renameIntoPlace(tmp_, path_);
}

void writeEventsTxt(const fs::path& path, std::span<const Event> events, int64_t t0_ns, int width,
                    int height) {
  EventTextWriter w(path, t0_ns, width, height);
  w.write(events);
  w.close();
}

EventFile parseEventsTxt(std::string_view text, const std::string& source, int64_t t0_ns) {
  TextParser parser(source, t0_ns);
  while (!text.empty()) {
    const size_t end = text.find('\n');
    const size_t len = end == std::string_view::npos ? text.size() : end + 1;
    parser.line(text.substr(0, len));
    text.remove_prefix(len);
  }
  return parser.take();
}

EventFile readEventsTxt(const fs::path& path, int64_t t0_ns) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path.string(), "", "file not found");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path.string(), "", std::string("cannot read: ") + std::strerror(errno));
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> guard(f, &std::fclose);
  TextParser parser(path.string(), t0_ns);
  char* line = nullptr;
  size_t cap = 0;
  std::unique_ptr<char*, void (*)(char**)> line_guard(&line, [](char** p) { std::free(*p); });
  for (ssize_t n; (n = ::getline(&line, &cap, f)) >= 0;)
    parser.line(std::string_view(line, static_cast<size_t>(n)));
  if (std::ferror(f)) throw InputError(path.string(), "", "read error");
  return parser.take();
}

// --- HDF5 helpers -------------------------------------------------------------------------------

namespace {

/// Owns an HDF5 id and closes it with the matching H5?close.
class H5Handle {
 public:
  H5Handle() = default;
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  H5Handle(H5Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  H5Handle& operator=(H5Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      close_ = o.close_;
      o.id_ = -1;
    }
    return *this;
  }
  ~H5Handle() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes now; returns false if H5?close failed.
  bool reset() {
    const bool ok = id_ < 0 || !close_ || close_(id_) >= 0;
    id_ = -1;
    return ok;
  }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

/// Turns off HDF5's printing of its error stack for a scope (we throw InputError instead).
class H5Quiet {
 public:
  H5Quiet() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~H5Quiet() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  H5Quiet(const H5Quiet&) = delete;
  H5Quiet& operator=(const H5Quiet&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// The descriptions on HDF5's error stack (deepest last), then clears it.
std::string h5ErrorText() {
  std::string msg;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        auto* s = static_cast<std::string*>(data);
        if (e->desc && *e->desc) *s += (s->empty() ? "" : "; ") + std::string(e->desc);
        return 0;
      },
      &msg);
  H5Eclear2(H5E_DEFAULT);
  return msg.empty() ? "HDF5 error" : msg;
}

hid_t need(hid_t id, const std::string& file, const std::string& field, const char* what) {
  if (id < 0) throw InputError(file, field, fmt::format("{} failed: {}", what, h5ErrorText()));
  return id;
}

/// Creates a 1-D chunked (and compressed) dataset of file type `type`, initial length `n`,
/// unlimited if `extendible`.
H5Handle createVector(hid_t loc, const char* name, hid_t type, hsize_t n, bool extendible,
                      const EventH5Options& o, const std::string& file) {
  const hsize_t max_dims = extendible ? H5S_UNLIMITED : n;
  H5Handle space(need(H5Screate_simple(1, &n, &max_dims), file, name, "H5Screate_simple"),
                 H5Sclose);
  H5Handle dcpl(need(H5Pcreate(H5P_DATASET_CREATE), file, name, "H5Pcreate"), H5Pclose);
  const hsize_t chunk =
      std::max<hsize_t>(1, extendible ? o.chunk_events : std::min<hsize_t>(n, o.chunk_events));
  need(H5Pset_chunk(dcpl.get(), 1, &chunk), file, name, "H5Pset_chunk");
  // no creation and modification times in the object header: same events, same bytes
  need(H5Pset_obj_track_times(dcpl.get(), false), file, name, "H5Pset_obj_track_times");
  if (o.shuffle) need(H5Pset_shuffle(dcpl.get()), file, name, "H5Pset_shuffle");
  if (o.deflate_level > 0)
    need(H5Pset_deflate(dcpl.get(), static_cast<unsigned>(o.deflate_level)), file, name,
         "H5Pset_deflate");
  return H5Handle(
      need(H5Dcreate2(loc, name, type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), file,
           name, "H5Dcreate2"),
      H5Dclose);
}

/// Appends n values of memory type `mem` to the 1-D extendible dataset `ds` of length `old_n`.
void appendVector(hid_t ds, hid_t mem, const void* data, hsize_t old_n, hsize_t n,
                  const std::string& file, const char* name) {
  const hsize_t new_n = old_n + n;
  need(H5Dset_extent(ds, &new_n), file, name, "H5Dset_extent");
  H5Handle fspace(need(H5Dget_space(ds), file, name, "H5Dget_space"), H5Sclose);
  need(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, &old_n, nullptr, &n, nullptr), file, name,
       "H5Sselect_hyperslab");
  H5Handle mspace(need(H5Screate_simple(1, &n, nullptr), file, name, "H5Screate_simple"), H5Sclose);
  need(H5Dwrite(ds, mem, mspace.get(), fspace.get(), H5P_DEFAULT, data), file, name, "H5Dwrite");
}

void writeIntAttribute(hid_t loc, const char* name, int value, const std::string& file) {
  H5Handle space(need(H5Screate(H5S_SCALAR), file, name, "H5Screate"), H5Sclose);
  H5Handle attr(need(H5Acreate2(loc, name, H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                     file, name, "H5Acreate2"),
                H5Aclose);
  need(H5Awrite(attr.get(), H5T_NATIVE_INT, &value), file, name, "H5Awrite");
}

}  // namespace

// --- DSEC HDF5 writer ---------------------------------------------------------------------------

struct EventH5Writer::Impl {
  fs::path path, tmp;
  std::string name;  // path as text, for errors
  EventH5Options opts;
  int64_t t0_us = 0;  // /t_offset
  H5Handle file, group, t, x, y, p;
  std::vector<uint64_t> bt;  // buffered, not yet in the file
  std::vector<uint16_t> bx, by;
  std::vector<uint8_t> bp;
  uint64_t written = 0, count = 0, last_t_us = 0;
  std::vector<uint64_t> ms_to_idx;
  bool open = false;

  void flush() {
    if (bt.empty()) return;
    const hsize_t n = bt.size();
    appendVector(t.get(), H5T_NATIVE_UINT64, bt.data(), written, n, name, "/events/t");
    appendVector(x.get(), H5T_NATIVE_UINT16, bx.data(), written, n, name, "/events/x");
    appendVector(y.get(), H5T_NATIVE_UINT16, by.data(), written, n, name, "/events/y");
    appendVector(p.get(), H5T_NATIVE_UINT8, bp.data(), written, n, name, "/events/p");
    written += n;
    bt.clear();
    bx.clear();
    by.clear();
    bp.clear();
  }

  void discard() {  // closes everything and removes the temporary
    for (H5Handle* h : {&t, &x, &y, &p, &group, &file}) h->reset();
    std::error_code ec;
    fs::remove(tmp, ec);
    open = false;
  }
};

EventH5Writer::EventH5Writer(const fs::path& path, int64_t t0_ns, int width, int height,
                             const EventH5Options& opts)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.tmp = temporaryFor(path);
  m.name = path.string();
  m.opts = opts;
  m.t0_us = floorDiv(t0_ns, 1000);
  if (opts.chunk_events < 1 || opts.chunk_events > (uint64_t{1} << 26))
    throw InputError(m.name, "chunk_events", "must be in [1, 2^26]");
  if (opts.deflate_level < 0 || opts.deflate_level > 9)
    throw InputError(m.name, "deflate_level", "must be in [0, 9]");
  checkSize(path, width, height);
  createParent(path);
  H5Quiet quiet;
  try {
    // HDF5 stamps every object with its creation and modification times unless told not to;
    // the file must be the same bytes whenever it is made (same seed, same bytes)
    H5Handle fcpl(need(H5Pcreate(H5P_FILE_CREATE), m.name, "", "H5Pcreate"), H5Pclose);
    need(H5Pset_obj_track_times(fcpl.get(), false), m.name, "/", "H5Pset_obj_track_times");
    H5Handle gcpl(need(H5Pcreate(H5P_GROUP_CREATE), m.name, "", "H5Pcreate"), H5Pclose);
    need(H5Pset_obj_track_times(gcpl.get(), false), m.name, "/events", "H5Pset_obj_track_times");
    H5Handle scalar_dcpl(need(H5Pcreate(H5P_DATASET_CREATE), m.name, "", "H5Pcreate"), H5Pclose);
    need(H5Pset_obj_track_times(scalar_dcpl.get(), false), m.name, "/t_offset",
         "H5Pset_obj_track_times");
    m.file = H5Handle(need(H5Fcreate(m.tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT), m.name,
                           "", "H5Fcreate"),
                      H5Fclose);
    m.open = true;
    m.group =
        H5Handle(need(H5Gcreate2(m.file.get(), "events", H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                      m.name, "/events", "H5Gcreate2"),
                 H5Gclose);
    m.t = createVector(m.group.get(), "t", H5T_STD_U64LE, 0, true, opts, m.name);
    m.x = createVector(m.group.get(), "x", H5T_STD_U16LE, 0, true, opts, m.name);
    m.y = createVector(m.group.get(), "y", H5T_STD_U16LE, 0, true, opts, m.name);
    m.p = createVector(m.group.get(), "p", H5T_STD_U8LE, 0, true, opts, m.name);
    if (width > 0) {
      writeIntAttribute(m.group.get(), "width", width, m.name);
      writeIntAttribute(m.group.get(), "height", height, m.name);
    }
    H5Handle space(need(H5Screate(H5S_SCALAR), m.name, "/t_offset", "H5Screate"), H5Sclose);
    H5Handle off(need(H5Dcreate2(m.file.get(), "t_offset", H5T_STD_I64LE, space.get(), H5P_DEFAULT,
                                 scalar_dcpl.get(), H5P_DEFAULT),
                      m.name, "/t_offset", "H5Dcreate2"),
                 H5Dclose);
    need(H5Dwrite(off.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &m.t0_us), m.name,
         "/t_offset", "H5Dwrite");
  } catch (...) {
    m.discard();
    throw;
  }
  m.bt.reserve(opts.chunk_events);
}

EventH5Writer::~EventH5Writer() {
  if (impl_ && impl_->open) {
    H5Quiet quiet;
    impl_->discard();
  }
}

uint64_t EventH5Writer::count() const {
  return impl_->count;
}

void EventH5Writer::write(std::span<const Event> events) {
  Impl& m = *impl_;
  INET_CHECK_MSG(m.open, "write after close");
  H5Quiet quiet;
  for (const Event& e : events) {
    const int64_t rel = floorDiv(e.t_ns, 1000) - m.t0_us;
    if (rel < 0)
      throw InputError(m.name, "/events/t",
                       fmt::format("{} precedes t0 ({} us)", e.toString(), m.t0_us));
    const uint64_t t_us = static_cast<uint64_t>(rel);
    if (m.count > 0 && t_us < m.last_t_us)
      throw InputError(m.name, "/events/t",
                       fmt::format("events must be sorted by time: {} (event {}) after {} us",
                                   e.toString(), m.count, m.last_t_us));
    if (t_us / 1000 >= kMaxMsToIdx)
      throw InputError(m.name, "/ms_to_idx",
                       fmt::format("{} lies more than {} ms after t0", e.toString(), kMaxMsToIdx));
    while (m.ms_to_idx.size() * 1000 <= t_us) m.ms_to_idx.push_back(m.count);
    m.bt.push_back(t_us);
    m.bx.push_back(e.x);
    m.by.push_back(e.y);
    m.bp.push_back(e.p ? 1 : 0);
    m.last_t_us = t_us;
    ++m.count;
    if (m.bt.size() >= m.opts.chunk_events) m.flush();
  }
}

void EventH5Writer::close() {
  Impl& m = *impl_;
  INET_CHECK_MSG(m.open, "close twice");
  H5Quiet quiet;
  try {
    m.flush();
    m.ms_to_idx.push_back(m.count);  // one past the last millisecond: the event count
    H5Handle idx = createVector(m.file.get(), "ms_to_idx", H5T_STD_U64LE, m.ms_to_idx.size(), false,
                                m.opts, m.name);
    need(H5Dwrite(idx.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.ms_to_idx.data()),
         m.name, "/ms_to_idx", "H5Dwrite");
    idx.reset();
    bool ok = true;
    for (H5Handle* h : {&m.t, &m.x, &m.y, &m.p, &m.group, &m.file}) ok = h->reset() && ok;
    if (!ok) throw InputError(m.name, "", "closing the HDF5 file failed: " + h5ErrorText());
  } catch (...) {
    m.discard();
    throw;
  }
  m.open = false;
  renameIntoPlace(m.tmp, m.path);
}

void writeEventsH5(const fs::path& path, std::span<const Event> events, int64_t t0_ns, int width,
                   int height, const EventH5Options& opts) {
  EventH5Writer w(path, t0_ns, width, height, opts);
  w.write(events);
  w.close();
}

// --- ms_to_idx ----------------------------------------------------------------------------------

std::vector<uint64_t> computeMsToIdx(std::span<const uint64_t> t_us) {
  std::vector<uint64_t> idx;
  for (size_t i = 0; i < t_us.size(); ++i)
    while (idx.size() * 1000 <= t_us[i]) idx.push_back(i);
  idx.push_back(t_us.size());
  return idx;
}

void validateMsToIdx(std::span<const uint64_t> t_us, std::span<const uint64_t> idx,
                     const std::string& file) {
  const uint64_t n = t_us.size();
  for (size_t m = 0; m < idx.size(); ++m) {
    auto bad = [&](const std::string& what) {
      throw InputError(file, "/ms_to_idx", fmt::format("entry {} = {}: {}", m, idx[m], what));
    };
    if (idx[m] > n) bad(fmt::format("beyond the {} events", n));
    if (m > 0 && idx[m] < idx[m - 1]) bad(fmt::format("decreases (previous {})", idx[m - 1]));
    if (idx[m] < n && t_us[idx[m]] < 1000 * m)
      bad(fmt::format("t[{}] = {} us < {} us", idx[m], t_us[idx[m]], 1000 * m));
    if (idx[m] > 0 && t_us[idx[m] - 1] >= 1000 * m)
      bad(fmt::format("t[{}] = {} us >= {} us", idx[m] - 1, t_us[idx[m] - 1], 1000 * m));
  }
}

// --- DSEC HDF5 reader ---------------------------------------------------------------------------

namespace {

/// Reads the integer dataset `name` (1-D, or scalar if allowed) as T: HDF5 converts from the
/// stored integer type to (u)int64, then each value is checked against T's range (HDF5's own
/// conversion would clip silently).
template <class T>
std::vector<T> readIntegers(hid_t f, const std::string& file, const char* name, bool allow_scalar) {
  H5Handle ds(need(H5Dopen2(f, name, H5P_DEFAULT), file, name, "H5Dopen2 (not a dataset?)"),
              H5Dclose);
  H5Handle type(need(H5Dget_type(ds.get()), file, name, "H5Dget_type"), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_INTEGER)
    throw InputError(file, name, "not an integer dataset");
  const bool is_signed = H5Tget_sign(type.get()) == H5T_SGN_2;
  H5Handle space(need(H5Dget_space(ds.get()), file, name, "H5Dget_space"), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  hsize_t n = 1;
  if (rank == 1) {
    H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  } else if (!(rank == 0 && allow_scalar)) {
    throw InputError(file, name, fmt::format("expected a 1-D dataset, got rank {}", rank));
  }
  std::vector<T> out(n);
  if (n == 0) return out;
  auto convert = [&](const auto& wide) {
    for (size_t i = 0; i < n; ++i) {
      if (!std::in_range<T>(wide[i]))
        throw InputError(file, name,
                         fmt::format("entry {} = {} does not fit the expected type", i, wide[i]));
      out[i] = static_cast<T>(wide[i]);
    }
  };
  if (is_signed) {
    std::vector<int64_t> wide(n);
    need(H5Dread(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, wide.data()), file,
         name, "H5Dread");
    convert(wide);
  } else {
    std::vector<uint64_t> wide(n);
    need(H5Dread(ds.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, wide.data()), file,
         name, "H5Dread");
    convert(wide);
  }
  return out;
}

bool linkExists(hid_t f, const char* name) {
  const htri_t r = H5Lexists(f, name, H5P_DEFAULT);
  H5Eclear2(H5E_DEFAULT);
  return r > 0;
}

int readIntAttribute(hid_t loc, const char* name, const std::string& file) {
  if (H5Aexists(loc, name) <= 0) return 0;
  const std::string field = fmt::format("/events@{}", name);
  H5Handle attr(need(H5Aopen(loc, name, H5P_DEFAULT), file, field, "H5Aopen"), H5Aclose);
  int v = 0;
  need(H5Aread(attr.get(), H5T_NATIVE_INT, &v), file, field, "H5Aread");
  return v;
}

}  // namespace

EventFile readEventsH5(const fs::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(file, "", "file not found");
  H5Quiet quiet;
  if (H5Fis_hdf5(file.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw InputError(file, "", "not an HDF5 file");
  }
  H5Handle f(need(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), file, "", "H5Fopen"),
             H5Fclose);
  if (!linkExists(f.get(), "events"))
    throw InputError(file, "/events", "missing group (DSEC layout: /events/{t,x,y,p})");
  for (const char* name : {"/events/t", "/events/x", "/events/y", "/events/p"})
    if (!linkExists(f.get(), name))
      throw InputError(file, name, "missing dataset (DSEC layout: /events/{t,x,y,p})");
  const auto t = readIntegers<uint64_t>(f.get(), file, "/events/t", false);
  const auto x = readIntegers<uint16_t>(f.get(), file, "/events/x", false);
  const auto y = readIntegers<uint16_t>(f.get(), file, "/events/y", false);
  const auto p = readIntegers<uint8_t>(f.get(), file, "/events/p", false);
  for (const auto& [name, n] : {std::pair<const char*, size_t>{"/events/x", x.size()},
                                {"/events/y", y.size()},
                                {"/events/p", p.size()}})
    if (n != t.size())
      throw InputError(file, name, fmt::format("{} entries, /events/t has {}", n, t.size()));
  EventFile out;
  if (linkExists(f.get(), "t_offset")) {
    const auto off = readIntegers<int64_t>(f.get(), file, "/t_offset", true);
    if (off.size() != 1) throw InputError(file, "/t_offset", "expected a single value");
    out.t_offset_us = off[0];
  }
  for (size_t i = 1; i < t.size(); ++i)
    if (t[i] < t[i - 1])
      throw InputError(
          file, "/events/t",
          fmt::format("not sorted: t[{}] = {} < t[{}] = {}", i, t[i], i - 1, t[i - 1]));
  if (linkExists(f.get(), "ms_to_idx")) {
    out.ms_to_idx = readIntegers<uint64_t>(f.get(), file, "/ms_to_idx", false);
    validateMsToIdx(t, out.ms_to_idx, file);
  }
  {
    H5Handle g(need(H5Gopen2(f.get(), "events", H5P_DEFAULT), file, "/events", "H5Gopen2"),
               H5Gclose);
    out.width = readIntAttribute(g.get(), "width", file);
    out.height = readIntAttribute(g.get(), "height", file);
  }
  out.events.resize(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    if (p[i] > 1)
      throw InputError(file, "/events/p", fmt::format("entry {} = {}, expected 0 or 1", i, p[i]));
    int64_t t_us = 0, t_ns = 0;
    if (t[i] > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()) ||
        __builtin_add_overflow(static_cast<int64_t>(t[i]), out.t_offset_us, &t_us) ||
        __builtin_mul_overflow(t_us, int64_t{1000}, &t_ns))
      throw InputError(file, "/events/t",
                       fmt::format("entry {} = {} us (+ t_offset) overflows int64 ns", i, t[i]));
    out.events[i] = Event{t_ns, x[i], y[i], p[i]};
  }
  return out;
}

}  // namespace inet
