// Stopping cleanly on SIGINT and SIGTERM. The handler only records the signal; long loops (frames,
// progressive passes) poll it and throw Interrupted, so that the stack unwinds, temporary files
// are removed and no output is written half-way.
#pragma once

#include "bounce/core/error.h"

namespace bounce {

// Thrown by throw_if_interrupted: an Error whose signal() says which signal asked for the stop.
class Interrupted : public Error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }

 private:
  int signal_;
};

// Installs handlers for SIGINT and SIGTERM that record the signal. Each handler is one-shot: a
// second signal of the same kind ends the process at once, as if no handler were installed.
void install_interrupt_handlers();
// The signal received since install_interrupt_handlers (0: none).
int interrupt_signal();
// Throws Interrupted when a signal has been received.
void throw_if_interrupted();
// For tests: records `signal` as if it had been received (0 clears it).
void set_interrupt_signal(int signal);

}  // namespace bounce
