#include "vdrive/cli/fault_inject_options.hpp"

#include <CLI/CLI.hpp>

#include "vdrive/cli/slave_option.hpp"

namespace vdrive::cli {

void add_fault_inject_options(CLI::App* inj, FaultInjectOptions& o) {
  inj->add_option("kind", o.kind, "Fault kind")->required();
  inj->add_option("--slave", o.slave,
                  "The slave: its position in cable order (1 = first) or its station address (0x1001) (esc, mailbox, "
                  "drive, plant faults; link_down)")
      ->check(slave_ref_validator());
  inj->add_option("--port", o.port, "link_down: the cable at this port of --slave (0 = the cable into it, 1-3 = out of it)");
  inj->add_option("--duration", o.duration, "How long, e.g. 250ms (default: until cleared)");
  inj->add_option("--probability", o.probability, "Per frame, 0..1 (drop, corrupt, duplicate, reorder; default 1)");
  inj->add_option("--direction", o.direction, "both, to_slaves or to_master (wire faults; default both)");
  inj->add_option("--delay", o.delay, "delay: how long every frame is held, e.g. 2ms");
  inj->add_option("--count", o.count, "lost_reply, duplicate_reply: how many replies (default 1)");
  inj->add_option("--abort-code", o.abort_code, "sdo_abort: the abort code, e.g. 0x06020000");
  inj->add_option("--code", o.code, "alarm: an alarm code of the product");
  inj->add_option("--position", o.position, "collision: the obstacle's load position");
  inj->add_option("--load-scale", o.load_scale, "load_change: inertia/mass factor");
  inj->add_option("--force", o.force, "load_change: added external load (N or N m)");
}

nlohmann::json fault_json(const FaultInjectOptions& o) {
  nlohmann::json f{{"kind", o.kind}};
  if (o.slave) f["slave"] = slave_json(*o.slave);
  if (o.port) f["port"] = *o.port;
  if (o.count) f["count"] = *o.count;
  if (o.duration) f["duration"] = *o.duration;
  if (o.direction) f["direction"] = *o.direction;
  if (o.delay) f["delay"] = *o.delay;
  if (o.abort_code) f["abort_code"] = *o.abort_code;
  if (o.code) f["code"] = *o.code;
  if (o.probability) f["probability"] = *o.probability;
  if (o.position) f["position"] = *o.position;
  if (o.load_scale) f["load_scale"] = *o.load_scale;
  if (o.force) f["force"] = *o.force;
  return f;
}

}  // namespace vdrive::cli
