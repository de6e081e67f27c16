#pragma once
// CoE SDO server (ETG.1000.6 5.6.2) on the slave's od::ObjectStore: expedited, normal and
// segmented upload and download, complete access where the product has it, aborts.
//
//  - Access rules, ranges and lengths are the store's: its abort code is sent as is.
//  - Segments carry a toggle bit starting at 0; a wrong toggle aborts 05030000h and ends the
//    transfer. A segment with no transfer in progress, or an unknown command specifier, aborts
//    05040001h. An abort from the master ends the transfer silently.
//  - Complete access (SII CoE details bit5): subindex 0 or 1 only, subindex 0 travels as 16 bits.
//    Products without it answer the product's code, ProductProfile::complete_access_abort
//    (profile.yaml `complete_access_abort`).
//  - A download is stored at once; objects whose effect the drive applies only at a transition or
//    at power-up are read from the store by the module that owns them at that moment (so the
//    store is the hook; see docs/coe.md). `after_download` tells the parameter store about
//    1010h/1011h commands.
// One staging buffer, the size of the largest object, is allocated at construction.
#include <cstdint>
#include <span>
#include <vector>

#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/mailbox/protocol.hpp"
#include "vdrive/firmware/sdo_abort_record.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::coe {

class ParameterStore;

// The abort a product answers to a complete-access request when it has no complete access
// (ProductProfile::complete_access_abort).
od::SdoAbort complete_access_refusal(const profile::ProductProfile& profile);

class SdoServer {
public:
  // `aborts` (may be null) counts every abort this server answers.
  SdoServer(const profile::ProductProfile& profile, od::ObjectStore& objects,
            const AlStateMachine& esm, ParameterStore* parameters, SdoAbortRecord* aborts = nullptr);

  // One SDO request (mailbox payload incl. the CoE header); the SDO response or abort is written
  // to `reply` (incl. the CoE header).
  mailbox::Outcome on_request(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply);
  void reset() { transfer_ = Transfer::None; }

private:
  enum class Transfer { None, Upload, Download };

  std::size_t initiate_upload(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply);
  std::size_t upload_segment(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply);
  std::size_t initiate_download(std::span<const std::uint8_t> request,
                                std::span<std::uint8_t> reply);
  std::size_t download_segment(std::span<const std::uint8_t> request,
                               std::span<std::uint8_t> reply);

  od::SdoAbort read_object(std::uint16_t index, std::uint8_t subindex, bool complete,
                           std::size_t& size);
  od::SdoAbort write_object(std::uint16_t index, std::uint8_t subindex, bool complete,
                            std::span<const std::uint8_t> data);
  std::size_t abort(std::span<std::uint8_t> reply, std::uint16_t index, std::uint8_t subindex,
                    od::SdoAbort code);
  std::size_t download_response(std::span<std::uint8_t> reply, std::uint16_t index,
                                std::uint8_t subindex);

  const profile::ProductProfile& profile_;
  od::ObjectStore& objects_;
  const AlStateMachine& esm_;
  ParameterStore* parameters_;
  SdoAbortRecord* aborts_;
  bool complete_access_;
  std::vector<std::uint8_t> value_;   // staging: one object (complete access) or one entry

  Transfer transfer_ = Transfer::None;
  std::uint16_t index_ = 0;
  std::uint8_t subindex_ = 0;
  bool complete_ = false;
  bool toggle_ = false;
  std::size_t size_ = 0, offset_ = 0;
};

}  // namespace vdrive::firmware::coe
