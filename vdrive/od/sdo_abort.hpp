#pragma once
// CiA 301 / ETG.1000.6 SDO abort codes. Every OD access returns one (Ok = success).
#include <cstdint>
#include <string_view>

namespace vdrive::od {

enum class SdoAbort : std::uint32_t {
  Ok = 0,
  ToggleBit = 0x05030000,
  Timeout = 0x05040000,
  UnknownCommand = 0x05040001,
  OutOfMemory = 0x05040005,
  UnsupportedAccess = 0x06010000,
  WriteOnly = 0x06010001,
  ReadOnly = 0x06010002,
  SubindexCannotBeWritten = 0x06010003,      // complete access: subindex 0 must be 0
  CompleteAccessUnsupported = 0x06010004,
  ObjectTooLong = 0x06010005,                // for the mailbox
  ObjectMappedToRxPdo = 0x06010006,
  NoSuchObject = 0x06020000,
  NotMappable = 0x06040041,
  PdoLengthExceeded = 0x06040042,
  ParameterIncompatible = 0x06040043,
  DeviceIncompatible = 0x06040047,
  HardwareError = 0x06060000,
  LengthMismatch = 0x06070010,
  LengthTooHigh = 0x06070012,
  LengthTooLow = 0x06070013,
  NoSuchSubindex = 0x06090011,
  ValueRangeExceeded = 0x06090030,
  ValueTooHigh = 0x06090031,
  ValueTooLow = 0x06090032,
  ModuleListMismatch = 0x06090033,
  MaxLessThanMin = 0x06090036,
  GeneralError = 0x08000000,
  CannotTransfer = 0x08000020,
  CannotTransferLocal = 0x08000021,
  WrongState = 0x08000022,                   // "in the present device state"
  NoObjectDictionary = 0x08000023,
};

std::string_view describe(SdoAbort code);

}  // namespace vdrive::od
