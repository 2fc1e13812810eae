#include "run/interrupt.hpp"

#include <csignal>
#include <string>

namespace isg::run {

namespace {

// A signal handler can reach nothing but a flag of static storage: this one variable is the
// process-wide state the C signal interface forces on us.
volatile std::sig_atomic_t received_signal = 0;

// The first signal raises the flag; a second one, while the command is still unwinding or is held
// in a wait no check reaches (a system call that does not return), ends the process at once, as
// the signal's default does: no wait outlasts a second Ctrl-C. Only async-signal-safe calls.
extern "C" void raiseInterruptFlag(int signal_number) {
  if (received_signal != 0) {
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
    return;
  }
  received_signal = signal_number;
}

}  // namespace

Interrupted::Interrupted(int signal_number)
    : std::runtime_error(signal_number == SIGINT
                             ? "interrupted (Ctrl-C)"
                             : "stopped by signal " + std::to_string(signal_number)),
      signal_number_(signal_number) {}

void installInterruptHandlers() {
  std::signal(SIGINT, raiseInterruptFlag);
  std::signal(SIGTERM, raiseInterruptFlag);
}

void throwIfInterrupted() {
  if (received_signal != 0) throw Interrupted(received_signal);
}

}  // namespace isg::run
