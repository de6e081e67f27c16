// The test machine of issue 19 (tests/products/networks/machine.yaml), served as `vdrive run
// --network` serves it: a coupler whose E-bus carries a digital input, a digital output, an analog
// input and an analog output terminal and a junction; on the junction's port 3 a branch of two A6B,
// on its port 2 a DS5C1 and the ESI servo; wires DO 1 -> DI 1 and AO 1 -> AI 1. The project master
// scans the tree in the order a frame visits it and reconstructs it from the receive times, takes
// the machine to Op with DC at 1 ms, runs a csp sine on the four drives and reads back through the
// input terminals what it writes to the output terminals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "master/cia402_program.hpp"
#include "master/dc.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/csp_sine_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/machine/network_file.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::master {
namespace {

// Positions as a frame visits the slaves (the file lists them in that order).
enum : std::size_t { kCoupler, kDi, kDo, kAi, kAo, kJunction, kA6bX, kA6bY, kDs5c1, kServo, kSlaves };

struct Machine {
  machine::NetworkFile file =
      machine::load_network_file(std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/networks/machine.yaml");
  std::vector<std::string> devices() const {
    std::vector<std::string> d;
    for (const machine::NetworkSlave& s : file.slaves) d.push_back(s.device);
    return d;
  }
  network::NetworkOptions options() const {
    network::NetworkOptions o;
    o.topology = file.topology;
    o.wires = file.wires;
    for (const machine::NetworkSlave& s : file.slaves) o.station_aliases.push_back(s.alias);
    return o;
  }
};

// Byte offset of entry index:sub in a slave's mapped PDOs (the master's layout), -1 if not mapped.
long entry_byte(const std::vector<PdoMapping>& pdos, std::uint16_t index, std::uint8_t sub) {
  std::uint32_t bit = 0;
  for (const PdoMapping& p : pdos)
    for (const std::uint32_t e : p.entries) {
      if ((e >> 16) == index && ((e >> 8) & 0xFF) == sub) return bit % 8 == 0 ? static_cast<long>(bit / 8) : -1;
      bit += e & 0xFF;
    }
  return -1;
}

TEST(MachineBench, TheMasterScansTheWholeTreeInFrameOrder) {
  const Machine m;
  ASSERT_EQ(m.file.slaves.size(), kSlaves);
  test::VirtualLine line(m.devices(), m.options());
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), kSlaves);
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> identities = {
      {0x00000002, 0x044C2C52}, {0x00000002, 0x03F03052}, {0x00000002, 0x07D83052}, {0x00000002, 0x0C1E3052},
      {0x00000002, 0x10063052}, {0x00000002, 0x04622C52}, {0x0000066F, 0x60380005}, {0x0000066F, 0x60380005},
      {0x00000556, 0x10305070}, {0x00FFFF01, 0x00000402}};
  for (std::size_t i = 0; i < kSlaves; ++i) {
    EXPECT_EQ(master.slaves()[i].info.vendor_id, identities[i].first) << "position " << i;
    EXPECT_EQ(master.slaves()[i].info.product_code, identities[i].second) << "position " << i;
  }
  EXPECT_EQ(master.slaves()[kServo].info.alias, 0x0102);
  // The analog terminals have a CoE mailbox; the coupler, the junction and the digital terminals none.
  EXPECT_TRUE(master.slaves()[kAi].info.has_mailbox());
  EXPECT_TRUE(master.slaves()[kAo].info.has_mailbox());
  EXPECT_FALSE(master.slaves()[kJunction].info.has_mailbox());
  EXPECT_FALSE(master.slaves()[kDi].info.has_mailbox());
  // The junction's four ports as its ESI says (KKYY: two E-bus, two MII); the coupler's YY K.
  EXPECT_EQ(line.network().esc(kJunction).peek_u16(0x0006) >> 8, 0xFA);
  EXPECT_EQ(line.network().esc(kCoupler).peek_u16(0x0006) >> 8, 0x8F);

  // The tree as the receive times and DL status show it, 500 ns per hop and direction: the
  // terminals and the junction in a line on the coupler's E-bus (port 3); the two A6B behind the
  // junction's port 3; the DS5C1 on its port 2, entered after the A6B branch came back (4 hops).
  const DcTopology t = measure_dc_topology(master);
  EXPECT_EQ(t.parent, (std::vector<std::size_t>{kCoupler, kCoupler, kDi, kDo, kAi, kAo, kJunction, kA6bX, kJunction,
                                                kDs5c1}));
  EXPECT_EQ(t.parent_port, (std::vector<int>{0, 3, 1, 1, 1, 1, 3, 1, 2, 1}));
  EXPECT_EQ(t.delay, (std::vector<std::int64_t>{0, 500, 1000, 1500, 2000, 2500, 3000, 3500, 5000, 5500}));
  for (std::size_t i = 0; i < kSlaves; ++i) {
    EXPECT_EQ(master.slaves()[i].parent, t.parent[i]) << "position " << i;
    EXPECT_EQ(master.slaves()[i].parent_port, t.parent_port[i]) << "position " << i;
  }
}

TEST(MachineBench, OpWithDcEveryDriveFollowsAndBothLoopbacksReadBack) {
  const Machine m;
  test::VirtualLine line(m.devices(), m.options());
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), kSlaves);
  master.set_mailbox_timeout(20'000'000);

  // Where the channels are in the process image (known once the process data is configured).
  struct Offsets {
    long do_byte, di_byte, ao1, ao2, ai1, ai2;
  };
  auto offsets = [&] {
    std::uint32_t start = UINT32_MAX;
    for (const Slave& s : master.slaves()) {
      if (s.process_data.output_bytes) start = std::min(start, s.process_data.output_logical);
      if (s.process_data.input_bytes) start = std::min(start, s.process_data.input_logical);
    }
    auto at = [&](std::size_t slave, bool outputs, std::uint16_t index, std::uint8_t sub) {
      const SlaveProcessData& pd = master.slaves()[slave].process_data;
      const long b = entry_byte(outputs ? pd.outputs : pd.inputs, index, sub);
      return b < 0 ? -1 : static_cast<long>((outputs ? pd.output_logical : pd.input_logical) - start) + b;
    };
    return Offsets{at(kDo, true, 0x7000, 1),    at(kDi, false, 0x6000, 1),    at(kAo, true, 0x7000, 1),
                   at(kAo, true, 0x7010, 1),    at(kAi, false, 0x6000, 0x11), at(kAi, false, 0x6010, 0x11)};
  };
  auto get16 = [](std::span<const std::uint8_t> image, long at) {
    std::int16_t v;
    std::memcpy(&v, image.data() + at, 2);
    return v;
  };
  std::uint64_t cycle = 0, compared = 0, digital_matched = 0, analog_matched = 0, channel2_quiet = 0;
  std::uint8_t written_bit = 0;
  std::int16_t written_value = 0;
  bool mapped = false;
  const test::CspSineRun run = test::run_csp_sine_at_1ms(master, 1'000'000'000, [&](OpRunOptions& options) {
    options.outputs = [&, sine = options.outputs](std::span<std::uint8_t> image) {
      sine(image);
      const Offsets o = offsets();
      mapped = o.do_byte >= 0 && o.di_byte >= 0 && o.ao1 >= 0 && o.ao2 >= 0 && o.ai1 >= 0 && o.ai2 >= 0;
      if (!mapped) return;
      ++cycle;
      // Every 50 cycles: DO channel 1 toggles and AO channel 1 takes the next value of a ramp
      // through both signs; AO channel 2 (not wired) holds a value of its own.
      written_bit = static_cast<std::uint8_t>((cycle / 50) & 1);
      written_value = static_cast<std::int16_t>(static_cast<std::int32_t>((cycle / 50) * 1999 % 60000) - 30000);
      image[o.do_byte] = written_bit;
      std::memcpy(image.data() + o.ao1, &written_value, 2);
      const std::int16_t other = 0x1234;
      std::memcpy(image.data() + o.ao2, &other, 2);
    };
    options.inputs = [&, sine = options.inputs, safeop = options.safeop_cycles](std::span<std::uint8_t> image) {
      sine(image);
      // Outputs act in Op only (after the Safe-Op cycles); then a few cycles for each change to arrive.
      if (!mapped || cycle <= safeop + 50 || cycle % 50 < 5) return;
      const Offsets o = offsets();
      ++compared;
      if ((image[o.di_byte] & 1) == written_bit) ++digital_matched;
      if (get16(image, o.ai1) == written_value) ++analog_matched;
      if (get16(image, o.ai2) == 0) ++channel2_quiet;
    };
  });
  ASSERT_TRUE(mapped) << "a terminal's channel is not in the process image";
  EXPECT_NE(run.result.sync0_start, 0u) << "DC configured and SYNC0 started";
  ASSERT_EQ(run.drives.size(), kSlaves);
  for (const std::size_t drive : {kA6bX, kA6bY, kDs5c1, kServo}) {
    SCOPED_TRACE("drive at position " + std::to_string(drive));
    test::expect_drive_followed(run, drive, [&] { return line.network().esc(drive).peek_u16(0x0134); });
  }
  // The terminals are no drives: the program left them alone.
  for (const std::size_t terminal : {kCoupler, kDi, kDo, kAi, kAo, kJunction}) EXPECT_FALSE(run.drives[terminal].enabled);
  EXPECT_GT(compared, 500u);
  EXPECT_EQ(digital_matched, compared) << "the digital input reads what the digital output drives";
  EXPECT_EQ(analog_matched, compared) << "analog input channel 1 reads what analog output channel 1 drives";
  EXPECT_EQ(channel2_quiet, compared) << "analog input channel 2 is wired to nothing";
  // What the master wrote last is in the output terminal's channel object, and it came over the wire.
  od::ObjectStore& ao = line.network().firmware(kAo).objects();
  od::ObjectStore& ai = line.network().firmware(kAi).objects();
  std::int16_t ao1 = 0, ai1 = 0, ao2 = 0;
  std::memcpy(&ao1, ao.raw(*ao.dictionary().find(0x7000, 1)).data(), 2);
  std::memcpy(&ao2, ao.raw(*ao.dictionary().find(0x7010, 1)).data(), 2);
  std::memcpy(&ai1, ai.raw(*ai.dictionary().find(0x6000, 0x11)).data(), 2);
  EXPECT_EQ(ao1, ai1);
  EXPECT_EQ(ao2, 0x1234);
}

}  // namespace
}  // namespace vdrive::master
