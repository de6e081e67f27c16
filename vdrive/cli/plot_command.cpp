#include "vdrive/cli/plot_command.hpp"

#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "ethercat/slave_ref.hpp"
#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/exit_codes.hpp"
#include "vdrive/cli/gnuplot_script.hpp"
#include "vdrive/cli/plot_markers.hpp"
#include "vdrive/cli/plot_units.hpp"
#include "vdrive/cli/slave_option.hpp"
#include "vdrive/cli/trace_csv.hpp"

extern char** environ;

namespace vdrive::cli {
namespace {

struct PlotOptions {
  std::string trace;
  std::string output;
  std::optional<std::string> slave;  // a position or a station address
  std::string title;
  std::string size = "1200x900";
  bool from_zero = false;  // time axis from the first row, for traces stamped with a monotonic clock
  std::vector<std::string> drives;  // --drive: each slave's product, in cable order (legend, --revolutions)
  std::string profile_dir;
  bool revolutions = false;
  bool normalise = false;
  std::string events;      // --events: an event log whose events are marked
  bool force = false;      // replace an existing output
};

// Each plotted slave's largest |value| per panel, as the factor that makes it 1.
PanelScale normalising_scale(const SlaveSeries& s) {
  const auto factor = [](const std::vector<double>& v) {
    double most = 0.0;
    for (const double x : v) most = std::max(most, std::abs(x));
    return most > 0.0 ? 1.0 / most : 1.0;
  };
  return PanelScale{factor(s.position), factor(s.velocity), factor(s.torque), factor(s.following_error)};
}

constexpr int kMinSide = 200, kMaxSide = 10000;

std::pair<int, int> parse_size(const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,5})x(\d{1,5}))")))
    throw CliError(kExitBadArguments, fmt::format("--size '{}': expected WIDTHxHEIGHT in pixels, e.g. 1200x900", text));
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < kMinSide || w > kMaxSide || h < kMinSide || h > kMaxSide)
    throw CliError(kExitBadArguments, fmt::format("--size '{}': width and height must be {}..{} pixels", text, kMinSide, kMaxSide));
  return {w, h};
}

// A private directory for the data and script files, removed with everything in it.
class TempDir {
public:
  TempDir() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/vdrive-plot-XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr)
      throw CliError(kExitFailure, fmt::format("cannot create a temporary directory '{}': {}", pattern, std::strerror(errno)));
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const char* name) const { return path_ + "/" + name; }

private:
  std::string path_;
};

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out.flush()) throw CliError(kExitFailure, fmt::format("cannot write '{}'", path));
}

std::string first_line_of(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  // gnuplot repeats the offending script line before its message; the message is what helps.
  while (std::getline(in, line))
    if (line.find_first_not_of(" ^") != std::string::npos) last = line;
  return last;
}

// Runs `gnuplot SCRIPT` (no shell), its output into LOG. $VDRIVE_GNUPLOT names another program.
void run_gnuplot(const std::string& script, const std::string& log) {
  const char* env = std::getenv("VDRIVE_GNUPLOT");
  const std::string program = env != nullptr && *env != '\0' ? env : "gnuplot";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::string arg0 = program, arg1 = script;
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int err = ::posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err == ENOENT)
    throw CliError(kExitMissingTool, fmt::format("'{}' not found: plot needs gnuplot (Debian package gnuplot-nox)", program));
  if (err != 0) throw CliError(kExitFailure, fmt::format("cannot run '{}': {}", program, std::strerror(err)));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string why = first_line_of(log);
    throw CliError(kExitFailure, WIFEXITED(status) ? fmt::format("{} failed (exit {}): {}", program, WEXITSTATUS(status), why)
                                                   : fmt::format("{} was killed by signal {}", program, WTERMSIG(status)));
  }
}

void run(const PlotOptions& o) {
  const auto [width, height] = parse_size(o.size);
  TraceCsv trace;
  try {
    trace = read_trace_csv(o.trace);
  } catch (const TraceCsvError& e) {
    throw CliError(kExitBadArguments, e.what());
  }
  double time_shift = 0.0;
  if (o.from_zero) {
    double first = trace.slaves.front().time_s.front();
    for (const SlaveSeries& s : trace.slaves) first = std::min(first, s.time_s.front());
    for (SlaveSeries& s : trace.slaves)
      for (double& t : s.time_s) t -= first;
    time_shift = first;
  }
  std::vector<const SlaveSeries*> series;
  std::vector<int> numbers;
  const bool only = o.slave.has_value();
  const ecat::SlaveRef ref = only ? ecat::parse_slave_ref(*o.slave) : ecat::SlaveRef{};
  for (const SlaveSeries& s : trace.slaves) {
    if (only && (ref.is_address() ? s.station : s.slave) != ref.value) continue;
    series.push_back(&s);
    numbers.push_back(s.slave);
  }
  if (series.empty()) {
    std::vector<std::string> present;
    bool stations = false;
    for (const SlaveSeries& s : trace.slaves) {
      present.push_back(ecat::slave_label(static_cast<std::size_t>(s.slave - 1), s.station, ""));
      stations = stations || s.station != 0;
    }
    throw CliError(kExitBadArguments, fmt::format("--slave {}: {} has {}{}", *o.slave, o.trace, fmt::join(present, ", "),
                                                  ref.is_address() && !stations
                                                      ? " (no station addresses: its slaves had none, or it has no station column)"
                                                      : ""));
  }

  // Products by cable order; the plotted slaves' own.
  std::vector<std::string> products;
  if (!o.drives.empty()) {
    for (const int slave : numbers) {
      if (slave < 1 || static_cast<std::size_t>(slave) > o.drives.size())
        throw CliError(kExitBadArguments, fmt::format("--drive: {} given, the trace has slave {}", o.drives.size(), slave));
      products.push_back(o.drives[static_cast<std::size_t>(slave) - 1]);
    }
  }
  if (o.revolutions && products.empty())
    throw CliError(kExitBadArguments, "--revolutions: give each slave's product in cable order with --drive (as to vdrive run)");
  PlotUnits units = o.revolutions ? revolution_units(products, o.profile_dir) : drive_units(series.size());
  std::array<std::string, 4> ylabels;
  for (std::size_t p = 0; p < 4; ++p) {
    const std::string& unit = p == 1 ? units.velocity : p == 2 ? units.torque : units.position;
    ylabels[p] = o.normalise ? fmt::format("{} (/ each slave's max)", kPanelNames[p]) : fmt::format("{} ({})", kPanelNames[p], unit);
  }
  if (o.normalise)
    for (std::size_t k = 0; k < series.size(); ++k) units.per_slave[k] = normalising_scale(*series[k]);
  std::vector<std::string> names;
  for (std::size_t k = 0; k < series.size(); ++k)
    names.push_back(ecat::slave_label(static_cast<std::size_t>(numbers[k] - 1), series[k]->station, products.empty() ? "" : products[k]));

  std::vector<PlotMarker> markers = trace_markers(series);
  if (!o.events.empty()) {
    try {
      std::vector<PlotMarker> more = read_event_markers(o.events);
      const double shift = o.from_zero ? time_shift : 0.0;
      for (PlotMarker& m : more) {
        m.time_s -= shift;
        if (only && m.slave != 0 && m.slave != numbers.front()) continue;  // the event log counts positions
        markers.push_back(std::move(m));
      }
    } catch (const TraceCsvError& e) {
      throw CliError(kExitBadArguments, fmt::format("--events: {}", e.what()));
    }
  }
  markers = merge_simultaneous(std::move(markers));

  const std::string output = o.output.empty() ? std::filesystem::path(o.trace).replace_extension(".png").string() : o.output;
  if (!o.force && std::filesystem::exists(output))
    throw CliError(kExitBadArguments, fmt::format("'{}' exists; --force replaces it", output));
  {  // gnuplot only warns about an output it cannot open; find out first and say so.
    std::ofstream probe(output, std::ios::binary | std::ios::app);
    if (!probe) throw CliError(kExitFailure, fmt::format("-o: cannot write '{}': {}", output, std::strerror(errno)));
  }
  TempDir dir;
  PlotSpec spec;
  spec.data_file = dir.file("trace.dat");
  spec.output = output;
  spec.width = width;
  spec.height = height;
  spec.title = o.title;
  spec.ylabels = ylabels;
  spec.series_names = names;
  spec.markers = markers;
  {
    std::ofstream data(spec.data_file);
    write_gnuplot_data(data, series, units.per_slave);
    if (!data.flush()) throw CliError(kExitFailure, fmt::format("cannot write '{}'", spec.data_file));
  }
  write_text(dir.file("plot.gp"), gnuplot_script(spec));
  run_gnuplot(dir.file("plot.gp"), dir.file("gnuplot.log"));
  std::error_code ec;
  if (std::filesystem::file_size(output, ec) == 0 || ec)
    throw CliError(kExitFailure, fmt::format("gnuplot wrote nothing to '{}': {}", output, first_line_of(dir.file("gnuplot.log"))));
  const double t0 = series.front()->time_s.front(), t1 = series.front()->time_s.back();
  fmt::print("{}: slave(s) {}, {:.3f} to {:.3f} s, {} marker(s)\n", output, fmt::join(numbers, ", "), t0, t1, markers.size());
  for (const std::string& note : units.notes) fmt::print("  {}\n", note);
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto o = std::make_shared<PlotOptions>();
  CLI::App* cmd = app.add_subcommand("plot", "Plot position, velocity, torque and following error of a trace CSV (PNG)");
  cmd->add_option("trace", o->trace, "Trace CSV: vdrive scenario run --trace, or a telemetry CSV")
      ->required()
      ->type_name("TRACE.csv");
  cmd->add_option("--output,-o", o->output, "PNG file to write (default: TRACE with .png instead of .csv)")
      ->type_name("FILE");
  cmd->add_option("--slave", o->slave, "Only this slave: its position (1 = first) or station address (0x1002); default: every slave")
      ->type_name("K|0xADDR")
      ->check(slave_ref_validator().description(""));
  cmd->add_option("--title", o->title, "Title above the panels")->type_name("TEXT");
  cmd->add_flag("--from-zero", o->from_zero,
                "Time axis from the first row (0 s) instead of the file's times, e.g. for a telemetry CSV stamped with "
                "the host's monotonic clock");
  cmd->add_option("--drive,-d", o->drives, "Each slave's product in cable order, as to vdrive run (legend, --revolutions)")
      ->take_all()
      ->type_name("ID");
  cmd->add_option("--profile-dir", o->profile_dir, "With --drive: profiles from DIR instead of the built-in ones");
  CLI::Option* rev = cmd->add_flag("--revolutions", o->revolutions,
                "Motor revolutions, rev/s and % rated torque instead of the drive's units (needs --drive; uses each "
                "product's factor group at power-on)");
  cmd->add_flag("--normalise", o->normalise, "Each slave's curve divided by its own largest |value| per panel")->excludes(rev);
  cmd->add_option("--events", o->events,
                  "Mark the events of an event log (vdrive telemetry --events-csv, the web page's events.csv)")
      ->type_name("EVENTS.csv");
  cmd->add_flag("--force,-f", o->force, "Replace an existing output file");
  cmd->add_option("--size", o->size, "Image size in pixels, WIDTHxHEIGHT (200..10000 each)")
      ->type_name("WxH")
      ->capture_default_str();
  cmd->footer(
      "Examples:\n"
      "  vdrive scenario run scenarios/modes_csp.yaml --trace csp.csv\n"
      "  vdrive plot csp.csv -o csp.png --title 'csp, 3 drives'\n"
      "  vdrive plot csp.csv --slave 2 --size 1600x1000\n"
      "  vdrive plot axes.csv --from-zero --events events.csv --drive a6b ds5c1 ds1000a --revolutions -o axes.png\n"
      "Needs gnuplot (Debian gnuplot-nox); $VDRIVE_GNUPLOT names another gnuplot program.");
  cmd->callback([o] { run(*o); });
}

}  // namespace vdrive::cli
