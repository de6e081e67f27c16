#pragma once
// `vdrive-master foe-write` / `foe-read`: FoE file transfer with one slave (master/foe.hpp).
//
//   vdrive-master foe-write --iface IF --slave N [--name NAME] [--password P] [--state boot|preop] FILE
//   vdrive-master foe-read  --iface IF --slave N --name NAME [--password P] [--state boot|preop] OUTPUT
//
// foe-write takes the slave to Boot (default; through Init, with the SII's bootstrap mailbox),
// writes FILE under NAME (default: FILE's base name), and then requests Init, which restarts a
// drive into the new firmware. foe-read reads NAME into OUTPUT (default state Pre-Op).
// Exit status: 0 done, 1 link error or the transfer failed (the FoE error code and text are
// printed), 2 the slave did not reach the state.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace vdrive::master::tool {

class FoeCommand {
public:
  explicit FoeCommand(CLI::App& app);
  bool selected() const;
  int run();

private:
  int run_write();
  int run_read();

  CLI::App* write_ = nullptr;
  CLI::App* read_ = nullptr;
  std::string iface_, name_, file_, state_;
  std::string slave_;
  std::uint32_t password_ = 0;
};

}  // namespace vdrive::master::tool
