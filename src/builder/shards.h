#pragma once
// WebDataset tar shards of a built dataset (issue 16, docs/dataset.md "WebDataset shards"):
// every frame of manifest.jsonl as one sample, in size-bounded tar files per split, with a
// shard index that webdataset's `wids` reads.
//
//   DIR/shards/train/train-000000.tar, train-000001.tar, ...
//   DIR/shards/train.json          {"__kind__": "wids-shard-index-v1", "wids_version": 1, ...}
//   DIR/shards/validation/..., DIR/shards/test/...
//
// A sample's key is "<layout folder>/<sequence folder>/<frame, at least 6 digits>", e.g.
// "procedural_12/seq_000_lighting_5/000042": the last two components of the row's folder,
// which name the frame's sequence and configuration uniquely within a split, with no dot,
// because WebDataset and wids split a member name at the first dot of its last path
// component. The key mirrors data/, so unpacking a shard gives a browsable tree. Members, in
// this order: <key>.json (the manifest row, its bytes as in manifest.jsonl) and
// <key>.<pass key> for each selected file of the row, in the row's order, with the file's
// extension appended when the pass key has none (key.cam0.png, key.depth0.exr,
// key.flow0.flo), so that loaders decode by the last extension.
//
// Shard membership is a function of the manifest and the files alone: samples in manifest
// order; a shard closes before a sample that would take its tar bytes (headers and the
// 1024-byte end marker included) over max_bytes; a sample larger than the bound is a shard
// alone. The tar is POSIX pax (libarchive's restricted pax: plain ustar headers unless a name
// needs more) with mtime 0, uid/gid 0, empty user and group names and mode 0644, unpadded
// after the end marker, so the same build gives the same bytes.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "builder/dataset_spec.h"

namespace inet {

struct ShardOptions {
  std::string name = "dataset";       ///< the index's name is "<name>-<split>" (wids' cache folder)
  int64_t max_bytes = 1'024'000'000;  ///< a shard's bound in tar bytes, >= 1
  /// Pass keys of the manifest's "files" to include (cam0, depth0.exr, label0_nyu, ...), or
  /// {"all"}. A key that no row has is an error that lists the keys there are.
  std::vector<std::string> passes = {"all"};
  bool progress = false;  ///< a progress bar over the samples on stderr
};

/// The options a spec's `shards` key gives (max_mb x 10^6 bytes, its passes, the spec's name).
ShardOptions shardOptions(const DatasetSpec& spec);

/// One shard as its index records it.
struct ShardRecord {
  std::string url;  ///< relative to the index file's folder: "train/train-000000.tar"
  int64_t samples = 0;
  int64_t bytes = 0;
  uint32_t crc32 = 0;  ///< zlib's CRC-32 of the whole file
  std::string first_key, last_key;
  bool reused = false;  ///< the file already held these bytes and was not rewritten
};

struct ShardReport {
  std::map<std::string, std::vector<ShardRecord>> splits;  ///< split name -> its shards
  int64_t samples = 0;
  int64_t bytes = 0;          ///< of every shard
  int64_t bytes_written = 0;  ///< of the shards written now (not reused)
  double seconds = 0.0;
};

/// Writes DIR/shards/ from DIR/manifest.jsonl and the files it lists. Everything is checked
/// before the first shard is written: InputError naming DIR when manifest.jsonl is missing
/// (the build is not complete), naming the manifest line for a malformed row, a key with a
/// dot or a listed file that is missing, and naming the option for an unknown pass key.
/// Then the old indexes are removed, each shard is written atomically (a temporary renamed
/// into place), and each split's index last, so an index always describes whole shards. A
/// shard whose index entry from an earlier run records the size and CRC-32 of exactly the
/// bytes it would get, and whose file still has them, is not rewritten. Shards numbered past
/// a split's new count, and the shards and index of a split left empty, are removed. A stop
/// signal (core/stop.h) throws StopRequested between samples.
ShardReport writeShards(const std::filesystem::path& dir, const ShardOptions& opt);

/// The sample key of a manifest row: "<folder's last two components>/<frame, 6+ digits>".
/// Throws InputError(file, field) when the folder has fewer than two components or the key
/// would hold a dot, a non-ASCII byte or another character outside [A-Za-z0-9_-/].
std::string shardSampleKey(const std::string& folder, int64_t frame, const std::string& file,
                           const std::string& field);

/// The member name of a frame file: "<key>.<pass key>", plus the file's extension when the
/// pass key has no dot ("k.cam0.png"; "k.depth0.exr" stays).
std::string shardMemberName(const std::string& key, const std::string& pass_key,
                            const std::string& file);

/// The bytes a regular file named `name` of `size` bytes takes in our tar: the 512-byte
/// header, the data padded to 512, and, when the name does not fit a ustar header (over 100
/// characters and no split at a '/' into <= 155 + <= 100) or the size needs more than 33 bits,
/// the pax extended header libarchive writes before it (512 + its records padded to 512).
int64_t tarMemberBytes(const std::string& name, int64_t size);

}  // namespace inet
