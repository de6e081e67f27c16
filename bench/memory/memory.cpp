// Resident memory of a line of N drives in one process (a6b, ds5c1, ds1000a in turn): RSS from
// /proc/self/statm before the line exists, after it is built (profiles, dictionaries, ESCs,
// firmware, plants: start-up) and after the master took it to Op with DC at 1 ms and enabled every
// drive in csp (process data, mailboxes, first ODE steps), then after 5,000 more cycles.
//
//   bench_memory --drives N
//
// Output: "drives N rss_empty_kib A rss_built_kib B rss_op_kib C rss_steady_kib D". The per-drive
// cost is the slope of these over N (bench/memory/run.sh fits it). Exit 1 if Op is not reached.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "bench/capacity/csp_line.hpp"

namespace {

long rss_kib() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

}  // namespace

int main(int argc, char** argv) {
  char* end = nullptr;
  const long n = argc == 3 && std::string(argv[1]) == "--drives" ? std::strtol(argv[2], &end, 10) : 0;
  if (n < 1 || n > 512 || end == nullptr || *end != '\0') {
    std::fprintf(stderr, "usage: bench_memory --drives N (1..512)\n");
    return 2;
  }
  const long empty = rss_kib();
  try {
    vdrive::bench::CspLine line(vdrive::bench::product_mix(static_cast<std::size_t>(n), false));
    const long built = rss_kib();
    line.bring_up(1'000'000);
    const long op = rss_kib();
    for (int k = 0; k < 5000; ++k) line.cycle();
    std::printf("drives %ld rss_empty_kib %ld rss_built_kib %ld rss_op_kib %ld rss_steady_kib %ld\n", n, empty, built, op,
                rss_kib());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_memory: %ld drives: %s\n", n, e.what());
    return 1;
  }
  return 0;
}
