#pragma once
// Helpers for the object-dictionary tests: a product directory in the temp dir holding a
// hand-written objects.yaml, a test product, and typed reads through an ObjectStore.
#include <gtest/gtest.h>

#include <cstdint>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::od::test {

namespace fs = std::filesystem;

// `<tmp>/<unique>/<id>/objects.yaml` = text; removed at the end of the test.
class TempObjectsDir {
public:
  TempObjectsDir(const std::string& id, const std::string& text) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("vdrive_od_test_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::create_directories(dir_ / id);
    std::ofstream(dir_ / id / "objects.yaml", std::ios::binary) << text;
  }
  ~TempObjectsDir() { fs::remove_all(dir_); }
  std::string path() const { return dir_.string(); }
  std::string file(const std::string& id) const { return (dir_ / id / "objects.yaml").string(); }

private:
  fs::path dir_;
};

// A product with a recognisable identity and no built-in data.
inline profile::ProductProfile test_product(const std::string& id = "odtest") {
  profile::ProductProfile p;
  p.id = id;
  p.identity.vendor_id = 0x12345678;
  p.identity.product_code = 0x00ABCDEF;
  p.identity.revision = 0x00020003;
  p.identity.serial = 0x00000042;
  p.identity.device_type = 0x00020192;
  p.identity.device_name = "Test drive";
  p.identity.hardware_version = "HW7";
  p.identity.software_version = "SW 1.2.3";
  return p;
}

// The header of a valid objects.yaml for `objects` objects with `entries` entries.
inline std::string yaml_header(const std::string& id, int objects, int entries) {
  return "product: " + id + "\nmanual: \"test\"\ntable_lines: \"L1-L2\"\nobject_count: " +
         std::to_string(objects) + "\nentry_count: " + std::to_string(entries) + "\nnotes: []\nobjects:\n";
}

inline std::vector<std::uint8_t> read_bytes(const ObjectStore& s, std::uint16_t index, std::uint8_t sub,
                                            ecat::AlState state = ecat::AlState::PreOp) {
  std::vector<std::uint8_t> buf(1024);
  std::size_t n = 0;
  const SdoAbort r = s.read(index, sub, buf, n, state);
  EXPECT_EQ(r, SdoAbort::Ok) << std::hex << index << ":" << int(sub);
  buf.resize(n);
  return buf;
}

inline std::uint64_t read_unsigned(const ObjectStore& s, std::uint16_t index, std::uint8_t sub) {
  const std::vector<std::uint8_t> b = read_bytes(s, index, sub);
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < b.size() && i < 8; ++i) v |= std::uint64_t{b[i]} << (8 * i);
  return v;
}

inline std::string read_string(const ObjectStore& s, std::uint16_t index, std::uint8_t sub) {
  const std::vector<std::uint8_t> b = read_bytes(s, index, sub);
  return std::string(b.begin(), b.end());
}

template <typename T>
std::vector<std::uint8_t> le(T value) {
  std::vector<std::uint8_t> out(sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out[i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i));
  return out;
}

}  // namespace vdrive::od::test
