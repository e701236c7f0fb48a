#pragma once
// Event files (SENSORS.md section 3, output formats 1 and 2). Both writers stream: events are
// appended in batches of any size (tens of millions in total are fine) to "<name>.tmp-<pid>"
// beside the final name (core/atomic_file.h's convention), renamed into place by close(); a
// writer destroyed without close() removes its temporary, so a crash or an exception never
// leaves a half-written file under the real name.
//
// 1. RPG Event-Camera Dataset `events.txt` (Mueggler et al., IJRR 2017): one event per line
//    "t x y p", t in seconds relative to t0 with exactly 9 decimals (printed from the integer
//    ns, so the round trip is exact for any int64 time), x column, y row (0-based, origin top
//    left), p 0 = OFF / 1 = ON, '\n' line ends. Optional E2VID-style first line "W H".
// 2. DSEC-style HDF5 `events.h5` (Gehrig et al., RA-L 2021, "DSEC" data format page):
//        /events/t    uint64  microseconds relative to /t_offset
//        /events/x    uint16  /events/y  uint16  /events/p  uint8 (0/1)
//        /t_offset    int64   scalar, microseconds (t0 floored to whole us)
//        /ms_to_idx   uint64  ms_to_idx[m] = index of the first event with t >= 1000 m, so
//                             t[ms_to_idx[m]] >= 1000 m and t[ms_to_idx[m] - 1] < 1000 m;
//                             length = (last event's t) / 1000 + 2, the last entry being the
//                             event count (so events of millisecond m are the index range
//                             [ms_to_idx[m], ms_to_idx[m + 1]) for every m up to the last);
//                             {0} for no events.
//    plus our attributes width, height (int32) on /events when known. Datasets are chunked
//    (65536 events) with byte shuffle + deflate level 1 (standard filters, readable by h5py and
//    every HDF5 build with zlib). Time resolution is 1 us: an event at t_ns is stored as
//    floor(t_ns / 1000) - t_offset, i.e. reading gives back t_ns rounded DOWN to whole us
//    (order is kept; events in (t_{k-1}, t_k] stay in [t_{k-1}, t_k] after flooring).
// HDF5 calls are not thread-safe in the serial library: use one writer or reader at a time.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sensors/event_sim.h"

namespace inet {

/// Events read from a file, times in ns on the writer's clock (t0 / t_offset added back).
struct EventFile {
  std::vector<Event> events;
  int width = 0;  ///< from the E2VID header line or the h5 attributes; 0 = not given
  int height = 0;
  int64_t t_offset_us = 0;          ///< h5: /t_offset (0 when absent); txt: unused
  std::vector<uint64_t> ms_to_idx;  ///< h5: /ms_to_idx as stored (validated); empty if absent
};

// --- RPG text ---------------------------------------------------------------------------------

/// Streaming writer of events.txt. t0_ns is written as time 0 (the sequence start); times before
/// it are written negative. width > 0 writes the E2VID header line "W H" first (width and
/// height: both 0 or both in [1, 65536], else InputError). Events are written in the order given
/// (the simulator's output is sorted).
class EventTextWriter {
 public:
  /// Creates parent folders and opens the temporary; throws InputError(path, ...) on failure.
  EventTextWriter(const std::filesystem::path& path, int64_t t0_ns, int width = 0, int height = 0);
  ~EventTextWriter();
  EventTextWriter(const EventTextWriter&) = delete;
  EventTextWriter& operator=(const EventTextWriter&) = delete;

  void write(std::span<const Event> events);
  /// Flushes, closes and renames into place; throws InputError(path, ...) on an I/O error.
  void close();
  uint64_t count() const { return count_; }

 private:
  void flushBuffer();
  std::filesystem::path path_, tmp_;
  std::FILE* file_ = nullptr;
  int64_t t0_ns_;
  uint64_t count_ = 0;
  std::string buf_;
};

/// Writes `events` to `path` in one go (EventTextWriter).
void writeEventsTxt(const std::filesystem::path& path, std::span<const Event> events, int64_t t0_ns,
                    int width = 0, int height = 0);

/// One RPG line "t x y p\n" for `e` (t relative to t0_ns, 9 decimals).
std::string formatEventLine(const Event& e, int64_t t0_ns);

/// Reads an RPG events.txt (t0_ns is added to every time). Accepts LF or CRLF, blank lines,
/// '#' comment lines (v2e writes a header of them), blanks or tabs between columns, the E2VID
/// first line "W H" (then x < W and y < H are checked), times with any number of decimals
/// (rounded to the nearest ns) or in exponent form ("1e-05", as Python's str(float) prints),
/// and p = -1 for OFF (the +-1 convention). Throws InputError(path, "line N", ...) for any other
/// line, a coordinate outside [0, 65535] or a time outside the int64 ns range.
EventFile readEventsTxt(const std::filesystem::path& path, int64_t t0_ns = 0);
/// The same on text in memory; `source` names it in errors.
EventFile parseEventsTxt(std::string_view text, const std::string& source, int64_t t0_ns = 0);

// --- DSEC HDF5 --------------------------------------------------------------------------------

struct EventH5Options {
  uint64_t chunk_events = 65536;  ///< chunk length of the per-event datasets
  int deflate_level = 1;          ///< 0 = no compression, 1-9 gzip levels
  bool shuffle = true;            ///< byte shuffle before deflate (better ratio for integers)
};

/// Streaming writer of events.h5. t0_ns becomes /t_offset (floored to us); events must be
/// non-decreasing in time and not before t0 (InputError(path, "/events/t", ...) otherwise).
/// Memory: one chunk of buffered events plus ms_to_idx (8 bytes per millisecond).
class EventH5Writer {
 public:
  EventH5Writer(const std::filesystem::path& path, int64_t t0_ns, int width = 0, int height = 0,
                const EventH5Options& opts = {});
  ~EventH5Writer();
  EventH5Writer(const EventH5Writer&) = delete;
  EventH5Writer& operator=(const EventH5Writer&) = delete;

  void write(std::span<const Event> events);
  /// Writes the buffered tail, /ms_to_idx, closes the file and renames it into place.
  void close();
  uint64_t count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes `events` to `path` in one go (EventH5Writer).
void writeEventsH5(const std::filesystem::path& path, std::span<const Event> events, int64_t t0_ns,
                   int width = 0, int height = 0, const EventH5Options& opts = {});

/// Reads a DSEC-style events.h5 with the plain HDF5 C API: /events/{t,x,y,p} by name (any
/// integer storage type: HDF5 converts to 64 bits, then each value is range-checked for uint64 /
/// uint16 / uint16 / uint8, so e.g. a uint32 t or an int8 p reads too), /t_offset and
/// /ms_to_idx when present (both optional: other tools omit them). Checks equal lengths, t
/// non-decreasing, p in {0, 1}, and ms_to_idx (validateMsToIdx). Event times come back as
/// (t + t_offset) * 1000 ns. Throws InputError(path, dataset name, ...) for a missing or
/// malformed dataset, InputError(path, "", ...) for a non-HDF5 file.
/// The DSEC downloads themselves are Blosc-compressed (h5py users import hdf5plugin): reading
/// them needs the Blosc filter plugin on HDF5_PLUGIN_PATH, otherwise H5Dread fails and the
/// InputError names the dataset and quotes HDF5's message. Our own files use deflate only.
EventFile readEventsH5(const std::filesystem::path& path);

/// DSEC's ms_to_idx for sorted times t_us (us): see the layout above (length last / 1000 + 2).
std::vector<uint64_t> computeMsToIdx(std::span<const uint64_t> t_us);
/// Checks ms_to_idx against sorted t_us: entries non-decreasing and <= t_us.size(), and for
/// each m, t[idx[m]] >= 1000 m (idx[m] < size) and t[idx[m] - 1] < 1000 m (idx[m] > 0).
/// Any length is accepted (other writers may stop one entry earlier). Throws InputError(file,
/// "/ms_to_idx", "entry m: ...").
void validateMsToIdx(std::span<const uint64_t> t_us, std::span<const uint64_t> ms_to_idx,
                     const std::string& file);

}  // namespace inet
