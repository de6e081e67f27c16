#include "bench/turnaround/round_trips.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <numeric>

namespace vdrive::bench {
namespace {

// Nearest rank: the smallest sample with at least q of all samples at or below it.
Nanos percentile(const std::vector<Nanos>& sorted, double q) {
  if (sorted.empty()) return 0;
  auto rank = static_cast<std::size_t>(q * static_cast<double>(sorted.size()) + 0.999999);
  rank = std::clamp<std::size_t>(rank, 1, sorted.size());
  return sorted[rank - 1];
}

}  // namespace

RoundTripSummary RoundTrips::summarize() {
  std::sort(samples_.begin(), samples_.end());
  RoundTripSummary s;
  s.sent = sent_;
  s.answered = samples_.size();
  s.wrong_wkc = wrong_wkc_;
  if (samples_.empty()) return s;
  s.min = samples_.front();
  s.max = samples_.back();
  s.p50 = percentile(samples_, 0.50);
  s.p90 = percentile(samples_, 0.90);
  s.p99 = percentile(samples_, 0.99);
  s.p999 = percentile(samples_, 0.999);
  s.mean = static_cast<double>(std::accumulate(samples_.begin(), samples_.end(), Nanos{0})) /
           static_cast<double>(samples_.size());
  return s;
}

std::string to_json(const std::string& label, const std::string& mode, const RoundTripSummary& s) {
  return fmt::format(
      R"({{"label":"{}","mode":"{}","sent":{},"answered":{},"lost":{},"wrong_wkc":{},)"
      R"("min_ns":{},"p50_ns":{},"p90_ns":{},"p99_ns":{},"p999_ns":{},"max_ns":{},"mean_ns":{:.0f}}})",
      label, mode, s.sent, s.answered, s.lost(), s.wrong_wkc, s.min, s.p50, s.p90, s.p99, s.p999, s.max, s.mean);
}

}  // namespace vdrive::bench
