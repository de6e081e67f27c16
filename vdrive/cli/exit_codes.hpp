#pragma once
// Exit codes of the `vdrive` command (documented in docs/cli.md).
namespace vdrive::cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,          // anything else: a broken profile, a system call that failed
  kExitBadArguments = 2,     // bad option or value, unknown product
  kExitNoInterface = 3,      // the interface does not exist or is down
  kExitNotPermitted = 4,     // missing privileges (EPERM/EACCES): root or CAP_NET_RAW needed
  kExitMissingTool = 5,      // a program vdrive runs is not installed (gnuplot for `plot`)
};

}  // namespace vdrive::cli
