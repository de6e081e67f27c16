// profiles/<id>/alarms.yaml: the product's alarm table, one entry per vendor alarm code.
#include <set>

#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {
namespace {

AlarmReaction read_reaction(YamlMapReader& m) {
  const std::string r = m.string("reaction");
  if (r == "none") return AlarmReaction::None;
  if (r == "immediate_stop") return AlarmReaction::ImmediateStop;
  if (r == "deceleration") return AlarmReaction::Deceleration;
  if (r == "free_run") return AlarmReaction::FreeRun;
  m.fail("reaction", "expected one of none, immediate_stop, deceleration, free_run");
}

// "L123", "L123-L130", "L123, L456": every citation names a manual line.
bool is_citation(const std::string& s) {
  if (s.size() < 2 || s[0] != 'L') return false;
  bool digit_after_l = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == 'L') {
      if (i + 1 >= s.size() || s[i + 1] < '0' || s[i + 1] > '9') return false;
      digit_after_l = true;
    } else if (!((c >= '0' && c <= '9') || c == '-' || c == ',' || c == ' ')) {
      return false;
    }
  }
  return digit_after_l;
}

}  // namespace

YAML::Node load_yaml(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw_at(file, e.mark, "YAML syntax error: " + e.msg);
  }
}

std::vector<AlarmSpec> parse_alarms(std::string_view id, const std::string& text, const std::string& file) {
  YamlMapReader root(load_yaml(text, file), file, "");
  if (root.string("product") != id) root.fail("product", "expected '" + std::string(id) + "' (the directory name)");
  (void)root.string("manual", 1024);
  const YAML::Node seq = root.sequence("alarms");
  std::vector<AlarmSpec> out;
  std::set<std::string> codes;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader m = root.element(seq, "alarms", i);
    AlarmSpec a;
    a.code = m.string("code", 16);
    if (a.code.empty()) m.fail("code", "expected the vendor's alarm code");
    if (!codes.insert(a.code).second) m.fail("code", "'" + a.code + "' appears twice");
    a.name = m.string("name");
    a.name_en = m.string("name_en");
    if (a.name.empty() || a.name_en.empty()) m.fail(a.name.empty() ? "name" : "name_en", "expected a name");
    a.error_code = m.u16("error_code");
    if (a.error_code == 0) m.fail("error_code", "0000h means 'no error' in 603Fh");
    a.emergency_code = m.u16("emergency_code");
    a.clearable = m.boolean("clearable");
    a.reaction = read_reaction(m);
    a.al_status_code = m.u16("al_status_code");
    a.history = m.boolean("history");
    if (m.has("warning")) a.warning = m.boolean("warning");
    a.source = m.string("source");
    if (!is_citation(a.source)) m.fail("source", "expected manual lines, e.g. L32596 or L4318-L4322");
    m.finish();
    out.push_back(std::move(a));
  }
  if (out.empty()) root.fail("alarms", "expected at least one alarm");
  root.finish();
  return out;
}

}  // namespace vdrive::profile
