#include "eval/paper_experiment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/plot.h"
#include "pipeline/sequence_job.h"
#include "trajectory/random_trajectory.h"

namespace inet {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr const char* kTypes[] = {"two-body", "hand-held", "look-forward"};

/// The paper's type number: two-body 1, hand-held 2, look-forward 3.
int typeNumber(const std::string& type) {
  for (int i = 0; i < 3; ++i)
    if (type == kTypes[i]) return i + 1;
  INET_CHECK(false);
}

/// "1", "2.5": a multiplier as it appears in names and tables.
std::string multiplier(double m) { return fmt::format("{:g}", m); }

/// A layout source as a folder name: "procedural:3" -> "procedural_3", "a/b.json" -> "b".
std::string folderOf(const std::string& layout) {
  std::string s = layout.find(':') != std::string::npos ? layout : fs::path(layout).stem().string();
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s;
}

/// One trajectory through one layout, rendered in one or more configurations.
struct SequencePlan {
  std::string layout, type;
  double v = 1, w = 1;
  std::set<std::string> configs;
  std::string name() const {
    return fmt::format("{}_v{}_w{}", type, multiplier(v), multiplier(w));
  }
};

/// Which parts a rendered configuration of a plan serves.
std::vector<std::string> partsOf(const PaperExperimentOptions& o, const SequencePlan& p,
                                 const std::string& config) {
  std::vector<std::string> parts;
  const bool apt = p.layout == o.apartment, unit = p.v == 1 && p.w == 1;
  const bool two_body = p.type == "two-body", original = config == "original";
  const auto has = [&](char c) { return o.parts.find(c) != std::string::npos; };
  const auto in = [](const std::vector<double>& g, double x) {
    return std::find(g.begin(), g.end(), x) != g.end();
  };
  if (has('a') && apt && two_body && unit) parts.push_back("a");
  if (has('b') && apt && two_body && original && in(o.v_grid, p.v) && in(o.w_grid, p.w))
    parts.push_back("b");
  if (has('c') && apt && unit && original) parts.push_back("c");
  if (has('d') && two_body && unit && original &&
      std::find(o.layouts.begin(), o.layouts.end(), p.layout) != o.layouts.end())
    parts.push_back("d");
  return parts;
}

/// Every sequence the selected parts need, each once.
std::vector<SequencePlan> planSequences(const PaperExperimentOptions& o) {
  std::map<std::string, SequencePlan> plans;  // by layout folder / name
  const auto add = [&](const std::string& layout, const std::string& type, double v, double w,
                       std::vector<std::string> configs) {
    SequencePlan p{layout, type, v, w, {}};
    SequencePlan& q = plans.try_emplace(folderOf(layout) + "/" + p.name(), p).first->second;
    q.configs.insert(configs.begin(), configs.end());
  };
  const auto has = [&](char c) { return o.parts.find(c) != std::string::npos; };
  if (has('a'))
    add(o.apartment, "two-body", 1, 1,
        {"original", fmt::format("lighting:{}", o.lighting),
         fmt::format("rearranged:{}", o.rearranged)});
  if (has('b'))
    for (double v : o.v_grid)
      for (double w : o.w_grid) add(o.apartment, "two-body", v, w, {"original"});
  if (has('c'))
    for (const char* t : kTypes) add(o.apartment, t, 1, 1, {"original"});
  if (has('d'))
    for (const std::string& l : o.layouts) add(l, "two-body", 1, 1, {"original"});
  std::vector<SequencePlan> out;
  for (auto& [key, p] : plans) out.push_back(p);
  return out;
}

/// The configurations in the pipeline's order: original first, then as named.
std::string configList(const std::set<std::string>& configs) {
  std::string s = configs.count("original") ? "original" : "";
  for (const std::string& c : configs)
    if (c != "original") s += (s.empty() ? "" : ",") + c;
  return s;
}

SequenceJob jobOf(const PaperExperimentOptions& o, const SequencePlan& p) {
  SequenceJob job;
  job.scene.path = p.layout;
  job.scene.rooms = o.rooms;
  job.trajectory = p.type;
  job.motion.v_mult = p.v;
  job.motion.w_mult = p.w;
  job.frames = o.frames;
  job.frames_set = true;
  job.fps = o.fps;
  job.spp = o.spp;
  job.seed = o.seed;
  job.passes = "rgb,depth";
  job.formats = "asl";
  job.sequence = p.name();
  job.config = configList(p.configs);
  job.out = (o.out / "sequences").string();
  job.folder = folderOf(p.layout);
  job.progress = o.progress;
  job.K.width = o.width;
  job.K.height = o.height;
  // the pipeline's field of view at 640 px (fx 600) unless given
  job.K.fx = job.K.fy = o.fx > 0 ? o.fx : 600.0 * o.width / 640.0;
  job.width_set = job.height_set = job.fx_set = job.fy_set = true;
  return job;
}

std::string csvField(const std::string& s) {
  return s.find_first_of(",\"") == std::string::npos ? s : "\"" + s + "\"";
}

double mean(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v;
  return x.empty() ? NAN : s / static_cast<double>(x.size());
}

double stddev(const std::vector<double>& x) {
  if (x.size() < 2) return NAN;
  const double m = mean(x);
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

std::string cm(double metres) {
  return std::isfinite(metres) ? fmt::format("{:.2f}", 100 * metres) : "-";
}

std::string resultsCsv(const PaperExperimentResult& r) {
  std::string s =
      "part,layout,sequence,configuration,type,v,w,system,frames,length_m,tracked_share,"
      "coverage,ate_se3_m,ate_sim3_m,rpe_m,seconds_per_frame\n";
  for (const ExperimentRow& row : r.rows) {
    const SlamScore& sc = row.score;
    s += fmt::format("{},{},{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{},{},{},{:.5f}\n", row.part,
                     csvField(row.layout), csvField(row.sequence), row.configuration, row.type,
                     multiplier(row.v), multiplier(row.w), sc.system, sc.frames,
                     sc.path_length_m, sc.tracked_share, sc.coverage,
                     sc.scored ? fmt::format("{:.6f}", sc.ate_se3.translation_m.rmse) : "",
                     sc.scored ? fmt::format("{:.6f}", sc.ate_sim3.translation_m.rmse) : "",
                     sc.scored ? fmt::format("{:.6f}", sc.rpe.translation_m.rmse) : "",
                     sc.seconds_per_frame);
  }
  return s;
}

/// Part b's figures: per system a panel of `value` against v, one line per w.
void writeSpeedPlot(const fs::path& path, const PaperExperimentResult& r,
                    const PaperExperimentOptions& o, const std::string& y_label,
                    double (*value)(const SlamScore&)) {
  std::vector<LinePlot> panels;
  for (const std::string& sys : o.systems) {
    LinePlot panel;
    panel.spec.title = sys;
    panel.spec.x_label = "v multiplier";
    panel.spec.y_label = y_label;
    panel.spec.width = 560;
    panel.spec.height = 420;
    for (double w : o.w_grid) {
      Series s;
      s.label = "w x" + multiplier(w);
      s.style = Series::Style::LinePoints;
      for (double v : o.v_grid)
        for (const ExperimentRow& row : r.rows)
          if (row.part == "b" && row.score.system == sys && row.v == v && row.w == w) {
            s.x.push_back(v);
            s.y.push_back(value(row.score));
          }
      panel.series.push_back(std::move(s));
    }
    panels.push_back(std::move(panel));
  }
  writeLinePlotRowPng(path, panels);
}

}  // namespace

void PaperExperimentOptions::validate() const {
  if (parts.empty() || parts.find_first_not_of("abcd") != std::string::npos)
    throw InputError("", "--parts",
                     fmt::format("'{}': give any of the letters a, b, c, d", parts));
  for (const auto& [grid, field] :
       {std::pair{&v_grid, "--v-mult"}, std::pair{&w_grid, "--w-mult"}}) {
    if (parts.find('b') != std::string::npos && grid->empty())
      throw InputError("", field, "part b needs at least one multiplier");
    for (double m : *grid)
      if (!(m > 0 && m <= 100))
        throw InputError("", field, fmt::format("multiplier {} is not in (0, 100]", m));
  }
  if (systems.empty()) throw InputError("", "--systems", "no system");
  const std::vector<std::string> builtin = builtinSlamSystems();
  for (const std::string& s : systems)
    if (std::find(builtin.begin(), builtin.end(), s) == builtin.end())
      throw InputError("", "--systems",
                       fmt::format("'{}' is not a built-in system (opencv-rgbd, opencv-icp, "
                                   "opencv-rgbd-icp); run external ones with eval slam",
                                   s));
  if (parts.find('d') != std::string::npos && layouts.empty())
    throw InputError("", "--layouts", "part d needs at least one layout");
  if (frames < 3) throw InputError("", "--frames", "at least 3 (SE(3) alignment)");
  if (!(fps > 0)) throw InputError("", "--fps", "must be > 0");
  if (width < 16 || height < 16) throw InputError("", "--width", "at least 16 x 16 pixels");
  if (spp < 1) throw InputError("", "--spp", "at least 1");
  if (lighting < 0) throw InputError("", "--lighting", "a seed, >= 0");
  if (rearranged < 0) throw InputError("", "--rearranged", "a seed, >= 0");
}

PaperExperimentResult runPaperExperiment(const PaperExperimentOptions& o) {
  o.validate();
  PaperExperimentResult res;
  const std::vector<SequencePlan> plans = planSequences(o);
  size_t n = 0;
  for (const SequencePlan& p : plans) {
    ++n;
    if (o.progress)
      fmt::print("[{}/{}] {} {} ({})\n", n, plans.size(), p.layout, p.name(),
                 configList(p.configs));
    const auto t0 = Clock::now();
    const SequenceJobResult made = runSequenceJob(jobOf(o, p));
    res.render_s += secondsSince(t0);
    for (const SequenceJobResult::Sequence& s : made.sequences) {
      const std::vector<std::string> parts = partsOf(o, p, s.configuration);
      if (parts.empty()) continue;
      for (const std::string& sys : o.systems) {
        const auto t1 = Clock::now();
        SlamEvalOptions eo;
        eo.system = sys;
        eo.reference = o.reference;
        const SlamReport rep = evalSlam(s.dir, eo);
        writeSlamReport(o.out / "runs" / folderOf(p.layout) / fs::path(s.dir).filename() / sys,
                        rep);
        res.eval_s += secondsSince(t1);
        if (o.progress)
          fmt::print("    {:<16} {:<14} ATE {:>7} cm  tracked {:5.1f} %\n", sys, s.configuration,
                     cm(rep.score.ate_se3.translation_m.rmse), 100 * rep.score.tracked_share);
        for (const std::string& part : parts)
          res.rows.push_back({part, p.layout, s.dir, s.configuration, p.type, p.v, p.w, rep.score});
      }
    }
  }
  // Table 1's order: by part, then type, speed, configuration (original, relit, rearranged),
  // then the layouts as given
  const auto configRank = [](const std::string& c) {
    return c == "original" ? 0 : c.starts_with("lighting") ? 1 : 2;
  };
  const auto layoutRank = [&o](const std::string& l) {
    return std::find(o.layouts.begin(), o.layouts.end(), l) - o.layouts.begin();
  };
  std::stable_sort(res.rows.begin(), res.rows.end(),
                   [&](const ExperimentRow& a, const ExperimentRow& b) {
                     return std::tuple(a.part, typeNumber(a.type), a.v, a.w,
                                       configRank(a.configuration), layoutRank(a.layout)) <
                            std::tuple(b.part, typeNumber(b.type), b.v, b.w,
                                       configRank(b.configuration), layoutRank(b.layout));
                   });

  writeTextAtomic(o.out / "results.csv", resultsCsv(res));
  writeTextAtomic(o.out / "table.md", experimentTableMarkdown(res, o.systems));
  if (o.parts.find('b') != std::string::npos) {
    writeSpeedPlot(o.out / "speed_tracked.png", res, o, "frames tracked (%)",
                   [](const SlamScore& s) { return 100 * s.tracked_share; });
    writeSpeedPlot(o.out / "speed_ate.png", res, o, "ATE (cm)",
                   [](const SlamScore& s) { return 100 * s.ate_se3.translation_m.rmse; });
  }
  if (o.parts.find('d') != std::string::npos) {
    std::vector<Bar> bars;
    for (size_t i = 0; i < o.systems.size(); ++i)
      for (const ExperimentRow& row : res.rows)
        if (row.part == "d" && row.score.system == o.systems[i])
          bars.push_back({folderOf(row.layout) + " " + o.systems[i],
                          100 * row.score.ate_se3.translation_m.rmse, paletteColour(int(i))});
    PlotSpec spec;
    spec.title = "The same two-body (1, 1) trajectory type and seed through several layouts";
    spec.y_label = "layout, system";
    spec.horizontal = true;
    spec.x_label = "ATE (cm)";
    writeBarChartPng(o.out / "layouts.png", spec, bars);
  }
  json j = {{"format", "interiornet-paper-experiment-1"},
            {"options",
             {{"parts", o.parts},
              {"apartment", o.apartment},
              {"rooms", o.rooms},
              {"layouts", o.layouts},
              {"v", o.v_grid},
              {"w", o.w_grid},
              {"lighting", o.lighting},
              {"rearranged", o.rearranged},
              {"systems", o.systems},
              {"reference", odometryReferenceName(o.reference)},
              {"frames", o.frames},
              {"fps", o.fps},
              {"width", o.width},
              {"height", o.height},
              {"spp", o.spp},
              {"seed", o.seed}}},
            {"render_s", res.render_s},
            {"eval_s", res.eval_s}};
  json rows = json::array();
  for (const ExperimentRow& row : res.rows) {
    json r = slamScoreJson(row.score);
    r["part"] = row.part;
    r["layout"] = row.layout;
    r["configuration"] = row.configuration;
    r["type"] = row.type;
    r["v"] = row.v;
    r["w"] = row.w;
    rows.push_back(std::move(r));
  }
  j["rows"] = std::move(rows);
  writeTextAtomic(o.out / "experiment.json", j.dump(2) + "\n");
  return res;
}

std::string experimentTableMarkdown(const PaperExperimentResult& r,
                                    const std::vector<std::string>& systems) {
  // one line per sequence (part, folder): the systems side by side
  std::string s = "| No | Part | Layout | Length (m) | (v, ω, type) | Configuration |";
  std::string rule = "|---|---|---|---|---|---|";
  for (const std::string& sys : systems) {
    s += fmt::format(" {} ATE (cm) | {} tracked |", sys, sys);
    rule += "---|---|";
  }
  s += "\n" + rule + "\n";
  std::vector<std::pair<std::string, std::string>> seen;
  int no = 0;
  for (const ExperimentRow& row : r.rows) {
    const std::pair key{row.part, row.sequence};
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    s += fmt::format("| {} | {} | {} | {:.2f} | ({}, {}, {}) | {} |", ++no, row.part, row.layout,
                     row.score.path_length_m, multiplier(row.v), multiplier(row.w),
                     typeNumber(row.type), row.configuration);
    for (const std::string& sys : systems) {
      const ExperimentRow* m = nullptr;
      for (const ExperimentRow& q : r.rows)
        if (q.part == row.part && q.sequence == row.sequence && q.score.system == sys) m = &q;
      if (!m) {
        s += " | |";
        continue;
      }
      s += fmt::format(" {} | {:.0f} % |", cm(m->score.ate_se3.translation_m.rmse),
                       100 * m->score.tracked_share);
    }
    s += "\n";
  }
  // part d: mean and spread over the layouts
  bool any_d = false;
  for (const ExperimentRow& row : r.rows) any_d |= row.part == "d";
  if (any_d) {
    s += "\nPart d, over layouts (mean ± standard deviation of the ATE):\n\n";
    for (const std::string& sys : systems) {
      std::vector<double> ate, tracked;
      for (const ExperimentRow& row : r.rows)
        if (row.part == "d" && row.score.system == sys && row.score.scored) {
          ate.push_back(row.score.ate_se3.translation_m.rmse);
          tracked.push_back(row.score.tracked_share);
        }
      s += fmt::format("- {}: {}{} cm over {} layout(s), {:.0f} % of frames tracked\n", sys,
                       cm(mean(ate)), ate.size() > 1 ? " ± " + cm(stddev(ate)) : "", ate.size(),
                       100 * mean(tracked));
    }
  }
  return s;
}

}  // namespace inet
