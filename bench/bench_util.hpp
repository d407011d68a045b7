#pragma once
// Small helpers shared by the benchmark programs: how loaded the machine is, the process's CPU time (the steadier
// figure on a shared machine), and running a peer's command line to read what it prints.
#include <time.h>

#include <cstdio>
#include <memory>
#include <string>

namespace tessera::bench {

/// The 1-minute load average (/proc/loadavg); 0 where it cannot be read.
inline double load_average() {
  double one = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &one) != 1) one = 0;
    std::fclose(f);
  }
  return one;
}

/// CPU seconds used by this process so far, all threads together.
inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// Runs `command` through the shell and collects its standard output in `output`. Returns its exit status as
/// pclose() reports it, or -1 when it could not be started.
inline int run_command(const std::string& command, std::string& output) {
  output.clear();
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return -1;
  char buffer[4096];
  while (size_t got = std::fread(buffer, 1, sizeof buffer, pipe.get())) output.append(buffer, got);
  return pclose(pipe.release());
}

}  // namespace tessera::bench
