#pragma once
// Ctrl+C (SIGINT) and SIGTERM as a request to stop at the next safe point: `tessera view` leaves
// its loop as if the window were closed; `bench` and `tradeoff` stop between measurements and
// report what they measured. A second one ends the process at once.

namespace tessera {

/// From now on the first SIGINT or SIGTERM only sets stop_signal(); the handler is then reset,
/// so that a second one ends the process as it would have without it. A signal the process was
/// started ignoring (a script's background command's SIGINT) is left ignored.
void catch_stop_signals();

/// The signal received since catch_stop_signals (SIGINT or SIGTERM), 0 for none.
int stop_signal();

/// "SIGINT" or "SIGTERM".
const char* stop_signal_name(int signal);

/// The exit status of a command that stopped early for `signal`: 128 + its number, as a shell
/// reports a process the signal ended (130 for SIGINT, 143 for SIGTERM).
int interrupted_exit_status(int signal);

}  // namespace tessera
