// LineRecord: the later parts' slaves of a line over processes, as their own pages show them.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include "vdrive/control/part_router.hpp"
#include "vdrive/web/line_record.hpp"

namespace vdrive::web {
namespace {

using json = nlohmann::json;

// A host stall's text (runtime::describe) names its slaves as lists, "slaves 1-3,5 missed ...,
// drive 2 caught up ...": every number of a list after those words moved by `offset`.
std::string shift_stall_slaves(const std::string& text, std::size_t offset) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t list = std::string::npos;
    for (const char* word : {"slaves ", "slave ", "drives ", "drive "}) {
      const std::string_view w(word);
      if (text.compare(at, w.size(), w) == 0 && (at == 0 || text[at - 1] == ' ')) {
        list = at + w.size();
        break;
      }
    }
    if (list == std::string::npos) {
      out += text[at++];
      continue;
    }
    out.append(text, at, list - at);
    at = list;
    // N, N-M, joined by ',': stop at anything else.
    while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])) != 0) {
      std::size_t end = at;
      while (end < text.size() && end - at < 9 && std::isdigit(static_cast<unsigned char>(text[end])) != 0) ++end;
      out += std::to_string(std::stoul(text.substr(at, end - at)) + offset);
      at = end;
      if (at + 1 < text.size() && (text[at] == '-' || text[at] == ',') && std::isdigit(static_cast<unsigned char>(text[at + 1])) != 0)
        out += text[at++];
    }
  }
  return out;
}

}  // namespace

LineRecord::LaterSlave* LineRecord::later_at(std::size_t position) {
  if (position <= slaves_.size() || position > slaves_.size() + later_.size()) return nullptr;
  return &later_[position - slaves_.size() - 1];
}

void LineRecord::set_part_line(std::size_t first, const json& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const json& s : line.at("slaves")) {
    const std::size_t position = first + s.at("position").get<std::size_t>();  // whole line, from 1
    LaterSlave* const found = later_at(position);
    if (found == nullptr) continue;
    LaterSlave& later = *found;
    later.view = s;
    later.view["position"] = position;
    // The part's first slave hangs on port 1 of the slave before the part, not on the master.
    const int parent = s.value("parent", 0);
    later.view["parent"] = parent == 0 ? static_cast<int>(first) : parent + static_cast<int>(first);
    if (parent == 0) later.view["parent_port"] = 1;
    later.answers = true;
  }
  const json& counters = line.at("counters");
  part_stalls_[first] = {counters.at("host_stalls").get<std::uint64_t>(), counters.at("longest_host_stall_ns").get<std::int64_t>()};
}

void LineRecord::add_part_samples(std::size_t first, const json& samples) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const json& axis : samples.at("axes")) {
    LaterSlave* const later = later_at(first + axis.at("slave").get<std::size_t>());
    if (later == nullptr) continue;
    std::deque<Point>& points = later->points;
    const json& t = axis.at("t");
    const json &target = axis.at("target_position"), &pos = axis.at("position"), &vel = axis.at("velocity"),
               &torque = axis.at("torque"), &ferr = axis.at("following_error");
    for (std::size_t n = 0; n < t.size(); ++n) {
      const auto time = origin_ + static_cast<Nanos>(std::llround(t.at(n).get<double>() * 1e9));
      points.push_back({++sample_seq_, time, target.at(n).get<std::int32_t>(), pos.at(n).get<std::int32_t>(),
                        vel.at(n).get<std::int32_t>(), ferr.at(n).get<std::int32_t>(), torque.at(n).get<std::int16_t>()});
    }
    while (points.size() > kPointsPerAxis) points.pop_front();
  }
}

void LineRecord::add_part_events(std::size_t first, const json& events) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const json& e : events.at("events")) {
    const int slave = e.at("slave").get<int>();
    const std::string kind = e.at("kind").get<std::string>();
    const std::string text = e.at("text").get<std::string>();
    push_event({0, origin_ + e.at("time_ns").get<Nanos>(), slave == 0 ? 0 : slave + static_cast<int>(first), kind,
                e.at("value").get<std::int64_t>(), e.at("previous").get<std::int64_t>(),
                kind == "host_stall" ? shift_stall_slaves(text, first) : control::shift_slave_numbers(text, first)});
  }
}

void LineRecord::set_part_silent(std::size_t first, std::size_t count, const std::string& why, Nanos time) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t position = first + 1; position <= first + count; ++position)
    if (LaterSlave* const later = later_at(position); later != nullptr) later->answers = false;
  push_event({0, time, static_cast<int>(first + 1), "part_silent", 0, 0, why});
}

json LineRecord::later_slave_json(std::size_t k) const {
  const LaterSlave& later = later_[k];
  const int position = static_cast<int>(slaves_.size() + k + 1);
  json j = later.view;
  if (!j.is_object()) {  // its part has not answered yet: a slave of the line, nothing known
    j = {{"position", position}, {"name", ""}, {"product", ""}, {"product_name", ""}, {"vendor_id", 0}, {"product_code", 0},
         {"revision", 0}, {"address", 0}, {"alias", 0}, {"al_state", 0}, {"al_error", false}, {"al_status_code", 0},
         {"al_status_text", "No error"}, {"rx_errors", {0, 0, 0, 0}}, {"lost_links", {0, 0, 0, 0}},
         {"parent", position - 1}, {"parent_port", position == 1 ? 0 : 1}};
    j["dc"] = {{"enabled", false}, {"system_time_difference_ns", 0}, {"locked", false}};
    j["drive"] = nullptr;
  }
  j["answers"] = later.answers;
  if (!later.answers) j["al_state_name"] = "no answer";
  return j;
}

}  // namespace vdrive::web
