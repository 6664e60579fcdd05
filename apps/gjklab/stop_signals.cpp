#include "gjklab/stop_signals.hpp"

#include <csignal>

namespace gjklab::cli {

namespace {

std::atomic<bool> requested{false};

extern "C" void on_stop_signal(int signal) {
  requested = true;
  std::signal(signal, SIG_DFL);
}

}  // namespace

std::atomic<bool>& stop_requested() {
  return requested;
}

StopSignals::StopSignals()
    : previous_int_(std::signal(SIGINT, on_stop_signal)),
      previous_term_(std::signal(SIGTERM, on_stop_signal)) {}

StopSignals::~StopSignals() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

}  // namespace gjklab::cli
