#include "master/cyclic_task.hpp"

#include <algorithm>
#include <array>

#include "master/registers.hpp"

namespace vdrive::master {

CyclicTask::CyclicTask(Transport& transport, const ProcessImageLayout& layout, std::size_t slave_count, Nanos cycle,
                       std::uint16_t reference_station)
    : transport_(transport), layout_(layout), slave_count_(static_cast<std::uint16_t>(slave_count)), cycle_(cycle),
      reply_timeout_(std::max<Nanos>(cycle, 1'000'000)), reference_(reference_station), image_(layout.size()), frame_(transport.options().source) {}

bool CyclicTask::run_cycle() {
  if (outputs_) outputs_(image_);
  frame_.clear();
  int lrw = -1;
  if (!image_.empty()) lrw = frame_.add(Command::LRW, transport_.next_index(), layout_.logical_start, image_);
  int frmw = -1;
  if (reference_ != 0) frmw = frame_.add(Command::FRMW, transport_.next_index(), station_address(reference_, reg::kDcSystemTime), 8);
  const int brd = frame_.add(Command::BRD, transport_.next_index(), station_address(0, reg::kAlStatus), 2);
  if (requested_ != 0) {
    const std::array<std::uint8_t, 2> control{static_cast<std::uint8_t>(requested_), 0};
    frame_.add(Command::BWR, transport_.next_index(), station_address(0, reg::kAlControl), control);
  }
  (void)frmw;
  ++stats_.cycles;
  // The reply must be back within the cycle; otherwise this cycle's data is lost.
  if (!transport_.exchange(frame_, reply_timeout_)) {
    ++stats_.lost_frames;
    ++stats_.wrong_wkc;
    stats_.last_wkc = 0;
    return false;
  }
  bool ok = true;
  if (lrw >= 0) {
    const auto slot = static_cast<std::size_t>(lrw);
    stats_.last_wkc = frame_.wkc(slot);
    ok = stats_.last_wkc == layout_.expected_wkc;
    if (ok) {
      // Only inputs that the slaves wrote this cycle are taken; outputs stay the master's.
      const auto reply = frame_.data(slot);
      std::copy(reply.begin() + layout_.output_bytes, reply.end(), image_.begin() + layout_.output_bytes);
    } else {
      ++stats_.wrong_wkc;
    }
  }
  const auto al = frame_.data(static_cast<std::size_t>(brd));
  stats_.al_status = static_cast<std::uint16_t>(al[0] | (al[1] << 8));
  stats_.al_wkc = frame_.wkc(static_cast<std::size_t>(brd));
  if (requested_ != 0 && all_in(static_cast<AlState>(requested_))) requested_ = 0;
  if (inputs_) inputs_(image_);
  return ok;
}

std::uint64_t CyclicTask::run(std::uint64_t cycles, const std::function<bool()>& until) {
  const Clock& clock = transport_.clock();
  if (next_ == 0 || next_ < clock.now()) next_ = clock.now() + cycle_;
  std::uint64_t done = 0;
  while (done < cycles) {
    transport_.idle_until(next_);
    stats_.max_late = std::max(stats_.max_late, clock.now() - next_);
    run_cycle();
    ++done;
    next_ += cycle_;
    // After an overrun, skip the deadlines already missed rather than sending a burst.
    const Nanos now = clock.now();
    if (next_ <= now) next_ += ((now - next_) / cycle_ + 1) * cycle_;
    if (until && until()) break;
  }
  return done;
}

}  // namespace vdrive::master
