#pragma once
// A veth pair that exists as long as this object does (created over rtnetlink, both ends set
// up, deleted in the destructor). Used by `vdrive demo`; needs CAP_NET_ADMIN (root).
#include <string>

namespace vdrive::cli {

class VethPair {
public:
  // Throws CliError: kExitNotPermitted without CAP_NET_ADMIN, kExitFailure when a name is taken
  // (what() names it) or the kernel refuses.
  VethPair(std::string master_end, std::string slave_end);
  ~VethPair();
  VethPair(const VethPair&) = delete;
  VethPair& operator=(const VethPair&) = delete;

  const std::string& master_end() const { return master_; }
  const std::string& slave_end() const { return slave_; }

private:
  std::string master_;
  std::string slave_;
};

}  // namespace vdrive::cli
