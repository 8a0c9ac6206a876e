// SIGINT and SIGTERM during a run. The first asks the run to stop after the
// step it is in: it then writes a final snapshot, the series, run.json and
// the summary ("stopped at step N, t = ..."), and exits with 128 + the
// signal (130, 143). A second one stops at once with the signal's default
// action; every file is replaced atomically, so the series stays valid.
#pragma once

namespace sph {

// Installs the handlers (once per process).
void installStopHandlers();

// The signal that asked the run to stop, or 0.
int stopSignal();

}  // namespace sph
