// Compiled with the drive library's include path: must compile (what the drive may see).
#include "common/clock.hpp"
#include "ethercat/al_state.hpp"
#include "plant/plant.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/product_profile.hpp"
