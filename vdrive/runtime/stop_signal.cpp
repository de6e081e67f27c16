#include "vdrive/runtime/stop_signal.hpp"

#include <csignal>

namespace vdrive::runtime {
namespace {

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_termination_signal(int) { g_stop.store(true, std::memory_order_relaxed); }

}  // namespace

std::atomic<bool>& stop_on_termination_signals() {
  struct sigaction action {};
  action.sa_handler = on_termination_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // deliberately no SA_RESTART
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  return g_stop;
}

}  // namespace vdrive::runtime
