// bench_spawn: run one program as bench/e2e.py measures it, and report its
// wall time and its own peak resident memory.
//
//   bench_spawn REPORT_FD PROGRAM [ARGS...]
//
// Forks, executes PROGRAM (looked up in PATH) with ARGS, waits for it
// (wait4) and writes "SECONDS MAXRSS_KIB STATUS\n" to the file descriptor
// REPORT_FD, which the child does not inherit.  STATUS is the exit status,
// or 128 + the signal that ended the child; 127 when PROGRAM could not be
// executed.  The clock (CLOCK_MONOTONIC) runs from just before fork to just
// after wait4 returns.  Standard input, output and error are the child's.
// bench_spawn exits 0 when it could report, 125 otherwise.
//
// Why a program of its own: Python starts a child with vfork (or
// posix_spawn), and when the child executes the program, Linux counts the
// peak resident memory of the address space it leaves (the parent's) in
// the child's ru_maxrss.  Every program started from a Python process that
// holds 70 MiB then reports at least 70 MiB (`/bin/true` started from
// python3 reports python3's own peak).  A child forked from this small
// program starts from a copy of its few pages, so ru_maxrss is the
// program's own.
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_spawn REPORT_FD PROGRAM [ARGS...]\n");
    return 125;
  }
  char* end = nullptr;
  const long fd = std::strtol(argv[1], &end, 10);
  if (*argv[1] == '\0' || *end != '\0' || fd < 0 || fcntl(int(fd), F_GETFD) == -1) {
    std::fprintf(stderr, "bench_spawn: '%s' is not an open file descriptor\n", argv[1]);
    return 125;
  }
  (void)fcntl(int(fd), F_SETFD, FD_CLOEXEC);
  timespec t0{}, t1{};
  clock_gettime(CLOCK_MONOTONIC, &t0);
  const pid_t pid = fork();
  if (pid < 0) {
    std::perror("bench_spawn: fork");
    return 125;
  }
  if (pid == 0) {
    execvp(argv[2], argv + 2);
    std::fprintf(stderr, "bench_spawn: cannot execute %s: %s\n", argv[2], std::strerror(errno));
    _exit(127);
  }
  int status = 0;
  rusage ru{};
  pid_t got;
  do got = wait4(pid, &status, 0, &ru);
  while (got < 0 && errno == EINTR);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  if (got != pid) {
    std::perror("bench_spawn: wait4");
    return 125;
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  const double seconds = double(t1.tv_sec - t0.tv_sec) + double(t1.tv_nsec - t0.tv_nsec) * 1e-9;
  char line[96];
  const int n = std::snprintf(line, sizeof line, "%.9f %ld %d\n", seconds, ru.ru_maxrss, code);
  if (n <= 0 || write(int(fd), line, std::size_t(n)) != n) {
    std::perror("bench_spawn: writing the report");
    return 125;
  }
  return 0;
}
