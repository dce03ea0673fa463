// SIGINT and SIGTERM: the first sets the flag, a second ends the process
// (docs/cli.md#interruption). Each case runs in a child process, which
// signals itself.
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <functional>

#include "cvtplant/files/interrupt.hpp"

namespace f = cvt::files;

namespace {

// Runs body in a child and returns its wait status.
int in_child(const std::function<int()>& body) {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(body());
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

}  // namespace

TEST_SUITE("interrupt") {
  TEST_CASE("no signal: no flag") {
    CHECK_FALSE(f::interrupted());
    CHECK(f::interrupt_signal() == 0);
    CHECK(std::strcmp(f::interrupt_signal_name(), "") == 0);
  }

  TEST_CASE("the first SIGINT sets the flag and the process goes on; status 130") {
    const int st = in_child([] {
      f::catch_interrupts();
      std::raise(SIGINT);
      const bool ok = f::interrupted() && f::interrupt_signal() == SIGINT && f::interrupted_exit_status() == 130 &&
                      std::strcmp(f::interrupt_signal_name(), "SIGINT") == 0;
      return ok ? 0 : 1;
    });
    REQUIRE(WIFEXITED(st));
    CHECK(WEXITSTATUS(st) == 0);
  }

  TEST_CASE("SIGTERM: status 143, and a second signal ends the process at once") {
    const int st = in_child([] {
      f::catch_interrupts();
      std::raise(SIGTERM);
      if (f::interrupted_exit_status() != 143) return 1;
      std::raise(SIGTERM);
      return 2;  // not reached
    });
    REQUIRE(WIFSIGNALED(st));
    CHECK(WTERMSIG(st) == SIGTERM);
  }

  TEST_CASE("inside ImmediateInterrupts a signal ends the process, also one caught before") {
    const int during = in_child([] {
      f::catch_interrupts();
      f::ImmediateInterrupts scope;
      std::raise(SIGINT);
      return 3;
    });
    REQUIRE(WIFSIGNALED(during));
    CHECK(WTERMSIG(during) == SIGINT);
    const int before = in_child([] {
      f::catch_interrupts();
      std::raise(SIGINT);
      f::ImmediateInterrupts scope;
      return 3;
    });
    REQUIRE(WIFSIGNALED(before));
    CHECK(WTERMSIG(before) == SIGINT);
    const int after = in_child([] {
      f::catch_interrupts();
      { f::ImmediateInterrupts scope; }
      std::raise(SIGINT);
      return f::interrupted() ? 0 : 1;
    });
    REQUIRE(WIFEXITED(after));
    CHECK(WEXITSTATUS(after) == 0);
  }
}
