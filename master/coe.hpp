#pragma once
// The project master keeps its own copy of this EtherCAT vocabulary on purpose, written from the
// specification and not shared with ethercat/: it is the independent test oracle of the slave, so a
// wrong value in one is caught by the other.
// CoE client of one slave (ETG.1000.6 clause 5.6.2) on top of its MailboxClient:
//
//  - SDO upload and download in every form the protocol has: expedited (up to 4 bytes), normal
//    (size in the initiate message) and segmented (toggle bit checked on every segment), each
//    optionally with complete access (the whole object from subindex 0 or 1);
//  - SDO abort decoding (SdoAbort carries the CiA 301 / ETG.1000.6 Table 41 code and its text);
//  - SDO information: OD list, object description, entry description, with fragmented replies
//    reassembled (an SDO info error request becomes SdoAbort too);
//  - emergencies are collected by the mailbox client (mailbox().emergencies()).
//
// The client talks to one slave at a time and blocks until the reply (or throws MailboxError on
// timeout). Configuration-time code: it allocates.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "master/mailbox.hpp"

namespace vdrive::master {

class SdoAbort : public std::runtime_error {
public:
  SdoAbort(std::uint16_t index, std::uint8_t subindex, std::uint32_t code);
  std::uint32_t code() const { return code_; }
  std::uint16_t index() const { return index_; }
  std::uint8_t subindex() const { return subindex_; }

private:
  std::uint16_t index_;
  std::uint8_t subindex_;
  std::uint32_t code_;
};

// The text of an SDO abort code ("Object does not exist in the object dictionary", ...).
std::string_view sdo_abort_text(std::uint32_t code);

// SDO information replies (ETG.1000.6 5.6.3).
struct ObjectDescription {
  std::uint16_t index = 0;
  std::uint16_t data_type = 0;
  std::uint8_t max_subindex = 0;
  std::uint8_t object_code = 0;    // 7 VAR, 8 ARRAY, 9 RECORD
  std::string name;
};
struct EntryDescription {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::uint8_t value_info = 0;
  std::uint16_t data_type = 0;
  std::uint16_t bit_length = 0;
  std::uint16_t access = 0;        // bits 0-5 read/write in Pre-Op/Safe-Op/Op, 6 RxPDO, 7 TxPDO mappable
  std::string name;
};

// OD list types for od_list().
namespace od_list_type {
constexpr std::uint16_t kLengths = 0, kAll = 1, kRxPdoMappable = 2, kTxPdoMappable = 3, kStoredForReplacement = 4,
                        kStartupParameters = 5;
}

class SdoClient {
public:
  explicit SdoClient(MailboxClient& mailbox) : mailbox_(mailbox) {}

  std::vector<std::uint8_t> upload(std::uint16_t index, std::uint8_t subindex, bool complete_access = false);
  void download(std::uint16_t index, std::uint8_t subindex, std::span<const std::uint8_t> data,
                bool complete_access = false);

  // Typed little-endian helpers for 1, 2, 4 and 8-byte values.
  template <class T> T upload_value(std::uint16_t index, std::uint8_t subindex) {
    const auto bytes = upload(index, subindex);
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < sizeof(T) && i < bytes.size(); ++i) v |= static_cast<std::uint64_t>(bytes[i]) << (8 * i);
    return static_cast<T>(v);
  }
  template <class T> void download_value(std::uint16_t index, std::uint8_t subindex, T value) {
    std::array<std::uint8_t, sizeof(T)> bytes{};
    for (std::size_t i = 0; i < sizeof(T); ++i) bytes[i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i));
    download(index, subindex, bytes);
  }

  std::vector<std::uint16_t> od_list(std::uint16_t list_type = od_list_type::kAll);
  ObjectDescription object_description(std::uint16_t index);
  EntryDescription entry_description(std::uint16_t index, std::uint8_t subindex, std::uint8_t value_info = 0);

  MailboxClient& mailbox() { return mailbox_; }

private:
  std::span<const std::uint8_t> sdo_reply(std::uint16_t index, std::uint8_t subindex);
  std::vector<std::uint8_t> info_request(std::uint8_t opcode, std::span<const std::uint8_t> data, std::uint16_t index,
                                         std::uint8_t subindex);

  MailboxClient& mailbox_;
};

}  // namespace vdrive::master
