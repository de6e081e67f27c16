// SII images built from the product profiles, read back the way a master reads them: the
// configuration-area CRC recomputed independently, the fixed words checked against the manuals,
// and the category list walked by a small parser written for this test.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "esc_model/sii_eeprom.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::profile {
namespace {

using Image = std::vector<std::uint8_t>;

std::uint16_t word(const Image& img, std::size_t w) {
  return static_cast<std::uint16_t>(img.at(2 * w) | img.at(2 * w + 1) << 8);
}
std::uint32_t dword(const Image& img, std::size_t w) { return word(img, w) | std::uint32_t{word(img, w + 1)} << 16; }

// CRC-8, x^8+x^2+x+1, initial 0xFF, no reflection: the data bits shifted MSB-first through an
// 8-bit register (a different formulation from the byte-wise one in esc_model).
std::uint8_t crc8_bitwise(const Image& img, std::size_t n) {
  unsigned reg = 0xFF;
  for (std::size_t i = 0; i < n; ++i) {
    for (int bit = 7; bit >= 0; --bit) {
      const unsigned in = (img[i] >> bit) & 1u;
      const unsigned top = (reg >> 7) & 1u;
      reg = (reg << 1) & 0xFFu;
      if (top ^ in) reg ^= 0x07u;
    }
  }
  return static_cast<std::uint8_t>(reg);
}

// The category list from word 0x40, as (type -> list of category bodies).
struct Categories {
  std::multimap<std::uint16_t, std::vector<std::uint8_t>> bodies;
  std::vector<std::uint16_t> order;
  bool ended = false;
  std::size_t end_word = 0;

  const std::vector<std::uint8_t>& one(std::uint16_t type) const {
    EXPECT_EQ(bodies.count(type), 1u) << "category " << type;
    return bodies.find(type)->second;
  }
};

Categories parse_categories(const Image& img) {
  Categories c;
  std::size_t w = 0x40;
  while (2 * w + 1 < img.size()) {
    const std::uint16_t type = word(img, w);
    if (type == 0xFFFF) {
      c.ended = true;
      c.end_word = w;
      break;
    }
    const std::uint16_t len = word(img, w + 1);
    std::vector<std::uint8_t> body(img.begin() + static_cast<long>(2 * (w + 2)),
                                   img.begin() + static_cast<long>(2 * (w + 2 + len)));
    c.bodies.emplace(type, std::move(body));
    c.order.push_back(type);
    w += 2 + len;
  }
  return c;
}

std::vector<std::string> parse_strings(const std::vector<std::uint8_t>& body) {
  std::vector<std::string> out;
  std::size_t i = 0;
  const unsigned n = body.at(i++);
  for (unsigned s = 0; s < n; ++s) {
    const unsigned len = body.at(i++);
    out.emplace_back(body.begin() + static_cast<long>(i), body.begin() + static_cast<long>(i + len));
    i += len;
  }
  return out;
}

std::string string_at(const std::vector<std::string>& strings, unsigned index) {
  return index == 0 || index > strings.size() ? std::string("<none>") : strings[index - 1];
}

class SiiImage : public ::testing::TestWithParam<std::string> {};

TEST_P(SiiImage, ConfigAreaCrcVerifies) {
  const Image img = build_sii_image(load_profile(GetParam()));
  ASSERT_GE(img.size(), 128u);
  EXPECT_EQ(img[14], crc8_bitwise(img, 14));
  EXPECT_EQ(img[15], 0x00);
  EXPECT_EQ(img[14], esc::sii_config_crc(std::span(img).first(14)));
  EXPECT_TRUE(esc::SiiEeprom(img).config_area_valid());
}

TEST_P(SiiImage, FixedWordsMatchTheProfile) {
  const ProductProfile p = load_profile(GetParam());
  const Image img = build_sii_image(p);
  EXPECT_EQ(img.size(), p.esc.eeprom_bytes);
  EXPECT_EQ(word(img, 0x00), p.esc.pdi_control);
  EXPECT_EQ(word(img, 0x01), p.esc.pdi_config);
  EXPECT_EQ(word(img, 0x02), p.esc.sync_pulse_length);
  EXPECT_EQ(word(img, 0x04), p.esc.station_alias);
  EXPECT_EQ(dword(img, 0x08), p.identity.vendor_id);
  EXPECT_EQ(dword(img, 0x0A), p.identity.product_code);
  EXPECT_EQ(dword(img, 0x0C), p.identity.revision);
  EXPECT_EQ(dword(img, 0x0E), p.identity.serial);
  EXPECT_EQ(word(img, 0x18), p.mailbox.rx_offset);
  EXPECT_EQ(word(img, 0x19), p.mailbox.rx_size);
  EXPECT_EQ(word(img, 0x1A), p.mailbox.tx_offset);
  EXPECT_EQ(word(img, 0x1B), p.mailbox.tx_size);
  EXPECT_EQ(word(img, 0x1C), p.mailbox.protocols);
  EXPECT_EQ(word(img, 0x3E), p.esc.eeprom_bytes * 8 / 1024 - 1);
  EXPECT_EQ(word(img, 0x3F), 1);
}

TEST_P(SiiImage, CategoriesReadBackAsTheProfile) {
  const ProductProfile p = load_profile(GetParam());
  const Image img = build_sii_image(p);
  const Categories c = parse_categories(img);
  ASSERT_TRUE(c.ended) << "no 0xFFFF end marker";
  // Everything after the end marker is erased EEPROM.
  for (std::size_t i = 2 * c.end_word + 2; i < img.size(); ++i) ASSERT_EQ(img[i], 0xFF) << "byte " << i;
  ASSERT_GE(c.order.size(), 4u);
  EXPECT_EQ(c.order[0], 10);  // Strings first, then General, FMMU, SyncManager (ETG.2010 order)
  EXPECT_EQ(c.order[1], 30);
  EXPECT_EQ(c.order[2], 40);
  EXPECT_EQ(c.order[3], 41);

  const auto strings = parse_strings(c.one(10));
  const auto& gen = c.one(30);
  ASSERT_EQ(gen.size(), 32u);
  EXPECT_EQ(string_at(strings, gen[0]), p.identity.group);
  EXPECT_EQ(string_at(strings, gen[2]), p.identity.order_code);
  EXPECT_EQ(string_at(strings, gen[3]), p.identity.device_name);
  EXPECT_EQ(gen[5], p.coe_details);
  EXPECT_EQ(gen[6], p.foe_details);
  EXPECT_EQ(gen[0x0B] & 0x08, p.explicit_device_id ? 0x08 : 0x00);
  EXPECT_EQ(gen[0x0E] | gen[0x0F] << 8, 0x0011) << "ports 0 and 1 MII";
  EXPECT_NE(std::find(strings.begin(), strings.end(), p.identity.vendor_name), strings.end());

  const auto& fmmu = c.one(40);
  ASSERT_GE(fmmu.size(), 3u);
  EXPECT_EQ(fmmu[0], 1);  // outputs
  EXPECT_EQ(fmmu[1], 2);  // inputs
  EXPECT_EQ(fmmu[2], 3);  // mailbox state

  const auto& sm = c.one(41);
  ASSERT_EQ(sm.size(), 8 * p.sync_managers.size());
  for (std::size_t i = 0; i < p.sync_managers.size(); ++i) {
    SCOPED_TRACE(i);
    const auto* e = &sm[8 * i];
    EXPECT_EQ(e[0] | e[1] << 8, p.sync_managers[i].start);
    EXPECT_EQ(e[2] | e[3] << 8, p.sync_managers[i].length);
    EXPECT_EQ(e[4], p.sync_managers[i].control);
    EXPECT_EQ(e[6] & 1, p.sync_managers[i].enable ? 1 : 0);
    EXPECT_EQ(e[7], static_cast<std::uint8_t>(p.sync_managers[i].kind));
  }

  // PDO categories: one per default PDO, header 8 bytes + 8 per entry.
  const auto check_pdos = [&](std::uint16_t type, const std::vector<PdoSpec>& pdos) {
    ASSERT_EQ(c.bodies.count(type), pdos.size());
    auto it = c.bodies.find(type);
    for (const auto& pdo : pdos) {
      const auto& b = (it++)->second;
      ASSERT_EQ(b.size(), 8 + 8 * pdo.entries.size());
      EXPECT_EQ(b[0] | b[1] << 8, pdo.index);
      EXPECT_EQ(b[2], pdo.entries.size());
      EXPECT_EQ(b[3], pdo.sync_manager);
      EXPECT_EQ(string_at(strings, b[5]), pdo.name);
      for (std::size_t j = 0; j < pdo.entries.size(); ++j) {
        const auto* e = &b[8 + 8 * j];
        EXPECT_EQ(e[0] | e[1] << 8, pdo.entries[j].index);
        EXPECT_EQ(e[2], pdo.entries[j].subindex);
        EXPECT_EQ(string_at(strings, e[3]), pdo.entries[j].name);
        EXPECT_EQ(e[4], pdo.entries[j].data_type);
        EXPECT_EQ(e[5], pdo.entries[j].bit_length);
      }
    }
  };
  check_pdos(50, p.tx_pdos);
  check_pdos(51, p.rx_pdos);
}

TEST_P(SiiImage, EscConfigCarriesResourcesAndImage) {
  const ProductProfile p = load_profile(GetParam());
  const esc::EscConfig cfg = make_esc_config(p);
  EXPECT_EQ(cfg.type, p.esc.type);
  EXPECT_EQ(cfg.build, p.esc.build);
  EXPECT_EQ(cfg.fmmu_count, p.esc.fmmu_count);
  EXPECT_EQ(cfg.sm_count, p.esc.sm_count);
  EXPECT_EQ(cfg.ram_kib, p.esc.ram_kib);
  EXPECT_EQ(cfg.features, p.esc.features);
  EXPECT_EQ(cfg.sii_image, build_sii_image(p));
}

INSTANTIATE_TEST_SUITE_P(Products, SiiImage, ::testing::Values("a6b", "ds5c1", "ds1000a"));

// Literal values from the A6B manual's SII table (L3599-L3851), not from the profile.
TEST(SiiImageA6b, WordsAreThoseOfTheManual) {
  const Image img = build_sii_image(load_profile("a6b"));
  EXPECT_EQ(word(img, 0x00), 0x0C05);
  EXPECT_EQ(word(img, 0x01), 0x6603);
  EXPECT_EQ(word(img, 0x02), 0x0064);
  EXPECT_EQ(word(img, 0x03), 0x0000);
  EXPECT_EQ(word(img, 0x04), 0x0000);
  EXPECT_EQ(dword(img, 0x08), 0x0000066Fu);
  EXPECT_EQ(word(img, 0x10), 0x0000);
  EXPECT_EQ(word(img, 0x14), 0x1000);
  EXPECT_EQ(word(img, 0x15), 0x0100);
  EXPECT_EQ(word(img, 0x16), 0x1200);
  EXPECT_EQ(word(img, 0x17), 0x0100);
  EXPECT_EQ(word(img, 0x18), 0x1000);
  EXPECT_EQ(word(img, 0x19), 0x0100);
  EXPECT_EQ(word(img, 0x1A), 0x1200);
  EXPECT_EQ(word(img, 0x1B), 0x0100);
  EXPECT_EQ(word(img, 0x1C), 0x000C);
  EXPECT_EQ(word(img, 0x3E), 0x000F);
  EXPECT_EQ(word(img, 0x3F), 0x0001);
  EXPECT_EQ(img.size(), 2048u);
  const auto strings = parse_strings(parse_categories(img).one(10));
  ASSERT_FALSE(strings.empty());
  EXPECT_EQ(strings[0], "MADLN15BE");
}

TEST(SiiImageDs5c1, NoBootstrapMailboxWords) {
  const Image img = build_sii_image(load_profile("ds5c1"));
  for (std::size_t w = 0x14; w <= 0x17; ++w) EXPECT_EQ(word(img, w), 0) << "word " << w;
}

TEST(SiiImage, ImageLargerThanTheEepromIsAnError) {
  ProductProfile p = load_profile("a6b");
  p.esc.eeprom_bytes = 256;  // 2 kbit: too small for the categories
  EXPECT_THROW(build_sii_image(p), ProfileError);
}

}  // namespace
}  // namespace vdrive::profile
