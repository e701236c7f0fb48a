#include "core/stop.h"

#include <csignal>
#include <cstdio>

namespace inet {
namespace {
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void onStopSignal(int sig) {
  g_stop_signal = sig;
}
}  // namespace

void installStopHandlers() {
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
}

int stopSignal() {
  return g_stop_signal;
}

void requestStop(int signal) {
  g_stop_signal = signal;
}

void stopIfSignalled(const std::string& done) {
  const int sig = g_stop_signal;
  if (sig == 0) return;
  const std::string message = std::string("stopped by ") +
                              (sig == SIGTERM  ? "SIGTERM"
                               : sig == SIGINT ? "SIGINT"
                                               : "a signal") +
                              " " + done + "; rerun the same command to resume";
  std::fprintf(stderr, "%s\n", message.c_str());
  throw StopRequested(sig, message);
}

}  // namespace inet
