// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the plain benchmark programs (bench_load, bench_bag) share: each measurement runs in a
// child process of its own, so that nothing else inflates its memory, and reads its own peak RSS.

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

namespace sg::bench {

// A /proc/self/status value in kB ("VmRSS", "VmHWM"), or -1.
inline long statusKb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) return std::strtol(line.c_str() + prefix.size(), nullptr, 10);
  }
  return -1;
}

inline double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Runs `body` in a child process and waits for it; false when it failed (its error on stderr,
// prefixed with `program`).
template <class Body>
bool inChild(const char* program, Body body) {
  const pid_t pid = fork();
  if (pid < 0) return false;
  if (pid == 0) {
    try {
      body();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", program, e.what());
      _exit(1);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace sg::bench
