// Ctrl-C and SIGTERM as LS-DYNA's sense switch: the first signal only sets a flag; the time loop
// (Simulation::run) sees it between cycles, ends the run as at termination (last frame, rows,
// a restart dump) and the CLI exits with 128 + the signal number (docs/cli.md). A second signal
// ends the process at once, but never inside a file write that must stay whole (a CSV block
// of complete rows): that write finishes first (WholeWrite below).
#pragma once

namespace rf::solver::interrupt {

// Installs the SIGINT/SIGTERM handlers (the CLI's run and restart commands). Without it
// requested() stays 0 and the library behaves as before.
void install_handlers();

// The first interrupting signal received (SIGINT, SIGTERM), or 0.
int requested();

// Exit status for an interrupted run: 128 + signal, as a shell reports a death by that signal.
int exit_status(int signal);

// Signal name for messages ("SIGINT", "SIGTERM").
const char* signal_name(int signal);

// While one exists, a second signal waits: the process ends when the scope closes, so a file
// never ends in the middle of what was written inside it.
class WholeWrite {
 public:
  WholeWrite();
  ~WholeWrite();
  WholeWrite(const WholeWrite&) = delete;
  WholeWrite& operator=(const WholeWrite&) = delete;
};

}  // namespace rf::solver::interrupt
