// The dataset spec: defaults, every kind of located error, JSON and YAML, the documented example.
#include "builder/dataset_spec.h"

#include <gtest/gtest.h>

#include "../expect_input_error.h"
#include "../temp_dir.h"

namespace inet {
namespace {

using test::expectInputError;

const char* const kFile = "/specs/spec.yaml";
const std::string kMinimal = "version: 1\nname: tiny\nlayouts: {procedural: {count: 3}}\n";

DatasetSpec parse(const std::string& text) {
  return parseDatasetSpecText(text, kFile);
}

InputError errorOf(const std::string& text) {
  return expectInputError([&] { parse(text); });
}

TEST(DatasetSpec, DefaultsFillEveryKey) {
  const DatasetSpec s = parse(kMinimal);
  EXPECT_EQ(s.name, "tiny");
  EXPECT_EQ(s.version, 1);
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.layouts.procedural.count, 3);
  EXPECT_EQ(s.layouts.procedural.first_seed, 0u);
  EXPECT_EQ(s.layouts.procedural.rooms_min, 1);
  EXPECT_EQ(s.layouts.procedural.rooms_max, 8);
  EXPECT_EQ(s.layouts.procedural.furniture, "catalog");
  EXPECT_TRUE(s.layouts.folders.empty());
  EXPECT_TRUE(s.layouts.front3d.empty());
  EXPECT_EQ(s.splits.train, 0.8);
  EXPECT_EQ(s.splits.validation, 0.1);
  EXPECT_EQ(s.splits.test, 0.1);
  EXPECT_EQ(s.sequences.per_layout, 1);
  EXPECT_EQ(s.sequences.frames, 1000);
  EXPECT_EQ(s.sequences.fps, 25.0);
  EXPECT_EQ(s.sequences.unit_frames, 100);
  EXPECT_EQ(s.sequences.trajectory, TrajectoryMix{});
  EXPECT_EQ(s.sequences.trajectory.hand_held, 1.0);
  // what `generate` draws today (trajectory/random_trajectory.cpp)
  EXPECT_EQ(s.sequences.v_mult_min, 0.5);
  EXPECT_EQ(s.sequences.v_mult_max, 5.0);
  EXPECT_EQ(s.sequences.w_mult_min, 0.5);
  EXPECT_EQ(s.sequences.w_mult_max, 3.0);
  ASSERT_EQ(s.sequences.configurations.size(), 1u);
  EXPECT_EQ(s.sequences.configurations[0].text(), "original");
  EXPECT_EQ(s.sparse.per_layout, 1);
  ASSERT_EQ(s.sparse.configurations.size(), 3u);
  EXPECT_EQ(s.sparse.configurations[1].text(), "lighting");
  EXPECT_TRUE(s.sparse.configurations[1].derived);
  EXPECT_EQ(s.sparse.configurations[2].text(), "rearranged");
  EXPECT_EQ(s.sparse.batch, 64);
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.camera.height, 480);
  EXPECT_EQ(s.camera.fx, 600.0);
  EXPECT_EQ(s.camera.fy, 600.0);
  EXPECT_EQ(s.camera.lens, "pinhole");
  EXPECT_EQ(s.camera.stereo, 0.0);
  EXPECT_EQ(s.render.spp, 16);
  EXPECT_TRUE(s.render.denoise);
  EXPECT_EQ(s.render.max_bounces, 8);
  EXPECT_EQ(s.passes, std::vector<std::string>{"default"});
  EXPECT_EQ(s.imu, 800.0);
  EXPECT_EQ(s.formats, (std::vector<std::string>{"asl", "tum"}));
  // today's writer: EXR zip (core/image_io.cpp), PNG zlib level 1, flow as .flo and KITTI png
  EXPECT_EQ(s.storage.exr_compression, "zip");
  EXPECT_EQ(s.storage.png_level, 1);
  EXPECT_EQ(s.storage.flow, "both");
  EXPECT_FALSE(s.shards.enabled);  // WebDataset shards only when asked for
  EXPECT_EQ(s.shards.max_mb, 1024.0);
  EXPECT_EQ(s.shards.passes, std::vector<std::string>{"all"});
  EXPECT_EQ(s.file, kFile);
  EXPECT_EQ(s.checksum, specChecksum(kMinimal));
}

TEST(DatasetSpec, UnknownKeyNamesFileFieldLineAndValidKeys) {
  const InputError e = errorOf(kMinimal + "sequences:\n  frames: 10\n  framez: 3\n");
  EXPECT_EQ(e.file(), kFile);
  EXPECT_EQ(e.field(), "sequences.framez (line 6)");
  EXPECT_NE(e.problem().find("unknown key 'framez'"), std::string::npos) << e.what();
  EXPECT_NE(e.problem().find("valid: per_layout, frames, fps"), std::string::npos) << e.what();

  const InputError top = errorOf(kMinimal + "colour: red\n");
  EXPECT_EQ(top.field(), "colour (line 4)");
  EXPECT_NE(top.problem().find("version, name, seed, layouts"), std::string::npos);
}

TEST(DatasetSpec, WrongTypesAreErrors) {
  InputError e = errorOf(kMinimal + "sequences:\n  frames: many\n");
  EXPECT_EQ(e.field(), "sequences.frames (line 5)");
  EXPECT_NE(e.problem().find("expected an integer"), std::string::npos) << e.what();

  // a quoted number is text, in YAML as in JSON
  e = errorOf(kMinimal + "sequences: {frames: \"12\"}\n");
  EXPECT_EQ(e.field(), "sequences.frames (line 4)");

  e = errorOf(kMinimal + "sequences:\n  frames: 12.5\n");
  EXPECT_EQ(e.field(), "sequences.frames (line 5)");

  e = errorOf(kMinimal + "camera: [640, 480]\n");
  EXPECT_EQ(e.field(), "camera (line 4)");
  EXPECT_NE(e.problem().find("expected a map"), std::string::npos) << e.what();

  e = errorOf(kMinimal + "render:\n  denoise: yes\n");
  EXPECT_EQ(e.field(), "render.denoise (line 5)");

  e = errorOf(kMinimal + "passes: default\n");
  EXPECT_EQ(e.field(), "passes (line 4)");
  EXPECT_NE(e.problem().find("expected a list"), std::string::npos) << e.what();

  // an empty value is nothing, not 0
  e = errorOf(kMinimal + "seed:\n");
  EXPECT_EQ(e.field(), "seed (line 4)");
}

TEST(DatasetSpec, OutOfRangeValuesAreErrors) {
  InputError e = errorOf(kMinimal + "sequences: {frames: 0}\n");
  EXPECT_EQ(e.field(), "sequences.frames (line 4)");
  EXPECT_NE(e.problem().find("outside 1..10000000"), std::string::npos) << e.what();
  e = errorOf(kMinimal + "sequences: {fps: 0}\n");
  EXPECT_EQ(e.field(), "sequences.fps (line 4)");
  e = errorOf(kMinimal + "sequences: {v_mult: [0.5, 200]}\n");
  EXPECT_EQ(e.field(), "sequences.v_mult[1] (line 4)");
  e = errorOf(kMinimal + "sparse: {per_layout: 2}\n");
  EXPECT_EQ(e.field(), "sparse.per_layout (line 4)");
  e = errorOf(kMinimal + "storage: {png_level: 10}\n");
  EXPECT_EQ(e.field(), "storage.png_level (line 4)");
  e = errorOf(kMinimal + "storage: {exr_compression: dwaa}\n");
  EXPECT_EQ(e.field(), "storage.exr_compression (line 4)");
  EXPECT_NE(e.problem().find("none, rle, zips, zip, piz"), std::string::npos) << e.what();
  e = errorOf(kMinimal + "storage: {flow: kitti+jpeg}\n");
  EXPECT_EQ(e.field(), "storage.flow (line 4)");
  e = errorOf(kMinimal + "storage: {rgb_exr: double}\n");
  EXPECT_EQ(e.field(), "storage.rgb_exr (line 4)");
  EXPECT_EQ(parse(kMinimal + "storage: {flow: exr+kitti, rgb_exr: half}\n").storage.flow,
            "exr+kitti");
  e = errorOf(kMinimal + "seed: -1\n");
  EXPECT_EQ(e.field(), "seed (line 4)");
  e = errorOf(kMinimal + "seed: 18446744073709551616\n");  // 2^64
  EXPECT_EQ(e.field(), "seed (line 4)");
  EXPECT_EQ(parse(kMinimal + "seed: 18446744073709551615\n").seed, UINT64_MAX);
}

TEST(DatasetSpec, VersionIsRequiredAndChecked) {
  InputError e = errorOf("version: 2\nname: x\nlayouts: {procedural: {count: 1}}\n");
  EXPECT_EQ(e.file(), kFile);
  EXPECT_EQ(e.field(), "version (line 1)");
  EXPECT_NE(e.problem().find("version 2 is not supported"), std::string::npos) << e.what();
  // a newer version's keys are not reported before its version
  e = errorOf("name: x\nfuture_key: 1\nversion: 3\n");
  EXPECT_EQ(e.field(), "version (line 3)");

  e = errorOf("name: x\nlayouts: {procedural: {count: 1}}\n");
  EXPECT_EQ(e.field(), "version");
  EXPECT_NE(e.problem().find("missing"), std::string::npos) << e.what();
  e = errorOf("version: one\nname: x\nlayouts: {procedural: {count: 1}}\n");
  EXPECT_EQ(e.field(), "version (line 1)");
}

TEST(DatasetSpec, RequiredKeysAndLayouts) {
  EXPECT_EQ(errorOf("version: 1\nlayouts: {procedural: {count: 1}}\n").field(), "name");
  EXPECT_EQ(errorOf("version: 1\nname: x\n").field(), "layouts");
  const InputError e = errorOf("version: 1\nname: x\nlayouts:\n  procedural: {count: 0}\n");
  EXPECT_EQ(e.field(), "layouts (line 4)");
  EXPECT_NE(e.problem().find("no layout"), std::string::npos) << e.what();
  EXPECT_EQ(errorOf("version: 1\nname: a/b\nlayouts: {procedural: {count: 1}}\n").field(),
            "name (line 2)");
  EXPECT_EQ(errorOf("version: 1\nname: ..\nlayouts: {procedural: {count: 1}}\n").field(),
            "name (line 2)");
}

TEST(DatasetSpec, SplitsMustSumToOne) {
  const InputError e =
      errorOf(kMinimal + "splits:\n  train: 0.7\n  validation: 0.1\n  test: 0.1\n");
  EXPECT_EQ(e.file(), kFile);
  EXPECT_EQ(e.field(), "splits (line 5)");
  EXPECT_NE(e.problem().find("sum to 1, got 0.9"), std::string::npos) << e.what();
  // 0.7 + 0.2 + 0.1 is 0.9999999999999999 in doubles: within 1e-9
  const DatasetSpec s = parse(kMinimal + "splits: {train: 0.7, validation: 0.2, test: 0.1}\n");
  EXPECT_EQ(s.splits.validation, 0.2);
  EXPECT_EQ(errorOf(kMinimal + "splits: {train: 1.5, validation: -0.5, test: 0}\n").field(),
            "splits.train (line 4)");
}

TEST(DatasetSpec, BadConfigurationStringsAreErrors) {
  InputError e = errorOf(kMinimal + "sequences:\n  configurations: [original, \"lighting:x\"]\n");
  EXPECT_EQ(e.field(), "sequences.configurations[1] (line 5)");
  EXPECT_NE(e.problem().find("seed 0..999999999"), std::string::npos) << e.what();
  e = errorOf(kMinimal + "sparse:\n  configurations:\n    - original\n    - sunset\n");
  EXPECT_EQ(e.field(), "sparse.configurations[1] (line 7)");
  EXPECT_NE(e.problem().find("not original, lighting[:N] or rearranged[:N]"), std::string::npos);
  e = errorOf(kMinimal + "sequences: {configurations: [original, original]}\n");
  EXPECT_EQ(e.field(), "sequences.configurations[1] (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "sequences: {configurations: []}\n").field(),
            "sequences.configurations (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "sequences: {configurations: [\"original:1\"]}\n").field(),
            "sequences.configurations[0] (line 4)");

  const DatasetSpec s =
      parse(kMinimal + "sequences: {configurations: [original, lighting:12, rearranged]}\n");
  ASSERT_EQ(s.sequences.configurations.size(), 3u);
  EXPECT_EQ(s.sequences.configurations[1].kind, SceneConfiguration::Kind::Lighting);
  EXPECT_EQ(s.sequences.configurations[1].seed, 12u);
  EXPECT_FALSE(s.sequences.configurations[1].derived);
  EXPECT_TRUE(s.sequences.configurations[2].derived);
}

TEST(DatasetSpec, RoomRangeMinAboveMaxIsAnError) {
  InputError e =
      errorOf("version: 1\nname: x\nlayouts:\n  procedural:\n    count: 5\n    rooms: [6, 2]\n");
  EXPECT_EQ(e.field(), "layouts.procedural.rooms (line 6)");
  EXPECT_NE(e.problem().find("minimum 6 is above the maximum 2"), std::string::npos) << e.what();
  e = errorOf("version: 1\nname: x\nlayouts:\n  procedural:\n    count: 5\n    rooms: [1, 17]\n");
  EXPECT_EQ(e.field(), "layouts.procedural.rooms[1] (line 6)");
  e = errorOf("version: 1\nname: x\nlayouts:\n  procedural:\n    count: 5\n    rooms: [3]\n");
  EXPECT_EQ(e.field(), "layouts.procedural.rooms (line 6)");
  EXPECT_EQ(parse("version: 1\nname: x\nlayouts: {procedural: {count: 5, rooms: [4, 4]}}\n")
                .layouts.procedural.rooms_max,
            4);
}

TEST(DatasetSpec, DuplicateKeysAndSyntaxErrorsAreLocated) {
  InputError e = errorOf(kMinimal + "seed: 1\nseed: 2\n");
  EXPECT_EQ(e.field(), "seed (line 5)");
  EXPECT_NE(e.problem().find("twice"), std::string::npos) << e.what();
  e = errorOf("version: 1\nname: [x\nlayouts: 3\n");
  EXPECT_EQ(e.file(), kFile);
  EXPECT_EQ(e.field().rfind("line ", 0), 0u) << e.field();
  EXPECT_NE(e.problem().find("not valid YAML or JSON"), std::string::npos) << e.what();
  e = errorOf("");
  EXPECT_NE(e.problem().find("empty"), std::string::npos) << e.what();
  e = errorOf("- a\n- b\n");
  EXPECT_NE(e.problem().find("expected a map"), std::string::npos) << e.what();
}

TEST(DatasetSpec, CameraLensRules) {
  DatasetSpec s = parse(kMinimal + "camera: {lens: fisheye}\n");
  EXPECT_EQ(s.camera.width, 600);
  EXPECT_EQ(s.camera.height, 600);
  EXPECT_EQ(s.camera.fx, 0.0);
  s = parse(kMinimal + "camera: {lens: panorama, width: 1000}\n");
  EXPECT_EQ(s.camera.height, 500);
  EXPECT_EQ(errorOf(kMinimal + "camera: {lens: fisheye, fx: 300}\n").field(), "camera.fx (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "camera: {lens: panorama, width: 1000, height: 400}\n").field(),
            "camera.height (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "camera: {lens: thin_lens}\n").field(), "camera.lens (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "camera: {lens: tele}\n").field(), "camera.lens (line 4)");
}

TEST(DatasetSpec, PassesAndFormats) {
  const DatasetSpec s = parse(kMinimal + "passes: [rgb, depth, imu, flow_bwd]\n");
  EXPECT_EQ(s.passes.size(), 4u);
  InputError e = errorOf(kMinimal + "passes: [rgb, colour]\n");
  EXPECT_EQ(e.field(), "passes[1] (line 4)");
  EXPECT_NE(e.problem().find("depth_noisy"), std::string::npos) << e.what();
  EXPECT_EQ(errorOf(kMinimal + "camera: {lens: fisheye}\npasses: [rgb, events]\n").field(),
            "passes[1] (line 5)");
  EXPECT_EQ(errorOf(kMinimal + "passes: [rgb, rgb]\n").field(), "passes[1] (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "formats: [asl, kitti]\n").field(), "formats[1] (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "formats: []\n").field(), "formats (line 4)");
  // TUM folders need colour and z-depth: said at the spec, not in every unit of a build
  InputError tum = errorOf(kMinimal + "passes: [depth, label]\n");
  EXPECT_EQ(tum.field(), "passes (line 4)");
  EXPECT_NE(tum.problem().find("format 'tum'"), std::string::npos) << tum.what();
  EXPECT_EQ(errorOf(kMinimal + "passes: [rgb, label]\nformats: [tum]\n").field(),
            "formats (line 5)");
  EXPECT_EQ(parse(kMinimal + "passes: [depth, label]\nformats: [asl]\n").formats.size(), 1u);
}

TEST(DatasetSpec, Shards) {
  const DatasetSpec s =
      parse(kMinimal + "shards: {enabled: true, max_mb: 0.05, passes: [cam0, depth0.exr]}\n");
  EXPECT_TRUE(s.shards.enabled);
  EXPECT_EQ(s.shards.max_mb, 0.05);
  EXPECT_EQ(s.shards.passes, (std::vector<std::string>{"cam0", "depth0.exr"}));
  EXPECT_EQ(parse(kMinimal + "shards: {enabled: true}\n").shards.passes,
            std::vector<std::string>{"all"});
  InputError e = errorOf(kMinimal + "shards: {enable: true}\n");
  EXPECT_EQ(e.field(), "shards.enable (line 4)");
  EXPECT_NE(e.problem().find("enabled, max_mb, passes"), std::string::npos) << e.what();
  EXPECT_EQ(errorOf(kMinimal + "shards: {enabled: yes}\n").field(), "shards.enabled (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "shards: {max_mb: 0}\n").field(), "shards.max_mb (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "shards: {max_mb: \"64\"}\n").field(), "shards.max_mb (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "shards:\n  passes: [cam0, cam0]\n").field(),
            "shards.passes[1] (line 5)");
  EXPECT_EQ(errorOf(kMinimal + "shards: {passes: [cam0/x]}\n").field(),
            "shards.passes[0] (line 4)");
  EXPECT_EQ(errorOf(kMinimal + "shards: {passes: []}\n").field(), "shards.passes (line 4)");
  e = errorOf(kMinimal + "shards: {passes: [all, cam0]}\n");
  EXPECT_EQ(e.field(), "shards.passes (line 4)");
  EXPECT_NE(e.problem().find("'all' stands alone"), std::string::npos) << e.what();
}

TEST(DatasetSpec, JsonSpecReadsAsItsYaml) {
  const std::string json = R"({
  "version": 1, "name": "tiny", "seed": 5,
  "layouts": {"procedural": {"count": 3, "rooms": [2, 4]}},
  "sequences": {"frames": 40, "configurations": ["original", "lighting:2"]},
  "splits": {"train": 0.5, "validation": 0.25, "test": 0.25}
})";
  const std::string yaml = R"(version: 1
name: tiny
seed: 5
layouts:
  procedural: {count: 3, rooms: [2, 4]}
sequences:
  frames: 40
  configurations: [original, "lighting:2"]
splits: {train: 0.5, validation: 0.25, test: 0.25}
)";
  EXPECT_EQ(parse(json), parse(yaml));
  EXPECT_EQ(parse(json).sequences.frames, 40);
  const InputError e = errorOf(R"({"version": 1, "name": "x",
  "layouts": {"procedural": {"count": "3"}}})");
  EXPECT_EQ(e.field(), "layouts.procedural.count (line 2)");
}

TEST(DatasetSpec, EffectiveSpecJsonParsesBackEqual) {
  const DatasetSpec s = parse(R"(version: 1
name: round-trip_1
seed: 18446744073709551615
layouts:
  procedural: {count: 7, first_seed: 40, rooms: [3, 9], furniture: mixed}
  folders: [layouts, ../shared/more]
  front3d: [houses/a.json]
splits: {train: 0.7, validation: 0.2, test: 0.1}
sequences:
  per_layout: 3
  frames: 77
  fps: 30.5
  unit_frames: 10
  trajectory: {two-body: 0, hand-held: 2.5, look-forward: 1}
  v_mult: [0.7, 0.7]
  w_mult: [0.1, 2]
  configurations: [original, "rearranged:4", lighting]
sparse: {per_layout: 0, configurations: ["lighting:3"], batch: 5}
camera: {lens: panorama, width: 800, stereo: 0.12}
render: {spp: 4, denoise: false, max_bounces: 3}
passes: [rgb, depth, imu, boxes]
imu: 200.5
formats: [tum]
storage: {exr_compression: piz, png_level: 6, flow: kitti, rgb_exr: half}
shards: {enabled: true, max_mb: 2.5, passes: [cam0, label0_nyu, depth0.exr]}
)");
  EXPECT_EQ(s.layouts.folders[1].resolved, std::filesystem::path("/shared/more"));
  EXPECT_EQ(s.layouts.front3d[0].resolved, std::filesystem::path("/specs/houses/a.json"));
  const std::string text = specToJson(s).dump(2);
  const DatasetSpec back = parseDatasetSpecText(text, kFile);
  EXPECT_EQ(back, s) << text;
  EXPECT_EQ(specToJson(back).dump(2), text);
  EXPECT_FALSE(back == parse(kMinimal));
}

TEST(DatasetSpec, RelativePathsAreRelativeToTheSpecFile) {
  test::TempDir dir("dataset_spec");
  const std::string file = dir.write("specs/d.yaml",
                                     "version: 1\nname: d\nlayouts:\n  folders: [../layouts]\n"
                                     "  front3d: [/abs/house.json]\n");
  const DatasetSpec s = parseDatasetSpec(file);
  ASSERT_EQ(s.layouts.folders.size(), 1u);
  EXPECT_EQ(s.layouts.folders[0].given, "../layouts");
  EXPECT_EQ(s.layouts.folders[0].resolved, dir.path() / "layouts");
  EXPECT_EQ(s.layouts.folders[0].field, "layouts.folders[0] (line 4)");
  EXPECT_EQ(s.layouts.front3d[0].resolved, std::filesystem::path("/abs/house.json"));
  EXPECT_EQ(expectInputError([&] { parseDatasetSpec(dir / "missing.yaml"); }).file(),
            (dir / "missing.yaml").string());
}

TEST(DatasetSpec, ChecksumFollowsTheText) {
  const DatasetSpec a = parse(kMinimal);
  const DatasetSpec b = parse(kMinimal + "# a comment\n");
  EXPECT_EQ(a, b);  // same content
  EXPECT_NE(a.checksum, b.checksum);
  EXPECT_EQ(a.checksum.size(), 16u);
}

TEST(DatasetSpec, StableHashNeverChanges) {
  // Splits and every draw of a plan are keyed by this hash: these values must hold forever.
  // (values from an independent Python implementation of FNV-1a + splitmix64's finaliser)
  EXPECT_EQ(stableHash64(""), 0xf52a15e9a9b5e89bull);
  EXPECT_EQ(stableHash64("procedural:0"), 0xdb19fd064f1068ffull);
  EXPECT_NE(stableHash64("procedural:0"), stableHash64("procedural:1"));
  // the finaliser makes neighbouring ids differ in about half their bits
  const int bits =
      __builtin_popcountll(stableHash64("procedural:10") ^ stableHash64("procedural:11"));
  EXPECT_GT(bits, 16);
  EXPECT_LT(bits, 48);
}

TEST(DatasetSpec, TheDocumentedExampleParses) {
  const std::filesystem::path file =
      std::filesystem::path(INET_SOURCE_DIR) / "docs" / "examples" / "dataset.yaml";
  const DatasetSpec s = parseDatasetSpec(file);
  EXPECT_EQ(s.name, "example");
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.layouts.procedural.count, 20);
  EXPECT_EQ(s.layouts.procedural.first_seed, 1000u);
  EXPECT_EQ(s.sequences.frames, 300);
  EXPECT_EQ(s.sequences.trajectory.hand_held, 2.0);
  ASSERT_EQ(s.sequences.configurations.size(), 3u);
  EXPECT_EQ(s.sequences.configurations[1].text(), "lighting:1");
  EXPECT_TRUE(s.sequences.configurations[2].derived);
  // every other value the example shows is the default
  DatasetSpec d = parse(kMinimal);
  d.name = s.name;
  d.seed = s.seed;
  d.layouts = s.layouts;
  d.sequences.frames = s.sequences.frames;
  d.sequences.trajectory = s.sequences.trajectory;
  d.sequences.configurations = s.sequences.configurations;
  EXPECT_EQ(s, d);
}

}  // namespace
}  // namespace inet
