// `vdrive esi`: runs the built program; the XML it writes is parsed back.
#include <gtest/gtest.h>
#include <tinyxml2.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "tests/support/child_process.hpp"
#include "vdrive/profile/profile_loader.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif

namespace {

using vdrive::test::run_process;

TEST(EsiCommand, WritesTheProductsEsiToAFile) {
  const std::string path = "/tmp/vdrive-esi-command-test-" + std::to_string(::getpid()) + ".xml";
  const auto r = run_process(VDRIVE_BINARY, {"esi", "--drive", "ds1000a", "-o", path});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.LoadFile(path.c_str()), tinyxml2::XML_SUCCESS);
  std::remove(path.c_str());
  const auto p = vdrive::profile::load_profile("ds1000a");
  const tinyxml2::XMLElement* type =
      doc.RootElement()->FirstChildElement("Descriptions")->FirstChildElement("Devices")->FirstChildElement("Device")->FirstChildElement("Type");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(std::stoul(std::string(type->Attribute("ProductCode")).substr(2), nullptr, 16), p.identity.product_code);
}

TEST(EsiCommand, WithoutOdGoesToStdoutWithoutDictionary) {
  const auto r = run_process(VDRIVE_BINARY, {"esi", "-d", "a6b", "--without-od"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(r.out.c_str(), r.out.size()), tinyxml2::XML_SUCCESS);
  EXPECT_EQ(r.out.find("<Dictionary>"), std::string::npos);
  EXPECT_NE(r.out.find("<ProfileNo>402</ProfileNo>"), std::string::npos);
}

TEST(EsiCommand, UnknownProductIsABadArgument) {
  const auto r = run_process(VDRIVE_BINARY, {"esi", "--drive", "nosuch"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown product 'nosuch'"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(EsiCommand, UnwritableOutputFailsNamingTheFile) {
  const auto r = run_process(VDRIVE_BINARY, {"esi", "-d", "ds5c1", "-o", "/nonexistent-dir/x.xml"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent-dir/x.xml"), std::string::npos) << r.err;
}

TEST(EsiCommand, DriveIsRequired) {
  const auto r = run_process(VDRIVE_BINARY, {"esi"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--drive"), std::string::npos) << r.err;
}

}  // namespace
