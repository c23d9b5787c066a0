#include "bounce/core/interrupt.h"

#include <csignal>
#include <cstring>

namespace bounce {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_signal(int signal) {
  g_signal = signal;
}

std::string describe(int signal) {
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
  return fmt::format("interrupted by {}: stopped before writing any output", name);
}

}  // namespace

Interrupted::Interrupted(int signal) : Error(describe(signal)), signal_(signal) {}

void install_interrupt_handlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() {
  return g_signal;
}

void throw_if_interrupted() {
  if (const int signal = g_signal; signal != 0) throw Interrupted(signal);
}

void set_interrupt_signal(int signal) {
  g_signal = signal;
}

}  // namespace bounce
