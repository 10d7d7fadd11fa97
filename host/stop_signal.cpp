#include "host/stop_signal.h"

#include <csignal>
#include <initializer_list>

namespace tessera {
namespace {

volatile std::sig_atomic_t g_signal = 0;

void on_signal(int signal) {
  g_signal = signal;
}

}  // namespace

void catch_stop_signals() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  // SA_RESTART: a write to a pipe or a file the signal lands in is resumed, not failed with
  // EINTR, as the command goes on to its next safe point.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM}) {
    // One the process was started ignoring stays ignored: a shell starts a script's background
    // commands ignoring SIGINT, so that a Ctrl+C meant for the script does not end them.
    struct sigaction old {};
    sigaction(signal, nullptr, &old);
    if (old.sa_handler != SIG_IGN) sigaction(signal, &action, nullptr);
  }
}

int stop_signal() {
  return g_signal;
}

const char* stop_signal_name(int signal) {
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
}

int interrupted_exit_status(int signal) {
  return 128 + signal;
}

}  // namespace tessera
