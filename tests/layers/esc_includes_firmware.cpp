// Compiled with the ESC model's include path: must not compile (the chip knows nothing of firmware).
#include "vdrive/firmware/pdi.hpp"
