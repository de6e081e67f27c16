#pragma once
// The fields of a fault as users write them, in scenario files and in the runtime control
// protocol alike: `kind`, then `slave`, `port`, `duration`, `direction`, `probability`, `delay`,
// `count`, `abort_code`, `code`, `position`, `load_scale`, `force` as the kind takes them. Which
// fields a kind takes, which it needs, their defaults (FaultSpec's), ranges and names live here
// only; each format supplies a FaultFieldSource that reads one named field in its own syntax and
// reports errors in its own form (a YAML file's line and column, a JSON request's field).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/fault/fault_spec.hpp"

namespace vdrive::fault {

class FaultFieldSource {
public:
  virtual ~FaultFieldSource() = default;
  virtual bool has(std::string_view field) const = 0;
  // Each reads a present field, or throws the format's error for a value of the wrong type.
  virtual std::string text(std::string_view field) = 0;
  virtual double real(std::string_view field) = 0;
  virtual std::int64_t integer(std::string_view field, std::int64_t min, std::int64_t max) = 0;
  virtual Nanos time(std::string_view field) = 0;
  // The field as text when it may name a station address: YAML's "0x..." scalars, JSON's strings
  // (which may also hold a position); nothing otherwise, and the field is read with integer().
  virtual std::optional<std::string> address_text(std::string_view field) = 0;
  // Errors: a field the kind needs is absent (`why`: what it is for); a value that is not one of
  // the accepted ones (`what` says which are); a value that breaks a rule such as a range.
  [[noreturn]] virtual void missing(std::string_view field, std::string_view why) = 0;
  [[noreturn]] virtual void invalid(std::string_view field, std::string_view what) = 0;
  [[noreturn]] virtual void out_of_range(std::string_view field, std::string_view rule) = 0;
};

// Reads `kind` and the fields that kind takes; the fields it does not take are left unread, for
// the source's own check of unexpected fields. Slaves are numbered 1..max_slave, or named by their
// station address ("0x1002", ethercat/slave_ref.hpp), found when the fault starts.
FaultSpec read_fault(FaultFieldSource& source, int max_slave);

// One field a kind takes, as read_fault() reads it: for forms and API descriptions.
struct FaultFieldInfo {
  std::string_view name;
  std::string_view type;           // "integer", "real", "time" ("250ms"), "text", "enum"
  bool required = false;
  std::string_view default_value;  // as a user would write it; empty when required
  std::string_view choices;        // enum: "both,to_slaves,to_master"
  std::string_view help;
};
// The fields of `kind`, `slave` and `duration` included where it takes them, in read_fault()'s order.
std::vector<FaultFieldInfo> fault_fields(FaultKind kind);

// "drop, corrupt, ..., brake_failure": the catalogue's names, for messages.
std::string fault_kind_names();

}  // namespace vdrive::fault
