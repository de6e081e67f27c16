// Units as the manuals print them, in English (unit_text.hpp): every unit of every built-in
// product's dictionary comes out without a CJK character, and the common ones read as intended.
#include "vdrive/od/unit_text.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::od {
namespace {

TEST(EnglishUnits, TheManualsTermsInEnglish) {
  EXPECT_EQ(english_units("指令单位/s"), "command unit/s");
  EXPECT_EQ(english_units("10000 指令单位/s²"), "10000 command unit/s²");
  EXPECT_EQ(english_units("1指令单位"), "1 command unit");
  EXPECT_EQ(english_units("0.1 圈"), "0.1 rev");
  EXPECT_EQ(english_units("r (电机)"), "r (motor)");
  EXPECT_EQ(english_units("转（轴）"), "rev (shaft)");
  EXPECT_EQ(english_units("%额定"), "% rated");
  EXPECT_EQ(english_units("0.1Ｎ /0.1Nm"), "0.1 N /0.1Nm");
  EXPECT_EQ(english_units("旋转/ Pulse (外部缩放上位 32bit)"), "rev/ Pulse (external scaling, upper 32bit)");
  EXPECT_EQ(english_units("ScanA 周期"), "ScanA cycles");
}

TEST(EnglishUnits, SymbolsAndEnglishPassThrough) {
  EXPECT_EQ(english_units("mN·m"), "mN·m");
  EXPECT_EQ(english_units("0.01Ω"), "0.01Ω");
  EXPECT_EQ(english_units("0.1°C"), "0.1°C");
  EXPECT_EQ(english_units("ms"), "ms");
  EXPECT_FALSE(has_cjk("mN·m 0.1°C Ω s²"));
  EXPECT_TRUE(has_cjk("指令"));
  EXPECT_TRUE(has_cjk("Ｎ"));
}

TEST(EnglishUnits, EveryUnitOfEveryProductHasAnEnglishReading) {
  for (const std::string& id : profile::known_products()) {
    const profile::ProductProfile profile = profile::load_profile(id);
    const std::shared_ptr<const Dictionary> d = shared_dictionary(profile);
    for (const ObjectDesc& o : d->objects())
      for (const EntryDesc& e : o.entries)
        if (!e.units.empty()) EXPECT_FALSE(has_cjk(english_units(e.units))) << id << " " << std::hex << e.index << ": " << e.units;
  }
}

}  // namespace
}  // namespace vdrive::od
