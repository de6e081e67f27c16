// profile.yaml `modes`, `homing` and `touch_probe`: what the CiA402 side of the product offers.
#include <algorithm>

#include <fmt/format.h>

#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {
namespace {

template <typename T>
bool distinct(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return std::adjacent_find(v.begin(), v.end()) == v.end();
}

template <typename T>
bool contains(const std::vector<T>& v, T x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

}  // namespace

ModesSpec read_modes(YamlMapReader m) {
  ModesSpec s;
  s.supported_drive_modes = m.u32("supported_drive_modes");
  s.modes = m.i8_list("modes");
  if (!distinct(s.modes)) m.fail("modes", "lists a mode twice");
  // CiA 402 6502h: bit (n - 1) is mode n for the standard modes 1..10 (bit 4 reserved).
  std::uint32_t bits = 0;
  for (const std::int8_t mode : s.modes) {
    if (mode < 1 || mode > 10 || mode == 5) m.fail("modes", fmt::format("{} is not a CiA 402 mode (1-4, 6-10)", mode));
    bits |= 1u << (mode - 1);
  }
  if ((s.supported_drive_modes & 0x3FF) != bits)
    m.fail("supported_drive_modes",
           fmt::format("bits 0-9 are 0x{:03X} but modes give 0x{:03X}", s.supported_drive_modes & 0x3FF, bits));
  s.default_mode = m.i8("default_mode");
  if (s.default_mode != 0 && !contains(s.modes, s.default_mode)) m.fail("default_mode", "is not 0 or one of modes");
  m.finish();
  return s;
}

HomingSpec read_homing(YamlMapReader m) {
  HomingSpec h;
  h.methods = m.i8_list("methods");
  if (!distinct(h.methods)) m.fail("methods", "lists a method twice");
  h.listed = m.i8_list("listed");
  if (!distinct(h.listed)) m.fail("listed", "lists a method twice");
  for (const std::int8_t x : h.listed)
    if (!contains(h.methods, x)) m.fail("listed", fmt::format("method {} is listed but not in methods", x));
  h.default_method = m.i8("default_method");
  if (h.default_method != 0 && !contains(h.methods, h.default_method))
    m.fail("default_method", "is not 0 or one of methods");
  read_homing_rules(m, h);
  m.finish();
  return h;
}

TouchProbeSpec read_touch_probe(YamlMapReader m) {
  TouchProbeSpec t;
  t.channels = m.u8("channels");
  if (t.channels > 2) m.fail("channels", "expected 0, 1 or 2 (60B8h has room for two)");
  t.rising_edge = m.boolean("rising_edge");
  t.falling_edge = m.boolean("falling_edge");
  t.both_edges_at_once = m.boolean("both_edges_at_once");
  if (t.both_edges_at_once && !(t.rising_edge && t.falling_edge))
    m.fail("both_edges_at_once", "needs rising_edge and falling_edge");
  t.continuous = m.boolean("continuous");
  const YAML::Node seq = m.sequence("sources");
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader s = m.element(seq, "sources", i);
    TouchProbeSource src;
    src.channel = s.u8("channel");
    if (src.channel < 1 || src.channel > t.channels) s.fail("channel", "expected 1..channels");
    src.trigger_select = s.u8("trigger_select");
    if (src.trigger_select > 3) s.fail("trigger_select", "expected 0..3 (60B8h has at most two select bits)");
    src.source = s.i16("source");
    src.name = s.string("name");
    s.finish();
    t.sources.push_back(std::move(src));
  }
  if (t.channels > 0 && t.sources.empty()) m.fail("sources", "a product with touch probes needs at least one source");
  m.finish();
  return t;
}

}  // namespace vdrive::profile
