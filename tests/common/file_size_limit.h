// Runs a write in a child process on a "full disk": RLIMIT_FSIZE caps every
// file the child writes (writes beyond it fail with EFBIG; SIGXFSZ, whose
// default would kill the child, is ignored). The child ends through exit(),
// so the libraries' exit handlers run as they would in granasym.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <functional>
#include <string>

#include "common/error.h"

namespace granasym::testing {

struct LimitedWrite {
  enum Outcome { kFileError, kReturned, kOtherException, kKilled } outcome = kKilled;
  std::string message;  // the exception's message
  int signal = 0;       // when killed
};

inline LimitedWrite WriteWithFileSizeLimit(rlim_t limit_bytes, const std::function<void()>& write) {
  int channel[2];
  if (pipe(channel) != 0) return {};
  const pid_t child = fork();
  if (child == 0) {
    close(channel[0]);
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{limit_bytes, limit_bytes};
    setrlimit(RLIMIT_FSIZE, &limit);
    int code = LimitedWrite::kReturned;
    std::string message;
    try {
      write();
    } catch (const FileError& error) {
      code = LimitedWrite::kFileError;
      message = error.what();
    } catch (const std::exception& error) {
      code = LimitedWrite::kOtherException;
      message = error.what();
    }
    if (!message.empty() && ::write(channel[1], message.data(), message.size()) < 0) code = 9;
    close(channel[1]);
    std::exit(code);
  }
  close(channel[1]);
  LimitedWrite result;
  char buffer[4096];
  ssize_t count = 0;
  while ((count = read(channel[0], buffer, sizeof(buffer))) > 0)
    result.message.append(buffer, count);
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (WIFSIGNALED(status)) {
    result.outcome = LimitedWrite::kKilled;
    result.signal = WTERMSIG(status);
  } else {
    result.outcome = static_cast<LimitedWrite::Outcome>(WEXITSTATUS(status));
  }
  return result;
}

}  // namespace granasym::testing
