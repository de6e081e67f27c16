// A frame through a tree allocates nothing: planning its path, processing it in every ESC,
// counting a corrupted one, and breaking and healing a cable between frames.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "esc_model/esc.hpp"
#include "tests/network/test_frame.hpp"
#include "tests/support/allocation_counter.hpp"
#include "vdrive/network/segment.hpp"
#include "vdrive/network/topology.hpp"

namespace vdrive::network {
namespace {

using namespace test_frames;

TEST(SegmentTreeNoAllocation, FramesThroughATreeAllocateNothing) {
  VirtualClock clock{1'000'000};
  std::vector<std::unique_ptr<esc::Esc>> escs;
  Segment segment{600};
  esc::EscConfig junction;
  junction.port_descriptor = 0xFF;
  escs.push_back(std::make_unique<esc::Esc>(junction, clock));
  for (int i = 0; i < 5; ++i) escs.push_back(std::make_unique<esc::Esc>(esc::EscConfig{}, clock));
  for (auto& e : escs) segment.append(*e);
  Topology t;
  t.uplinks = {Uplink{Uplink::kMaster, 0}, Uplink{0, 3}, Uplink{1, 1}, Uplink{0, 1}, Uplink{0, 2}, Uplink{4, 1}};
  segment.set_topology(t);

  TestFrame f;
  const std::size_t brd = f.read(BRD, 0, 0x0000, 1);
  f.add(BWR, 0, 0x0900, le_bytes(0, 4));
  f.read(APRD, static_cast<std::uint16_t>(-3), 0x0900, 16);

  const long before = test::allocation_count();
  int returned = 0;
  for (int i = 0; i < 100; ++i) {
    clock.advance(1'000'000);
    f[brd + 1] = f[brd + 2] = 0;  // the BRD's working counter back to 0
    returned += segment.process(f.span(), clock.now()) ? 1 : 0;
    segment.process_corrupted(f.span(), clock.now());
    segment.set_port_cable(0, 1, i % 2 == 0);
  }
  EXPECT_EQ(test::allocation_count() - before, 0);
  EXPECT_EQ(returned, 100);
  EXPECT_GE(f.wkc(brd, 1), 5);
}

}  // namespace
}  // namespace vdrive::network
