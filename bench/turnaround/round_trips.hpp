#pragma once
// Round-trip times of the measured frames, recorded into storage sized before the run (the
// measuring loop allocates nothing), and their distribution afterwards.
#include <cstdint>
#include <string>
#include <vector>

#include "common/clock.hpp"

namespace vdrive::bench {

struct RoundTripSummary {
  std::uint64_t sent = 0;
  std::uint64_t answered = 0;   // replies recorded (lost = sent - answered)
  std::uint64_t wrong_wkc = 0;  // answered, but a working counter was not the expected one
  Nanos p50 = 0, p90 = 0, p99 = 0, p999 = 0, max = 0, min = 0;
  double mean = 0;
  std::uint64_t lost() const { return sent - answered; }
};

class RoundTrips {
public:
  explicit RoundTrips(std::size_t capacity) { samples_.reserve(capacity); }
  // No allocation while fewer than `capacity` samples were added; later ones are not kept.
  void add(Nanos round_trip) {
    if (samples_.size() < samples_.capacity()) samples_.push_back(round_trip);
  }
  void count_sent() { ++sent_; }
  void count_wrong_wkc() { ++wrong_wkc_; }

  // Nearest-rank percentiles over the recorded samples (sorts them).
  RoundTripSummary summarize();

private:
  std::vector<Nanos> samples_;
  std::uint64_t sent_ = 0, wrong_wkc_ = 0;
};

// One JSON object: label, mode, counts, percentiles in ns.
std::string to_json(const std::string& label, const std::string& mode, const RoundTripSummary& s);

}  // namespace vdrive::bench
