#pragma once
// FoE firmware download in the mailbox (ETG.1000.6 5.7), for products whose SII General category
// advertises FoE (ProductProfile::foe_details != 0: the DS1000A-EC, "Firmware Download 対応",
// L746-L752). The manual leaves file name, password and Boot-state rules to the master, so the
// server follows the ETG defaults of the ETG slave stack code (SSC foeappl.c), see docs/foe.md:
//
//  - Write request (WRQ), by default (profile foe_strict_firmware_check false): any file, any
//    name and password, is firmware, accepted in Boot only (elsewhere 0x8008 "Bootstrap only").
//    Strict (the SSC's checks, for testing a master's error handling): a file whose name starts
//    with "ECATFW__" is firmware, accepted in Boot only, with password 0 (else 0x800A "No
//    rights"); in Boot any other name gets 0x8009 "Not Bootstrap", outside Boot 0x8002 "Access
//    denied" (the drive keeps no other files). Accepted: ACK with packet number 0.
//  - DATA n: n = last acknowledged + 1 is stored and acknowledged; n = the last acknowledged one
//    again (the master lost our ACK) is acknowledged again and not stored twice; any other n ends
//    the transfer with 0x8005 "Packet number wrong". More than max_file_bytes in all: 0x8003
//    "Disk full". A packet shorter than (SM0 length - 12) is the last. Strict: the file is checked
//    as a firmware image (firmware_image.hpp) and answered with ACK, or with 0x800C / 0x800D.
//    By default it is kept as given and acknowledged; its size and CRC-32 are last_download().
//  - With a programming time, the last packet is answered BUSY (done/entire in percent) until
//    the image is "programmed"; the master repeats that packet until it gets the ACK.
//  - Read request (RRQ): the product documents download only, so every name is 0x8001 "Not found".
//  - ERR from the master ends the transfer without a reply; ACK/BUSY/unknown op codes: 0x8004.
//  - A request shorter than the FoE header: mailbox error 0x0006 "size too short".
//
// A valid image is saved to the drive's FirmwareStore at once; the drive runs it from the next
// restart: Boot -> Init (restart()) or power-on, when 100Ah shows its version.
// The download buffer is allocated at construction; a request allocates nothing.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ethercat/foe.hpp"
#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/foe/firmware_image.hpp"
#include "vdrive/firmware/foe/firmware_store.hpp"
#include "vdrive/firmware/mailbox/protocol.hpp"

namespace vdrive::od { struct EntryDesc; }

namespace vdrive::firmware::foe {

inline constexpr std::string_view kFirmwareNamePrefix = "ECATFW__";  // SSC aFirmwareDownloadHeader
inline constexpr std::uint32_t kFirmwarePassword = 0;                // ETG: no password
inline constexpr std::size_t kMaxFirmwareBytes = 256 * 1024;         // not in manual: our limit

struct FoeOptions {
  std::string state_dir;                        // empty: coe::default_state_dir()
  std::size_t max_file_bytes = kMaxFirmwareBytes;
  Nanos programming_time = 0;                   // BUSY this long after the last packet (0: none)
};

class FoeServer final : public mailbox::Protocol {
public:
  FoeServer(FirmwareContext& context, const FoeOptions& options);
  ~FoeServer() override;

  mailbox::Outcome on_request(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply,
                              Nanos now) override;
  // The mailbox stopped: a transfer in progress is forgotten (an image being programmed is
  // finished first: the flash write does not depend on the master).
  void reset() override;

  // SM0 length as the master configured it: DATA packets carry up to this - 12 bytes.
  void set_request_window(std::size_t sm0_length) { sm0_length_ = sm0_length; }
  // Boot -> Init: the drive restarts and runs the image downloaded in Boot (100Ah changes).
  void restart();
  // Power-on (the object store was reset): the drive runs the stored image, if any.
  void power_on();

  std::string_view running_version() const { return {running_.data(), running_length_}; }
  // The last file taken (the image as given): its size and CRC-32 (IEEE 802.3, as zlib's crc32).
  struct Download {
    std::size_t bytes = 0;
    std::uint32_t crc32 = 0;
  };
  const Download& last_download() const { return last_download_; }
  const FirmwareStore& store() const { return store_; }

private:
  enum class Phase : std::uint8_t { Idle, Writing, Programming, Done };

  mailbox::Outcome write_request(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply);
  mailbox::Outcome data(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply, Nanos now);
  mailbox::Outcome last_packet(std::span<std::uint8_t> reply, Nanos now);
  mailbox::Outcome programming(std::span<std::uint8_t> reply, Nanos now);
  void program_image();
  void show_version(std::string_view version);

  static mailbox::Outcome ack(std::span<std::uint8_t> reply, std::uint32_t packet);
  mailbox::Outcome error(std::span<std::uint8_t> reply, ecat::foe::ErrorCode code);

  FirmwareContext& context_;
  FirmwareStore store_;
  std::size_t max_file_bytes_;
  Nanos programming_time_;
  const od::EntryDesc* version_entry_ = nullptr;  // 100Ah
  std::string factory_version_;
  std::vector<std::uint8_t> buffer_;              // the file being received
  std::size_t received_ = 0;
  std::size_t sm0_length_ = 0;
  Phase phase_ = Phase::Idle;
  std::uint32_t packet_ = 0;                      // last acknowledged packet number
  Nanos programmed_at_ = 0;                       // Programming: when the flash write is done
  std::array<char, kImageFieldSize> pending_{};   // version of the image programmed in this Boot
  std::size_t pending_length_ = 0;
  std::array<char, kImageFieldSize> running_{};   // version the drive runs (100Ah)
  std::size_t running_length_ = 0;
  std::array<char, kImageFieldSize> flash_{};     // version in "flash" (file or memory)
  std::size_t flash_length_ = 0;
  bool strict_ = false;                           // profile foe_strict_firmware_check
  Download last_download_;
};

}  // namespace vdrive::firmware::foe
