#pragma once
// One Dictionary per product per process: loading a large objects.yaml once, however many slaves
// of that product a network holds. Thread-safe; called at construction time only.
#include <memory>
#include <string>

#include "vdrive/od/dictionary.hpp"

namespace vdrive::od {

std::shared_ptr<const Dictionary> shared_dictionary(const profile::ProductProfile& profile,
                                                    const std::string& profile_dir = {});

}  // namespace vdrive::od
