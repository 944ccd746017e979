#include "studies/interrupt.hpp"

#include <csignal>
#include <cstdio>

namespace hsr::studies {
namespace {

volatile std::sig_atomic_t interruptions = 0;
struct sigaction previous;

void onInterrupt(int) {
  interruptions = 1;
  // The second Ctrl-C is the default one: the process ends at once.
  std::signal(SIGINT, SIG_DFL);
}

}  // namespace

InterruptibleRun::InterruptibleRun() {
  interruptions = 0;
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous);
}

InterruptibleRun::~InterruptibleRun() { sigaction(SIGINT, &previous, nullptr); }

bool InterruptibleRun::requested() { return interruptions != 0; }

void reportInterrupted(std::size_t measured, std::size_t planned, const char* what) {
  std::fprintf(stderr, "hsr: interrupted: %zu of %zu %s measured%s\n", measured, planned, what,
               measured ? "; their rows are written" : "; nothing is written");
}

}  // namespace hsr::studies
