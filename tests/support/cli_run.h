// Runs the `snh` command line this build made (SNH_CLI_BINARY) with arguments,
// for the tests of its output and exit status.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace snh::test {

struct CliRun {
  int status = -1;
  std::string output;  // stdout and stderr
};

inline CliRun run_cli(const std::string& arguments) {
  CliRun r;
  FILE* pipe = popen((std::string(SNH_CLI_BINARY) + " " + arguments + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace snh::test
