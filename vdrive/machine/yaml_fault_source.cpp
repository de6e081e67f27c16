#include "vdrive/machine/yaml_fault_source.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <set>

#include "common/time_text.hpp"
#include "ethercat/slave_ref.hpp"
#include "vdrive/fault/fault_fields.hpp"
#include "vdrive/machine/network_file.hpp"

namespace vdrive::machine {
namespace {

class YamlFaultSource final : public fault::FaultFieldSource {
public:
  YamlFaultSource(const YAML::Node& n, const std::string& file, const std::string& where,
                  const std::vector<std::string>& names)
      : n_(n), file_(file), where_(where), names_(names) {}

  bool has(std::string_view f) const override { return bool(n_[std::string(f)]); }
  std::string text(std::string_view f) override {
    const YAML::Node v = at(f);
    if (!v.IsScalar()) fail(v, f, "expected a text");
    return v.Scalar();
  }
  double real(std::string_view f) override {
    const YAML::Node v = at(f);
    double d = 0.0;
    if (!v.IsScalar() || !YAML::convert<double>::decode(v, d)) fail(v, f, fmt::format("'{}' is not a number", scalar(v)));
    return d;
  }
  std::int64_t integer(std::string_view f, std::int64_t min, std::int64_t max) override {
    const YAML::Node v = at(f);
    if (f == "slave" && v.IsScalar())
      for (std::size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == v.Scalar()) return static_cast<std::int64_t>(i + 1);
    std::int64_t x = 0;
    if (!v.IsScalar() || !YAML::convert<std::int64_t>::decode(v, x))
      fail(v, f, f == "slave" ? fmt::format("no slave '{}' (a name or a position 1-{})", scalar(v), names_.size())
                              : fmt::format("'{}' is not a whole number", scalar(v)));
    if (x < min || x > max) fail(v, f, fmt::format("{} is out of range ({}..{})", x, min, max));
    return x;
  }
  std::optional<std::string> address_text(std::string_view f) override {
    const YAML::Node v = at(f);
    if (!v.IsScalar() || !ecat::is_address_text(v.Scalar())) return std::nullopt;
    return v.Scalar();
  }
  Nanos time(std::string_view f) override {
    const YAML::Node v = at(f);
    const auto t = v.IsScalar() ? parse_time(v.Scalar()) : std::nullopt;
    if (!t) fail(v, f, fmt::format("'{}' is not a time with a unit (e.g. 250ms, 1.5s)", scalar(v)));
    return *t;
  }
  [[noreturn]] void missing(std::string_view f, std::string_view why) override {
    fail(n_, f, fmt::format("missing: {}", why));
  }
  [[noreturn]] void invalid(std::string_view f, std::string_view what) override { fail(n_[std::string(f)], f, what); }
  [[noreturn]] void out_of_range(std::string_view f, std::string_view rule) override {
    fail(n_[std::string(f)], f, fmt::format("{} {}", scalar(n_[std::string(f)]), rule));
  }

  bool read(const std::string& f) const { return read_.contains(f); }
  [[noreturn]] void fail(const YAML::Node& at, std::string_view f, std::string_view what) const {
    const YAML::Mark m = (at && !at.Mark().is_null()) ? at.Mark() : n_.Mark();
    throw NetworkFileError(fmt::format("{}:{}: {}.{}: {}", file_, m.line + 1, where_, f, what));
  }

private:
  static std::string scalar(const YAML::Node& v) { return v.IsScalar() ? v.Scalar() : "(not a value)"; }
  YAML::Node at(std::string_view f) {
    read_.insert(std::string(f));
    return n_[std::string(f)];
  }
  YAML::Node n_;
  const std::string& file_;
  const std::string& where_;
  const std::vector<std::string>& names_;
  std::set<std::string, std::less<>> read_;
};

}  // namespace

fault::FaultSpec read_yaml_fault(const YAML::Node& entry, const std::string& file, const std::string& where,
                                 const std::vector<std::string>& slave_names,
                                 const std::vector<std::string>& extra_keys) {
  YamlFaultSource source(entry, file, where, slave_names);
  const fault::FaultSpec f = fault::read_fault(source, static_cast<int>(slave_names.size()));
  for (const auto& kv : entry) {
    const std::string key = kv.first.Scalar();
    if (source.read(key) || std::find(extra_keys.begin(), extra_keys.end(), key) != extra_keys.end()) continue;
    source.fail(kv.first, key, fmt::format("does not apply to kind {}", fault::info(f.kind).name));
  }
  return f;
}

}  // namespace vdrive::machine
