#include "plant/plant_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

namespace vdrive::plant {

namespace {

constexpr double kRpm = 2.0 * M_PI / 60.0;

// Walks one YAML file, keeping the origin for messages.
class Reader {
public:
  explicit Reader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const YAML::Node& n, const std::string& path, const std::string& what) const {
    std::ostringstream os;
    os << origin_;
    if (n.IsDefined() && n.Mark().line >= 0) os << ':' << n.Mark().line + 1 << ':' << n.Mark().column + 1;
    os << ": " << path << ": " << what;
    throw PlantYamlError(os.str());
  }

  // Every key of map `n` must be one of `allowed`.
  void keys(const YAML::Node& n, const std::string& path, std::initializer_list<const char*> allowed) const {
    if (!n.IsMap()) fail(n, path, "must be a mapping");
    for (const auto& kv : n) {
      const std::string k = kv.first.as<std::string>();
      bool ok = false;
      for (const char* a : allowed) ok = ok || k == a;
      if (!ok) fail(kv.first, join(path, k), "unknown field");
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  double number(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar()) fail(n, path, "must be a number");
    try {
      const double v = n.as<double>();
      if (!std::isfinite(v)) fail(n, path, "must be finite");
      return v;
    } catch (const YAML::Exception&) {
      fail(n, path, "must be a number, got '" + n.Scalar() + "'");
    }
  }
  // Optional numeric field with a range check: min < v (strict) or min <= v.
  void num(const YAML::Node& m, const std::string& path, const char* key, double& out,
           double min = -INFINITY, bool strict = false) const {
    const YAML::Node n = m[key];
    if (!n) return;
    const double v = number(n, join(path, key));
    if (strict ? !(v > min) : !(v >= min)) {
      std::ostringstream os;
      os << "must be " << (strict ? "> " : ">= ") << min;
      fail(n, join(path, key), os.str());
    }
    out = v;
  }
  void opt(const YAML::Node& m, const std::string& path, const char* key, std::optional<double>& out) const {
    const YAML::Node n = m[key];
    if (n) out = number(n, join(path, key));
  }
  std::string text(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar()) fail(n, path, "must be a string");
    return n.Scalar();
  }
  void str(const YAML::Node& m, const std::string& path, const char* key, std::string& out) const {
    if (const YAML::Node n = m[key]) out = text(n, join(path, key));
  }
  bool boolean(const YAML::Node& m, const std::string& path, const char* key, bool def) const {
    const YAML::Node n = m[key];
    if (!n) return def;
    try {
      return n.as<bool>();
    } catch (const YAML::Exception&) {
      fail(n, join(path, key), "must be true or false");
    }
  }
  Vec3 vec3(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence() || n.size() != 3) fail(n, path, "must be a list of 3 numbers");
    return {number(n[0], path + "[0]"), number(n[1], path + "[1]"), number(n[2], path + "[2]")};
  }
  const YAML::Node& required(const YAML::Node& m, const std::string& path, const char* key,
                             YAML::Node& holder) const {
    holder = m[key];
    if (!holder) fail(m, join(path, key), "missing");
    return holder;
  }

private:
  std::string origin_;
};

std::optional<PositionWindow> window(const Reader& r, const YAML::Node& m, const std::string& path,
                                     const char* key) {
  const YAML::Node n = m[key];
  if (!n) return std::nullopt;
  const std::string p = Reader::join(path, key);
  if (!n.IsSequence() || n.size() != 2) r.fail(n, p, "must be [from, to]");
  PositionWindow w{r.number(n[0], p + "[0]"), r.number(n[1], p + "[1]")};
  if (w.to < w.from) r.fail(n, p, "'to' must not be below 'from'");
  return w;
}

MotorParams parse_motor(const Reader& r, const YAML::Node& m, const std::string& path,
                        const ProductLookup& products) {
  r.keys(m, path, {"product", "model", "kind", "torque_constant_nm_per_a", "rotor_inertia_kgm2",
                   "winding_resistance_ohm", "winding_inductance_h", "current_bandwidth_hz",
                   "rated_torque_nm", "peak_torque_nm", "rated_current_a", "max_speed_rpm",
                   "ambient_c", "winding_limit_c", "winding_capacity_j_per_k",
                   "housing_capacity_j_per_k", "winding_to_housing_k_per_w",
                   "housing_to_ambient_k_per_w", "stepper_rotor_teeth"});
  MotorParams p;
  if (const YAML::Node prod = m["product"]) {
    const std::string id = r.text(prod, path + ".product");
    const std::optional<MotorCatalogue> catalogue = products ? products(id) : std::nullopt;
    if (!catalogue) r.fail(prod, path + ".product", "unknown product '" + id + "'");
    p = catalogue->default_motor;
    if (const YAML::Node model = m["model"]) {
      const std::string name = r.text(model, path + ".model");
      const MotorParams* found = catalogue->find(name);
      if (!found) r.fail(model, path + ".model", "no motor '" + name + "' in " + id + "'s catalogue");
      p = *found;
    }
  } else {
    r.str(m, path, "model", p.model);
  }
  if (const YAML::Node k = m["kind"]) {
    const std::string kind = r.text(k, path + ".kind");
    if (kind == "servo") p.kind = MotorKind::servo;
    else if (kind == "stepper") p.kind = MotorKind::stepper;
    else r.fail(k, path + ".kind", "must be servo or stepper");
  }
  r.num(m, path, "torque_constant_nm_per_a", p.torque_constant_nm_per_a, 0, true);
  r.num(m, path, "rotor_inertia_kgm2", p.rotor_inertia_kgm2, 0, true);
  r.num(m, path, "winding_resistance_ohm", p.winding_resistance_ohm, 0, true);
  r.num(m, path, "winding_inductance_h", p.winding_inductance_h, 0, true);
  r.num(m, path, "current_bandwidth_hz", p.current_bandwidth_hz, 0, true);
  r.num(m, path, "rated_torque_nm", p.rated_torque_nm, 0, true);
  r.num(m, path, "peak_torque_nm", p.peak_torque_nm, 0, true);
  r.num(m, path, "rated_current_a", p.rated_current_a, 0, true);
  double rpm = p.max_speed_rad_s / kRpm;
  r.num(m, path, "max_speed_rpm", rpm, 0, true);
  p.max_speed_rad_s = rpm * kRpm;
  r.num(m, path, "ambient_c", p.ambient_c);
  r.num(m, path, "winding_limit_c", p.winding_limit_c);
  r.num(m, path, "winding_capacity_j_per_k", p.winding_capacity_j_per_k, 0, true);
  r.num(m, path, "housing_capacity_j_per_k", p.housing_capacity_j_per_k, 0, true);
  r.num(m, path, "winding_to_housing_k_per_w", p.winding_to_housing_k_per_w, 0, true);
  r.num(m, path, "housing_to_ambient_k_per_w", p.housing_to_ambient_k_per_w, 0, true);
  double teeth = p.stepper_rotor_teeth;
  r.num(m, path, "stepper_rotor_teeth", teeth, 1);
  p.stepper_rotor_teeth = static_cast<int>(teeth);
  if (p.peak_torque_nm < p.rated_torque_nm) r.fail(m, path + ".peak_torque_nm", "must not be below rated_torque_nm");
  return p;
}

TransmissionSpec parse_transmission(const Reader& r, const YAML::Node& m, const std::string& path) {
  r.keys(m, path, {"type", "ratio", "pulley_diameter_m", "lead_m", "efficiency", "backlash",
                   "stiffness", "damping"});
  TransmissionSpec t;
  if (const YAML::Node k = m["type"]) {
    const std::string type = r.text(k, path + ".type");
    if (type == "direct") t.kind = TransmissionKind::direct;
    else if (type == "gearbox") t.kind = TransmissionKind::gearbox;
    else if (type == "belt") t.kind = TransmissionKind::belt;
    else if (type == "ball_screw") t.kind = TransmissionKind::ball_screw;
    else r.fail(k, path + ".type", "must be direct, gearbox, belt or ball_screw");
  }
  r.num(m, path, "ratio", t.ratio, 0, true);
  r.num(m, path, "pulley_diameter_m", t.pulley_diameter_m, 0, true);
  r.num(m, path, "lead_m", t.lead_m, 0, true);
  r.num(m, path, "efficiency", t.efficiency, 0, true);
  if (t.efficiency > 1) r.fail(m["efficiency"], path + ".efficiency", "must be <= 1");
  r.num(m, path, "backlash", t.backlash, 0);
  r.num(m, path, "stiffness", t.stiffness, 0);
  r.num(m, path, "damping", t.damping, 0);
  if (t.kind == TransmissionKind::ball_screw && !(t.lead_m > 0)) r.fail(m, path + ".lead_m", "missing (ball_screw)");
  if (t.backlash > 0 && !(t.stiffness > 0)) r.fail(m, path + ".stiffness", "must be > 0 when backlash is set");
  return t;
}

AxisSpec parse_axis(const Reader& r, const YAML::Node& m, const std::string& path,
                    const ProductLookup& products) {
  r.keys(m, path, {"name", "motor", "joint", "load_inertia_kgm2", "transmission", "friction",
                   "encoder", "brake", "switches", "load_profile"});
  AxisSpec a;
  YAML::Node h;
  a.name = r.text(r.required(m, path, "name", h), path + ".name");
  if (const YAML::Node n = m["motor"]) a.motor = parse_motor(r, n, path + ".motor", products);
  r.str(m, path, "joint", a.joint);
  r.num(m, path, "load_inertia_kgm2", a.load_inertia_kgm2, 0);
  if (const YAML::Node n = m["transmission"]) a.transmission = parse_transmission(r, n, path + ".transmission");
  if (const YAML::Node n = m["friction"]) {
    const std::string p = path + ".friction";
    r.keys(n, p, {"coulomb", "breakaway", "stribeck_velocity", "viscous"});
    r.num(n, p, "coulomb", a.friction.coulomb, 0);
    r.num(n, p, "breakaway", a.friction.breakaway, 0);
    r.num(n, p, "stribeck_velocity", a.friction.stribeck_velocity, 0, true);
    r.num(n, p, "viscous", a.friction.viscous, 0);
    if (a.friction.breakaway > 0 && a.friction.breakaway < a.friction.coulomb)
      r.fail(n["breakaway"], p + ".breakaway", "must not be below coulomb");
  }
  if (const YAML::Node n = m["encoder"]) {
    const std::string p = path + ".encoder";
    r.keys(n, p, {"counts_per_rev", "absolute", "multiturn_bits", "index_angle_rad"});
    double cpr = a.encoder.counts_per_rev, bits = a.encoder.multiturn_bits;
    r.num(n, p, "counts_per_rev", cpr, 1);
    if (cpr != std::floor(cpr) || cpr > 4294967295.0) r.fail(n["counts_per_rev"], p + ".counts_per_rev", "must be a 32-bit whole number");
    r.num(n, p, "multiturn_bits", bits, 0);
    if (bits != std::floor(bits) || bits > 32) r.fail(n["multiturn_bits"], p + ".multiturn_bits", "must be a whole number 0..32");
    a.encoder.counts_per_rev = static_cast<std::uint32_t>(cpr);
    a.encoder.multiturn_bits = static_cast<unsigned>(bits);
    a.encoder.absolute = r.boolean(n, p, "absolute", a.encoder.absolute);
    r.num(n, p, "index_angle_rad", a.encoder.index_angle_rad);
  }
  if (const YAML::Node n = m["brake"]) {
    const std::string p = path + ".brake";
    r.keys(n, p, {"holding_torque_nm"});
    a.brake.fitted = true;
    YAML::Node hold;
    a.brake.holding_torque_nm = r.number(r.required(n, p, "holding_torque_nm", hold), p + ".holding_torque_nm");
    if (!(a.brake.holding_torque_nm > 0)) r.fail(hold, p + ".holding_torque_nm", "must be > 0");
  }
  if (const YAML::Node n = m["switches"]) {
    const std::string p = path + ".switches";
    r.keys(n, p, {"negative_limit", "positive_limit", "home", "probe1", "probe2"});
    r.opt(n, p, "negative_limit", a.switches.negative_limit);
    r.opt(n, p, "positive_limit", a.switches.positive_limit);
    a.switches.home = window(r, n, p, "home");
    a.switches.probe1 = window(r, n, p, "probe1");
    a.switches.probe2 = window(r, n, p, "probe2");
  }
  if (const YAML::Node n = m["load_profile"]) {
    const std::string p = path + ".load_profile";
    if (!n.IsSequence()) r.fail(n, p, "must be a list of [time_s, value]");
    for (std::size_t i = 0; i < n.size(); ++i) {
      const std::string pi = p + "[" + std::to_string(i) + "]";
      if (!n[i].IsSequence() || n[i].size() != 2) r.fail(n[i], pi, "must be [time_s, value]");
      const double t = r.number(n[i][0], pi + "[0]"), v = r.number(n[i][1], pi + "[1]");
      if (!a.load_profile.empty() && t < a.load_profile.back().first) r.fail(n[i], pi, "times must not decrease");
      a.load_profile.emplace_back(t, v);
    }
  }
  return a;
}

}  // namespace

PlantDescription parse_plant_yaml(std::string_view text, const std::string& origin,
                                  const ProductLookup& products) {
  const Reader r(origin);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    throw PlantYamlError(origin + ":" + std::to_string(e.mark.line + 1) + ":" +
                         std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  // An empty document (nothing but comments) has no node to carry a line: it is line 1.
  if (!root.IsMap() && root.Mark().is_null())
    throw PlantYamlError(origin + ":1:1: plant: missing (top-level key 'plant:'; the file has no content)");
  // A document that is a scalar or a list has no keys: yaml-cpp throws on subscripting it.
  if (!root.IsMap() || !root["plant"]) r.fail(root, "plant", "missing (top-level key 'plant:')");
  const YAML::Node plant = root["plant"];
  r.keys(root, "", {"plant"});
  r.keys(plant, "plant", {"step_s", "substeps", "gravity", "bodies", "joints", "axes"});
  PlantDescription d;
  r.num(plant, "plant", "step_s", d.step_s, 0, true);
  double sub = d.substeps;
  r.num(plant, "plant", "substeps", sub, 1);
  if (sub != std::floor(sub)) r.fail(plant["substeps"], "plant.substeps", "must be a whole number");
  d.substeps = static_cast<int>(sub);
  if (const YAML::Node g = plant["gravity"]) d.gravity = r.vec3(g, "plant.gravity");

  std::set<std::string> body_names, joint_names, axis_names;
  if (const YAML::Node bodies = plant["bodies"]) {
    if (!bodies.IsSequence()) r.fail(bodies, "plant.bodies", "must be a list");
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const std::string p = "plant.bodies[" + std::to_string(i) + "]";
      const YAML::Node n = bodies[i];
      r.keys(n, p, {"name", "mass_kg", "position_m", "inertia_kgm2"});
      BodySpec b;
      YAML::Node h;
      b.name = r.text(r.required(n, p, "name", h), p + ".name");
      if (!body_names.insert(b.name).second) r.fail(n["name"], p + ".name", "duplicate body '" + b.name + "'");
      r.num(n, p, "mass_kg", b.mass_kg, 0, true);
      if (n["position_m"]) b.position_m = r.vec3(n["position_m"], p + ".position_m");
      if (n["inertia_kgm2"]) {
        b.inertia_kgm2 = r.vec3(n["inertia_kgm2"], p + ".inertia_kgm2");
        for (double v : b.inertia_kgm2)
          if (!(v > 0)) r.fail(n["inertia_kgm2"], p + ".inertia_kgm2", "entries must be > 0");
      }
      d.bodies.push_back(b);
    }
  }
  if (const YAML::Node joints = plant["joints"]) {
    if (!joints.IsSequence()) r.fail(joints, "plant.joints", "must be a list");
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const std::string p = "plant.joints[" + std::to_string(i) + "]";
      const YAML::Node n = joints[i];
      r.keys(n, p, {"name", "type", "parent", "child", "anchor_m", "axis", "lower_stop", "upper_stop",
                    "stop_bounce", "initial"});
      JointSpec j;
      YAML::Node h;
      j.name = r.text(r.required(n, p, "name", h), p + ".name");
      if (!joint_names.insert(j.name).second) r.fail(n["name"], p + ".name", "duplicate joint '" + j.name + "'");
      if (const YAML::Node t = n["type"]) {
        const std::string type = r.text(t, p + ".type");
        if (type == "hinge") j.type = JointType::hinge;
        else if (type == "slider") j.type = JointType::slider;
        else r.fail(t, p + ".type", "must be hinge or slider");
      }
      r.str(n, p, "parent", j.parent);
      j.child = r.text(r.required(n, p, "child", h), p + ".child");
      if (!body_names.count(j.child)) r.fail(n["child"], p + ".child", "no body named '" + j.child + "'");
      if (!j.parent.empty() && !body_names.count(j.parent))
        r.fail(n["parent"], p + ".parent", "no body named '" + j.parent + "'");
      if (n["anchor_m"]) j.anchor_m = r.vec3(n["anchor_m"], p + ".anchor_m");
      if (n["axis"]) {
        j.axis = r.vec3(n["axis"], p + ".axis");
        if (std::hypot(j.axis[0], j.axis[1], j.axis[2]) < 1e-9) r.fail(n["axis"], p + ".axis", "must not be zero");
      }
      r.opt(n, p, "lower_stop", j.lower_stop);
      r.opt(n, p, "upper_stop", j.upper_stop);
      if (j.lower_stop && j.upper_stop && *j.upper_stop < *j.lower_stop)
        r.fail(n["upper_stop"], p + ".upper_stop", "must not be below lower_stop");
      if (j.type == JointType::hinge && ((j.lower_stop && *j.lower_stop < -M_PI) || (j.upper_stop && *j.upper_stop > M_PI)))
        r.fail(n, p, "hinge stops must lie within [-pi, pi]");
      r.num(n, p, "stop_bounce", j.stop_bounce, 0);
      r.num(n, p, "initial", j.initial);
      d.joints.push_back(j);
    }
  }
  const YAML::Node axes = plant["axes"];
  if (!axes || !axes.IsSequence() || axes.size() == 0) r.fail(axes ? axes : plant, "plant.axes", "at least one axis is needed");
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const std::string p = "plant.axes[" + std::to_string(i) + "]";
    AxisSpec a = parse_axis(r, axes[i], p, products);
    if (!axis_names.insert(a.name).second) r.fail(axes[i]["name"], p + ".name", "duplicate axis '" + a.name + "'");
    if (!a.joint.empty() && !joint_names.count(a.joint))
      r.fail(axes[i]["joint"], p + ".joint", "no joint named '" + a.joint + "'");
    d.axes.push_back(std::move(a));
  }
  return d;
}

PlantDescription load_plant_file(const std::string& path, const ProductLookup& products) {
  std::ifstream in(path);
  if (!in) throw PlantYamlError(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_plant_yaml(text.str(), path, products);
}

}  // namespace vdrive::plant
