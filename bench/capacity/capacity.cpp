// Capacity: can one core carry N drives at bus cycle T? The line (bench/capacity/csp_line.hpp):
// N drives in Op with DC SYNC0 at T, enabled in csp following a sine with their default plants,
// the master's frames every cycle (LRW of the process image, split over frames past ~71 drives,
// + FRMW of the DC reference time + BRD AL status). The work of cycle k is the frame through the line and the firmware IRQs it raises,
// then every ESC/firmware/drive/plant timer due before the start of cycle k+1; the master's own
// share (building the frame, reading the reply: a few % of the cycle) is included.
//
//   bench_capacity --drives N --cycle-us T [--cycles K] [--realtime] [--cpu C] [--rt-priority P]
//
// Without --realtime (virtual time): the cycles run back to back and each one's CPU time (thread
// CPU clock) is recorded; a cycle whose CPU time exceeds T would miss its deadline on this core.
// With --realtime: the thread is pinned to CPU C (default 0) and, with --rt-priority, runs
// SCHED_FIFO with locked memory; cycle k starts at t0 + k*T (absolute sleep) and misses its
// deadline when its work ends after t0 + (k+1)*T (the sync event of cycle k+1). A late cycle
// starts at once (as a real line would, behind); the next ones keep their own deadlines.
//
// Output: one line "drives N cycle_us T cycles K mode M misses X p50_us p99_us p999_us max_us
// mean_us max_wake_us" (cost per cycle: CPU time in virtual mode, wall time from the later of the
// cycle's start and the wake-up in real time; max_wake_us: the worst wake-up after a cycle's
// start, 0 in virtual mode) and exit 0; exit 1
// when the line did not reach Op or lost its working counter; exit 2 for bad arguments.
#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

#include "bench/capacity/csp_line.hpp"

namespace {

long long nanos(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<long long>(ts.tv_sec) * 1'000'000'000LL + ts.tv_nsec;
}

void sleep_until(long long t) {
  timespec ts{static_cast<time_t>(t / 1'000'000'000LL), static_cast<long>(t % 1'000'000'000LL)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

int usage(const std::string& what) {
  std::fprintf(stderr,
               "bench_capacity: %s\nusage: bench_capacity --drives N --cycle-us T [--cycles K] [--realtime] [--cpu C] "
               "[--rt-priority P]\n",
               what.c_str());
  return 2;
}

bool parse_long(const char* text, long lo, long hi, long& out) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || v < lo || v > hi) return false;
  out = v;
  return true;
}

double percentile(std::vector<long long>& sorted, double p) {
  const auto i = static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1));
  return 1e-3 * static_cast<double>(sorted[i]);
}

}  // namespace

int main(int argc, char** argv) {
  long drives = 0, cycle_us = 0, cycles = 100'000, cpu = 0, rt_priority = 0;
  bool realtime = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--realtime") {
      realtime = true;
      continue;
    }
    if (i + 1 >= argc) return usage("missing value after " + arg);
    const char* v = argv[++i];
    if (arg == "--drives") {
      if (!parse_long(v, 1, 512, drives)) return usage("--drives takes 1..512");
    } else if (arg == "--cycle-us") {
      if (!parse_long(v, 125, 10'000, cycle_us)) return usage("--cycle-us takes 125..10000");
    } else if (arg == "--cycles") {
      if (!parse_long(v, 1, 100'000'000, cycles)) return usage("--cycles takes 1..100000000");
    } else if (arg == "--cpu") {
      if (!parse_long(v, 0, 1023, cpu)) return usage("--cpu takes a CPU number");
    } else if (arg == "--rt-priority") {
      if (!parse_long(v, 1, 99, rt_priority)) return usage("--rt-priority takes 1..99");
    } else {
      return usage("unknown option " + arg);
    }
  }
  if (drives == 0 || cycle_us == 0) return usage("--drives and --cycle-us are required");

  // Single core: everything (the line, the master, this loop) on one CPU.
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<int>(cpu), &set);
  if (sched_setaffinity(0, sizeof set, &set) != 0) {
    std::fprintf(stderr, "bench_capacity: cannot pin to CPU %ld: %s\n", cpu, std::strerror(errno));
    return 2;
  }

  const vdrive::Nanos cycle = cycle_us * 1000;
  // Only the A6B runs cycles below 1 ms (DS5C1 and DS1000A-EC: 1 ms and up).
  vdrive::bench::CspLine line(vdrive::bench::product_mix(static_cast<std::size_t>(drives), cycle < 1'000'000));
  try {
    line.bring_up(cycle);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_capacity: %ld drives at %ld us: %s\n", drives, cycle_us, e.what());
    return 1;
  }
  for (int k = 0; k < 1000; ++k) line.cycle();  // warm-up, untimed

  if (realtime && rt_priority > 0) {
    sched_param sp{};
    sp.sched_priority = static_cast<int>(rt_priority);
    if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0 || mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
      std::fprintf(stderr, "bench_capacity: --rt-priority: %s\n", std::strerror(errno));
      return 2;
    }
  }

  std::vector<long long> cost(static_cast<std::size_t>(cycles));
  long long misses = 0;
  long long max_wake = 0;  // real time: worst wake-up after a cycle's start (scheduler, VM)
  const std::uint64_t wrong_before = line.stats().wrong_wkc;
  if (realtime) {
    const long long t0 = nanos(CLOCK_MONOTONIC) + 1'000'000;
    for (long k = 0; k < cycles; ++k) {
      const long long start = t0 + k * cycle;
      sleep_until(start);
      const long long woke = nanos(CLOCK_MONOTONIC);
      max_wake = std::max(max_wake, woke - start);
      const long long begun = std::max(start, woke);
      line.cycle();
      const long long end = nanos(CLOCK_MONOTONIC);
      cost[static_cast<std::size_t>(k)] = end - begun;
      if (end > start + cycle) ++misses;
    }
  } else {
    for (long k = 0; k < cycles; ++k) {
      const long long begun = nanos(CLOCK_THREAD_CPUTIME_ID);
      line.cycle();
      const long long c = nanos(CLOCK_THREAD_CPUTIME_ID) - begun;
      cost[static_cast<std::size_t>(k)] = c;
      if (c > cycle) ++misses;
    }
  }
  double mean = 0;
  for (const long long c : cost) mean += static_cast<double>(c);
  mean = 1e-3 * mean / static_cast<double>(cost.size());
  std::sort(cost.begin(), cost.end());
  std::printf("drives %ld cycle_us %ld cycles %ld mode %s misses %lld p50_us %.1f p99_us %.1f p999_us %.1f max_us %.1f mean_us %.1f max_wake_us %.1f\n",
              drives, cycle_us, cycles, realtime ? "realtime" : "virtual", misses, percentile(cost, 0.5),
              percentile(cost, 0.99), percentile(cost, 0.999), 1e-3 * static_cast<double>(cost.back()), mean,
              1e-3 * static_cast<double>(max_wake));
  if (line.stats().wrong_wkc != wrong_before || !line.drives_enabled()) {
    std::fprintf(stderr, "bench_capacity: wrong working counters or a drive not enabled during the run\n");
    return 1;
  }
  return 0;
}
