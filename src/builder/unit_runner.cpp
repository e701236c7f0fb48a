#include "builder/unit_runner.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/text.h"

namespace inet {

namespace fs = std::filesystem;

std::string layoutFolderName(const std::string& layout_id) {
  size_t n = layout_id.size();
  if (n > 5 && layout_id.compare(n - 5, 5, ".json") == 0) n -= 5;
  std::string id;
  id.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const char c = layout_id[i];
    id.push_back(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_');
  }
  return id;
}

fs::path layoutFolder(const PlannedLayout& layout) {
  return fs::path(splitName(layout.split)) / layout.subset / layoutFolderName(layout.id);
}

namespace {

/// What every job of the plan shares: the scene source, camera, render settings, passes.
SequenceJob baseJob(const DatasetPlan& plan, const PlannedLayout& layout, const fs::path& data) {
  const DatasetSpec& spec = plan.spec;
  SequenceJob job;
  if (layout.kind == LayoutKind::Procedural) {
    job.scene.path = fmt::format("procedural:{}", layout.seed);
    job.scene.rooms = layout.rooms;
    job.scene.furniture = spec.layouts.procedural.furniture;
  } else {
    job.scene.path = layout.path;
  }
  job.out = data.string();
  job.folder = layoutFolder(layout).string();
  job.lens.lens = spec.camera.lens;
  job.K.width = spec.camera.width;
  job.K.height = spec.camera.height;
  job.width_set = job.height_set = true;
  if (spec.camera.lens == "pinhole" || spec.camera.lens == "thin_lens") {
    job.K.fx = spec.camera.fx;
    job.K.fy = spec.camera.fy;
    job.fx_set = job.fy_set = true;
  }
  job.stereo = spec.camera.stereo;
  job.spp = spec.render.spp;
  job.denoise = spec.render.denoise;
  job.max_bounces = spec.render.max_bounces;
  job.passes = joinCommaList(spec.passes);
  job.formats = joinCommaList(spec.formats);
  job.imu_rate = spec.imu;
  job.storage.png_level = spec.storage.png_level;
  job.storage.exr = parseExrCompression(spec.storage.exr_compression, spec.file,
                                        "storage.exr_compression");
  parseFlowFiles(spec.storage.flow, job.storage, spec.file, "storage.flow");
  job.hdr = spec.storage.rgb_exr != "none";
  job.storage.rgb_exr_half = spec.storage.rgb_exr == "half";
  job.progress = false;
  return job;
}

}  // namespace

std::vector<SequenceJob> jobsOf(const DatasetPlan& plan, const WorkUnit& unit,
                                const fs::path& data) {
  const DatasetSpec& spec = plan.spec;
  std::vector<SequenceJob> jobs;
  if (unit.kind == UnitKind::Sequence) {
    const PlannedLayout& layout = plan.layouts.at(static_cast<size_t>(unit.layout));
    const PlannedSequence& seq = layout.sequences.at(static_cast<size_t>(unit.sequence));
    SequenceJob job = baseJob(plan, layout, data);
    job.trajectory = seq.trajectory;
    job.motion.v_mult = seq.v_mult;
    job.motion.w_mult = seq.w_mult;
    job.seed = seq.seed;
    job.frames = spec.sequences.frames;
    job.fps = spec.sequences.fps;
    job.sequence = seq.name;
    job.config = configurationName(
        spec.sequences.configurations.at(static_cast<size_t>(unit.configuration)), layout);
    job.frame_begin = static_cast<size_t>(unit.frame_begin);
    job.frame_end = static_cast<size_t>(unit.frame_end);
    // the other ranges of the sequence may be in flight on other ranks
    job.shared_folder = true;
    jobs.push_back(std::move(job));
    return jobs;
  }
  for (int i = 0; i < unit.layout_count; ++i) {
    const PlannedLayout& layout = plan.layouts.at(static_cast<size_t>(unit.layout + i));
    SequenceJob job = baseJob(plan, layout, data);
    // one view: the first pose of a random trajectory of the view seed, in every configuration
    job.trajectory = "two-body";
    job.seed = layout.view_seed;
    job.frames = 1;
    job.fps = spec.sequences.fps;
    job.imu_rate = 0;
    job.sequence = "sparse";
    std::vector<std::string> configs, passes;
    for (const SceneConfiguration& c : spec.sparse.configurations)
      configs.push_back(configurationName(c, layout));
    job.config = joinCommaList(configs);
    // a single view has no motion: no events
    for (const std::string& p : spec.passes)
      if (p != "events") passes.push_back(p);
    job.passes = joinCommaList(passes);
    jobs.push_back(std::move(job));
  }
  return jobs;
}

std::string fileChecksum(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot read it");
  uLong crc = crc32(0L, Z_NULL, 0);
  std::vector<char> buf(1 << 16);
  uint64_t size = 0;
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize n = in.gcount();
    if (n <= 0) break;
    crc = crc32(crc, reinterpret_cast<const Bytef*>(buf.data()), static_cast<uInt>(n));
    size += static_cast<uint64_t>(n);
  }
  return fmt::format("{:08x}:{}", static_cast<uint32_t>(crc), size);
}

fs::path unitManifestPath(const fs::path& root, int64_t order) {
  return root / "manifest" / "units" / fmt::format("{:08d}.jsonl", order);
}

namespace {

/// The manifest key of a frame file at `rel` (relative to its sequence folder).
std::string passKey(const fs::path& rel) {
  std::string key = rel.begin()->string();
  const std::string stem = rel.stem().string();
  const size_t us = stem.rfind('_');
  if (us != std::string::npos) key += stem.substr(us);
  if (rel.extension() != ".png") key += rel.extension().string();
  return key;
}

/// The credits of the catalog pieces an instance image shows, in piece-id order, each once.
nlohmann::ordered_json assetsInView(const ImageU16& instance,
                                    const std::map<int, AssetCredit>& credits) {
  std::vector<uint8_t> seen(65536, 0);
  for (uint16_t id : instance.data) seen[id] = 1;
  std::map<std::string, const AssetCredit*> shown;
  for (const auto& [id, credit] : credits)
    if (id >= 0 && id < 65536 && seen[static_cast<size_t>(id)]) shown[credit.id] = &credit;
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& [piece, c] : shown)
    out.push_back({{"id", c->id}, {"name", c->name}, {"creator", c->creator},
                   {"license", c->license}});
  return out;
}

}  // namespace

UnitOutput runUnit(const DatasetPlan& plan, const WorkUnit& unit, int64_t order,
                   const fs::path& root) {
  const fs::path data = root / "data";
  std::map<std::string, std::string> sums;  // ordered: the same text for the same files
  UnitOutput out;
  std::string manifest;
  const std::vector<SequenceJob> jobs = jobsOf(plan, unit, data);
  for (size_t j = 0; j < jobs.size(); ++j) {
    const SequenceJob& job = jobs[j];
    const SequenceJobResult r = runSequenceJob(job);
    out.setup_s += r.setup_s;
    out.sequences_s += r.sequences_s;
    const PlannedLayout& layout = plan.layouts.at(static_cast<size_t>(unit.layout) + j);
    const PlannedSequence* planned =
        unit.kind == UnitKind::Sequence
            ? &layout.sequences.at(static_cast<size_t>(unit.sequence))
            : nullptr;
    for (const auto& seq : r.sequences) {
      for (const auto& frame : seq.range) {
        nlohmann::ordered_json row;
        row["split"] = splitName(layout.split);
        row["subset"] = layout.subset;
        row["layout"] = layout.id;
        row["configuration"] = seq.configuration;
        row["sequence"] = job.sequence;
        row["folder"] = fs::path(seq.dir).lexically_relative(root).generic_string();
        row["trajectory"] = job.trajectory;
        if (planned) {
          row["v_mult"] = planned->v_mult;
          row["w_mult"] = planned->w_mult;
        }
        row["frame"] = frame.index;
        row["t_ns"] = frame.t_ns;
        nlohmann::ordered_json files = nlohmann::ordered_json::object();
        for (const std::string& f : frame.files)
          files[passKey(fs::path(f).lexically_relative(seq.dir))] =
              fs::path(f).lexically_relative(root).generic_string();
        row["files"] = std::move(files);
        // the catalog pieces in view, with their credits, where the instance image says
        for (const std::string& f : frame.files) {
          const fs::path rel = fs::path(f).lexically_relative(seq.dir);
          if (rel.begin()->string() != "label0" || !rel.string().ends_with("_instance.png"))
            continue;
          row["assets"] = assetsInView(readPng16(f), seq.assets);
        }
        manifest += row.dump() + "\n";
      }
      out.finished_sequence |= seq.finished && unit.kind == UnitKind::Sequence;
      for (const std::string& f : seq.files) {
        const std::string rel = fs::path(f).lexically_relative(root).generic_string();
        sums[rel] = fileChecksum(f);
        out.bytes += static_cast<int64_t>(fs::file_size(f));
      }
    }
  }
  const fs::path rows = unitManifestPath(root, order);
  writeTextAtomic(rows, manifest);
  sums[rows.lexically_relative(root).generic_string()] = fileChecksum(rows);
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [path, sum] : sums) j[path] = sum;
  out.checksums = j.dump();
  out.files = static_cast<int64_t>(sums.size());
  return out;
}

}  // namespace inet
