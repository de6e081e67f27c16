// Virtual-time speed: simulated seconds per wall-clock second of a line in steady state — N drives
// (a6b, ds5c1, ds1000a in turn) in Op with DC at 1 ms, enabled in csp following a sine with their
// default plants, the project master exchanging process data every cycle (bench/capacity/csp_line.hpp).
//
//   bench_virtual_speed [--drives N]... [--seconds S] [--cycle-us C]
//
// Bring-up (scan, Pre-Op, DC, Op, enabling) and 1000 cycles after it are not timed: it is start-up, not steady state. One
// line per N: drives, simulated seconds, wall seconds, CPU seconds, ratio (simulated / wall and
// simulated / CPU). Exit 0; 1 if a line did not stay in Op with every drive enabled.
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "bench/capacity/csp_line.hpp"

namespace {

double seconds(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The timed part, apart so a profiler can collect it alone
// (valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*run_cycles*').
[[gnu::noinline]] void run_cycles(vdrive::bench::CspLine& line, std::uint64_t cycles) {
  for (std::uint64_t k = 0; k < cycles; ++k) line.cycle();
}

int usage(const char* what) {
  std::fprintf(stderr, "bench_virtual_speed: %s\nusage: bench_virtual_speed [--drives N]... [--seconds S] [--cycle-us C]\n", what);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> drives;
  double sim_seconds = 10.0;
  long cycle_us = 1000;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return usage(("missing value after " + arg).c_str());
    const char* value = argv[++i];
    char* end = nullptr;
    if (arg == "--drives") {
      const long n = std::strtol(value, &end, 10);
      if (*end != '\0' || n < 1 || n > 256) return usage("--drives takes 1..256");
      drives.push_back(static_cast<std::size_t>(n));
    } else if (arg == "--seconds") {
      sim_seconds = std::strtod(value, &end);
      if (*end != '\0' || !(sim_seconds > 0)) return usage("--seconds takes a positive number");
    } else if (arg == "--cycle-us") {
      cycle_us = std::strtol(value, &end, 10);
      if (*end != '\0' || cycle_us < 125) return usage("--cycle-us takes 125 or more");
    } else {
      return usage(("unknown option " + arg).c_str());
    }
  }
  if (drives.empty()) drives = {1, 8};

  int status = 0;
  std::printf("%-6s %-10s %-10s %-10s %-12s %-12s\n", "drives", "sim_s", "wall_s", "cpu_s", "sim/wall", "sim/cpu");
  for (const std::size_t n : drives) {
    try {
      vdrive::bench::CspLine line(vdrive::bench::product_mix(n, false));
      const vdrive::Nanos cycle = cycle_us * 1000;
      line.bring_up(cycle);
      const auto cycles = static_cast<std::uint64_t>(sim_seconds * 1e9 / static_cast<double>(cycle));
      // Untimed warm-up: the first cycles after bring-up include one-off catch-up work.
      run_cycles(line, 1000);
      const vdrive::Nanos t0 = line.clock().now();
      const double wall0 = seconds(CLOCK_MONOTONIC), cpu0 = seconds(CLOCK_PROCESS_CPUTIME_ID);
      run_cycles(line, cycles);
      const double wall = seconds(CLOCK_MONOTONIC) - wall0, cpu = seconds(CLOCK_PROCESS_CPUTIME_ID) - cpu0;
      const double sim = 1e-9 * static_cast<double>(line.clock().now() - t0);
      std::printf("%-6zu %-10.3f %-10.3f %-10.3f %-12.1f %-12.1f\n", n, sim, wall, cpu, sim / wall, sim / cpu);
      if (line.stats().wrong_wkc != 0 || !line.drives_enabled()) {
        std::fprintf(stderr, "%zu drives: %llu wrong working counters or a drive not enabled\n", n,
                     static_cast<unsigned long long>(line.stats().wrong_wkc));
        status = 1;
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%zu drives: %s\n", n, e.what());
      status = 1;
    }
  }
  return status;
}
