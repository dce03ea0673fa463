// A program the harness starts for a run and stops after it: the plant
// (--plant-cmd) or the controller under test (--controller-cmd),
// docs/sil.md#external-lockstep. Host only (POSIX).
#pragma once

#include <sys/types.h>

#include <string>

namespace cvt::sil::harness {

class ChildProcess {
 public:
  ChildProcess() = default;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() { stop(); }

  // Runs `/bin/sh -c command` in its own process group, its stdout and
  // stderr into `log` (appended); false (with error()) when it cannot be
  // started.
  bool start(const std::string& command, const std::string& log);
  // Still running? Reaps it if it has ended.
  bool running();
  // SIGTERM to its process group, SIGKILL after `grace_ms`; returns the
  // exit description ("exit 0", "signal 15", ...).
  std::string stop(int grace_ms = 5000);
  const std::string& error() const { return error_; }
  // How it ended, once it has.
  const std::string& ended() const { return ended_; }
  const std::string& command() const { return command_; }

 private:
  void record(int status);
  pid_t pid_ = -1;
  std::string command_, error_, ended_;
};

}  // namespace cvt::sil::harness
