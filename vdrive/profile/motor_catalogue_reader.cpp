// profiles/<id>/motors.yaml: the motors the manual lists with their ratings. A value the manual
// does not give is left out of the file and reads 0.
#include <set>

#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {

std::vector<MotorSpec> parse_motors(std::string_view id, const std::string& text, const std::string& file) {
  YamlMapReader root(load_yaml(text, file), file, "");
  if (root.string("product") != id) root.fail("product", "expected '" + std::string(id) + "' (the directory name)");
  (void)root.string("manual", 1024);
  const YAML::Node seq = root.sequence("motors");
  std::vector<MotorSpec> out;
  std::set<std::string> models;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader m = root.element(seq, "motors", i);
    MotorSpec s;
    s.model = m.string("model");
    s.condition = m.has("condition") ? m.string("condition") : std::string();
    if (s.model.empty() || !models.insert(s.model + "\n" + s.condition).second)
      m.fail("model", "expected a model name distinct from the others (with its condition)");
    s.source = m.string("source");
    if (s.source.empty() || s.source[0] != 'L') m.fail("source", "expected manual lines, e.g. L5827-L5831");
    auto optional = [&m](std::string_view key) { return m.has(key) ? m.real(key) : 0.0; };
    s.rated_power_w = optional("rated_power_w");
    s.rated_torque_nm = optional("rated_torque_nm");
    s.peak_torque_nm = optional("peak_torque_nm");
    s.rated_speed_rpm = optional("rated_speed_rpm");
    s.max_speed_rpm = optional("max_speed_rpm");
    s.rated_current_a = optional("rated_current_a");
    s.torque_constant_nm_per_a = optional("torque_constant_nm_per_a");
    s.rotor_inertia_kgm2 = optional("rotor_inertia_kgm2");
    s.encoder_counts_per_rev = m.has("encoder_counts_per_rev") ? m.u32("encoder_counts_per_rev") : 0;
    if (s.peak_torque_nm != 0 && s.peak_torque_nm < s.rated_torque_nm)
      m.fail("peak_torque_nm", "is below rated_torque_nm");
    if (s.max_speed_rpm != 0 && s.max_speed_rpm < s.rated_speed_rpm) m.fail("max_speed_rpm", "is below rated_speed_rpm");
    m.finish();
    out.push_back(std::move(s));
  }
  root.finish();
  return out;
}

}  // namespace vdrive::profile
