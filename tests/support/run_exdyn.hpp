// Test helper: runs the exdyn executable with arguments and captures its exit
// status and output (stdout and stderr together). Standard output is a pipe,
// so exdyn behaves as when it is not on a terminal.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace exdyn::testing {

struct CommandResult {
  int status = -1;     // exit status; -1 if the process did not exit normally
  std::string output;  // stdout and stderr
};

// `environment`: assignments put before the command (e.g. "LD_DEBUG=files").
inline CommandResult run_exdyn(const std::string& arguments, const std::string& environment = "") {
  const std::string command = (environment.empty() ? "" : environment + " ") + std::string(EXDYN_EXECUTABLE) +
                              " " + arguments + " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace exdyn::testing
