// interiornet trajectory train-style: trains the learned hand-held style model (docs/style.md)
// with LibTorch and writes the weights plus a JSON record of data and settings. Declared in
// common.h as
//   void addTrainStyleCommand(CLI::App* trajectory_cmd);
#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "cli_main.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "trajectory/style_train.h"

namespace inet::app {
namespace {

struct TrainStyleArgs {
  StyleTrainOptions opt;
  std::string out;
  std::string record;
};

void runTrainStyle(const TrainStyleArgs& a) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(a.opt.data_dir))
    throw InputError(a.opt.data_dir, "--data", "is not a folder");
  const std::string record = recordPath(a.out, a.record);
  ProgressBar bar(a.opt.epochs, "epochs");
  StyleTrainResult r = trainStyleModel(a.opt, [&](int epoch, int, double) { bar.update(epoch); });
  bar.finish();
  saveStyleModel(r.model, a.out);
  writeTextAtomic(record, r.record_json);
  fmt::print("style model: {} parameters, train NLL {:.4f}, held-out NLL {:.4f}\n  {}\n  {}\n",
             r.model.parameterCount(), r.train_nll, r.holdout_nll, a.out, record);
}

}  // namespace

void addTrainStyleCommand(CLI::App* trajectory_cmd) {
  auto* cmd = trajectory_cmd->add_subcommand(
      "train-style",
      "Train the learned hand-held trajectory style (a WaveNet over velocity residuals) on real "
      "camera trajectories with LibTorch; writes the weights and a JSON record of the data, "
      "split, settings and losses (docs/style.md)");
  auto a = std::make_shared<TrainStyleArgs>();
  cmd->add_option("--data", a->opt.data_dir,
                  "folder of real trajectories (TUM .txt, EuRoC/TUM-VI .csv)")
      ->required();
  cmd->add_option("--train", a->opt.train, "training files in --data (hand-held only)")
      ->delimiter(',')
      ->default_str(fmt::format("{}", fmt::join(a->opt.train, ",")));
  cmd->add_option("--holdout", a->opt.holdout, "held-out files in --data, for the losses")
      ->delimiter(',')
      ->default_str(fmt::format("{}", fmt::join(a->opt.holdout, ",")));
  cmd->add_option("--epochs", a->opt.epochs, "passes of --windows windows")->capture_default_str();
  cmd->add_option("--windows", a->opt.windows_per_epoch, "training windows per epoch")
      ->capture_default_str();
  cmd->add_option("--seed", a->opt.seed, "seed of initialisation and sampling")
      ->capture_default_str();
  cmd->add_option("--threads", a->opt.threads, "torch threads")->capture_default_str();
  cmd->add_option("--out", a->out, "weights file to write (.bin)")->required();
  cmd->add_option("--record", a->record, "record to write; default: <out stem>_record.json");
  cmd->callback([a] { runTrainStyle(*a); });
}

}  // namespace inet::app
