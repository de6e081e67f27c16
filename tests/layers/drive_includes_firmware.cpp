// Compiled with the drive library's include path: must not compile (the firmware is above the drive).
#include "vdrive/firmware/slave_firmware.hpp"
