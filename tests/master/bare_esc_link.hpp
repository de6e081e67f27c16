#pragma once
// One product's ESC with no firmware behind it, as a Link for master tests: frames go through
// Esc::process_frame in virtual time, and `after_frame` plays the firmware (e.g. CoeTestServer).
// Used where a test needs to control exactly what the slave's mailbox answers.
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::master::test {

class BareEscLink final : public link::Link {
public:
  static constexpr Nanos kRoundTrip = 10'000;

  explicit BareEscLink(const std::string& product)
      : esc_(profile::make_esc_config(profile::load_profile(product)), clock_) {
    esc_.reset();
    esc::PortLinks links;
    links.port[0] = true;
    esc_.set_links(links);
  }

  bool send(std::span<const std::uint8_t> frame) override {
    std::vector<std::uint8_t> f(frame.begin(), frame.end());
    if (f.size() < 16) return true;
    esc::FrameTiming timing;
    timing.port0_rx = clock_.now();
    if (!esc_.process_frame(std::span(f).subspan(14), timing)) return true;  // destroyed
    if (!drop_reply || !drop_reply(f)) replies_.push_back(std::move(f));
    return true;
  }

  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    if (replies_.empty()) {
      clock_.advance(std::max<Nanos>(timeout, 0));
      esc_.tick(clock_.now());
      if (after_frame) after_frame();
      return 0;
    }
    clock_.advance(kRoundTrip);
    esc_.tick(clock_.now());
    if (after_frame) after_frame();
    auto f = std::move(replies_.front());
    replies_.pop_front();
    std::copy(f.begin(), f.end(), buf.begin());
    return f.size();
  }

  std::function<void()> after_frame;
  std::function<bool(std::span<const std::uint8_t>)> drop_reply;
  VirtualClock& clock() { return clock_; }
  esc::Esc& esc() { return esc_; }

private:
  VirtualClock clock_;
  esc::Esc esc_;
  std::deque<std::vector<std::uint8_t>> replies_;
};

}  // namespace vdrive::master::test
