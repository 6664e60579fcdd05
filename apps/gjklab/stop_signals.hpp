// SIGINT (Ctrl-C) and SIGTERM (a cluster's scheduler stopping a job) for the long commands,
// `gjklab run` and `gjklab simulate`: they poll stop_requested(), finish what they started and
// leave a resumable file.
#pragma once

#include <atomic>

namespace gjklab::cli {

/// Set by the first SIGINT or SIGTERM while a StopSignals is alive. A command resets it before
/// it starts.
std::atomic<bool>& stop_requested();

/// While alive, SIGINT and SIGTERM set stop_requested(); each signal's default action is then
/// restored, so a second one terminates the process.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

}  // namespace gjklab::cli
