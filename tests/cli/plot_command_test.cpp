// `vdrive plot` as a user meets it: a trace from a real scenario run (the built binary running
// scenarios/modes_csp.yaml), plotted, and the PNG decoded with libpng: its size is what was asked
// and each of the four panels has the data line's colour inside its frame. Errors: exit codes
// and messages (docs/cli.md).
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/cli/plot_png_image.hpp"
#include "tests/support/child_process.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif
#ifndef VDRIVE_SOURCE_DIR
#error "tests/CMakeLists.txt defines VDRIVE_SOURCE_DIR (the scenarios are read from it)"
#endif

namespace vdrive::cli {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;

ProcessResult vdrive(const std::vector<std::string>& args) { return test::run_process(VDRIVE_BINARY, args); }

// The colour of the first line drawn (vdrive/cli/gnuplot_script.cpp, series_colour(0)).
constexpr const char* kFirstSeriesColour = "#0072B2";

class PlotCommand : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("vdrive-plot-test-" + std::to_string(::getpid())));
    fs::create_directories(*dir_);
    const ProcessResult r = vdrive({"scenario", "run", std::string(VDRIVE_SOURCE_DIR) + "/scenarios/modes_csp.yaml", "--trace",
                                    (*dir_ / "csp.csv").string()});
    trace_ok_ = r.exit_code == 0;
    trace_log_ = r.out + r.err;
  }
  static void TearDownTestSuite() {
    std::error_code ignored;
    fs::remove_all(*dir_, ignored);
    delete dir_;
  }
  void SetUp() override { ASSERT_TRUE(trace_ok_) << "the scenario producing the trace failed: " << trace_log_; }

  static std::string path(const std::string& name) { return (*dir_ / name).string(); }

  static fs::path* dir_;
  static bool trace_ok_;
  static std::string trace_log_;
};
fs::path* PlotCommand::dir_ = nullptr;
bool PlotCommand::trace_ok_ = false;
std::string PlotCommand::trace_log_;

TEST_F(PlotCommand, FourPanelsWithDataAtTheRequestedSize) {
  const ProcessResult r = vdrive({"plot", path("csp.csv"), "-o", path("csp.png"), "--size", "1000x800", "--title", "modes_csp"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("slave(s) 1, 2, 3"), std::string::npos) << r.out;

  const test::PngImage img = test::read_png(path("csp.png"));
  ASSERT_TRUE(img.error.empty()) << img.error;
  EXPECT_EQ(img.width, 1000);
  EXPECT_EQ(img.height, 800);

  const std::vector<test::Frame> frames = test::find_frames(img);
  ASSERT_EQ(frames.size(), 4u) << "expected four stacked panels";
  const test::Rgb line = test::parse_colour(kFirstSeriesColour);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const test::Frame& f = frames[i];
    SCOPED_TRACE("panel " + std::to_string(i));
    EXPECT_GT(f.right - f.left, 500);  // a real plotting area, not a legend box
    EXPECT_GT(f.bottom - f.top, 60);
    if (i > 0) {
      EXPECT_GT(f.top, frames[i - 1].bottom);  // stacked, top to bottom
    }
    const int data = test::count_inside(img, f, line, 40);
    EXPECT_GT(data, 100) << "no line of slave 1 inside the panel";
    // A line, not a filled area.
    EXPECT_LT(data, (f.right - f.left) * (f.bottom - f.top) / 4);
  }
}

TEST_F(PlotCommand, OneSlaveOnlyDrawsOneLine) {
  // Slave 2 is drawn in the first colour when it is the only one; the second colour is absent.
  const ProcessResult r = vdrive({"plot", path("csp.csv"), "-o", path("slave2.png"), "--slave", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PngImage img = test::read_png(path("slave2.png"));
  ASSERT_TRUE(img.error.empty()) << img.error;
  EXPECT_EQ(img.width, 1200);  // the default size
  EXPECT_EQ(img.height, 900);
  const std::vector<test::Frame> frames = test::find_frames(img);
  ASSERT_EQ(frames.size(), 4u);
  for (const test::Frame& f : frames) {
    EXPECT_GT(test::count_inside(img, f, test::parse_colour(kFirstSeriesColour), 40), 100);
    EXPECT_EQ(test::count_inside(img, f, test::parse_colour("#D55E00"), 10), 0);
  }
}

TEST_F(PlotCommand, ColumnsAreFoundByNameNotPosition) {
  // The same trace with its columns in reverse order (as another writer might order them) gives
  // the same picture, pixel for pixel.
  std::ifstream in(path("csp.csv"));
  std::ofstream out(path("reversed.csv"));
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    for (std::size_t i = cells.size(); i-- > 0;) out << cells[i] << (i == 0 ? "\n" : ",");
  }
  out.close();
  ASSERT_EQ(vdrive({"plot", path("csp.csv"), "-o", path("a.png")}).exit_code, 0);
  const ProcessResult r = vdrive({"plot", path("reversed.csv"), "-o", path("b.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PngImage a = test::read_png(path("a.png")), b = test::read_png(path("b.png"));
  ASSERT_TRUE(a.error.empty() && b.error.empty());
  EXPECT_TRUE(a.pixels == b.pixels);
}

TEST_F(PlotCommand, FromZeroStartsTheTimeAxisAtTheFirstRow) {
  // The same trace stamped 1000 s later (as a monotonic clock would): with --from-zero both give
  // the same picture; without it they differ.
  std::ifstream in(path("csp.csv"));
  std::ofstream out(path("later.csv"));
  std::string line;
  std::getline(in, line);
  out << line << "\n";
  while (std::getline(in, line)) {
    const std::size_t comma = line.find(',');
    out << std::stoll(line.substr(0, comma)) + 1'000'000'000'000LL << line.substr(comma) << "\n";
  }
  out.close();
  ASSERT_EQ(vdrive({"plot", path("csp.csv"), "-o", path("zero_a.png"), "--from-zero"}).exit_code, 0);
  ASSERT_EQ(vdrive({"plot", path("later.csv"), "-o", path("zero_b.png"), "--from-zero"}).exit_code, 0);
  ASSERT_EQ(vdrive({"plot", path("later.csv"), "-o", path("later.png")}).exit_code, 0);
  const test::PngImage a = test::read_png(path("zero_a.png")), b = test::read_png(path("zero_b.png")),
                       c = test::read_png(path("later.png"));
  ASSERT_TRUE(a.error.empty() && b.error.empty() && c.error.empty());
  EXPECT_TRUE(a.pixels == b.pixels);
  EXPECT_FALSE(b.pixels == c.pixels);
}

TEST_F(PlotCommand, DefaultOutputIsTheTraceNameWithPng) {
  fs::copy_file(path("csp.csv"), path("named.csv"), fs::copy_options::overwrite_existing);
  const ProcessResult r = vdrive({"plot", path("named.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(test::read_png(path("named.png")).error.empty());
}

void expect_error(const ProcessResult& r, int code, const std::string& must_contain) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_EQ(r.err.rfind("vdrive: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(must_contain), std::string::npos) << r.err;
}

TEST_F(PlotCommand, AnExistingOutputIsReplacedOnlyWithForce) {
  ASSERT_EQ(vdrive({"plot", path("csp.csv"), "-o", path("twice.png")}).exit_code, 0);
  const auto written = fs::last_write_time(path("twice.png"));
  expect_error(vdrive({"plot", path("csp.csv"), "-o", path("twice.png")}), 2, "twice.png' exists; --force replaces it");
  EXPECT_EQ(fs::last_write_time(path("twice.png")), written);
  const ProcessResult r = vdrive({"plot", path("csp.csv"), "-o", path("twice.png"), "--force"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(PlotCommand, AxesNameTheirUnitsAndRevolutionsUseEachProductsResolution) {
  // The scenario's drives in cable order; the units come from each product's factor group.
  ProcessResult r = vdrive({"plot", path("csp.csv"), "-o", path("rev.png"), "--drive", "a6b", "ds5c1", "ds1000a", "--revolutions"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("a6b: 8.38861e+06 position units per motor revolution"), std::string::npos) << r.out;  // 23-bit encoder
  EXPECT_NE(r.out.find("ds5c1: 131072 position units per motor revolution"), std::string::npos) << r.out;   // 17-bit
  const test::PngImage img = test::read_png(path("rev.png"));
  ASSERT_TRUE(img.error.empty()) << img.error;
  ASSERT_EQ(test::find_frames(img).size(), 4u);

  r = vdrive({"plot", path("csp.csv"), "-o", path("norev.png"), "--revolutions"});
  expect_error(r, 2, "--revolutions: give each slave's product in cable order with --drive");
  r = vdrive({"plot", path("csp.csv"), "-o", path("norev.png"), "--drive", "a6b"});
  expect_error(r, 2, "--drive: 1 given, the trace has slave 2");
  r = vdrive({"plot", path("csp.csv"), "-o", path("norev.png"), "--normalise", "--revolutions", "--drive", "a6b", "ds5c1", "ds1000a"});
  EXPECT_EQ(r.exit_code, 2) << "--normalise and --revolutions exclude each other";
}

TEST_F(PlotCommand, AlChangesAlarmsAndLoggedEventsAreMarked) {
  // The trace's own AL changes (every slave to Op) are markers; an event log adds its events.
  ProcessResult r = vdrive({"plot", path("csp.csv"), "-o", path("marks.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto count = [](const std::string& out) {
    const std::size_t at = out.find(" marker(s)");
    const std::size_t from = out.rfind(' ', at - 1) + 1;
    return at == std::string::npos ? -1 : std::stoi(out.substr(from, at - from));
  };
  const int own = count(r.out);
  EXPECT_GT(own, 0) << r.out;
  const test::PngImage img = test::read_png(path("marks.png"));
  ASSERT_TRUE(img.error.empty()) << img.error;
  const std::vector<test::Frame> frames = test::find_frames(img);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_GT(test::count_inside(img, frames[3], test::parse_colour("#888888"), 12), 20) << "an AL marker crosses every panel";

  std::ofstream(path("events.csv")) << "time_ns,slave,kind,value,previous,text\n"
                                    << "500000000,2,fault_injected,0,0,\"overload, until cleared\"\n"
                                    << "900000000,2,alarm,65296,0,E-161 overload\n";
  r = vdrive({"plot", path("csp.csv"), "-o", path("marks2.png"), "--events", path("events.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count(r.out), own + 2) << r.out;
  const test::PngImage with_events = test::read_png(path("marks2.png"));
  ASSERT_TRUE(with_events.error.empty());
  EXPECT_GT(test::count_inside(with_events, test::find_frames(with_events)[2], test::parse_colour("#C00000"), 12), 20)
      << "the logged alarm's marker";

  std::ofstream(path("bad_events.csv")) << "time_ns,slave,text\n1,1,x\n";
  expect_error(vdrive({"plot", path("csp.csv"), "-o", path("marks3.png"), "--events", path("bad_events.csv")}), 2,
               "--events: " + path("bad_events.csv") + ":1: an event log needs the columns time_ns, slave, kind and text");
}

TEST_F(PlotCommand, BadInputIsABadArgumentNamingTheFile) {
  expect_error(vdrive({"plot", path("nosuch.csv")}), 2, "nosuch.csv: cannot open");

  std::ofstream(path("empty.csv")).close();
  expect_error(vdrive({"plot", path("empty.csv")}), 2, "empty file");

  std::ofstream(path("header_only.csv")) << "time_ns,slave,position,velocity,torque,following_error\n";
  expect_error(vdrive({"plot", path("header_only.csv")}), 2, "no rows");

  std::ofstream(path("no_torque.csv")) << "time_ns,slave,position,velocity,following_error\n1,1,2,3,4\n";
  expect_error(vdrive({"plot", path("no_torque.csv")}), 2, "lacks column(s) torque");

  std::ofstream(path("bad_value.csv")) << "time_ns,slave,position,velocity,torque,following_error\n1,1,2,fast,4,5\n";
  expect_error(vdrive({"plot", path("bad_value.csv")}), 2, "bad_value.csv:2: velocity 'fast' is not a number");
}

TEST_F(PlotCommand, ASlaveIsAPositionOrItsStationAddress) {
  // The scenario's master gave the slaves 0x1001.. (the trace's station column).
  ProcessResult r = vdrive({"plot", path("csp.csv"), "-o", path("by_address.png"), "--slave", "0x1002"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = vdrive({"plot", path("csp.csv"), "-o", path("by_position.png"), "--slave", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream a(path("by_address.png"), std::ios::binary), b(path("by_position.png"), std::ios::binary);
  const std::string by_address{std::istreambuf_iterator<char>(a), {}}, by_position{std::istreambuf_iterator<char>(b), {}};
  EXPECT_FALSE(by_address.empty());
  EXPECT_TRUE(by_address == by_position) << "the same slave, the same plot";

  expect_error(vdrive({"plot", path("csp.csv"), "--slave", "0x1009"}), 2, "has slave 1 @0x1001, slave 2 @0x1002, slave 3 @0x1003");
  std::ofstream(path("no_station.csv")) << "time_ns,slave,position,velocity,torque,following_error\n1,1,2,3,4,5\n";
  expect_error(vdrive({"plot", path("no_station.csv"), "--slave", "0x1001"}), 2,
               "has slave 1 (no station addresses: its slaves had none, or it has no station column)");
  expect_error(vdrive({"plot", path("csp.csv"), "--slave", "0x10G1"}), 2, "'0x10G1' names no slave");
}

TEST_F(PlotCommand, BadOptionsAreNamed) {
  for (const char* size : {"big", "100x100", "1000x", "20000x600"})
    expect_error(vdrive({"plot", path("csp.csv"), "--size", size}), 2, "--size");
  expect_error(vdrive({"plot", path("csp.csv"), "--slave", "7"}), 2, "--slave 7");
  expect_error(vdrive({"plot", path("csp.csv"), "--bogus"}), 2, "--bogus");
  expect_error(vdrive({"plot"}), 2, "trace");
}

TEST_F(PlotCommand, UnwritableOutputExitsOne) {
  expect_error(vdrive({"plot", path("csp.csv"), "-o", path("no/such/dir/x.png")}), 1, "cannot write");
}

TEST_F(PlotCommand, MissingGnuplotExitsFive) {
  ::setenv("VDRIVE_GNUPLOT", "/nonexistent/gnuplot", 1);
  const ProcessResult r = vdrive({"plot", path("csp.csv"), "-o", path("never.png")});
  ::unsetenv("VDRIVE_GNUPLOT");
  expect_error(r, 5, "gnuplot-nox");
}

}  // namespace
}  // namespace vdrive::cli
