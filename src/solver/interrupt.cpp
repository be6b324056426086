#include "solver/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace rf::solver::interrupt {

namespace {

// Lock-free atomics only: they are all a signal handler may touch (POSIX async-signal safety).
std::atomic<int> g_first_signal{0};
std::atomic<int> g_abort_signal{0};  // a second signal, waiting for a whole write to end
std::atomic<int> g_writes_open{0};   // WholeWrite scopes open (the main thread's, normally one)

void on_signal(int signal) {
  int none = 0;
  if (g_first_signal.compare_exchange_strong(none, signal)) return;  // first: finish cleanly
  // Second: end now, unless a whole write is under way; then its scope ends the process.
  // Stored before the check, read by WholeWrite after its count: one of the two ends the
  // process before a write starts, or the write's scope ends it after the write.
  g_abort_signal.store(signal);
  if (g_writes_open.load() == 0) _exit(exit_status(signal));
}

}  // namespace

void install_handlers() {
  struct sigaction action = {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // interrupted reads and writes resume
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int requested() {
  return g_first_signal.load(std::memory_order_relaxed);
}

int exit_status(int signal) {
  return 128 + signal;
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "signal";
  }
}

WholeWrite::WholeWrite() {
  g_writes_open.fetch_add(1);
  // A second signal that came just before: end before writing anything (the handler may have
  // seen no open write and be ending the process too; either way nothing half-written).
  if (const int signal = g_abort_signal.load(); signal != 0) _exit(exit_status(signal));
}

WholeWrite::~WholeWrite() {
  if (g_writes_open.fetch_sub(1) == 1) {
    const int signal = g_abort_signal.load();
    if (signal != 0) _exit(exit_status(signal));
  }
}

}  // namespace rf::solver::interrupt
