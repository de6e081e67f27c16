#pragma once
// CoE SDO Information service (ETG.1000.6 5.6.3): Get OD List (list types 0-5), Get Object
// Description, Get Entry Description (with value info), fragmented replies and the SDO Info Error
// Request. Each reply carries the header opcode | 0x80 "incomplete" while fragments follow, and the
// number of fragments still to come; the mailbox asks for the next fragment when a reply buffer is
// free (next_fragment). A new request drops a listing in progress.
//
// List types: 1 all objects; 2 objects with an RxPDO-mappable entry; 3 with a TxPDO-mappable
// entry; 4 objects stored for device replacement = what 1010h "save" keeps (none without 1010h);
// 5 startup parameters = objects with an entry writable in PreOp (outside 1010h/1011h); 0 the
// five counts. Entry description value info: bit3 unit type (UINT16, 0: the dictionary has unit
// names only), bit4 default, bit5 minimum, bit6 maximum (each as wide as the entry).
#include <cstdint>
#include <span>
#include <vector>

#include "ethercat/coe.hpp"
#include "vdrive/firmware/mailbox/protocol.hpp"
#include "vdrive/od/dictionary.hpp"

namespace vdrive::firmware::coe {

class SdoInfo {
public:
  SdoInfo(const od::Dictionary& dictionary, bool has_store);

  mailbox::Outcome on_request(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply);
  std::size_t next_fragment(std::span<std::uint8_t> reply);
  void reset() { pending_ = Body::None; }

  // Objects in list `type` (1-5), as the listing counts them.
  std::size_t count(std::uint16_t list_type) const;

private:
  enum class Body { None, OdList, Rendered };
  bool in_list(const od::ObjectDesc& object, std::uint16_t list_type) const;
  void copy_body(std::size_t offset, std::span<std::uint8_t> out);
  std::size_t fragment(std::span<std::uint8_t> reply);
  std::size_t error(std::span<std::uint8_t> reply, std::uint32_t code);
  std::size_t render_object(const od::ObjectDesc& object);
  std::size_t render_entry(const od::EntryDesc& entry, std::uint8_t value_info);

  const od::Dictionary& dict_;
  bool has_store_;
  std::vector<std::uint8_t> rendered_;   // an object or entry description, sized at start-up
  Body pending_ = Body::None;
  ecat::coe::info::Opcode opcode_ = ecat::coe::info::Opcode::GetOdListResponse;
  std::uint16_t list_type_ = 0;
  std::size_t size_ = 0, offset_ = 0, fragments_left_ = 0;
  // OD-list cursor: the next object to look at.
  std::size_t cursor_object_ = 0;
};

}  // namespace vdrive::firmware::coe
