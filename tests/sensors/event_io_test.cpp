// Event files (sensors/event_io.h): RPG events.txt and DSEC-style events.h5 round trips, the
// real RPG sample, reader variants and errors, ms_to_idx, atomic writes, file sizes.
#include "sensors/event_io.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <vector>

#include "../expect_input_error.h"
#include "../temp_dir.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/rng.h"
#include "motion.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

using test::expectInputError;

/// n sorted events from t0_ns on, steps of 0-2999 ns (runs of equal times included), random
/// pixels of a 240 x 180 sensor and polarities.
std::vector<Event> randomEvents(size_t n, int64_t t0_ns, uint64_t seed) {
  std::vector<Event> ev(n);
  int64_t t = t0_ns;
  for (size_t i = 0; i < n; ++i) {
    CounterRng rng(seed, RngStream::Sensor, static_cast<uint32_t>(i), 0, 0x494f54u);
    const uint32_t r = rng.nextU32();
    t += (r % 4 == 0) ? 0 : rng.nextU32() % 3000;
    ev[i] = {t, static_cast<uint16_t>(rng.nextU32() % 240),
             static_cast<uint16_t>(rng.nextU32() % 180), static_cast<uint8_t>(r >> 31)};
  }
  return ev;
}

/// Files in `dir` (names), to see that no temporary is left behind.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(EventIo, TextRoundTripIsExactToTheNanosecond) {
  test::TempDir dir("events_txt");
  const int64_t t0 = 1'403'715'273'262'142'976;                     // a EuRoC-like absolute stamp
  std::vector<Event> ev = randomEvents(20'000, t0 - 5'000'000, 1);  // some before t0
  ev.push_back({t0 + 3'600'000'000'123, 239, 179, 1});              // an hour later
  const fs::path path = dir / "out/events.txt";
  {
    EventTextWriter w(path, t0);
    w.write(std::span(ev).first(7));  // in batches
    w.write(std::span(ev).subspan(7));
    EXPECT_FALSE(fs::exists(path));  // only the temporary so far
    w.close();
    EXPECT_EQ(w.count(), ev.size());
  }
  EXPECT_EQ(listing(dir / "out"), std::vector<std::string>{"events.txt"});
  const EventFile back = readEventsTxt(path, t0);
  EXPECT_EQ(back.width, 0);
  ASSERT_EQ(back.events.size(), ev.size());
  EXPECT_TRUE(back.events == ev);
  EXPECT_EQ(formatEventLine(ev.back(), t0), "3600.000000123 239 179 1\n");
  EXPECT_EQ(formatEventLine({t0 - 1500, 1, 2, 0}, t0), "-0.000001500 1 2 0\n");
  // the E2VID header
  writeEventsTxt(dir / "e2vid.txt", ev, t0, 240, 180);
  EXPECT_EQ(readTextFile(dir / "e2vid.txt").substr(0, 8), "240 180\n");
  const EventFile e2 = readEventsTxt(dir / "e2vid.txt", t0);
  EXPECT_EQ(e2.width, 240);
  EXPECT_EQ(e2.height, 180);
  EXPECT_TRUE(e2.events == ev);
}

TEST(EventIo, TextReaderAcceptsCommonVariants) {
  const std::string text =
      "#!events.txt\r\n# This is a text DVS created by v2e\r\n\r\n"
      "346 260\r\n"
      "0.5 1 2 1\r\n"
      "  1e-05\t3 4 0  \r\n"  // exponent form, tabs, extra blanks
      "\r\n"
      "0.0000000015 5 6 -1\r\n"  // 10 decimals round to the nearest ns; -1 = OFF
      "2.000000001 345 259 1";   // no final line end
  const EventFile f = parseEventsTxt(text, "v2e.txt", 100);
  EXPECT_EQ(f.width, 346);
  EXPECT_EQ(f.height, 260);
  const std::vector<Event> expected = {
      {500'000'100, 1, 2, 1}, {10'100, 3, 4, 0}, {102, 5, 6, 0}, {2'000'000'101, 345, 259, 1}};
  EXPECT_TRUE(f.events == expected) << f.events.size();
}

TEST(EventIo, TextReaderNamesFileAndLine) {
  const struct {
    std::string text;
    std::string line;
  } cases[] = {
      {"0.1 1 2 1\n0.2 1 2\n", "line 2"},      // 3 columns
      {"0.1 1 2 1\n\nabc 1 2 1\n", "line 3"},  // time not a number
      {"0.1 1 2 2\n", "line 1"},               // polarity
      {"0.1 70000 2 1\n", "line 1"},           // x out of range
      {"0.1 -1 2 1\n", "line 1"},              // negative x
      {"10 10\n0.1 10 2 1\n", "line 2"},       // outside the header's size
      {"0.1 1 2 1\n240 180\n", "line 2"},      // a header line not first
      {"0.1 1 2 1 7\n", "line 1"},             // 5 columns
      {"99999999999.5 1 2 1\n", "line 1"},     // beyond int64 ns
  };
  for (const auto& c : cases) {
    const InputError e = expectInputError([&] { parseEventsTxt(c.text, "bad.txt"); });
    EXPECT_EQ(e.file(), "bad.txt") << c.text;
    EXPECT_EQ(e.field(), c.line) << c.text << " -> " << e.what();
  }
  test::TempDir dir("events_bad");
  const std::string path = dir.write("events.txt", "0.1 1 2 1\r\n0.2 x 2 1\r\n");
  const InputError e = expectInputError([&] { readEventsTxt(path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.field(), "line 2");
  EXPECT_EQ(expectInputError([&] { readEventsTxt(dir / "missing.txt"); }).problem(),
            "file not found");
}

// ../shared/data/formats/events_rpg/events_head.txt: the first 9 lines of the RPG dataset's
// shapes_rotation/events.txt. Our writer, given t0 = 0, must reproduce it byte for byte.
TEST(EventIo, RpgSampleReadsAndIsReproducedByteForByte) {
  const std::string shared = test::sharedDir();
  const fs::path path = shared + "/data/formats/events_rpg/events_head.txt";
  if (shared.empty() || !fs::exists(path))
    GTEST_SKIP() << "needs ../shared/data/formats/events_rpg/events_head.txt (absent)";
  const EventFile f = readEventsTxt(path);
  ASSERT_EQ(f.events.size(), 9u);
  EXPECT_EQ(f.events[0], (Event{0, 33, 39, 1}));
  EXPECT_EQ(f.events[8], (Event{148'001, 192, 79, 1}));
  for (size_t i = 0; i < f.events.size(); ++i) {
    EXPECT_LE(f.events[i].p, 1);
    if (i > 0) {
      EXPECT_LE(f.events[i - 1].t_ns, f.events[i].t_ns);
    }
  }
  test::TempDir dir("events_rpg");
  writeEventsTxt(dir / "events.txt", f.events, 0);
  EXPECT_EQ(readTextFile(dir / "events.txt"), readTextFile(path));
}

TEST(EventIo, H5RoundTripKeepsMicroseconds) {
  test::TempDir dir("events_h5");
  const int64_t t0 = 1'000'000'123'456;  // not a whole microsecond
  const std::vector<Event> ev = randomEvents(50'000, t0 + 700, 2);
  EventH5Options o;
  o.chunk_events = 4096;  // several chunks and a partial one
  const fs::path path = dir / "seq/events.h5";
  {
    EventH5Writer w(path, t0, 240, 180, o);
    for (size_t i = 0; i < ev.size(); i += 10'007)
      w.write(std::span(ev).subspan(i, std::min<size_t>(10'007, ev.size() - i)));
    w.close();
  }
  EXPECT_EQ(listing(dir / "seq"), std::vector<std::string>{"events.h5"});
  const EventFile f = readEventsH5(path);
  EXPECT_EQ(f.width, 240);
  EXPECT_EQ(f.height, 180);
  EXPECT_EQ(f.t_offset_us, t0 / 1000);
  ASSERT_EQ(f.events.size(), ev.size());
  std::vector<uint64_t> t_us;
  for (size_t i = 0; i < ev.size(); ++i) {
    const Event& a = ev[i];
    const Event& b = f.events[i];
    ASSERT_EQ(b.t_ns, a.t_ns / 1000 * 1000) << i;  // floored to whole us
    ASSERT_EQ(b.x, a.x);
    ASSERT_EQ(b.y, a.y);
    ASSERT_EQ(b.p, a.p);
    t_us.push_back(static_cast<uint64_t>(a.t_ns / 1000 - t0 / 1000));
  }
  EXPECT_EQ(f.ms_to_idx, computeMsToIdx(t_us));
  EXPECT_EQ(f.ms_to_idx.size(), t_us.back() / 1000 + 2);
  // no events: an empty file with ms_to_idx = {0}
  writeEventsH5(dir / "empty.h5", {}, t0);
  const EventFile empty = readEventsH5(dir / "empty.h5");
  EXPECT_TRUE(empty.events.empty());
  EXPECT_EQ(empty.ms_to_idx, std::vector<uint64_t>{0});
}

// ms_to_idx[m] is the first index with t >= 1000 m (checked against a binary search), the last
// entry is the event count, and validateMsToIdx accepts it and rejects a corrupted entry.
TEST(EventIo, MsToIdxPropertyOnRandomData) {
  for (uint64_t seed = 0; seed < 20; ++seed) {
    std::vector<uint64_t> t;
    uint64_t now = seed * 777;  // need not start at 0
    for (uint32_t i = 0; i < 3000; ++i) {
      CounterRng rng(seed, RngStream::Sensor, i, 1, 0x4d5349u);
      const uint32_t r = rng.nextU32();
      now += r % 5 == 0 ? 0 : (r % 7 == 0 ? 5000 + r % 4000 : r % 700);  // gaps of empty ms
      t.push_back(now);
    }
    const std::vector<uint64_t> idx = computeMsToIdx(t);
    ASSERT_EQ(idx.size(), t.back() / 1000 + 2);
    for (size_t m = 0; m < idx.size(); ++m) {
      const auto lb = std::lower_bound(t.begin(), t.end(), 1000 * m) - t.begin();
      ASSERT_EQ(idx[m], static_cast<uint64_t>(lb)) << "seed " << seed << " ms " << m;
      if (idx[m] < t.size()) {
        ASSERT_GE(t[idx[m]], 1000 * m);
      }
      if (idx[m] > 0) {
        ASSERT_LT(t[idx[m] - 1], 1000 * m);
      }
    }
    EXPECT_NO_THROW(validateMsToIdx(t, idx, "x.h5"));
    std::vector<uint64_t> bad = idx;
    const size_t m = idx.size() / 2;
    bad[m] = bad[m] > 0 ? bad[m] - 1 : bad[m] + 1;
    const InputError e = expectInputError([&] { validateMsToIdx(t, bad, "x.h5"); });
    EXPECT_EQ(e.field(), "/ms_to_idx");
    EXPECT_EQ(e.file(), "x.h5");
  }
  EXPECT_EQ(computeMsToIdx({}), std::vector<uint64_t>{0});
}

/// Writes a DSEC-like file with the plain HDF5 API: t as uint32 (DSEC's own type), p as int8,
/// t_offset int64; datasets in `skip` are left out, ms_to_idx as given (empty = none).
void writeDsecLike(const std::string& path, const std::vector<uint32_t>& t,
                   const std::vector<uint64_t>& ms_to_idx, const std::string& skip) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t g = H5Gcreate2(f, "events", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  auto put = [&](hid_t loc, const char* name, hid_t ftype, hid_t mtype, const void* data,
                 hsize_t n) {
    if (skip == name) return;
    const hid_t s = H5Screate_simple(1, &n, nullptr);
    const hid_t d = H5Dcreate2(loc, name, ftype, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(d);
    H5Sclose(s);
  };
  const size_t n = t.size();
  std::vector<uint16_t> x(n, 7), y(n, 9);
  std::vector<int8_t> p(n, 1);
  put(g, "t", H5T_STD_U32LE, H5T_NATIVE_UINT32, t.data(), n);
  put(g, "x", H5T_STD_U16LE, H5T_NATIVE_UINT16, x.data(), n);
  put(g, "y", H5T_STD_U16LE, H5T_NATIVE_UINT16, y.data(), n);
  put(g, "p", H5T_STD_I8LE, H5T_NATIVE_INT8, p.data(), n);
  if (!ms_to_idx.empty())
    put(f, "ms_to_idx", H5T_STD_U64LE, H5T_NATIVE_UINT64, ms_to_idx.data(), ms_to_idx.size());
  const int64_t offset = 5'000'000;
  const hid_t s = H5Screate(H5S_SCALAR);
  const hid_t d =
      H5Dcreate2(f, "t_offset", H5T_STD_I64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &offset);
  H5Dclose(d);
  H5Sclose(s);
  H5Gclose(g);
  H5Fclose(f);
}

TEST(EventIo, H5ReaderConvertsDsecTypesAndNamesMissingDatasets) {
  test::TempDir dir("events_dsec");
  const std::vector<uint32_t> t = {0, 999, 1000, 1000, 3500};
  const std::vector<uint64_t> good = {0, 2, 4, 4};  // one entry shorter than ours: accepted
  const std::string ok = (dir / "ok.h5").string();
  writeDsecLike(ok, t, good, "");
  const EventFile f = readEventsH5(ok);
  ASSERT_EQ(f.events.size(), 5u);
  EXPECT_EQ(f.t_offset_us, 5'000'000);
  EXPECT_EQ(f.events[3], (Event{(1000 + 5'000'000) * 1000LL, 7, 9, 1}));
  EXPECT_EQ(f.ms_to_idx, good);

  const std::string no_x = (dir / "no_x.h5").string();
  writeDsecLike(no_x, t, good, "x");
  InputError e = expectInputError([&] { readEventsH5(no_x); });
  EXPECT_EQ(e.file(), no_x);
  EXPECT_EQ(e.field(), "/events/x");

  const std::string bad_idx = (dir / "bad_idx.h5").string();
  writeDsecLike(bad_idx, t, {0, 3, 4, 4, 5}, "");  // t[3 - 1] = 1000 is not < 1000
  e = expectInputError([&] { readEventsH5(bad_idx); });
  EXPECT_EQ(e.field(), "/ms_to_idx");
  EXPECT_NE(e.problem().find("entry 1"), std::string::npos) << e.what();

  const std::string unsorted = (dir / "unsorted.h5").string();
  writeDsecLike(unsorted, {5, 3}, {}, "");
  EXPECT_EQ(expectInputError([&] { readEventsH5(unsorted); }).field(), "/events/t");

  const std::string text = dir.write("not.h5", "0.1 1 2 1\n");
  e = expectInputError([&] { readEventsH5(text); });
  EXPECT_EQ(e.file(), text);
  EXPECT_EQ(e.problem(), "not an HDF5 file");
}

TEST(EventIo, WritersAreAtomicAndCheckOrder) {
  test::TempDir dir("events_atomic");
  const std::vector<Event> ev = randomEvents(1000, 0, 3);
  {
    EventTextWriter w(dir / "a.txt", 0);
    w.write(ev);
  }  // destroyed without close(): nothing stays
  {
    EventH5Writer w(dir / "a.h5", 0);
    w.write(ev);
  }
  EXPECT_TRUE(listing(dir.path()).empty());
  {
    EventH5Writer w(dir / "b.h5", 0);
    std::vector<Event> unsorted = {{2000, 1, 1, 1}, {1000, 1, 1, 1}};
    const InputError e = expectInputError([&] { w.write(unsorted); });
    EXPECT_EQ(e.field(), "/events/t");
    const InputError before = expectInputError([&] {
      w.write(std::vector<Event>{{-5000, 0, 0, 0}});
    });
    EXPECT_NE(before.problem().find("precedes t0"), std::string::npos);
  }
  EXPECT_TRUE(listing(dir.path()).empty());
  // an existing file is replaced only by the complete new one
  writeEventsTxt(dir / "c.txt", ev, 0);
  {
    EventTextWriter w(dir / "c.txt", 0);
    w.write(std::span(ev).first(3));
  }
  EXPECT_EQ(readEventsTxt(dir / "c.txt").events.size(), ev.size());
}

// Sizes and write speeds on the simulator's own output (a moving texture seen by a 240 x 180
// sensor), printed for the report.
TEST(EventIo, FileSizesPerMillionEvents) {
  const int W = 240, H = 180;
  EventSimulator sim(W, H, EventOptions{});
  std::vector<Event> ev;
  ImageF L(W, H, 1);
  for (int k = 0; ev.size() < 1'000'000; ++k) {
    const double shift = 0.3 * k;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        L.at(x, y) = static_cast<float>(
            -2 + 0.8 * std::sin(2 * std::numbers::pi * (x - shift) / 23.0 + 0.1 * y));
    sim.addSample(1'000'000'000LL + k * 1'000'000LL, L, ev);
  }
  test::TempDir dir("events_size");
  auto timed = [](auto f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const double w_txt = timed([&] { writeEventsTxt(dir / "events.txt", ev, 1'000'000'000); });
  const double w_h5 = timed([&] { writeEventsH5(dir / "events.h5", ev, 1'000'000'000); });
  EventFile back;
  const double r_txt = timed([&] { back = readEventsTxt(dir / "events.txt", 1'000'000'000); });
  EXPECT_TRUE(back.events == ev);
  const double r_h5 = timed([&] { back = readEventsH5(dir / "events.h5"); });
  ASSERT_EQ(back.events.size(), ev.size());
  const double m = ev.size() * 1e-6;
  const double txt_mb = fs::file_size(dir / "events.txt") * 1e-6 / m;
  const double h5_mb = fs::file_size(dir / "events.h5") * 1e-6 / m;
  std::printf(
      "%zu events over %.3f s: txt %.1f MB per million (write %.2f s, read %.2f s per "
      "million), h5 %.2f MB per million (write %.2f s, read %.2f s per million)\n",
      ev.size(), (ev.back().t_ns - ev.front().t_ns) * 1e-9, txt_mb, w_txt / m, r_txt / m, h5_mb,
      w_h5 / m, r_h5 / m);
  EXPECT_LT(h5_mb, txt_mb / 2);
  // worst case for compression: random pixels, ~0.9 Mevents/s
  const std::vector<Event> rnd = randomEvents(1'000'000, 0, 4);
  writeEventsTxt(dir / "random.txt", rnd, 0);
  writeEventsH5(dir / "random.h5", rnd, 0);
  std::printf("random pixels, %.2f s: txt %.1f MB, h5 %.2f MB per million\n",
              rnd.back().t_ns * 1e-9, fs::file_size(dir / "random.txt") * 1e-6,
              fs::file_size(dir / "random.h5") * 1e-6);
}

}  // namespace
}  // namespace inet
