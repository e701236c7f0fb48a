#pragma once
// Stopping long work cleanly. A scheduler (Slurm, Kubernetes) sends SIGTERM some seconds before
// it kills a job, a user Ctrl-C (SIGINT). After installStopHandlers() such a signal only raises
// a flag; the work stops at its next safe point (between frames, between layouts, between work
// units), where every file written so far is whole, by throwing StopRequested, which main()
// turns into the exit status 128 + the signal (130 for SIGINT, 143 for SIGTERM).
#include <stdexcept>
#include <string>

namespace inet {

/// Thrown at a safe point after a stop signal; what() says what was done and how to resume.
class StopRequested : public std::runtime_error {
 public:
  StopRequested(int signal, const std::string& message)
      : std::runtime_error(message), signal_(signal) {}
  int signal() const { return signal_; }
  int exitCode() const { return 128 + signal_; }

 private:
  int signal_;
};

/// Installs the SIGINT and SIGTERM handlers (idempotent).
void installStopHandlers();
/// The signal that asked to stop (SIGINT, SIGTERM), or 0.
int stopSignal();
/// Raises the flag as a signal would (for a coordinator that tells its own loop to drain).
void requestStop(int signal);
/// If a signal came: prints "stopped by SIGTERM <done>; rerun the same command to resume" on
/// stderr and throws StopRequested.
void stopIfSignalled(const std::string& done);

}  // namespace inet
