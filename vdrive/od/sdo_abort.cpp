#include "vdrive/od/sdo_abort.hpp"

namespace vdrive::od {

// Texts as CiA 301 / ETG.1000.6 word them.
std::string_view describe(SdoAbort code) {
  switch (code) {
    case SdoAbort::Ok: return "no error";
    case SdoAbort::ToggleBit: return "toggle bit not changed";
    case SdoAbort::Timeout: return "SDO protocol timeout";
    case SdoAbort::UnknownCommand: return "client/server command specifier not valid or unknown";
    case SdoAbort::OutOfMemory: return "out of memory";
    case SdoAbort::UnsupportedAccess: return "unsupported access to an object";
    case SdoAbort::WriteOnly: return "attempt to read a write-only object";
    case SdoAbort::ReadOnly: return "attempt to write a read-only object";
    case SdoAbort::SubindexCannotBeWritten: return "subindex cannot be written, SI0 must be 0 for write access";
    case SdoAbort::CompleteAccessUnsupported: return "SDO complete access not supported";
    case SdoAbort::ObjectTooLong: return "object length exceeds mailbox size";
    case SdoAbort::ObjectMappedToRxPdo: return "object mapped to RxPDO, SDO download blocked";
    case SdoAbort::NoSuchObject: return "the object does not exist in the object directory";
    case SdoAbort::NotMappable: return "the object cannot be mapped into the PDO";
    case SdoAbort::PdoLengthExceeded: return "the number and length of the objects to be mapped would exceed the PDO length";
    case SdoAbort::ParameterIncompatible: return "general parameter incompatibility reason";
    case SdoAbort::DeviceIncompatible: return "general internal incompatibility in the device";
    case SdoAbort::HardwareError: return "access failed due to a hardware error";
    case SdoAbort::LengthMismatch: return "data type does not match, length of service parameter does not match";
    case SdoAbort::LengthTooHigh: return "data type does not match, length of service parameter too high";
    case SdoAbort::LengthTooLow: return "data type does not match, length of service parameter too low";
    case SdoAbort::NoSuchSubindex: return "subindex does not exist";
    case SdoAbort::ValueRangeExceeded: return "value range of parameter exceeded";
    case SdoAbort::ValueTooHigh: return "value of parameter written too high";
    case SdoAbort::ValueTooLow: return "value of parameter written too low";
    case SdoAbort::ModuleListMismatch: return "detected module ident list (0xF030) and configured module list (0xF020) do not match";
    case SdoAbort::MaxLessThanMin: return "maximum value is less than minimum value";
    case SdoAbort::GeneralError: return "general error";
    case SdoAbort::CannotTransfer: return "data cannot be transferred or stored to the application";
    case SdoAbort::CannotTransferLocal: return "data cannot be transferred or stored to the application because of local control";
    case SdoAbort::WrongState: return "data cannot be transferred or stored to the application because of the present device state";
    case SdoAbort::NoObjectDictionary: return "object dictionary dynamic generation fails or no object dictionary is present";
  }
  return "unknown abort code";
}

}  // namespace vdrive::od
