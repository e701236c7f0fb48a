// The sequence pipeline as a library (pipeline/sequence_job.h): a SequenceJob filled in code,
// without the command line, writes a sequence; frame ranges report what they did; a rerun skips
// what is done; bad jobs are refused before anything is written.
#include <gtest/gtest.h>

#include <filesystem>

#include "../expect_input_error.h"
#include "../temp_dir.h"
#include "assets/catalog_library.h"
#include "core/error.h"
#include "pipeline/sequence_job.h"

namespace inet {
namespace {

namespace fs = std::filesystem;

SequenceJob smallJob(const fs::path& out) {
  SequenceJob job;
  job.scene.path = "builtin:room";
  job.frames = 4;
  job.spp = 1;
  job.K = CameraIntrinsics::centred(48, 36, 45.0);
  job.width_set = job.height_set = job.fx_set = job.fy_set = true;
  job.passes = "rgb,depth,label,boxes";
  job.formats = "asl";
  job.progress = false;
  job.out = out.string();
  return job;
}

size_t pngs(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".png";
  return n;
}

TEST(SequenceJob, RangesReportWhatTheyRenderedAndTheLastOneFinishes) {
  test::TempDir dir("seqjob");
  SequenceJob job = smallJob(dir.path());
  job.frame_begin = 2;
  SequenceJobResult r = runSequenceJob(job);
  ASSERT_EQ(r.sequences.size(), 1u);
  const fs::path seq = r.sequences[0].dir;
  EXPECT_EQ(seq, dir.path() / "default_room" / "seq_000");
  EXPECT_EQ(r.sequences[0].frames, 4u);
  EXPECT_EQ(r.sequences[0].rendered, 2u);
  EXPECT_EQ(r.sequences[0].skipped, 0u);
  EXPECT_FALSE(r.sequences[0].finished);
  EXPECT_EQ(pngs(seq / "cam0" / "data"), 2u);
  EXPECT_FALSE(fs::exists(seq / "boxes.json"));

  job.frame_begin = 0;  // the whole sequence: frames 2 and 3 are done
  r = runSequenceJob(job);
  EXPECT_EQ(r.sequences[0].rendered, 2u);
  EXPECT_EQ(r.sequences[0].skipped, 2u);
  EXPECT_TRUE(r.sequences[0].finished);
  EXPECT_TRUE(fs::exists(seq / "boxes.json"));
  EXPECT_TRUE(fs::exists(seq / "cam0" / "data.csv"));

  r = runSequenceJob(job);  // all done: nothing rendered, finished again (same bytes)
  EXPECT_EQ(r.sequences[0].rendered, 0u);
  EXPECT_EQ(r.sequences[0].skipped, 4u);
  EXPECT_TRUE(r.sequences[0].finished);
}

TEST(SequenceJob, EveryConfigurationIsOneSequence) {
  test::TempDir dir("seqjob_configs");
  SequenceJob job = smallJob(dir.path());
  job.frames = 2;
  job.config = "original,lighting:3";
  const SequenceJobResult r = runSequenceJob(job);
  ASSERT_EQ(r.sequences.size(), 2u);
  EXPECT_EQ(fs::path(r.sequences[1].dir).filename(), "seq_000_lighting_3");
  for (const auto& s : r.sequences) {
    EXPECT_TRUE(s.finished);
    EXPECT_EQ(pngs(fs::path(s.dir) / "cam0" / "data"), 2u);
  }
}

// The credits of what a frame shows: an apartment furnished from the Sweet Home 3D catalogs
// names its pieces with creator and licence; the parametric furniture has none.
TEST(SequenceJob, CatalogFurnitureComesWithItsCredits) {
  if (!catalogsAvailable())
    GTEST_SKIP() << "the Sweet Home 3D catalogs are not installed (scripts/setup.sh)";
  test::TempDir dir("seqjob_credits");
  SequenceJob job = smallJob(dir.path());
  job.scene.path = "procedural:5";
  job.scene.rooms = 2;
  job.scene.furniture = "catalog";
  job.frames = 1;
  job.passes = "label,instance";
  const SequenceJobResult r = runSequenceJob(job);
  ASSERT_EQ(r.sequences.size(), 1u);
  const auto& credits = r.sequences[0].assets;
  EXPECT_GE(credits.size(), 3u) << "a furnished 2-room apartment";
  for (const auto& [instance, c] : credits) {
    EXPECT_GT(instance, 0);
    EXPECT_NE(c.id.find('#'), std::string::npos) << c.id;  // "<catalog id>#<piece>"
    EXPECT_FALSE(c.creator.empty()) << c.id;
    EXPECT_FALSE(c.license.empty()) << c.id;
  }
  job.scene.furniture = "parametric";
  job.out = (dir / "parametric").string();
  EXPECT_TRUE(runSequenceJob(job).sequences[0].assets.empty());
}

TEST(SequenceJob, BadJobsAreRefusedBeforeAnythingIsWritten) {
  test::TempDir dir("seqjob_bad");
  SequenceJob job = smallJob(dir.path() / "out");
  job.frame_begin = 4;  // the path has 4 frames
  auto expectRefused = [&](const std::string& field, const std::string& problem) {
    const InputError e = test::expectInputError([&] { runSequenceJob(job); });
    EXPECT_EQ(e.field(), field);
    EXPECT_NE(e.problem().find(problem), std::string::npos) << e.what();
  };
  expectRefused("frame range", "starts at frame 4");
  job.frame_begin = 2;
  job.frame_end = 2;
  expectRefused("frame range", "before the end");
  job.frame_end = 3;
  job.config = "original,original";
  expectRefused("--config", "listed twice");
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

}  // namespace
}  // namespace inet
