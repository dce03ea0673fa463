#include "cvtplant/sil/harness/child_process.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>

namespace cvt::sil::harness {

bool ChildProcess::start(const std::string& command, const std::string& log) {
  command_ = command;
  ended_.clear();
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    error_ = log + ": " + std::strerror(errno);
    return false;
  }
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) {
    error_ = std::string("fork: ") + std::strerror(errno);
    close(fd);
    return false;
  }
  if (pid == 0) {
    setpgid(0, 0);
    dup2(fd, 1);
    dup2(fd, 2);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);
  close(fd);
  pid_ = pid;
  return true;
}

void ChildProcess::record(int status) {
  if (WIFEXITED(status)) ended_ = "exit " + std::to_string(WEXITSTATUS(status));
  else if (WIFSIGNALED(status)) ended_ = "signal " + std::to_string(WTERMSIG(status));
  else ended_ = "ended";
  pid_ = -1;
}

bool ChildProcess::running() {
  if (pid_ < 0) return false;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
    record(status);
    return false;
  }
  return true;
}

std::string ChildProcess::stop(int grace_ms) {
  if (!running()) return ended_;
  kill(-pid_, SIGTERM);
  for (int waited = 0; waited < grace_ms; waited += 10) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      record(status);
      return ended_;
    }
    const timespec ts{0, 10000000};
    nanosleep(&ts, nullptr);
  }
  kill(-pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
  record(status);
  ended_ += " (killed after " + std::to_string(grace_ms) + " ms)";
  return ended_;
}

}  // namespace cvt::sil::harness
