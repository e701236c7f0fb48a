#pragma once
// What every `main` of the command line does around CLI11: one-line errors, the last value of a
// repeated option, and the only place errors become exit codes (STYLE.md section 4): 2 for bad
// input (InputError), 128 + the signal after a stop signal (core/stop.h), 1 for anything else.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/stop.h"

namespace inet::app {

/// Sets `app` up as above (call before adding options).
inline void configureCli(CLI::App& app) {
  // a repeated option takes its last value, as in most command lines (scripts append overrides)
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("error: ") + e.what() + " (see --help)\n";
  });
}

/// Parses and runs; returns the exit code.
inline int runCli(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const StopRequested& e) {  // stopped at a safe point; the message is printed
    return e.exitCode();
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}

/// The training record of the LibTorch tools: `record` if given, else <out stem>_record.json
/// beside the weights file `out`.
inline std::string recordPath(const std::string& out, const std::string& record) {
  if (!record.empty()) return record;
  const std::filesystem::path o(out);
  return (o.parent_path() / (o.stem().string() + "_record.json")).string();
}

}  // namespace inet::app
