#include "builder/dataset_stats.h"

#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <numeric>
#include <set>
#include <string_view>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "builder/dataset_plan.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/plot.h"
#include "core/progress.h"
#include "trajectory/formats.h"

namespace inet {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

std::vector<int64_t> evenSample(int64_t n, int64_t k) {
  INET_CHECK(n >= 0 && k >= 1 && k <= 1000000000);
  std::vector<int64_t> out;
  if (k >= n) {
    out.resize(static_cast<size_t>(n));
    std::iota(out.begin(), out.end(), int64_t{0});
    return out;
  }
  // (2i + 1) n / 2k without overflow: with n = q 2k + r it is (2i + 1) q + (2i + 1) r / 2k,
  // and (2i + 1) r < (2k)^2 <= 4e18 fits int64.
  const int64_t d = 2 * k, q = n / d, r = n % d;
  out.reserve(static_cast<size_t>(k));
  for (int64_t i = 0; i < k; ++i) out.push_back((2 * i + 1) * q + (2 * i + 1) * r / d);
  return out;
}

std::vector<MotionStep> motionSteps(const Trajectory& traj) {
  std::vector<MotionStep> out;
  for (size_t k = 0; k + 1 < traj.size(); ++k) {
    const TimedPose& a = traj.poses[k];
    const TimedPose& b = traj.poses[k + 1];
    INET_CHECK_MSG(b.t_ns > a.t_ns, "trajectory times must increase");
    const double dt_s = static_cast<double>(b.t_ns - a.t_ns) * 1e-9;
    const Quat dq = (a.T_world_camera.q.conjugate() * b.T_world_camera.q).normalized();
    // atan2 keeps small angles accurate, where acos(w) loses them to rounding
    const double angle_rad = 2.0 * std::atan2(dq.vec().norm(), std::abs(dq.w()));
    out.push_back(
        {(b.T_world_camera.t - a.T_world_camera.t).norm() / dt_s, angle_rad * 180.0 / M_PI / dt_s});
  }
  return out;
}

FixedHistogram::FixedHistogram(double width, int bins)
    : bin_width(width), counts(static_cast<size_t>(bins), 0) {
  INET_CHECK(width > 0 && bins >= 1);
}

void FixedHistogram::add(double v) {
  INET_CHECK_MSG(std::isfinite(v) && v >= 0, fmt::format("histogram value {}", v));
  ++n;
  sum += v;
  max = std::max(max, v);
  const double bin = std::floor(v / bin_width);
  if (bin >= static_cast<double>(counts.size()))
    ++overflow;
  else
    ++counts[static_cast<size_t>(bin)];
}

double FixedHistogram::quantile(double p) const {
  if (n == 0) return 0.0;
  const auto rank =
      std::max<int64_t>(1, static_cast<int64_t>(std::ceil(p * static_cast<double>(n))));
  int64_t seen = 0;
  for (size_t k = 0; k < counts.size(); ++k)
    if ((seen += counts[k]) >= rank) return std::min(max, static_cast<double>(k + 1) * bin_width);
  return max;
}

namespace {

// How a manifest row names its NYU40 image: the key as nlohmann's dump() writes it. Both passes
// over the manifest find labelled rows by it, so they agree on which rows are labelled without
// the second pass parsing every row.
constexpr std::string_view kLabelKey = "\"label0_nyu\":";
// Items per parallel batch between two progress updates (and the most results held at once).
constexpr size_t kBatch = 64;
// Progress bars only for work that takes seconds; below these sizes a bar would only flash by.
constexpr int64_t kSlowManifestMb = 16, kSlowImages = 500, kSlowTrajectories = 500;

int splitIndex(const std::string& name, const fs::path& file, int64_t line) {
  for (int i = 0; i < 3; ++i)
    if (name == splitName(static_cast<Split>(i))) return i;
  throw InputError(file.string(), fmt::format("line {}", line),
                   "unknown split '" + name + "' (valid: train, validation, test)");
}

ojson parseRow(const std::string& line, const fs::path& file, int64_t line_no) {
  ojson row;
  try {
    row = ojson::parse(line);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string(), fmt::format("line {}", line_no),
                     std::string("not a JSON manifest row: ") + e.what());
  }
  if (!row.is_object())
    throw InputError(file.string(), fmt::format("line {}", line_no), "not a JSON object");
  return row;
}

const std::string& rowText(const ojson& row, const char* key, const fs::path& file,
                           int64_t line_no) {
  const auto it = row.find(key);
  if (it == row.end() || !it->is_string())
    throw InputError(file.string(), fmt::format("line {}", line_no),
                     fmt::format("manifest row without the text field '{}'", key));
  return it->get_ref<const std::string&>();
}

/// The manifest's files in row order: manifest.jsonl once the build is complete, else the
/// units' rows so far (their names are the 8-digit unit order, so name order is plan order).
std::vector<fs::path> manifestFiles(const fs::path& root, bool* complete) {
  std::error_code ec;
  *complete = fs::is_regular_file(root / "manifest.jsonl", ec);
  if (*complete) return {root / "manifest.jsonl"};
  std::vector<fs::path> files;
  const fs::path units = root / "manifest" / "units";
  if (!fs::is_directory(units, ec)) return files;
  for (const auto& e : fs::directory_iterator(units, ec))
    if (e.is_regular_file(ec) && e.path().extension() == ".jsonl" &&
        !isTemporaryName(e.path().filename().string()))
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// Calls f(file, line number, line) for each non-empty line of `files` in order until f
/// returns false; draws a progress bar over the bytes when `progress`.
void forEachLine(const std::vector<fs::path>& files, bool progress,
                 const std::function<bool(const fs::path&, int64_t, const std::string&)>& f) {
  constexpr int64_t kMb = 1 << 20;
  int64_t total = 0, done = 0;
  std::error_code ec;
  for (const fs::path& p : files) total += static_cast<int64_t>(fs::file_size(p, ec));
  ProgressBar bar((total + kMb - 1) / kMb, "MB of manifest",
                  progress && total >= kSlowManifestMb * kMb);
  std::string line;
  for (const fs::path& p : files) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw InputError(p.string(), "", "cannot read it");
    for (int64_t n = 1; std::getline(in, line); ++n) {
      done += static_cast<int64_t>(line.size()) + 1;
      if ((n & 4095) == 0) bar.update(done / kMb);
      if (!line.empty() && !f(p, n, line)) return;
    }
  }
  bar.update((total + kMb - 1) / kMb);
  bar.finish();
}

/// What the first pass over the manifest learns besides the counts.
struct ManifestScan {
  std::set<std::string> layouts;  ///< ids with at least one frame
  /// (layout id, sequence) -> its folder in the original configuration, else in the first
  /// configuration seen (a spec may list no original), and whether it is the original
  std::map<std::pair<std::string, std::string>, std::pair<std::string, bool>> folders;
};

/// The plan's side: rooms, planned layouts, sequences and frames, the sequences' draws.
void addPlanned(const DatasetPlan& plan, DatasetStats& s) {
  const SequencesSpec& q = plan.spec.sequences;
  s.v_mult_range = {q.v_mult_min, q.v_mult_max};
  s.w_mult_range = {q.w_mult_min, q.w_mult_max};
  s.fps = q.fps;
  for (const PlannedLayout& L : plan.layouts) ++s.layouts_per_rooms[L.rooms];
  const SplitStats st = splitStats(plan);
  auto copy = [](const SplitCount& c, SplitTally& t) {
    t.layouts = c.layouts;
    t.sequences = c.sequences;
    t.frames_planned = c.sequence_frames + c.sparse_views;
  };
  for (int i = 0; i < 3; ++i) copy(st.splits[i], s.splits[i]);
  for (const auto& [name, by] : st.subsets)
    for (int i = 0; i < 3; ++i) copy(by[i], s.subsets[name][i]);
  for (const PlannedLayout& L : plan.layouts)
    for (const PlannedSequence& q : L.sequences) {
      s.sequences.push_back({L.id, q.name, q.trajectory, q.v_mult, q.w_mult, "", 0, 0, 0});
      ++s.trajectories[q.trajectory].sequences;
    }
}

ManifestScan scanManifest(const DatasetPlan& plan, const std::vector<fs::path>& files,
                          bool progress, DatasetStats& s) {
  ManifestScan scan;
  forEachLine(files, progress, [&](const fs::path& file, int64_t n, const std::string& line) {
    const ojson row = parseRow(line, file, n);
    auto text = [&](const char* key) -> const std::string& { return rowText(row, key, file, n); };
    const int split = splitIndex(text("split"), file, n);
    const bool sparse = text("sequence") == "sparse";
    for (SplitTally* t : {&s.splits[split], &s.subsets[text("subset")][split]}) {
      ++t->frames;
      ++(sparse ? t->sparse_views : t->sequence_frames);
    }
    scan.layouts.insert(text("layout"));
    if (line.find(kLabelKey) != std::string::npos) ++s.labelled_frames;
    if (!sparse) {
      const bool original = text("configuration") == "original";
      auto [it, added] =
          scan.folders.try_emplace({text("layout"), text("sequence")}, text("folder"), original);
      if (!added && original && !it->second.second) it->second = {text("folder"), true};
    }
    return true;
  });
  for (const PlannedLayout& L : plan.layouts) {
    if (!scan.layouts.count(L.id)) continue;
    const int split = static_cast<int>(L.split);
    ++s.splits[split].layouts_built;
    ++s.subsets[L.subset][split].layouts_built;
  }
  return scan;
}

/// Pixels per NYU40 id of one label image.
struct LabelCount {
  std::array<int64_t, kNyu40Count> pixels{};
  int64_t invalid = 0;
  int width = 0, height = 0;
};

LabelCount countLabelImage(const fs::path& file) {
  const ImageU8 img = readPng8(file);
  if (img.channels != 1)
    throw InputError(
        file.string(), "",
        fmt::format("not an 8-bit grey NYU40 label image ({} channels)", img.channels));
  LabelCount c;
  c.width = img.width, c.height = img.height;
  for (const uint8_t v : img.data) {
    if (v < kNyu40Count)
      ++c.pixels[v];
    else
      ++c.invalid;
  }
  return c;
}

/// The second pass: the label images of the evenly spaced sample of labelled rows, decoded in
/// parallel batches and summed in sample order.
void countLabels(const fs::path& root, const std::vector<fs::path>& files,
                 const DatasetStatsOptions& opt, DatasetStats& s) {
  const std::vector<int64_t> pick = evenSample(s.labelled_frames, opt.max_frames);
  if (pick.empty()) return;
  std::vector<fs::path> images;
  int64_t labelled = 0;
  forEachLine(files, false, [&](const fs::path& file, int64_t n, const std::string& line) {
    if (line.find(kLabelKey) == std::string::npos) return true;
    if (labelled++ == pick[images.size()]) {
      const ojson row = parseRow(line, file, n);
      const auto f = row.find("files");
      if (f == row.end() || !f->is_object() || !f->contains("label0_nyu") ||
          !(*f)["label0_nyu"].is_string())
        throw InputError(file.string(), fmt::format("line {}", n),
                         "files.label0_nyu is not a path");
      images.push_back(root / (*f)["label0_nyu"].get<std::string>());
    }
    return images.size() < pick.size();
  });
  if (images.size() != pick.size())  // a unit rewritten between the two passes
    throw InputError(root.string(), "manifest", "changed while it was read; run stats again");
  ProgressBar bar(static_cast<int64_t>(images.size()), "label images",
                  opt.progress && static_cast<int64_t>(images.size()) >= kSlowImages);
  for (size_t b = 0; b < images.size(); b += kBatch) {
    const size_t e = std::min(images.size(), b + kBatch);
    std::vector<LabelCount> part(e - b);
    tbb::parallel_for(b, e, [&](size_t i) { part[i - b] = countLabelImage(images[i]); });
    for (const LabelCount& c : part) {
      for (int k = 0; k < kNyu40Count; ++k) s.nyu40_pixels[k] += c.pixels[k];
      s.invalid_label_pixels += c.invalid;
      if (s.label_width == 0) s.label_width = c.width, s.label_height = c.height;
    }
    bar.update(static_cast<int64_t>(e));
  }
  bar.finish();
  s.sampled_frames = static_cast<int64_t>(images.size());
}

/// A sequence folder's ground-truth poses; none while the sequence is unfinished (its ground
/// truth is written with its last frame).
Trajectory groundTruth(const fs::path& dir) {
  std::error_code ec;
  const fs::path euroc = dir / "state_groundtruth_estimate0" / "data.csv";
  const fs::path tum = dir / "groundtruth.txt";
  if (fs::is_regular_file(euroc, ec))
    return readTrajectory(euroc.string(), TrajectoryFormat::Euroc);
  if (fs::is_regular_file(tum, ec)) return readTrajectory(tum.string(), TrajectoryFormat::Tum);
  return {};
}

/// Speeds and turn rates of every built sequence, read in parallel batches and added in plan
/// order, so the sums (and the means in stats.json) do not depend on the threads.
void measureMotion(const ManifestScan& scan, const fs::path& root, bool progress, DatasetStats& s) {
  std::vector<size_t> todo;
  for (size_t i = 0; i < s.sequences.size(); ++i) {
    SequenceMotion& q = s.sequences[i];
    const auto it = scan.folders.find({q.layout, q.sequence});
    if (it == scan.folders.end()) continue;
    q.folder = it->second.first;
    todo.push_back(i);
  }
  ProgressBar bar(static_cast<int64_t>(todo.size()), "trajectories",
                  progress && static_cast<int64_t>(todo.size()) >= kSlowTrajectories);
  for (size_t b = 0; b < todo.size(); b += kBatch) {
    const size_t e = std::min(todo.size(), b + kBatch);
    std::vector<std::vector<MotionStep>> steps(e - b);
    tbb::parallel_for(b, e, [&](size_t i) {
      steps[i - b] = motionSteps(groundTruth(root / s.sequences[todo[i]].folder));
    });
    for (size_t i = b; i < e; ++i) {
      const std::vector<MotionStep>& st = steps[i - b];
      if (st.empty()) continue;
      SequenceMotion& q = s.sequences[todo[i]];
      TrajectoryTypeStats& t = s.trajectories[q.trajectory];
      ++t.sequences_measured;
      double v = 0, w = 0;
      for (const MotionStep& m : st) {
        t.speed_m_s.add(m.speed_m_s);
        t.turn_deg_s.add(m.turn_deg_s);
        v += m.speed_m_s, w += m.turn_deg_s;
      }
      q.steps = static_cast<int64_t>(st.size());
      q.mean_speed_m_s = v / static_cast<double>(st.size());
      q.mean_turn_deg_s = w / static_cast<double>(st.size());
    }
    bar.update(static_cast<int64_t>(e));
  }
  bar.finish();
}

}  // namespace

DatasetStats computeDatasetStats(const fs::path& root, const DatasetStatsOptions& opt) {
  if (opt.max_frames < 1 || opt.max_frames > 1000000000)
    throw InputError("", "max_frames",
                     fmt::format("must be 1 .. 1000000000, got {}", opt.max_frames));
  std::error_code ec;
  if (!fs::is_regular_file(root / "plan.json", ec))
    throw InputError(root.string(), "",
                     fs::is_directory(root, ec)
                         ? "not a build folder: it has no plan.json (`interiornet dataset plan "
                           "SPEC --out DIR` makes one)"
                         : "no such folder");
  const DatasetPlan plan = readPlan(root / "plan.json");
  DatasetStats s;
  s.name = plan.spec.name;
  s.root = root;
  s.max_frames = opt.max_frames;
  addPlanned(plan, s);
  const std::vector<fs::path> files = manifestFiles(root, &s.complete);
  const ManifestScan scan = scanManifest(plan, files, opt.progress, s);
  countLabels(root, files, opt, s);
  measureMotion(scan, root, opt.progress, s);
  for (const SplitTally& t : s.splits) {
    s.total.layouts += t.layouts, s.total.sequences += t.sequences;
    s.total.frames_planned += t.frames_planned, s.total.layouts_built += t.layouts_built;
    s.total.frames += t.frames, s.total.sequence_frames += t.sequence_frames;
    s.total.sparse_views += t.sparse_views;
  }
  return s;
}

namespace {

ojson tallyJson(const SplitTally& t) {
  return {{"layouts", t.layouts},
          {"sequences", t.sequences},
          {"frames_planned", t.frames_planned},
          {"layouts_built", t.layouts_built},
          {"frames", t.frames},
          {"sequence_frames", t.sequence_frames},
          {"sparse_views", t.sparse_views}};
}

ojson histogramJson(const FixedHistogram& h) {
  size_t used = h.counts.size();
  while (used > 0 && h.counts[used - 1] == 0) --used;  // trailing empty bins say nothing
  return {{"steps", h.n},
          {"mean", h.mean()},
          {"p50", h.quantile(0.5)},
          {"p95", h.quantile(0.95)},
          {"p99", h.quantile(0.99)},
          {"max", h.max},
          {"histogram",
           {{"bin_width", h.bin_width},
            {"counts", std::vector<int64_t>(h.counts.begin(), h.counts.begin() + long(used))},
            {"overflow", h.overflow}}}};
}

int64_t labelledPixels(const DatasetStats& s) {
  return std::accumulate(s.nyu40_pixels.begin(), s.nyu40_pixels.end(), int64_t{0});
}

/// The motion half of stats.json: per trajectory type, then every sequence.
ojson motionJson(const DatasetStats& s) {
  ojson types = ojson::object();
  for (const auto& [name, t] : s.trajectories) {
    double v[3] = {INFINITY, 0, -INFINITY}, w[3] = {INFINITY, 0, -INFINITY};  // min, mean, max
    for (const SequenceMotion& q : s.sequences) {
      if (q.trajectory != name) continue;
      v[0] = std::min(v[0], q.v_mult), v[1] += q.v_mult / double(t.sequences);
      v[2] = std::max(v[2], q.v_mult);
      w[0] = std::min(w[0], q.w_mult), w[1] += q.w_mult / double(t.sequences);
      w[2] = std::max(w[2], q.w_mult);
    }
    types[name] = {{"sequences", t.sequences},
                   {"sequences_measured", t.sequences_measured},
                   {"v_mult", {{"min", v[0]}, {"mean", v[1]}, {"max", v[2]}}},
                   {"w_mult", {{"min", w[0]}, {"mean", w[1]}, {"max", w[2]}}},
                   {"speed_m_s", histogramJson(t.speed_m_s)},
                   {"turn_rate_deg_s", histogramJson(t.turn_deg_s)}};
  }
  ojson seqs = ojson::array();
  for (const SequenceMotion& q : s.sequences)
    seqs.push_back({{"layout", q.layout},
                    {"sequence", q.sequence},
                    {"trajectory", q.trajectory},
                    {"v_mult", q.v_mult},
                    {"w_mult", q.w_mult},
                    {"folder", q.folder},
                    {"steps", q.steps},
                    {"mean_speed_m_s", q.mean_speed_m_s},
                    {"mean_turn_rate_deg_s", q.mean_turn_deg_s}});
  return {{"fps", s.fps},
          {"v_mult_range", s.v_mult_range},
          {"w_mult_range", s.w_mult_range},
          {"trajectories", types},
          {"sequences", seqs}};
}

}  // namespace

std::string datasetStatsJson(const DatasetStats& s) {
  ojson j;
  j["format"] = "interiornet dataset stats";
  j["version"] = 1;
  j["dataset"] = s.name;
  j["build_folder"] = fs::absolute(s.root).lexically_normal().string();
  j["complete"] = s.complete;
  j["totals"] = tallyJson(s.total);
  ojson rooms = ojson::object();
  for (const auto& [r, n] : s.layouts_per_rooms) rooms[r > 0 ? std::to_string(r) : "unknown"] = n;
  j["rooms_per_layout"] = rooms;
  for (int i = 0; i < 3; ++i)
    j["splits"][splitName(static_cast<Split>(i))] = tallyJson(s.splits[i]);
  j["subsets"] = ojson::object();
  for (const auto& [name, by] : s.subsets)
    for (int i = 0; i < 3; ++i)
      j["subsets"][name][splitName(static_cast<Split>(i))] = tallyJson(by[i]);
  const int64_t pixels = labelledPixels(s);
  ojson classes = ojson::array();
  for (int k = 0; k < kNyu40Count; ++k)
    classes.push_back({{"id", k},
                       {"name", std::string(nyu40Name(k))},
                       {"pixels", s.nyu40_pixels[k]},
                       {"share", pixels > 0 ? double(s.nyu40_pixels[k]) / double(pixels) : 0.0}});
  j["nyu40"] = {{"labelled_frames", s.labelled_frames},
                {"sampled_frames", s.sampled_frames},
                {"max_frames", s.max_frames},
                {"image_width", s.label_width},
                {"image_height", s.label_height},
                {"pixels", pixels},
                {"invalid_pixels", s.invalid_label_pixels},
                {"classes", classes}};
  j["motion"] = motionJson(s);
  return j.dump(2);
}

// ---- charts ---------------------------------------------------------------------------------

namespace {

using Panel = std::function<void(const fs::path&)>;

/// Draws each panel into its own PNG in a scratch folder, then pastes them into one image,
/// `columns` per row, each cell as wide as its column's widest and as tall as its row's
/// tallest: plot.h draws one chart per image, and a figure of related charts side by side is
/// what a reader compares at a glance.
void writePanelGrid(const fs::path& path, const std::vector<Panel>& panels, int columns) {
  const fs::path scratch =
      path.parent_path() / fmt::format(".{}.tmp-{}", path.filename().string(), ::getpid());
  struct Remove {
    fs::path dir;
    ~Remove() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } remove{scratch};
  fs::create_directories(scratch);
  std::vector<ImageU8> images;
  for (size_t k = 0; k < panels.size(); ++k) {
    const fs::path f = scratch / fmt::format("{}.png", k);
    panels[k](f);
    images.push_back(readPng8(f));
  }
  const size_t cols = static_cast<size_t>(columns), rows = (images.size() + cols - 1) / cols;
  std::vector<int> col_x(cols + 1, 0), row_y(rows + 1, 0);
  for (size_t k = 0; k < images.size(); ++k) {
    col_x[k % cols + 1] = std::max(col_x[k % cols + 1], images[k].width);
    row_y[k / cols + 1] = std::max(row_y[k / cols + 1], images[k].height);
  }
  std::partial_sum(col_x.begin(), col_x.end(), col_x.begin());
  std::partial_sum(row_y.begin(), row_y.end(), row_y.begin());
  ImageU8 out(col_x.back(), row_y.back(), 3, 255);
  for (size_t k = 0; k < images.size(); ++k) {
    const ImageU8& im = images[k];
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        for (int c = 0; c < 3; ++c)
          out.at(col_x[k % cols] + x, row_y[k / cols] + y, c) =
              im.at(x, y, im.channels >= 3 ? c : 0);
  }
  writePng(path, out);
}

Rgb splitColour(int split) {
  return paletteColour(split);
}

/// 1234567 -> "1,234,567" (v >= 0): counts of a large dataset stay readable in titles.
std::string thousands(int64_t v) {
  const std::string digits = std::to_string(v);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

void plotRooms(const DatasetStats& s, const fs::path& path) {
  std::vector<Bar> bars;
  const auto first = s.layouts_per_rooms.upper_bound(0);
  if (first != s.layouts_per_rooms.end())  // every count from the least to the most, gaps shown
    for (int r = first->first; r <= s.layouts_per_rooms.rbegin()->first; ++r)
      bars.push_back({std::to_string(r),
                      double(s.layouts_per_rooms.count(r) ? s.layouts_per_rooms.at(r) : 0),
                      {}});
  if (s.layouts_per_rooms.count(0))
    bars.push_back({"unknown", double(s.layouts_per_rooms.at(0)), paletteColour(7)});
  PlotSpec spec;
  spec.title =
      fmt::format("{}: layouts per room count ({} layouts)", s.name, thousands(s.total.layouts));
  spec.x_label = "rooms in the layout";
  spec.y_label = "layouts";
  writeBarChartPng(path, spec, bars);
}

/// Bars of one count per split ("train 80 %"), or per subset and split, coloured by split.
std::vector<Bar> splitBars(const DatasetStats& s, int64_t SplitTally::*count, bool by_subset) {
  std::vector<Bar> bars;
  int64_t all = 0;
  for (const SplitTally& t : s.splits) all += t.*count;
  for (int i = 0; i < 3; ++i) {
    const int64_t v = s.splits[i].*count;
    if (!by_subset)
      bars.push_back({fmt::format("{} ({:.1f} %)", splitName(Split(i)), all ? 100.0 * v / all : 0),
                      double(v), splitColour(i)});
  }
  if (by_subset)
    for (const auto& [name, by] : s.subsets)
      for (int i = 0; i < 3; ++i)
        bars.push_back({name + "  " + splitName(Split(i)), double(by[i].*count), splitColour(i)});
  return bars;
}

void plotSplits(const DatasetStats& s, const fs::path& path) {
  const std::string built = s.complete ? "" : " built so far";
  const int sub_h = std::clamp(130 + 22 * 3 * int(s.subsets.size()), 420, 8000);
  auto chart = [&s](std::string title, int64_t SplitTally::*count, bool by_subset, int h,
                    std::string axis) -> Panel {
    return [&s, title, count, by_subset, h, axis](const fs::path& p) {
      PlotSpec spec;
      spec.title = title;
      spec.width = 650, spec.height = h;
      spec.horizontal = by_subset;
      (by_subset ? spec.x_label : spec.y_label) = axis;
      writeBarChartPng(p, spec, splitBars(s, count, by_subset));
    };
  };
  writePanelGrid(
      path,
      {chart(fmt::format("Layouts per split ({})", thousands(s.total.layouts)),
             &SplitTally::layouts, false, 420, "layouts"),
       chart(fmt::format("Frames per split ({} built of {} planned)", thousands(s.total.frames),
                         thousands(s.total.frames_planned)),
             &SplitTally::frames, false, 420, "frames (sequence frames + sparse views)"),
       chart("Layouts per subset (room count) and split", &SplitTally::layouts, true, sub_h,
             "layouts"),
       chart("Frames per subset and split" + built, &SplitTally::frames, true, sub_h, "frames")},
      2);
}

void plotNyu40(const DatasetStats& s, const fs::path& path) {
  const int64_t pixels = labelledPixels(s);
  std::vector<int> ids;
  for (int k = 0; k < kNyu40Count; ++k)
    if (s.nyu40_pixels[k] > 0) ids.push_back(k);
  std::stable_sort(ids.begin(), ids.end(),
                   [&](int a, int b) { return s.nyu40_pixels[a] > s.nyu40_pixels[b]; });
  std::vector<Bar> bars;
  for (int k : ids) {
    unsigned char rgb[3];
    nyu40Color(k, rgb);
    bars.push_back({k == 0 ? "void (no surface)" : std::string(nyu40Name(k)),
                    100.0 * double(s.nyu40_pixels[k]) / double(pixels),
                    k == 0 ? paletteColour(7) : Rgb{rgb[0], rgb[1], rgb[2]}});
  }
  PlotSpec spec;
  spec.title = fmt::format("NYU40 classes: share of labelled pixels ({} of {} labelled frames{})",
                           thousands(s.sampled_frames), thousands(s.labelled_frames),
                           s.sampled_frames < s.labelled_frames ? ", evenly spaced" : "");
  spec.x_label = fmt::format("share of labelled pixels (%), {} x {} px per frame", s.label_width,
                             s.label_height);
  spec.horizontal = true;
  spec.height = std::clamp(120 + 22 * int(bars.size()), 300, 8000);
  writeBarChartPng(path, spec, bars);
}

/// A round bin width of about x: 1, 2 or 5 x 10^k.
double niceStep(double x) {
  const double mag = std::pow(10.0, std::floor(std::log10(x)));
  const double r = x / mag;
  return (r <= 1 ? 1 : r <= 2 ? 2 : r <= 5 ? 5 : 10) * mag;
}

/// A histogram's outline as a step line: the share of the values (%) per bin of about `step`
/// (a whole number of the histogram's own bins) from 0 to `hi`.
Series histogramSeries(const FixedHistogram& h, double step, double hi, std::string label,
                       Rgb colour) {
  const size_t per = std::max<size_t>(1, size_t(std::lround(step / h.bin_width)));
  const double w = double(per) * h.bin_width;
  const size_t bins = size_t(std::ceil(hi / w - 1e-9));
  Series s;
  s.label = std::move(label);
  s.colour = colour;
  s.line_width_px = 2.0;
  s.x = {0}, s.y = {0};
  for (size_t j = 0; j < bins; ++j) {
    int64_t c = 0;
    for (size_t k = j * per; k < (j + 1) * per && k < h.counts.size(); ++k) c += h.counts[k];
    const double y = 100.0 * double(c) / double(h.n);
    s.x.insert(s.x.end(), {double(j) * w, double(j + 1) * w});
    s.y.insert(s.y.end(), {y, y});
  }
  s.x.push_back(double(bins) * w), s.y.push_back(0);
  return s;
}

// The panels of speeds.png: wide enough for a legend of three trajectory types with their
// means beside a plot area of about 500 px.
constexpr int kMotionPanelW = 800, kMotionPanelH = 480;

/// The histograms of one quantity, one step line per trajectory type; the axis ends at the
/// largest 99.5th percentile so that one outlier does not squeeze the rest into a bin or two
/// (the legend gives each type's maximum).
LinePlot motionHistogram(const DatasetStats& s, FixedHistogram TrajectoryTypeStats::*h,
                         const std::string& what, const std::string& unit) {
  double hi = 0;
  for (const auto& [name, t] : s.trajectories) hi = std::max(hi, (t.*h).quantile(0.995));
  const double fine = (s.trajectories.begin()->second.*h).bin_width;
  hi = std::max(hi, 10 * fine);
  LinePlot p;
  int64_t measured = 0;
  for (const auto& [name, t] : s.trajectories) measured += t.sequences_measured;
  p.spec.title = fmt::format("{} between consecutive frames ({} of {} sequences)", what,
                             thousands(measured), thousands(s.total.sequences));
  p.spec.x_label = what + " (" + unit + ")";
  p.spec.y_label = "share of the type's frame steps (%)";
  p.spec.width = kMotionPanelW, p.spec.height = kMotionPanelH;
  int k = 0;
  for (const auto& [name, t] : s.trajectories) {
    const FixedHistogram& x = t.*h;
    if (x.n > 0)
      p.series.push_back(histogramSeries(
          x, std::max(fine, niceStep(hi / 30)), hi,
          fmt::format("{}: mean {:.3g}, max {:.3g}", name, x.mean(), x.max), paletteColour(k)));
    ++k;
  }
  return p;
}

/// One dot per sequence, coloured by trajectory type (the histograms' colours): xy(q) of every
/// sequence, or of the measured ones.
LinePlot sequenceScatter(const DatasetStats& s, const std::string& title,
                         const std::string& x_label, const std::string& y_label,
                         const std::function<std::pair<double, double>(const SequenceMotion&)>& xy,
                         bool measured_only) {
  LinePlot p;
  p.spec.title = title, p.spec.x_label = x_label, p.spec.y_label = y_label;
  p.spec.width = kMotionPanelW, p.spec.height = kMotionPanelH;
  int k = 0;
  for (const auto& [name, t] : s.trajectories) {
    Series d;
    d.label = name, d.colour = paletteColour(k++);
    d.style = Series::Style::Points, d.point_radius_px = 3.0;
    for (const SequenceMotion& q : s.sequences) {
      if (q.trajectory != name || (measured_only && q.steps == 0)) continue;
      const auto [x, y] = xy(q);
      d.x.push_back(x), d.y.push_back(y);
    }
    if (!d.x.empty()) p.series.push_back(std::move(d));
  }
  return p;
}

/// The spec's draw range [lo, hi] padded by 5 % (0.1 when a spec fixes the value): the dots
/// then show how the draws fill the range, not only how they spread among themselves.
std::pair<double, double> drawRange(const std::array<double, 2>& r) {
  const double pad = r[1] > r[0] ? 0.05 * (r[1] - r[0]) : 0.1;
  return {r[0] - pad, r[1] + pad};
}

void plotSpeeds(const DatasetStats& s, const fs::path& path, bool measured) {
  std::vector<LinePlot> panels;
  if (measured) {
    panels.push_back(motionHistogram(s, &TrajectoryTypeStats::speed_m_s, "Linear speed", "m/s"));
    panels.push_back(motionHistogram(s, &TrajectoryTypeStats::turn_deg_s, "Turn rate", "deg/s"));
  }
  LinePlot planned = sequenceScatter(
      s, fmt::format("Planned multipliers of the {} sequences", thousands(s.total.sequences)),
      "v_mult (linear speed)", "w_mult (turn rate)",
      [](const SequenceMotion& q) {
        return std::pair{q.v_mult, q.w_mult};
      },
      false);
  planned.spec.x_range = drawRange(s.v_mult_range);
  planned.spec.y_range = drawRange(s.w_mult_range);
  panels.push_back(std::move(planned));
  if (measured) {
    LinePlot speed = sequenceScatter(
        s, "Mean speed of each built sequence", "v_mult", "mean linear speed (m/s)",
        [](const SequenceMotion& q) {
          return std::pair{q.v_mult, q.mean_speed_m_s};
        },
        true);
    speed.spec.x_range = drawRange(s.v_mult_range);
    panels.push_back(std::move(speed));
  }
  std::vector<Panel> draw;
  for (const LinePlot& p : panels)
    draw.push_back([p](const fs::path& f) { writeLinePlotPng(f, p.spec, p.series); });
  writePanelGrid(path, draw, 2);
}

}  // namespace

std::vector<fs::path> writeDatasetStats(const DatasetStats& s, const fs::path& out) {
  std::vector<fs::path> written;
  writeTextAtomic(out / "stats.json", datasetStatsJson(s) + "\n");
  written.push_back(out / "stats.json");
  bool measured = false;
  for (const SequenceMotion& q : s.sequences) measured |= q.steps > 0;
  auto chart = [&](const char* name, bool has_data, const std::function<void(const fs::path&)>& f) {
    const fs::path p = out / name;
    std::error_code ec;
    if (!has_data) {
      fs::remove(p, ec);  // a chart of an earlier run would no longer describe the folder
      return;
    }
    f(p);
    written.push_back(p);
  };
  chart("rooms_per_layout.png", true, [&](const fs::path& p) { plotRooms(s, p); });
  chart("splits.png", true, [&](const fs::path& p) { plotSplits(s, p); });
  chart("nyu40_pixels.png", labelledPixels(s) > 0, [&](const fs::path& p) { plotNyu40(s, p); });
  chart("speeds.png", !s.sequences.empty(), [&](const fs::path& p) { plotSpeeds(s, p, measured); });
  return written;
}

}  // namespace inet
