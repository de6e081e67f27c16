// Compiled with the plant library's include path: must not compile (the plant knows no products).
#include "vdrive/profile/product_profile.hpp"
