// libFuzzer target: a CiA 402 drive in Op with cyclic process data, moving its plant. One slave
// (a real ESC and its whole SlaveFirmware: mailbox, CoE, FoE, PDO, sync, the drive and its plant)
// is brought to Op over the wire as a master brings it (mailbox SMs, PreOp, SM2/SM3 and FMMUs for
// the product's default mapping, SafeOp, Op; free run), then arbitrary outputs run as cycles.
//
// Input: byte 0 picks the product (a6b, ds5c1, ds1000a); then records [op(1) bytes...]:
//   op & 3 == 0: [n(1) bytes(n)] overwrite the RxPDO image from its start (the rest keeps its
//                value), then run (op >> 2) + 1 cycles of 1 ms;
//   op & 3 == 1: [entry(1) value(4, LE)] set one mapped RxPDO entry (6040h, 6060h, 607Ah, ...,
//                by its position in the mapping, modulo the count) to the value's low bits, then
//                run (op >> 2) + 1 cycles; this reaches the controlword/mode/set-point fields
//                without knowing the product's layout;
//   op & 3 == 2: [index(2, LE) sub(1) value(4, LE)] an expedited SDO download of (op >> 2) & 3
//                + 1 bytes over the mailbox (a mode, a limit, a gain...), its answer read back;
//   op & 3 == 3: [control(1)] AL control request, then one cycle.
// At most kMaxCycles cycles per input. After every cycle: the plant's state, the command the
// drive gave it and the drive's sample (what 6064h, 606Ch and 6077h are rounded from) must be
// finite; anything else is a trap. A slave that does not reach Op at the start is a trap too (a
// broken bench would fuzz nothing). Each input starts from the same state: a fresh firmware and
// plant on a reset ESC at time 0, with an empty parameter directory (1010h "save" may be reached).
#include <stdlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "plant/plant.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace {

constexpr std::uint8_t kAprd = 0x01, kApwr = 0x02, kLrw = 0x0C;
constexpr std::uint32_t kLogical = 0x00010000;
constexpr vdrive::Nanos kCycle = 1'000'000;
constexpr int kMaxCycles = 256;  // bounds an input's cost (the plant steps every control period)

struct Entry {
  std::size_t bit = 0;  // offset in the RxPDO image
  std::uint8_t bits = 0;
};

// Bytes of the default mapping assigned to `sm`, and its entries' places.
std::size_t mapped_bytes(const std::vector<vdrive::profile::PdoSpec>& pdos,
                         std::uint8_t sm, std::vector<Entry>* entries) {
  std::size_t bit = 0;
  for (const auto& pdo : pdos) {
    if (pdo.sync_manager != sm) continue;
    for (const auto& e : pdo.entries) {
      if (entries != nullptr && e.index != 0) entries->push_back({bit, e.bit_length});
      bit += e.bit_length;
    }
  }
  return (bit + 7) / 8;
}

bool finite(double v) { return std::isfinite(v); }

class DriveBench {
public:
  explicit DriveBench(const std::string& id)
      : product_(vdrive::profile::load_profile(id)), esc_(vdrive::profile::make_esc_config(product_), clock_) {
    out_bytes_ = mapped_bytes(product_.rx_pdos, 2, &entries_);
    in_bytes_ = mapped_bytes(product_.tx_pdos, 3, nullptr);
    outputs_.assign(out_bytes_, 0);
    lrw_ = datagram(kLrw, kLogical, nullptr, out_bytes_ + in_bytes_);
  }

  // A fresh firmware and plant at time 0, taken to Op with outputs that hold the drive still.
  void reset() {
    firmware_.reset();
    clock_.set(0);
    esc_.reset();
    firmware_ = std::make_unique<vdrive::firmware::SlaveFirmware>(product_, esc_);
    firmware_->power_on(0);
    counter_ = 0;
    for (int n = 0; n < 2; ++n) {
      const auto& s = product_.sync_managers.at(static_cast<std::size_t>(n));
      sm(n, s.start, s.length, s.control, true);
    }
    request(0x02);
    const auto& s2 = product_.sync_managers.at(2);
    const auto& s3 = product_.sync_managers.at(3);
    sm(2, s2.start, static_cast<std::uint16_t>(out_bytes_), s2.control, out_bytes_ > 0);
    sm(3, s3.start, static_cast<std::uint16_t>(in_bytes_), s3.control, in_bytes_ > 0);
    if (out_bytes_ > 0) fmmu(0, kLogical, static_cast<std::uint16_t>(out_bytes_), s2.start, 0x02);
    if (in_bytes_ > 0) fmmu(1, static_cast<std::uint32_t>(kLogical + out_bytes_), static_cast<std::uint16_t>(in_bytes_), s3.start, 0x01);
    request(0x04);
    std::fill(outputs_.begin(), outputs_.end(), 0);
    cycle();
    request(0x08);
    if ((read_u16(0x0130) & 0x0F) != 0x08) __builtin_trap();  // the bench must reach Op
  }

  // One 1 ms bus cycle: outputs out and inputs in (LRW), then the firmware runs until the next.
  void cycle() {
    std::copy(outputs_.begin(), outputs_.end(), lrw_.begin() + 12);
    run(lrw_);
    const vdrive::Nanos end = clock_.now() + kCycle;
    while (clock_.now() < end) {
      const vdrive::Nanos step = std::clamp<vdrive::Nanos>(firmware_->next_deadline() - clock_.now(), 1, end - clock_.now());
      clock_.advance(step);
      esc_.tick(clock_.now());
      service();
      if (firmware_->next_deadline() <= clock_.now()) firmware_->tick(clock_.now());
    }
    check();
  }

  void set_entry(std::uint8_t which, std::uint32_t value) {
    if (entries_.empty()) return;
    const Entry& e = entries_[which % entries_.size()];
    for (std::size_t i = 0; i < e.bits; ++i) {
      const std::size_t bit = e.bit + i;
      if (bit / 8 >= outputs_.size()) break;
      const auto mask = static_cast<std::uint8_t>(1u << (bit % 8));
      if (i < 32 && (value >> i) & 1u) outputs_[bit / 8] |= mask;
      else outputs_[bit / 8] &= static_cast<std::uint8_t>(~mask);
    }
  }
  void set_outputs(const std::uint8_t* bytes, std::size_t n) {
    std::copy_n(bytes, std::min(n, outputs_.size()), outputs_.begin());
  }

  // An expedited SDO download (CoE), then SM1 read so the answer does not block the mailbox.
  void sdo_download(std::uint16_t index, std::uint8_t sub, std::uint32_t value, int size) {
    const auto& sm0 = product_.sync_managers.at(0);
    const auto& sm1 = product_.sync_managers.at(1);
    std::vector<std::uint8_t> mbx(sm0.length, 0);
    if (mbx.size() < 16) return;
    counter_ = static_cast<std::uint8_t>(counter_ % 7 + 1);
    const std::uint8_t command = static_cast<std::uint8_t>(0x23 | ((4 - size) << 2));
    const std::uint8_t head[] = {10, 0, 0, 0, 0, static_cast<std::uint8_t>(0x03 | (counter_ << 4)),
                                 0x00, 0x20, command, static_cast<std::uint8_t>(index), static_cast<std::uint8_t>(index >> 8), sub,
                                 static_cast<std::uint8_t>(value), static_cast<std::uint8_t>(value >> 8),
                                 static_cast<std::uint8_t>(value >> 16), static_cast<std::uint8_t>(value >> 24)};
    std::copy(std::begin(head), std::end(head), mbx.begin());
    auto w = datagram(kApwr, static_cast<std::uint32_t>(sm0.start) << 16, mbx.data(), mbx.size());
    run(w);
    cycle();
    auto r = datagram(kAprd, static_cast<std::uint32_t>(sm1.start) << 16, nullptr, sm1.length);
    run(r);
  }

  void request(std::uint8_t control) {
    write(0x0120, {control, 0x00});
    cycle();
  }

private:
  static std::vector<std::uint8_t> datagram(std::uint8_t cmd, std::uint32_t address, const std::uint8_t* data, std::size_t n) {
    const std::size_t dg_len = 10 + n + 2;
    std::vector<std::uint8_t> pdu = {static_cast<std::uint8_t>(dg_len & 0xFF), static_cast<std::uint8_t>(0x10 | ((dg_len >> 8) & 0x07)),
                                     cmd, 0x00, static_cast<std::uint8_t>(address), static_cast<std::uint8_t>(address >> 8),
                                     static_cast<std::uint8_t>(address >> 16), static_cast<std::uint8_t>(address >> 24),
                                     static_cast<std::uint8_t>(n & 0xFF), static_cast<std::uint8_t>((n >> 8) & 0x07), 0x00, 0x00};
    if (data != nullptr) pdu.insert(pdu.end(), data, data + n);
    else pdu.resize(pdu.size() + n, 0);
    pdu.push_back(0);
    pdu.push_back(0);
    return pdu;
  }
  void run(std::vector<std::uint8_t>& pdu) {
    pdu[pdu.size() - 2] = 0;
    pdu[pdu.size() - 1] = 0;
    esc_.process_frame(pdu, vdrive::esc::FrameTiming{clock_.now()});
    service();
  }
  void service() {
    if (esc_.pdi_irq() != 0) firmware_->on_irq(clock_.now());
  }
  void write(std::uint16_t ado, std::vector<std::uint8_t> bytes) {
    auto pdu = datagram(kApwr, static_cast<std::uint32_t>(ado) << 16, bytes.data(), bytes.size());
    run(pdu);
  }
  std::uint16_t read_u16(std::uint16_t ado) {
    auto pdu = datagram(kAprd, static_cast<std::uint32_t>(ado) << 16, nullptr, 2);
    run(pdu);
    return static_cast<std::uint16_t>(pdu[12] | (pdu[13] << 8));
  }
  void sm(int n, std::uint16_t start, std::uint16_t length, std::uint8_t control, bool enable) {
    const auto at = static_cast<std::uint16_t>(0x0800 + 8 * n);
    write(static_cast<std::uint16_t>(at + 6), {0x00});
    write(at, {static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8), static_cast<std::uint8_t>(length),
               static_cast<std::uint8_t>(length >> 8), control});
    write(static_cast<std::uint16_t>(at + 6), {static_cast<std::uint8_t>(enable ? 1 : 0)});
  }
  void fmmu(int n, std::uint32_t logical, std::uint16_t length, std::uint16_t physical, std::uint8_t type) {
    write(static_cast<std::uint16_t>(0x0600 + 16 * n),
          {static_cast<std::uint8_t>(logical), static_cast<std::uint8_t>(logical >> 8), static_cast<std::uint8_t>(logical >> 16),
           static_cast<std::uint8_t>(logical >> 24), static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8), 0x00,
           0x07, static_cast<std::uint8_t>(physical), static_cast<std::uint8_t>(physical >> 8), 0x00, type, 0x01, 0x00, 0x00, 0x00});
  }

  // What reaches the plant, the plant itself, and what the drive reports must be numbers.
  void check() {
    vdrive::drive::DriveEngine* drive = firmware_->drive();
    if (drive == nullptr) return;
    const vdrive::plant::Plant& plant = drive->plant();
    for (std::size_t a = 0; a < plant.axis_count(); ++a) {
      const vdrive::plant::AxisFeedback& fb = plant.feedback(a);
      const vdrive::plant::AxisCommand& cmd = plant.last_command(a);
      if (!finite(fb.motor_angle_rad) || !finite(fb.motor_velocity_rad_s) || !finite(fb.load_position) ||
          !finite(fb.load_velocity) || !finite(fb.torque_nm) || !finite(fb.current_a) || !finite(fb.winding_c) ||
          !finite(fb.housing_c) || !finite(cmd.torque_nm) || !finite(cmd.stepper_angle_rad) || !finite(cmd.stepper_current))
        __builtin_trap();
    }
    const vdrive::drive::AxisSample& s = drive->sample();
    if (!finite(s.position) || !finite(s.velocity) || !finite(s.torque) || !finite(s.position_demand) ||
        !finite(s.velocity_demand) || !finite(s.torque_demand))
      __builtin_trap();
  }

  vdrive::VirtualClock clock_;
  vdrive::profile::ProductProfile product_;
  vdrive::esc::Esc esc_;
  std::unique_ptr<vdrive::firmware::SlaveFirmware> firmware_;
  std::vector<Entry> entries_;
  std::size_t out_bytes_ = 0, in_bytes_ = 0;
  std::vector<std::uint8_t> outputs_, lrw_;
  std::uint8_t counter_ = 0;
};

const std::filesystem::path& state_dir() {
  static const std::filesystem::path dir = [] {
    std::string d = (std::filesystem::temp_directory_path() / "vdrive-fuzz-drive-XXXXXX").string();
    ::setenv("VDRIVE_STATE_DIR", ::mkdtemp(d.data()), 1);
    return std::filesystem::path(d);
  }();
  return dir;
}

DriveBench& bench(std::uint8_t which) {
  (void)state_dir();
  static std::array<std::unique_ptr<DriveBench>, 3> benches = {std::make_unique<DriveBench>("a6b"),
                                                               std::make_unique<DriveBench>("ds5c1"),
                                                               std::make_unique<DriveBench>("ds1000a")};
  return *benches[which % 3];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // Parameters a previous input saved (1010h) would be loaded at power-on: every input starts clean.
  std::error_code ec;
  for (const auto& f : std::filesystem::directory_iterator(state_dir(), ec)) std::filesystem::remove_all(f.path(), ec);
  DriveBench& b = bench(data[0]);
  b.reset();
  int cycles = 0;
  std::size_t at = 1;
  auto run_cycles = [&](int n) {
    for (int i = 0; i < n && cycles < kMaxCycles; ++i, ++cycles) b.cycle();
  };
  while (at < size && cycles < kMaxCycles) {
    const std::uint8_t op = data[at++];
    const std::size_t left = size - at;
    switch (op & 3) {
      case 0: {
        const std::size_t n = left == 0 ? 0 : std::min<std::size_t>(data[at], left - 1);
        if (left > 0) b.set_outputs(data + at + 1, n);
        at += left == 0 ? 0 : n + 1;
        run_cycles((op >> 2) + 1);
        break;
      }
      case 1: {
        if (left < 5) return 0;
        const std::uint32_t v = static_cast<std::uint32_t>(data[at + 1] | (data[at + 2] << 8) | (data[at + 3] << 16)) |
                                (static_cast<std::uint32_t>(data[at + 4]) << 24);
        b.set_entry(data[at], v);
        at += 5;
        run_cycles((op >> 2) + 1);
        break;
      }
      case 2: {
        if (left < 7) return 0;
        const auto index = static_cast<std::uint16_t>(data[at] | (data[at + 1] << 8));
        const std::uint32_t v = static_cast<std::uint32_t>(data[at + 3] | (data[at + 4] << 8) | (data[at + 5] << 16)) |
                                (static_cast<std::uint32_t>(data[at + 6]) << 24);
        b.sdo_download(index, data[at + 2], v, ((op >> 2) & 3) + 1);
        at += 7;
        ++cycles;
        break;
      }
      case 3:
        if (left < 1) return 0;
        b.request(data[at++]);
        ++cycles;
        break;
    }
  }
  return 0;
}
