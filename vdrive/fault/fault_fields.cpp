#include "vdrive/fault/fault_fields.hpp"

#include <limits>

#include <fmt/format.h>

#include "ethercat/slave_ref.hpp"

namespace vdrive::fault {

std::string fault_kind_names() {
  std::string names;
  for (const FaultKindInfo& i : fault_catalogue()) names += (names.empty() ? "" : ", ") + std::string(i.name);
  return names;
}

std::vector<FaultFieldInfo> fault_fields(FaultKind kind) {
  using K = FaultKind;
  const FaultKindInfo& i = info(kind);
  std::vector<FaultFieldInfo> f;
  if (acts_at_slave(kind))
    f.push_back({"slave", "integer", true, "", "", kind == K::link_down ? "the slave whose port's cable breaks (1 = first, or its station address 0x1001)"
                                                             : "the slave it acts on (1 = first, or its station address 0x1001)"});
  if (kind == K::link_down) f.push_back({"port", "integer", false, "0", "", "0: the cable into the slave; 1-3: to the slaves behind it"});
  if (!i.one_shot) f.push_back({"duration", "time", false, "0", "", "how long it lasts (0: until cleared)"});
  switch (kind) {
    case K::drop: case K::corrupt: case K::duplicate: case K::reorder: case K::delay:
      f.push_back({"direction", "enum", false, "both", "both,to_slaves,to_master", "which frames it acts on"});
      if (kind == K::delay) f.push_back({"delay", "time", true, "", "", "how long every frame is held"});
      else f.push_back({"probability", "real", false, "1", "", "per frame, 0 to 1"});
      break;
    case K::lost_reply: case K::duplicate_reply:
      f.push_back({"count", "integer", false, "1", "", "how many mailbox replies (1-1000)"});
      break;
    case K::sdo_abort:
      f.push_back({"abort_code", "integer", false, "0x08000000", "", "the abort the next SDO request gets"});
      break;
    case K::alarm:
      f.push_back({"code", "text", true, "", "", "an alarm code of the product (e.g. 16.0, E-161)"});
      break;
    case K::collision:
      f.push_back({"position", "real", true, "", "", "the obstacle's load position (load units)"});
      break;
    case K::load_change:
      f.push_back({"load_scale", "real", false, "1", "", "the load's inertia/mass factor (> 0)"});
      f.push_back({"force", "real", false, "0", "", "added external load (N or N m)"});
      f.push_back({"friction_scale", "real", false, "1", "", "the load-side friction's factor (>= 0; 0: none)"});
      break;
    default:
      break;
  }
  return f;
}

FaultSpec read_fault(FaultFieldSource& src, int max_slave) {
  using K = FaultKind;
  if (!src.has("kind")) src.missing("kind", "one of: " + fault_kind_names());
  const std::string kind = src.text("kind");
  const auto k = fault_kind_from_name(kind);
  if (!k) src.invalid("kind", fmt::format("unknown fault kind \"{}\" ({})", kind, fault_kind_names()));
  FaultSpec f;
  f.kind = *k;
  const FaultKindInfo& i = info(f.kind);
  if (acts_at_slave(f.kind)) {
    if (!src.has("slave")) src.missing("slave", fmt::format("kind \"{}\" acts on one slave (1 = first)", kind));
    if (const std::optional<std::string> written = src.address_text("slave")) {
      ecat::SlaveRef ref;
      try {
        ref = ecat::parse_slave_ref(*written);
      } catch (const std::invalid_argument& e) {
        src.invalid("slave", e.what());
      }
      if (ref.is_address()) f.station = ref.value;
      else if (ref.value > max_slave) src.out_of_range("slave", fmt::format("is out of range (1..{})", max_slave));
      else f.slave = ref.value;
    } else {
      f.slave = static_cast<int>(src.integer("slave", 1, max_slave));
    }
  }
  if (f.kind == K::link_down && src.has("port")) f.port = static_cast<int>(src.integer("port", 0, 3));
  if (!i.one_shot && src.has("duration")) f.duration = src.time("duration");
  switch (f.kind) {
    case K::drop: case K::corrupt: case K::duplicate: case K::reorder: case K::delay:
      if (src.has("direction")) {
        const std::string d = src.text("direction");
        if (d == "both") f.direction = WireDirection::both;
        else if (d == "to_slaves") f.direction = WireDirection::to_slaves;
        else if (d == "to_master") f.direction = WireDirection::to_master;
        else src.invalid("direction", fmt::format("unknown direction \"{}\" (both, to_slaves, to_master)", d));
      }
      if (f.kind == K::delay) {
        if (!src.has("delay")) src.missing("delay", "kind \"delay\" needs how long (e.g. \"2ms\")");
        f.delay = src.time("delay");
      } else if (src.has("probability")) {
        f.probability = src.real("probability");
        if (f.probability < 0.0 || f.probability > 1.0) src.out_of_range("probability", "must be between 0 and 1");
      }
      break;
    case K::lost_reply: case K::duplicate_reply:
      if (src.has("count")) f.count = static_cast<int>(src.integer("count", 1, 1000));
      break;
    case K::sdo_abort:
      if (src.has("abort_code"))
        f.abort_code = static_cast<std::uint32_t>(src.integer("abort_code", 1, std::numeric_limits<std::uint32_t>::max()));
      break;
    case K::alarm:
      if (!src.has("code")) src.missing("code", "kind \"alarm\" needs an alarm code of the product");
      f.alarm = src.text("code");
      break;
    case K::collision:
      if (!src.has("position")) src.missing("position", "kind \"collision\" needs the obstacle's position");
      f.position = src.real("position");
      break;
    case K::load_change:
      if (src.has("load_scale")) {
        f.load_scale = src.real("load_scale");
        if (!(f.load_scale > 0.0)) src.out_of_range("load_scale", "must be > 0");
      }
      if (src.has("force")) f.force = src.real("force");
      if (src.has("friction_scale")) {
        f.friction_scale = src.real("friction_scale");
        if (!(f.friction_scale >= 0.0)) src.out_of_range("friction_scale", "must be >= 0");
      }
      break;
    default:
      break;
  }
  return f;
}

}  // namespace vdrive::fault
