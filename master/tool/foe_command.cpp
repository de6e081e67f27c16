#include "master/tool/foe_command.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <vector>

#include "master/foe.hpp"
#include "master/master.hpp"
#include "master/tool/slave_option.hpp"
#include "vdrive/link/raw_socket_link.hpp"

namespace vdrive::master::tool {

namespace {
void add_common(CLI::App* cmd, std::string& iface, std::string& slave, std::uint32_t& password, std::string& state) {
  cmd->add_option("--iface,-i", iface, "Network interface the line is connected to")->required();
  add_slave_option(cmd, slave);
  cmd->add_option("--password", password, "FoE password (default 0: none)");
  cmd->add_option("--state", state, "State for the transfer: boot or preop")
      ->check(CLI::IsMember({"boot", "preop"}, CLI::ignore_case));
}

// Scans, finds the slave --slave names and takes it to `state`: its index, or nothing (with a line
// on stderr) when the slave does not reach it: exit status 1.
std::optional<std::size_t> open(Master& master, const std::string& slave_text, const std::string& state) {
  if (master.scan() == 0) throw std::runtime_error("no EtherCAT slaves on the interface");
  const std::size_t slave = resolve_slave(master, slave_text);
  const AlState target = state == "boot" ? AlState::Boot : AlState::PreOp;
  if (master.request_state(slave, target)) return slave;
  std::fprintf(stderr, "vdrive-master: %s did not reach %s: %s\n", label(master.slaves()[slave]).c_str(),
               std::string(to_string(target)).c_str(), describe(master.slaves()[slave]).c_str());
  return std::nullopt;
}
}  // namespace

FoeCommand::FoeCommand(CLI::App& app) {
  write_ = app.add_subcommand("foe-write", "Write a file to a slave with FoE (firmware download: in Boot)");
  add_common(write_, iface_, slave_, password_, state_);
  write_->add_option("--name", name_, "File name sent to the slave (default: FILE's base name)");
  write_->add_option("FILE", file_, "The file to send")->required()->check(CLI::ExistingFile);
  read_ = app.add_subcommand("foe-read", "Read a file from a slave with FoE");
  add_common(read_, iface_, slave_, password_, state_);
  read_->add_option("--name", name_, "File name on the slave")->required();
  read_->add_option("OUTPUT", file_, "Where to store the file")->required();
}

bool FoeCommand::selected() const { return write_->parsed() || read_->parsed(); }

int FoeCommand::run() {
  try {
    return write_->parsed() ? run_write() : run_read();
  } catch (const FoeError& e) {
    // 0x8009: the name is not one the slave takes in Boot (SSC and the vdrive DS1000A-EC: a
    // firmware file's name starts with ECATFW__, docs/foe.md).
    std::fprintf(stderr, "vdrive-master: %s%s\n", e.what(),
                 e.code() == 0x8009 ? " (firmware files are taken in Boot under a name starting ECATFW__)" : "");
    return 1;
  }
}

int FoeCommand::run_write() {
  std::ifstream in(file_, std::ios::binary);
  const std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw std::runtime_error("cannot read " + file_);
  const std::string name = name_.empty() ? std::filesystem::path(file_).filename().string() : name_;
  vdrive::link::RawSocketLink link(iface_);
  Master master(link);
  const std::optional<std::size_t> slave = open(master, slave_, state_.empty() ? "boot" : state_);
  if (!slave) return 1;
  FoeClient foe(master, *slave);
  foe.write(name, data, password_);
  std::printf("%s: %zu bytes written as \"%s\" in %zu packets (%llu sent again, %llu busy)\n",
              describe(master.slaves()[*slave]).c_str(), data.size(), name.c_str(), data.size() / foe.max_data() + 1,
              static_cast<unsigned long long>(foe.resent_packets()), static_cast<unsigned long long>(foe.busy_replies()));
  // Boot -> Init restarts the drive into what it was given.
  if (!master.request_state(*slave, AlState::Init)) {
    std::fprintf(stderr, "vdrive-master: %s did not return to Init: %s\n", label(master.slaves()[*slave]).c_str(),
                 describe(master.slaves()[*slave]).c_str());
    return 1;
  }
  return 0;
}

int FoeCommand::run_read() {
  vdrive::link::RawSocketLink link(iface_);
  Master master(link);
  const std::optional<std::size_t> slave = open(master, slave_, state_.empty() ? "preop" : state_);
  if (!slave) return 1;
  FoeClient foe(master, *slave);
  const std::vector<std::uint8_t> data = foe.read(name_, password_);
  std::ofstream out(file_, std::ios::binary);
  out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  if (!out) throw std::runtime_error("cannot write " + file_);
  std::printf("%zu bytes read from \"%s\" into %s\n", data.size(), name_.c_str(), file_.c_str());
  return 0;
}

}  // namespace vdrive::master::tool
