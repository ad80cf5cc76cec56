// Tests that run a command line through the shell: its standard output and
// its exit status (128 + the signal's number when a signal ended it).
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

struct ShellOutput {
  int status = -1;  // -1: the shell could not be started
  std::string out;
};

inline ShellOutput shell_stdout(const std::string& line) {
  ShellOutput r;
  FILE* p = ::popen(line.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;) r.out.append(buf.data(), n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  return r;
}
