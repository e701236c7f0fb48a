#pragma once
// Running one work unit of a dataset plan (dataset_plan.h) through the sequence pipeline
// (pipeline/sequence_job.h), and the checksums of what it wrote.
//
// A build folder holds:
//   plan.json                 the plan (`dataset plan`)
//   state.sqlite              the job state (build_state.h), written by the coordinator only
//   data/<split>/<subset>/<layout>/<sequence>[_lighting_N|_rearranged_N]/   ASL/TUM folders
//   data/<split>/<subset>/<layout>/sparse[...]/                             the sparse views
// where <layout> is layoutFolderName(layout id).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "builder/dataset_plan.h"
#include "pipeline/sequence_job.h"

namespace inet {

/// A layout id as a folder name: "procedural:12" -> "procedural_12", "file:homes/a.json" ->
/// "file_homes_a" (every character but letters, digits, '-' and '_' becomes '_').
std::string layoutFolderName(const std::string& layout_id);
/// The folder of a layout's sequences below the build folder's data/.
std::filesystem::path layoutFolder(const PlannedLayout& layout);

/// The sequence jobs of a unit: one for a sequence unit (its frame range, in its
/// configuration), one per layout for a sparse batch (one frame of a random trajectory drawn
/// from the layout's view seed, in every sparse configuration). `data` is the build's data/.
std::vector<SequenceJob> jobsOf(const DatasetPlan& plan, const WorkUnit& unit,
                                const std::filesystem::path& data);

/// The manifest rows of a unit: one JSON object per line, per frame (sparse: per view), in
/// frame order: split, subset, layout, configuration, sequence, folder, trajectory, v_mult,
/// w_mult, frame, t_ns and files {pass key: path relative to the build folder}. A pass key is
/// the file's folder in the sequence (cam0, depth0, rgb, ...), with the name's suffix after
/// '_' (label0_nyu, label0_instance) and the extension when it is not .png (cam0.exr, flow0.flo).
/// With the instance pass, a row also has `assets`: the Sweet Home 3D catalog pieces the frame
/// shows ({id, name, creator, license}, in id order; [] for parametric furniture).
/// Written by runUnit to manifest/units/<order, 8 digits>.jsonl; `dataset build` joins them
/// into manifest.jsonl in plan order when every unit is done.
std::filesystem::path unitManifestPath(const std::filesystem::path& root, int64_t order);

/// What a unit wrote: its files (relative to the build folder) with their checksums.
struct UnitOutput {
  /// JSON object {"relative/path": "crc32:size"} in path order: what `dataset verify` checks.
  std::string checksums;
  int64_t files = 0;
  int64_t bytes = 0;
  bool finished_sequence = false;  ///< it also wrote its sequence's index files
  double setup_s = 0.0;      ///< in the pipeline before the first frame (scene, trajectory)
  double sequences_s = 0.0;  ///< in the pipeline rendering and writing frames
};

/// Runs every job of `unit` (the plan's unit number `order`) into `root`/data (resumable: what
/// is done is skipped), writes its manifest rows, and returns the checksums of the files it is
/// answerable for, its manifest file included. Throws what runSequenceJob throws.
UnitOutput runUnit(const DatasetPlan& plan, const WorkUnit& unit, int64_t order,
                   const std::filesystem::path& root);

/// "crc32:size" of a file (zlib's CRC-32, lower-case hex, 8 digits); InputError if unreadable.
std::string fileChecksum(const std::filesystem::path& file);

}  // namespace inet
