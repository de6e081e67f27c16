#pragma once
// Test helpers for the real links and the `vdrive` binary: a veth pair that exists for the
// lifetime of a test (root only), and EtherCAT frame builders.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace vdrive::test {

inline bool running_as_root() { return ::geteuid() == 0; }

inline bool run_quiet(const std::string& command) {
  return std::system((command + " >/dev/null 2>&1").c_str()) == 0;
}

inline std::string operstate(const std::string& iface) {
  std::ifstream in("/sys/class/net/" + iface + "/operstate");
  std::string s;
  in >> s;
  return s;
}

// A veth pair named uniquely for this process (vdt<pid>_<n>a / ...b), both ends up; deleted
// again on destruction. Deleting one end removes both.
class VethPair {
public:
  VethPair() {
    static std::atomic<int> counter{0};
    const std::string base = "vdt" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    a_ = base + "a";
    b_ = base + "b";
    ok_ = run_quiet("ip link add " + a_ + " type veth peer name " + b_) &&
          run_quiet("ip link set " + a_ + " up") && run_quiet("ip link set " + b_ + " up");
    // Carrier follows within milliseconds; frames sent before that are dropped.
    for (int i = 0; ok_ && i < 200 && !(operstate(a_) == "up" && operstate(b_) == "up"); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  ~VethPair() { run_quiet("ip link del " + a_); }
  VethPair(const VethPair&) = delete;
  VethPair& operator=(const VethPair&) = delete;

  bool ok() const { return ok_; }
  const std::string& a() const { return a_; }
  const std::string& b() const { return b_; }

private:
  std::string a_, b_;
  bool ok_ = false;
};

// An Ethernet frame: destination, source, EtherType, then `payload`.
inline std::vector<std::uint8_t> ethernet_frame(std::uint16_t ethertype,
                                                const std::vector<std::uint8_t>& payload,
                                                std::uint8_t dst_last = 0xFF) {
  const std::uint8_t header[14] = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, dst_last,
                                   0x02, 0x00, 0x00, 0x00, 0x00, 0x01,
                                   static_cast<std::uint8_t>(ethertype >> 8),
                                   static_cast<std::uint8_t>(ethertype & 0xFF)};
  // Sized once and filled: GCC 12 at -O3 warns (wrongly) about insert() after a 14-byte list.
  std::vector<std::uint8_t> f(sizeof(header) + payload.size());
  std::copy(std::begin(header), std::end(header), f.begin());
  std::copy(payload.begin(), payload.end(), f.begin() + sizeof(header));
  if (dst_last != 0xFF) {  // a unicast address that belongs to nobody on the test link
    f[0] = 0x02; f[1] = 0x11; f[2] = 0x22; f[3] = 0x33; f[4] = 0x44;
  }
  return f;
}

// An EtherCAT frame with one datagram (ETG.1000.4): `cmd` at `adp:ado` carrying `data`,
// working counter 0. Unpadded.
inline std::vector<std::uint8_t> ethercat_frame(std::uint8_t cmd, std::uint16_t adp,
                                                std::uint16_t ado,
                                                const std::vector<std::uint8_t>& data) {
  std::vector<std::uint8_t> pdu;
  const auto len = static_cast<std::uint16_t>(data.size());
  const std::uint16_t frame_len = static_cast<std::uint16_t>(10 + len + 2);  // header+data+wkc
  pdu.push_back(static_cast<std::uint8_t>(frame_len & 0xFF));
  pdu.push_back(static_cast<std::uint8_t>(0x10 | ((frame_len >> 8) & 0x07)));  // type 1: PDU
  pdu.push_back(cmd);
  pdu.push_back(0x42);  // index
  pdu.push_back(static_cast<std::uint8_t>(adp & 0xFF));
  pdu.push_back(static_cast<std::uint8_t>(adp >> 8));
  pdu.push_back(static_cast<std::uint8_t>(ado & 0xFF));
  pdu.push_back(static_cast<std::uint8_t>(ado >> 8));
  pdu.push_back(static_cast<std::uint8_t>(len & 0xFF));
  pdu.push_back(static_cast<std::uint8_t>((len >> 8) & 0x07));  // no more datagrams
  pdu.push_back(0);  // IRQ
  pdu.push_back(0);
  pdu.insert(pdu.end(), data.begin(), data.end());
  pdu.push_back(0);  // working counter
  pdu.push_back(0);
  return ethernet_frame(0x88A4, pdu);
}

// The same with `len` data bytes of zero (a read).
inline std::vector<std::uint8_t> ethercat_frame(std::uint8_t cmd, std::uint16_t adp,
                                                std::uint16_t ado, std::uint16_t len) {
  return ethercat_frame(cmd, adp, ado, std::vector<std::uint8_t>(len, 0));
}

// Data of the first datagram of an EtherCAT frame built by ethercat_frame().
inline std::vector<std::uint8_t> first_data(const std::vector<std::uint8_t>& frame) {
  const std::size_t len = (frame[14 + 2 + 6] | ((frame[14 + 2 + 7] & 0x07) << 8));
  const auto begin = frame.begin() + 14 + 2 + 10;
  return {begin, begin + static_cast<std::ptrdiff_t>(len)};
}

// Working counter of the first datagram of an EtherCAT frame built by ethercat_frame().
inline std::uint16_t first_wkc(const std::vector<std::uint8_t>& frame) {
  const std::size_t len = (frame[14 + 2 + 6] | ((frame[14 + 2 + 7] & 0x07) << 8));
  const std::size_t at = 14 + 2 + 10 + len;
  return static_cast<std::uint16_t>(frame[at] | (frame[at + 1] << 8));
}

}  // namespace vdrive::test
