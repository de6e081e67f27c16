#pragma once
// The mailbox of the slave firmware (ETG.1000.4/.6): serves SM0 (master -> slave, AL event bit 8)
// and SM1 (slave -> master, AL event bit 9) through the PDI while the slave is in PreOp, SafeOp,
// Op or Boot.
//
//  - A request is read from SM0 only when a reply slot is free (otherwise it stays in SM0 and the
//    master cannot write the next one); reading its last byte hands SM0 back to the master.
//  - Header checks, in the order slave stacks apply them: type 0 or length 0 -> error 0x05
//    (invalid header); length beyond SM0 -> 0x08 (invalid size); a repeated counter (1..7) is a
//    duplicate and is dropped; a protocol the slave does not serve -> 0x02 (unsupported protocol).
//    FoE goes to foe::FoeServer on products whose SII FoE details say so (foe_details != 0), every
//    other product answers it 0x02 (A6B: FoE unsupported L656/L705 although SII word 1Ch has the
//    bit); in Boot only FoE is served (docs/foe.md).
//  - Replies wait in a small fixed queue and go to SM1 when it is empty (written up to its last
//    byte, which hands it to the master); the reply counter cycles 1..7.
//  - Repeat request (SM1 activate bit1 toggled by the master): the last reply is written again and
//    PDI control 0x080F bit1 is set equal to it (repeat ack).
//  - Injected faults (mailbox_faults.hpp): lost, duplicated replies, a wrong toggle bit, an
//    abort instead of an answer; set_faults() arms them, each is used up as it acts.
//  - Emergencies: up to kEmergencySlots are kept (oldest dropped) while the mailbox cannot send,
//    e.g. in Init, and sent first once it can (A6B L4565-L4569).
// Buffers are sized from the profile's mailbox sizes at construction; nothing allocates later.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ethercat/emergency.hpp"
#include "ethercat/mailbox_header.hpp"
#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/foe/foe_server.hpp"
#include "vdrive/firmware/mailbox/mailbox_faults.hpp"
#include "vdrive/firmware/mailbox/reply_queue.hpp"

namespace vdrive::firmware::coe { class CoeServer; }

namespace vdrive::firmware::mailbox {

struct MailboxOptions {
  // Where 1010h "save" keeps this drive's parameters; empty: $VDRIVE_STATE_DIR, else
  // $XDG_STATE_HOME/vdrive, else /var/lib/vdrive.
  std::string state_dir;
  // FoE firmware download (products with FoE): file size limit, and how long the drive reports
  // BUSY while it programs an image (0: it acknowledges the last packet at once).
  std::size_t foe_max_file_bytes = foe::kMaxFirmwareBytes;
  Nanos foe_programming_time = 0;
};

class MailboxModule final : public FirmwareModule {
public:
  static constexpr std::size_t kReplySlots = 4;
  static constexpr std::size_t kEmergencySlots = 8;  // A6B buffers 8 (L4565-L4569)

  MailboxModule(FirmwareContext& context, const MailboxOptions& options = {});
  ~MailboxModule() override;

  std::uint32_t serviced_events() const override;
  void on_events(std::uint32_t events, Nanos now) override;
  void entered(ecat::AlState from, ecat::AlState to, Nanos now) override;
  // Stored parameters are loaded; queued replies and emergencies (RAM) are gone.
  void power_on(Nanos now) override;

  // Queues an emergency; sent as soon as the mailbox runs and SM1 is free.
  void post_emergency(const ecat::coe::Emergency& emergency);

  std::size_t pending_replies() const { return queue_.size(); }
  std::size_t pending_emergencies() const { return emergency_count_; }
  // Fault injection: replaces the faults still to come; faults() counts down as they act.
  void set_faults(const MailboxFaults& faults) { faults_ = faults; }
  const MailboxFaults& faults() const { return faults_; }

  // The FoE server, nullptr for products without FoE.
  foe::FoeServer* foe() { return foe_.get(); }

private:
  void service(Nanos now);
  bool receive_request(Nanos now);
  void dispatch(const ecat::mailbox::Header& header, std::span<const std::uint8_t> payload, Nanos now);
  void queue_reply(Protocol& protocol, ecat::mailbox::Type type, std::span<const std::uint8_t> payload, Nanos now);
  void queue_error(ecat::mailbox::ErrorCode code);
  bool inject_abort(std::span<const std::uint8_t> payload);
  void inject_toggle_error(std::span<std::uint8_t> coe_payload);
  void queue_fragments();
  bool send_next();
  bool write_sm1(std::span<const std::uint8_t> message);
  void put_sm1(std::span<const std::uint8_t> message);
  void service_repeat_request();
  bool sm_full(int n);
  bool has_outgoing() const;  // a reply, an emergency or an injected duplicate waits for SM1
  void watch_sm1(bool on);    // SM1's event in the AL event mask
  bool write_duplicate();

  FirmwareContext& context_;
  std::unique_ptr<coe::CoeServer> coe_;
  std::unique_ptr<foe::FoeServer> foe_;
  bool running_ = false;
  bool sm1_watched_ = false;
  bool boot_ = false;
  std::uint16_t sm0_start_ = 0, sm0_length_ = 0, sm1_start_ = 0, sm1_length_ = 0;
  std::size_t reply_capacity_ = 0;   // bytes of a reply incl. header: min(SM1 length, buffer)
  std::uint8_t last_request_counter_ = 0;
  std::uint8_t reply_counter_ = 0;
  std::vector<std::uint8_t> request_;     // SM0 image (header + payload)
  ReplyQueue queue_;
  std::vector<std::uint8_t> sent_;        // last message written to SM1 (for a repeat)
  std::size_t sent_length_ = 0;
  std::vector<std::uint8_t> previous_;    // the one before (if the master lost it, `sent_` waits unread)
  std::size_t previous_length_ = 0;
  std::vector<std::uint8_t> zeros_;       // padding up to SM1's last byte
  std::vector<std::uint8_t> resend_;      // a repeated message while sent_/previous_ rotate
  MailboxFaults faults_;
  bool duplicate_pending_ = false;        // sent_ goes to SM1 once more when it is free
  std::array<ecat::coe::Emergency, kEmergencySlots> emergencies_{};
  std::size_t emergency_head_ = 0, emergency_count_ = 0;
};

}  // namespace vdrive::firmware::mailbox
