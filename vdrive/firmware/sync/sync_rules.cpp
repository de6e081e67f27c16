// Sync rules of a product: ProductProfile::sync (profile.yaml `sync:`) in the form the module applies them.
#include "vdrive/firmware/sync/sync_rules.hpp"

namespace vdrive::firmware::sync {

SyncRules rules_for(const profile::ProductProfile& product) {
  SyncRules r;
  r.spec = product.sync;
  return r;
}

bool cycle_time_accepted(const profile::SyncSpec& spec, std::uint32_t cycle_ns) {
  return spec.accepts_cycle(cycle_ns);
}

}  // namespace vdrive::firmware::sync
