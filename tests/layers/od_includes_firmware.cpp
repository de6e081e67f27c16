// Compiled with the object dictionary library's include path: must not compile.
#include "vdrive/firmware/al_state_machine.hpp"
