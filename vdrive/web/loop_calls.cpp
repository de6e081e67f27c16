#include "vdrive/web/loop_calls.hpp"

#include <chrono>
#include <thread>

namespace vdrive::web {

LoopCalls::LoopCalls(std::function<void()> wake) : wake_(std::move(wake)) {}

LoopCalls::~LoopCalls() = default;

void LoopCalls::poll(Nanos now) {
  if (queue_.empty()) return;
  while (std::optional<std::shared_ptr<Job>> job = queue_.try_pop()) {
    int expected = Job::queued;
    if (!(*job)->state.compare_exchange_strong(expected, Job::running)) continue;  // its caller gave up
    (*job)->work(now);
    (*job)->state.store(Job::done, std::memory_order_release);
  }
}

bool LoopCalls::run(Work work, Nanos timeout) {
  if (closed_.load()) return false;
  auto job = std::make_shared<Job>();
  job->work = std::move(work);
  {
    const std::lock_guard<std::mutex> lock(producers_);
    std::shared_ptr<Job> queued = job;
    if (!queue_.try_push(std::move(queued))) return false;
  }
  if (wake_) wake_();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::nanoseconds(timeout);
  // Requests are rare and short: a short sleep between looks costs nothing the loop would notice.
  while (std::chrono::steady_clock::now() < deadline && !closed_.load()) {
    if (job->state.load(std::memory_order_acquire) == Job::done) return true;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  int expected = Job::queued;
  if (job->state.compare_exchange_strong(expected, Job::abandoned)) return false;
  // Already running: it refers to our stack, so wait for it to finish.
  while (job->state.load(std::memory_order_acquire) != Job::done) std::this_thread::sleep_for(std::chrono::microseconds(200));
  return true;
}

}  // namespace vdrive::web
