#include "master/cyclic_task.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace vdrive::master {
namespace {

// The LRW pieces of `layout`: cut on its slaves' windows, or, for a layout made by hand without
// them, one piece with the layout's own expected counter.
std::vector<LrwPiece> pieces_of(const ProcessImageLayout& layout) {
  if (!layout.slaves.empty() || layout.size() == 0) {
    return split_process_image(layout.logical_start, layout.size(), layout.slaves, CycleFrames::kMaxLrwBytes);
  }
  if (layout.size() > CycleFrames::kMaxLrwBytes) {
    throw std::invalid_argument("process image of " + std::to_string(layout.size()) +
                                " bytes without the slaves' FMMU windows: cannot split it");
  }
  return {LrwPiece{layout.logical_start, 0, static_cast<std::uint16_t>(layout.size()), layout.expected_wkc}};
}

std::uint16_t sum_expected(const std::vector<LrwPiece>& pieces) {
  unsigned sum = 0;
  for (const LrwPiece& p : pieces) sum += p.expected_wkc;
  return static_cast<std::uint16_t>(sum);
}

}  // namespace

CyclicTask::CyclicTask(Transport& transport, const ProcessImageLayout& layout, std::size_t slave_count, Nanos cycle,
                       std::uint16_t reference_station)
    : transport_(transport), inputs_from_(layout.output_bytes), slave_count_(static_cast<std::uint16_t>(slave_count)),
      cycle_(cycle), reply_timeout_(std::max<Nanos>(cycle, 1'000'000)), image_(layout.size()),
      frames_(transport.options().source, pieces_of(layout), reference_station, static_cast<std::uint16_t>(slave_count)),
      all_frames_(frames_.count() == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << frames_.count()) - 1),
      expected_wkc_(sum_expected(frames_.pieces())) {}

bool CyclicTask::run_cycle() {
  if (outputs_) outputs_(image_);
  frames_.build(image_, transport_.next_indexes(frames_.indexes_per_cycle()), requested_);
  ++stats_.cycles;
  // Every reply must be back within the cycle; a frame that is not loses its piece for this cycle.
  const std::uint64_t answered = transport_.exchange(frames_.frames(), reply_timeout_);
  bool ok = answered == all_frames_;
  unsigned wkc = 0;
  for (std::size_t i = 0; i < frames_.count(); ++i) {
    if ((answered & (std::uint64_t{1} << i)) == 0) {
      ++stats_.lost_frames;
      continue;
    }
    wkc += frames_.lrw_wkc(i);
    // Only inputs that the slaves wrote this cycle are taken; outputs stay the master's.
    if (frames_.lrw_ok(i)) {
      frames_.take_inputs(i, image_, inputs_from_);
    } else {
      ok = false;
    }
  }
  stats_.last_wkc = static_cast<std::uint16_t>(wkc);
  if (!ok) ++stats_.wrong_wkc;
  if ((answered & 1) != 0) {
    stats_.al_status = frames_.al_status();
    stats_.al_wkc = frames_.al_wkc();
    if (requested_ != 0 && all_in(static_cast<AlState>(requested_))) requested_ = 0;
  }
  if (answered != all_frames_) return false;
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
