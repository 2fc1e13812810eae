#pragma once

#include <stdexcept>

namespace isg::run {

// Ctrl-C and SIGTERM end a long command cleanly: the signal only raises a flag, the command's
// progress callback throws Interrupted at the next scan, and the exception unwinds through the
// atomic folder writers, which remove their temporary folder. Nothing half-written is left, and
// the command exits with 128 + the signal's number (130 for Ctrl-C), as shells expect. A second
// signal ends the process at once (its temporary files may then stay behind, never its outputs).
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal_number);
  int signalNumber() const { return signal_number_; }

 private:
  int signal_number_;
};

// Routes SIGINT and SIGTERM to the flag. Called once, by main.
void installInterruptHandlers();

// Throws Interrupted once a signal has arrived.
void throwIfInterrupted();

}  // namespace isg::run
