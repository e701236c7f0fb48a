// Frames stream to disk: the peak resident memory of a 250-frame run is within 10% of a
// 25-frame run (nothing accumulates per frame).
#include <gtest/gtest.h>

#include <cstdio>

#include "cli_util.h"

namespace inet::test {
namespace {

TEST(GenerateMemory, PeakRssFlatOverLongSequences) {
  TempDir dir("gen_mem");
  std::string common =
      "generate --layout builtin:room --width 320 --height 240 --fx 300 --fy 300 --spp 1 "
      "--max-bounces 2 --no-progress ";
  RunResult short_run = runInterinet(common + "--frames 25 --out " + (dir / "a").string());
  ASSERT_EQ(short_run.exit_code, 0) << short_run.err;
  RunResult long_run = runInterinet(common + "--frames 250 --out " + (dir / "b").string());
  ASSERT_EQ(long_run.exit_code, 0) << long_run.err;
  double ratio = static_cast<double>(long_run.peak_rss_kb) / short_run.peak_rss_kb;
  RecordProperty("rss_25_kb", std::to_string(short_run.peak_rss_kb));
  RecordProperty("rss_250_kb", std::to_string(long_run.peak_rss_kb));
  std::printf("peak RSS: 25 frames %ld kB, 250 frames %ld kB (ratio %.3f)\n", short_run.peak_rss_kb,
              long_run.peak_rss_kb, ratio);
  EXPECT_LT(ratio, 1.10) << short_run.peak_rss_kb << " kB vs " << long_run.peak_rss_kb << " kB";
}

}  // namespace
}  // namespace inet::test
