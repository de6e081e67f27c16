#pragma once
// A malformed or unusable ESI file: what() names the file, the line and the element
// ("EL1008.xml:42: <Sm>: StartAddress 'x12' is not a number"). A ProfileError, so every place that
// reports a broken product reports it.
#include <string>

#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::esi {

class EsiError : public profile::ProfileError {
public:
  using profile::ProfileError::ProfileError;
};

}  // namespace vdrive::esi
