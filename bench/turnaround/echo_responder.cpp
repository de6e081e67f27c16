// bench_echo_responder: the floor of the frame-turnaround benchmark. A raw socket on one end of a
// veth pair that sends every EtherCAT frame straight back, unchanged: the least any responder on
// this path can cost. Same socket as vdrive's (RawSocketLink: qdisc bypass, promiscuous), and the
// same speed options, so the comparison differs only in what happens between receive and send.
// Runs until SIGINT/SIGTERM; prints how many frames it echoed.
#include <CLI/CLI.hpp>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>

#include "vdrive/link/raw_socket_link.hpp"
#include "vdrive/runtime/time_slice.hpp"

namespace {
std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }
}  // namespace

int main(int argc, char** argv) {
  std::string iface;
  long busy_poll_us = 0, wake_us = 0, slice_us = 0;
  bool no_rx_ring = false;
  int rt_priority = 0, cpu = -1;
  CLI::App app{"Frame turnaround benchmark: a bare raw-socket echo (the floor)"};
  app.add_option("--iface,-i", iface, "Interface to answer on")->required();
  app.add_option("--busy-poll-us", busy_poll_us, "Spin this long on the socket before sleeping (default 0)")->check(CLI::Range(0L, 1'000'000L));
  app.add_option("--rt-priority", rt_priority, "SCHED_FIFO priority 1..99 and locked memory")->check(CLI::Range(1, 99));
  app.add_option("--cpu", cpu, "Pin to this CPU")->check(CLI::Range(0, 1023));
  app.add_option("--slice-us", slice_us, "Time slice in us, as vdrive run --slice-us (default: the kernel's)")
      ->check(CLI::Range(100L, 100'000L));
  app.add_flag("--no-rx-ring", no_rx_ring, "One recvfrom per frame instead of the receive ring, as vdrive run --no-rx-ring");
  app.add_option("--wake-us", wake_us,
                 "Wait at most US microseconds at a time, as vdrive wakes for its control steps (default: 100 ms)")
      ->check(CLI::Range(1L, 100'000L));
  CLI11_PARSE(app, argc, argv);

  // No SA_RESTART: a signal ends the wait in receive() at once.
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);

  try {
    vdrive::link::RawSocketLink::Options lo;
    lo.busy_poll = static_cast<vdrive::Nanos>(busy_poll_us) * 1000;
    lo.rx_ring = !no_rx_ring;
    vdrive::link::RawSocketLink link(iface, lo);
    if (cpu >= 0) {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(static_cast<unsigned>(cpu), &set);
      if (::sched_setaffinity(0, sizeof set, &set) != 0) std::perror("--cpu");
    }
    if (slice_us > 0) {
      if (const int err = vdrive::runtime::set_time_slice(slice_us * 1000); err != 0) {
        std::fprintf(stderr, "bench_echo_responder: --slice-us: %s\n", std::strerror(err));
        return 2;
      }
    }
    if (rt_priority > 0) {
      sched_param p{};
      p.sched_priority = rt_priority;
      if (::sched_setscheduler(0, SCHED_FIFO, &p) != 0) std::perror("--rt-priority");
      ::mlockall(MCL_CURRENT | MCL_FUTURE);
    }
    std::array<std::uint8_t, vdrive::link::kMaxFrame> buf{};
    unsigned long long echoed = 0;
    while (!g_stop.load(std::memory_order_relaxed)) {
      const std::size_t n = link.receive(buf, wake_us > 0 ? wake_us * 1000 : 100'000'000);
      if (n != 0 && link.send(std::span<const std::uint8_t>(buf.data(), n))) ++echoed;
    }
    std::fprintf(stderr, "bench_echo_responder: %llu frames echoed\n", echoed);
    return 0;
  } catch (const vdrive::link::LinkError& e) {
    std::fprintf(stderr, "bench_echo_responder: %s\n", e.what());
    return 2;
  }
}
