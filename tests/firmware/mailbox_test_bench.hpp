#pragma once
// A bench for the mailbox module: one ESC, the module on a real od::ObjectStore, and a master's
// view over the wire (APWR into SM0, APRD from SM1, as SOEM does). The AL state machine is driven
// directly (its own tests live elsewhere); the module sees its events as SlaveFirmware delivers
// them. The dictionary is the product's own, or a test-only objects.yaml from `profile_dir`.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/mailbox/mailbox_module.hpp"
#include "vdrive/firmware/pdi.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::firmware::mailbox_test {

// A fresh directory under the system temp dir, removed with the object.
class TempDir {
public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "vdrive-coe-XXXXXX").string();
    path = ::mkdtemp(pattern.data()) ? pattern : std::string();
  }
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) std::filesystem::remove_all(path, ec);
  }
  std::string path;
};

inline std::vector<std::uint8_t> message(std::uint8_t type, std::uint8_t counter,
                                         std::vector<std::uint8_t> payload) {
  std::vector<std::uint8_t> m{static_cast<std::uint8_t>(payload.size()),
                              static_cast<std::uint8_t>(payload.size() >> 8), 0, 0, 0,
                              static_cast<std::uint8_t>((type & 0x0F) | ((counter & 7) << 4))};
  m.insert(m.end(), payload.begin(), payload.end());
  return m;
}

inline std::uint16_t u16_at(const std::vector<std::uint8_t>& b, std::size_t at) {
  return static_cast<std::uint16_t>(b.at(at) | (b.at(at + 1) << 8));
}
inline std::uint32_t u32_at(const std::vector<std::uint8_t>& b, std::size_t at) {
  return static_cast<std::uint32_t>(u16_at(b, at)) | (static_cast<std::uint32_t>(u16_at(b, at + 2)) << 16);
}

class Bench final : TransitionHooks {
public:
  explicit Bench(profile::ProductProfile p, const std::string& profile_dir = {},
                 std::string state_dir = {})
      : product(std::move(p)),
        esc(profile::make_esc_config(product), clock),
        pdi(esc),
        dictionary(od::Dictionary::load(product, profile_dir)),
        objects(dictionary),
        esm(EsmTraits::of(product)),
        context{product, pdi, objects, esm, &aborts},
        module(context, mailbox::MailboxOptions{state_dir.empty() ? temp.path : state_dir}) {
    pdi.write_u32(reg::kAlEventMask, module.serviced_events());
    module.power_on(clock.now());
  }

  // ---- the wire -------------------------------------------------------------------------------
  std::uint16_t datagram(std::uint8_t cmd, std::uint16_t ado, std::span<std::uint8_t> data) {
    std::vector<std::uint8_t> pdu;
    const std::size_t dg_len = 10 + data.size() + 2;
    pdu.push_back(static_cast<std::uint8_t>(dg_len & 0xFF));
    pdu.push_back(static_cast<std::uint8_t>(0x10 | ((dg_len >> 8) & 0x07)));
    pdu.insert(pdu.end(), {cmd, 0x00, 0x00, 0x00, static_cast<std::uint8_t>(ado & 0xFF),
                           static_cast<std::uint8_t>(ado >> 8),
                           static_cast<std::uint8_t>(data.size() & 0xFF),
                           static_cast<std::uint8_t>((data.size() >> 8) & 0x07), 0x00, 0x00});
    pdu.insert(pdu.end(), data.begin(), data.end());
    pdu.push_back(0x00);
    pdu.push_back(0x00);
    EXPECT_TRUE(esc.process_frame(pdu, esc::FrameTiming{clock.now()}));
    std::copy(pdu.begin() + 12, pdu.begin() + 12 + static_cast<std::ptrdiff_t>(data.size()),
              data.begin());
    const std::size_t wkc_at = 12 + data.size();
    service();
    return static_cast<std::uint16_t>(pdu[wkc_at] | (pdu[wkc_at + 1] << 8));
  }
  // A prebuilt one-datagram frame, and running it (in place) as the event loop does.
  static std::vector<std::uint8_t> pdu(std::uint8_t cmd, std::uint16_t ado,
                                       const std::vector<std::uint8_t>& data) {
    const std::size_t dg_len = 10 + data.size() + 2;
    std::vector<std::uint8_t> p{static_cast<std::uint8_t>(dg_len & 0xFF),
                                static_cast<std::uint8_t>(0x10 | ((dg_len >> 8) & 0x07)),
                                cmd, 0x00, 0x00, 0x00, static_cast<std::uint8_t>(ado & 0xFF),
                                static_cast<std::uint8_t>(ado >> 8),
                                static_cast<std::uint8_t>(data.size() & 0xFF),
                                static_cast<std::uint8_t>((data.size() >> 8) & 0x07), 0x00, 0x00};
    p.insert(p.end(), data.begin(), data.end());
    p.push_back(0x00);
    p.push_back(0x00);
    return p;
  }
  void run(std::vector<std::uint8_t>& frame) {
    esc.process_frame(frame, esc::FrameTiming{clock.now()});
    service();
  }
  // What SlaveFirmware does on the PDI interrupt for this module.
  void service() {
    if (esc.pdi_irq() == 0) return;
    module.on_events(pdi.read_u32(reg::kAlEventRequest), clock.now());
  }
  std::uint16_t write(std::uint16_t ado, std::vector<std::uint8_t> bytes) {
    return datagram(0x02, ado, bytes);
  }
  std::vector<std::uint8_t> read(std::uint16_t ado, std::size_t n) {
    std::vector<std::uint8_t> b(n);
    last_read_wkc = datagram(0x01, ado, b);
    return b;
  }

  void configure_sm(int n, std::uint16_t start, std::uint16_t length, std::uint8_t control) {
    const auto base = static_cast<std::uint16_t>(0x0800 + 8 * n);
    write(static_cast<std::uint16_t>(base + 6), {0x00});
    write(base, {static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8),
                 static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8), control});
    write(static_cast<std::uint16_t>(base + 6), {0x01});
  }
  void request_state(ecat::AlState s) { esm.on_al_control(ecat::AlControl{static_cast<std::uint8_t>(s)}, 0, *this); }
  void to_preop() {
    for (int n = 0; n < 2; ++n) {
      const auto& sm = product.sync_managers.at(static_cast<std::size_t>(n));
      configure_sm(n, sm.start, sm.length, sm.control);
    }
    request_state(ecat::AlState::PreOp);
    ASSERT_EQ(esm.state(), ecat::AlState::PreOp);
  }
  std::uint16_t sm0_start() const { return product.sync_managers.at(0).start; }
  std::uint16_t sm0_length() const { return product.sync_managers.at(0).length; }
  std::uint16_t sm1_start() const { return product.sync_managers.at(1).start; }
  std::uint16_t sm1_length() const { return product.sync_managers.at(1).length; }

  // A master's mailbox write: the whole SM0 window. Returns the working counter (0 = SM0 full).
  std::uint16_t send(const std::vector<std::uint8_t>& m) {
    std::vector<std::uint8_t> window(sm0_length(), 0);
    std::copy_n(m.begin(), std::min(m.size(), window.size()), window.begin());
    return write(sm0_start(), window);
  }
  // A master's mailbox poll: SM1 status, then the whole SM1 window if it is full. Returns the
  // message (header + payload as its length says).
  std::optional<std::vector<std::uint8_t>> receive() {
    if ((read(0x080D, 1)[0] & 0x08) == 0) return std::nullopt;
    std::vector<std::uint8_t> window = read(sm1_start(), sm1_length());
    if (last_read_wkc != 1) return std::nullopt;
    const std::size_t n = std::min<std::size_t>(6 + u16_at(window, 0), window.size());
    window.resize(n);
    return window;
  }
  // Sends with the next request counter (1..7) and returns the reply.
  std::optional<std::vector<std::uint8_t>> exchange(std::uint8_t type, std::vector<std::uint8_t> payload) {
    counter = counter >= 7 ? 1 : counter + 1;
    EXPECT_EQ(send(message(type, counter, std::move(payload))), 1);
    return receive();
  }

  // ---- TransitionHooks: every check passes, the module learns the new state ----------------
  CheckResult check_init_to_preop() override { return CheckResult::pass(); }
  CheckResult check_init_to_boot() override { return CheckResult::pass(); }
  CheckResult check_preop_to_safeop() override { return CheckResult::pass(); }
  CheckResult check_safeop_to_op() override { return CheckResult::pass(); }
  void entered(ecat::AlState from, ecat::AlState to) override { module.entered(from, to, clock.now()); }

  TempDir temp;
  VirtualClock clock;
  profile::ProductProfile product;
  esc::Esc esc;
  Pdi pdi;
  od::Dictionary dictionary;
  od::ObjectStore objects;
  AlStateMachine esm;
  SdoAbortRecord aborts;  // the SDO server's count of its aborts
  FirmwareContext context;
  mailbox::MailboxModule module;
  std::uint8_t counter = 0;
  std::uint16_t last_read_wkc = 0;
};

}  // namespace vdrive::firmware::mailbox_test
