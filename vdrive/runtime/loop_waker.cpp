#include "vdrive/runtime/loop_waker.hpp"

#include <csignal>

namespace vdrive::runtime {
namespace {
extern "C" void on_wake_signal(int) {}
}  // namespace

LoopWaker::LoopWaker() : loop_thread_(::pthread_self()) {
  struct sigaction action {};
  action.sa_handler = on_wake_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // deliberately no SA_RESTART: the wait must end
  sigaction(SIGUSR1, &action, nullptr);
}

void LoopWaker::wake() const { ::pthread_kill(loop_thread_, SIGUSR1); }

}  // namespace vdrive::runtime
