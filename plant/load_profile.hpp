#pragma once
// External load force/torque as a function of plant time: piecewise linear through (t, value)
// points, held constant before the first and after the last point.
#include <utility>
#include <vector>

namespace vdrive::plant {

inline double load_at(const std::vector<std::pair<double, double>>& points, double t) {
  if (points.empty()) return 0.0;
  if (t <= points.front().first) return points.front().second;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (t <= points[i].first) {
      const auto& [t0, v0] = points[i - 1];
      const auto& [t1, v1] = points[i];
      return t1 > t0 ? v0 + (v1 - v0) * (t - t0) / (t1 - t0) : v1;
    }
  }
  return points.back().second;
}

}  // namespace vdrive::plant
