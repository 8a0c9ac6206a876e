#include "sph/run_signals.hpp"

#include <csignal>

namespace sph {
namespace {

volatile std::sig_atomic_t requested = 0;

extern "C" void onStopSignal(int sig) {
  if (requested != 0) {  // the second: stop now
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  requested = sig;
}

}  // namespace

void installStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int stopSignal() { return requested; }

}  // namespace sph
