#pragma once
// SIGINT and SIGTERM during a long command (docs/cli.md#interruption). The
// first one only sets a flag: the command polls it between rows, steps or
// stages and ends with whole rows, its summary and exit status 128 + the
// signal (130, 143). A second one ends the process at once (the signal's
// default action), for a command stuck where it cannot poll.
namespace cvt::files {

// Installs the handlers (SA_RESTART: a write under way is finished, so a
// row is never cut). Idempotent.
void catch_interrupts();

// Whether a signal asked the run to stop, and which (0: none).
bool interrupted() noexcept;
int interrupt_signal() noexcept;
// 128 + the signal, the shell's status of a process the signal ended.
int interrupted_exit_status() noexcept;
// "SIGINT", "SIGTERM" (or "" when none).
const char* interrupt_signal_name() noexcept;

// While one exists, a signal ends the process at once as if uncaught: for
// work that cannot stop early (worker threads that do not poll) and whose
// output is written only at its end. A signal already caught ends it at
// construction.
class ImmediateInterrupts {
 public:
  ImmediateInterrupts();
  ~ImmediateInterrupts();
  ImmediateInterrupts(const ImmediateInterrupts&) = delete;
  ImmediateInterrupts& operator=(const ImmediateInterrupts&) = delete;
};

}  // namespace cvt::files
