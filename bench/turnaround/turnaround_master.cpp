// bench_turnaround_master: the measuring end of the frame-turnaround benchmark. On one
// end of a veth pair it sends a master's per-cycle frames (master/cycle_frames.hpp: the image cut
// into LRW pieces as the project master's cyclic task cuts it, FRMW and BRD in the first frame) to
// whatever answers on the other end and records each round trip, first send -> last matching
// reply, on CLOCK_MONOTONIC.
//
//   --line op    the far end is a line of slaves (vdrive, KickCAT's network_simulator): the project
//                master takes it to Op first (scan, PDOs, FMMUs/SMs, DC, Safe-Op, Op) so the LRW
//                hits mapped process data; every working counter is then checked.
//   --line echo  the far end returns frames unchanged (echo_responder, the floor): no start-up,
//                the image is --image-bytes long, the working counters must come back 0.
//
// One line of text and (with --json) one JSON object per run. Exit: 0 measured, 1 the line did not
// reach Op or nothing answered, 2 bad arguments or interface (docs/performance.md).
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "bench/turnaround/round_trips.hpp"
#include "master/cycle_frames.hpp"
#include "master/lrw_split.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "master/transport.hpp"
#include "vdrive/link/raw_socket_link.hpp"

namespace {

using vdrive::Nanos;
using vdrive::master::CycleFrames;
using vdrive::master::SlaveImage;
using vdrive::bench::RoundTrips;

struct Options {
  std::string iface;
  std::string line = "op";
  std::string label;
  std::string json;
  unsigned rate_hz = 1000;       // 0: back-to-back
  std::size_t samples = 10000;
  std::size_t warmup = 500;
  std::size_t image_bytes = 64;  // echo only
  long timeout_us = 10000;
  long busy_poll_us = 0;
  int rt_priority = 0;
  int cpu = -1;
  bool dc = true;
};

Nanos now_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<Nanos>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void sleep_until(Nanos t) {
  const timespec ts{static_cast<time_t>(t / 1'000'000'000), static_cast<long>(t % 1'000'000'000)};
  while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

void set_scheduling(const Options& o) {
  if (o.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(o.cpu), &set);
    if (::sched_setaffinity(0, sizeof set, &set) != 0) throw std::runtime_error(fmt::format("--cpu {}: {}", o.cpu, std::strerror(errno)));
  }
  if (o.rt_priority > 0) {
    sched_param p{};
    p.sched_priority = o.rt_priority;
    if (::sched_setscheduler(0, SCHED_FIFO, &p) != 0) throw std::runtime_error(fmt::format("--rt-priority: {}", std::strerror(errno)));
    if (::mlockall(MCL_CURRENT | MCL_FUTURE) != 0) throw std::runtime_error(fmt::format("mlockall: {}", std::strerror(errno)));
  }
}

struct Line {
  std::uint32_t logical_start = 0;
  std::size_t image_bytes = 0;
  std::uint16_t reference = 0x1001;
  std::vector<SlaveImage> slaves;  // empty: an echo, every working counter stays 0
};

// The line in Op through the project master (vdrive-master op's way), left there.
std::optional<Line> bring_to_op(vdrive::link::Link& link, const Options& o) {
  vdrive::master::Master master(link);
  const std::size_t n = master.scan();
  if (n == 0) {
    std::fprintf(stderr, "bench_turnaround_master: no slave answers on %s\n", o.iface.c_str());
    return std::nullopt;
  }
  vdrive::master::OpRunOptions op;
  op.cycle = 1'000'000;
  op.reply_timeout = 200'000'000;  // start-up only; a loaded host can be slow
  op.dc = o.dc;
  op.drift_frames = 1000;
  op.cycles = 100;
  op.back_to_init = false;
  const vdrive::master::OpRunResult r = vdrive::master::run_to_op(master, op);
  for (const std::string& note : r.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
  if (!r.reached_op) {
    std::fprintf(stderr, "bench_turnaround_master: the line did not reach Op: %s\n", r.error.c_str());
    return std::nullopt;
  }
  Line line;
  line.logical_start = r.layout.logical_start;
  line.image_bytes = r.layout.size();
  line.reference = r.reference_station != 0 ? r.reference_station : master.slaves().front().station;
  line.slaves = r.layout.slaves;
  return line;
}

int measure(vdrive::link::Link& link, const Options& o, const Line& line) {
  CycleFrames cycle(vdrive::master::kDefaultMasterMac,
                    vdrive::master::split_process_image(line.logical_start, static_cast<std::uint32_t>(line.image_bytes),
                                                        line.slaves, CycleFrames::kMaxLrwBytes),
                    line.reference, static_cast<std::uint16_t>(line.slaves.size()));
  // The Transport sends a cycle's frames and matches their replies (one attempt: a late cycle is a
  // lost one); the round trip is timed here, around it.
  const vdrive::MonotonicClock clock;
  vdrive::master::Transport transport(link, clock);
  const std::vector<std::uint8_t> image(line.image_bytes, 0);  // outputs stay 0: the drives stay put
  const std::uint64_t all = cycle.count() == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << cycle.count()) - 1;
  RoundTrips trips(o.samples);
  const Nanos period = o.rate_hz == 0 ? 0 : 1'000'000'000 / o.rate_hz;
  const Nanos timeout = static_cast<Nanos>(o.timeout_us) * 1000;
  Nanos next = now_ns();
  for (std::size_t n = 0; n < o.warmup + o.samples; ++n) {
    if (period != 0) {
      next += period;
      sleep_until(next);
    }
    const bool measured = n >= o.warmup;
    if (measured) trips.count_sent();
    // The round trip of a cycle: first frame built and sent -> last reply in (one frame up to ~47 drives
    // with the default mappings).
    const Nanos t0 = now_ns();
    cycle.build(image, transport.next_indexes(cycle.indexes_per_cycle()));
    const std::uint64_t answered = transport.exchange(cycle.frames(), timeout);
    const Nanos t1 = now_ns();
    if (answered != all || !measured) continue;  // lost
    trips.add(t1 - t0);
    bool wkc_ok = true;
    for (std::size_t i = 0; i < cycle.count(); ++i) wkc_ok = wkc_ok && cycle.counters_ok(i);
    if (!wkc_ok) trips.count_wrong_wkc();
  }
  const vdrive::bench::RoundTripSummary s = trips.summarize();
  const std::string mode = o.rate_hz == 0 ? "back-to-back" : fmt::format("{}Hz", o.rate_hz);
  const std::string label = o.label.empty() ? o.line : o.label;
  std::printf("%-14s %-12s slaves %3zu image %4zu B in %zu frame(s)  sent %6llu lost %4llu wrong-wkc %4llu  p50 %7.1f  p99 %7.1f  p99.9 %7.1f  max %8.1f us\n",
              label.c_str(), mode.c_str(), line.slaves.size(), line.image_bytes, cycle.count(), static_cast<unsigned long long>(s.sent),
              static_cast<unsigned long long>(s.lost()), static_cast<unsigned long long>(s.wrong_wkc), s.p50 / 1e3, s.p99 / 1e3,
              s.p999 / 1e3, s.max / 1e3);
  if (!o.json.empty()) {
    std::ofstream out(o.json, std::ios::app);
    std::string j = vdrive::bench::to_json(label, mode, s);
    j.insert(j.size() - 1, fmt::format(R"(,"slaves":{},"image_bytes":{},"frames":{})", line.slaves.size(), line.image_bytes, cycle.count()));
    out << j << '\n';
    if (!out) throw std::runtime_error("--json: cannot write " + o.json);
  }
  return s.answered == 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Frame turnaround benchmark: the master end (docs/performance.md)"};
  app.add_option("--iface,-i", o.iface, "Interface to the line (one end of a veth pair)")->required();
  app.add_option("--line", o.line, "op: take the line to Op first; echo: the far end echoes")->check(CLI::IsMember({"op", "echo"}));
  app.add_option("--label", o.label, "Name of this run in the output");
  app.add_option("--json", o.json, "Append one JSON object with the results to FILE");
  app.add_option("--rate-hz", o.rate_hz, "Frames per second, paced with clock_nanosleep; 0: back-to-back (default 1000)")
      ->check(CLI::Range(0u, 100000u));
  app.add_option("--samples", o.samples, "Measured frames (default 10000)")->check(CLI::Range(std::size_t{1}, std::size_t{10'000'000}));
  app.add_option("--warmup", o.warmup, "Frames sent before measuring (default 500)");
  app.add_option("--image-bytes", o.image_bytes, "--line echo: LRW length (default 64)")->check(CLI::Range(std::size_t{1}, CycleFrames::kMaxLrwBytes * (CycleFrames::kMaxFrames - 1)));
  app.add_option("--timeout-us", o.timeout_us, "A reply later than this is lost (default 10000)")->check(CLI::Range(1L, 10'000'000L));
  app.add_option("--busy-poll-us", o.busy_poll_us, "Spin this long on the socket before sleeping (default 0)")->check(CLI::Range(0L, 1'000'000L));
  app.add_option("--rt-priority", o.rt_priority, "SCHED_FIFO priority 1..99 and locked memory")->check(CLI::Range(1, 99));
  app.add_option("--cpu", o.cpu, "Pin to this CPU")->check(CLI::Range(0, 1023));
  app.add_flag("!--no-dc", o.dc, "--line op: configure without distributed clocks");
  CLI11_PARSE(app, argc, argv);

  try {
    vdrive::link::RawSocketLink::Options lo;
    lo.busy_poll = static_cast<Nanos>(o.busy_poll_us) * 1000;
    vdrive::link::RawSocketLink link(o.iface, lo);
    Line line;
    if (o.line == "op") {
      const std::optional<Line> op = bring_to_op(link, o);
      if (!op) return 1;
      line = *op;
    } else {
      line.image_bytes = o.image_bytes;
    }
    set_scheduling(o);
    return measure(link, o, line);
  } catch (const vdrive::link::LinkError& e) {
    std::fprintf(stderr, "bench_turnaround_master: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_turnaround_master: %s\n", e.what());
    return 1;
  }
}
