// The control socket: round trip, modes 0700/0600, a stale socket replaced, a live one
// refused, removed at the end, default paths, and the client's errors naming the path.
#include "vdrive/control/control_socket.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace vdrive::control {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

class ControlSocketTest : public ::testing::Test {
protected:
  void SetUp() override {
    char tmpl[] = "/tmp/vdrive-ctl-test-XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    base_ = tmpl;
    path_ = base_ + "/sub/line.sock";
  }
  void TearDown() override { fs::remove_all(base_); }

  static ControlServer::Handler echo() {
    return [](std::string_view line) { return "echo " + std::string(line); };
  }
  static ControlServer::Refuser refuse() {
    return [](unsigned uid) { return "denied " + std::to_string(uid); };
  }
  static unsigned mode(const std::string& p) {
    struct stat st{};
    ::lstat(p.c_str(), &st);
    return st.st_mode & 0777;
  }

  std::string base_, path_;
};

TEST_F(ControlSocketTest, RoundTripWithPrivateModesAndCleanup) {
  {
    ControlServer server(path_, echo(), refuse());
    EXPECT_EQ(mode(base_ + "/sub"), 0700u);
    EXPECT_EQ(mode(path_), 0600u);
    EXPECT_EQ(control_call(path_, "hello", 2'000'000'000), "echo hello");
    EXPECT_EQ(control_call(path_, "again", 2'000'000'000), "echo again");
  }
  EXPECT_FALSE(fs::exists(path_));
}

// A flood is answered at once past the burst, never reaching the handler; the bound refills.
TEST_F(ControlSocketTest, AFloodOfRequestsIsBounded) {
  int handled = 0;
  ControlServer server(
      path_, [&handled](std::string_view) { return std::to_string(++handled); }, refuse());
  int refused = 0;
  std::string refusal;
  for (int i = 0; i < 200; ++i) {
    const std::string reply = control_call(path_, "x", 2'000'000'000);
    if (reply.find("too many requests") != std::string::npos) {
      ++refused;
      refusal = reply;
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_EQ(handled + refused, 200);
  EXPECT_GE(handled, static_cast<int>(kRequestBurst));
  EXPECT_THAT(refusal, HasSubstr(R"("ok":false)"));
  EXPECT_THAT(refusal, HasSubstr("at most 100 a second (50 at once); try again in "));
  ::usleep(100'000);  // 10 more allowed by now
  EXPECT_THAT(control_call(path_, "x", 2'000'000'000), ::testing::Not(HasSubstr("too many")));
}

TEST_F(ControlSocketTest, StaleSocketIsReplacedLiveOneRefused) {
  fs::create_directory(base_ + "/sub");
  {  // a socket file nobody listens on, as a killed vdrive leaves it
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path_.c_str());
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    ::close(fd);
  }
  ControlServer server(path_, echo(), refuse());
  EXPECT_EQ(control_call(path_, "x", 2'000'000'000), "echo x");
  try {
    ControlServer second(path_, echo(), refuse());
    FAIL() << "a second server on a live socket";
  } catch (const ControlSocketError& e) {
    EXPECT_THAT(e.what(), HasSubstr("another vdrive already listens on " + path_));
  }
  EXPECT_EQ(control_call(path_, "still", 2'000'000'000), "echo still");  // the first one untouched
}

TEST_F(ControlSocketTest, NotASocketIsRefused) {
  fs::create_directory(base_ + "/sub");
  { std::FILE* f = std::fopen(path_.c_str(), "w"); std::fclose(f); }
  EXPECT_THROW(ControlServer(path_, echo(), refuse()), ControlSocketError);
}

TEST_F(ControlSocketTest, ClientErrorsNameThePath) {
  try {
    control_call(path_, "x", 1'000'000'000);
    FAIL();
  } catch (const ControlSocketError& e) {
    EXPECT_EQ(e.kind(), ControlSocketError::Kind::no_server);
    EXPECT_THAT(e.what(), HasSubstr(path_));
  }
}

TEST(ControlSocketPath, DefaultFollowsXdgRuntimeDir) {
  const char* old = std::getenv("XDG_RUNTIME_DIR");
  const std::string saved = old ? old : "";
  ::setenv("XDG_RUNTIME_DIR", "/run/user/1234", 1);
  EXPECT_EQ(default_control_path("eth1"), "/run/user/1234/vdrive/eth1.sock");
  ::unsetenv("XDG_RUNTIME_DIR");
  EXPECT_EQ(default_control_path("eth1"),
            ::geteuid() == 0 ? "/run/vdrive/eth1.sock" : "/tmp/vdrive-" + std::to_string(::geteuid()) + "/eth1.sock");
  if (old) ::setenv("XDG_RUNTIME_DIR", saved.c_str(), 1);
}

}  // namespace
}  // namespace vdrive::control
