#pragma once
// LineRecord: the web server's picture of the line, kept off the loop thread. The sampler's
// samples come in through add() (the latest values of each axis, the last 12 s of plot points,
// events), the loop's register copies through set_registers(), active faults through
// set_faults(); the page and the API read it as JSON. Every sample and event gets a sequence
// number, so a client asks for what is new since the last one it saw. Thread-safe (one mutex,
// web threads only).
//
// In part 1 of a line over processes the record holds the later parts' slaves too, after its
// own: their views, plot points and events as those parts' own pages gave them (PartPages), with
// whole-line positions and this record's sequence numbers (line_record_parts.cpp).
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vdrive/control/control_request.hpp"
#include "vdrive/telemetry/samples.hpp"
#include "vdrive/web/scenario_view.hpp"
#include "vdrive/web/slave_view.hpp"

namespace vdrive::web {

struct LineIdentity {
  std::string source;     // "run", "demo", "scenario"
  std::string interface;  // the served interface
  std::string version;
  bool token_required = false;
};

class LineRecord {
public:
  static constexpr std::size_t kPointsPerAxis = 600;  // 12 s at 50 Hz
  static constexpr std::size_t kEvents = 2000;
  static constexpr std::size_t kEmergencies = 16;     // per axis

  // `later_slaves`: slaves after these that later parts of the run serve (0: none).
  LineRecord(std::vector<SlaveInfo> slaves, LineIdentity identity, Nanos origin, std::size_t later_slaves = 0);

  void add(const telemetry::Sample& sample);
  // `now`: when they were copied (an SDO abort found then is an event at that time).
  void set_registers(const std::vector<SlaveRegisters>& registers, Nanos now);
  void set_faults(std::vector<control::FaultStatus> faults);
  // An event that does not come from the sampler (an OD write, a plant change, a scenario step).
  void note(int slave, const std::string& kind, std::int64_t value, std::int64_t previous, const std::string& text, Nanos time);
  void set_scenario(const ScenarioView& scenario);
  template <typename F> void update_scenario(F&& change) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!scenario_) scenario_.emplace();
    change(*scenario_);
  }

  // A later part's slaves, `first` the whole-line index of its first: as its own page's line
  // shows them (positions made whole-line), its plot points and events as its API answers them
  // after the last taken. Throw nlohmann::json::exception on a line of another shape.
  void set_part_line(std::size_t first, const nlohmann::json& line);
  void add_part_samples(std::size_t first, const nlohmann::json& samples);
  void add_part_events(std::size_t first, const nlohmann::json& events);
  // The part does not answer (`why`): its slaves keep their last view, their AL state shown as
  // "no answer", and an event says so.
  void set_part_silent(std::size_t first, std::size_t count, const std::string& why, Nanos time);

  // Every slave of the line, this process's and the later parts'.
  std::size_t size() const { return slaves_.size() + later_.size(); }
  // Whether slave index `i` is this process's (SlaveInfo, dictionaries, the loop reach it).
  bool served_here(std::size_t i) const { return i < slaves_.size(); }
  // Each slave's station address (0010h) in cable order, as last copied (0: none set yet).
  std::vector<std::uint16_t> stations() const;
  const SlaveInfo& slave(std::size_t i) const { return slaves_[i]; }
  const LineIdentity& identity() const { return identity_; }

  nlohmann::json line(Nanos now) const;
  // Plot points with a sequence number above `since`, of one slave (from 1) or all (0).
  nlohmann::json samples(std::uint64_t since, int slave) const;
  // Events above `since`; `kind` empty and `slave` 0 take all.
  nlohmann::json events(std::uint64_t since, const std::string& kind, int slave) const;
  std::string events_csv(const std::string& kind, int slave) const;
  std::uint64_t sample_seq() const;
  std::uint64_t event_seq() const;

private:
  struct Point {
    std::uint64_t seq = 0;
    Nanos time = 0;
    std::int32_t target_position = 0, position = 0, velocity = 0, following_error = 0;
    std::int16_t torque = 0;
  };
  struct Event {
    std::uint64_t seq = 0;
    Nanos time = 0;
    int slave = 0;
    std::string kind;
    std::int64_t value = 0, previous = 0;
    std::string text;
  };
  struct Emergency {
    Nanos time = 0;
    std::uint16_t error_code = 0;
    std::string text;
  };
  struct Axis {
    std::optional<telemetry::AxisSample> latest;
    std::deque<Point> points;
    std::deque<Emergency> emergencies;
  };
  // A later part's slave (index among the later ones) and what its part last said of its own
  // host stalls.
  struct LaterSlave {
    nlohmann::json view;  // null until its part first answers
    bool answers = false;
    std::deque<Point> points;
  };
  struct PartStalls {
    std::uint64_t count = 0;
    std::int64_t longest_ns = 0;
  };
  void push_event(Event e);
  // The later slave at whole-line `position` (from 1), or null for one of this process's or beyond the line.
  LaterSlave* later_at(std::size_t position);
  nlohmann::json later_slave_json(std::size_t j) const;
  nlohmann::json points_json(int slave, const std::deque<Point>& points, std::uint64_t since) const;
  nlohmann::json slave_json(std::size_t i) const;
  nlohmann::json drive_json(std::size_t i) const;
  std::string alarm_text(std::size_t i, std::uint16_t error_code) const;

  const std::vector<SlaveInfo> slaves_;
  const LineIdentity identity_;
  const Nanos origin_;
  mutable std::mutex mutex_;
  std::vector<Axis> axes_;
  std::vector<SlaveRegisters> registers_;
  bool registers_seen_ = false;  // the first copy is the baseline, not news
  telemetry::BusSample bus_{};
  std::vector<control::FaultStatus> faults_;
  std::deque<Event> events_;
  std::optional<ScenarioView> scenario_;
  std::vector<LaterSlave> later_;
  std::map<std::size_t, PartStalls> part_stalls_;  // by the part's first slave
  std::uint64_t sample_seq_ = 0, event_seq_ = 0;
};

}  // namespace vdrive::web
