#pragma once
// Motor thermal model: a two-node RC network (winding -> housing -> ambient) heated by copper loss.
// Discretised exactly (matrix exponential) for the fixed step, so step() is two multiply-adds per
// node and allocates nothing.
#include "plant/plant_description.hpp"

namespace vdrive::plant {

class ThermalNetwork {
public:
  ThermalNetwork(const MotorParams& m, double step_s);
  // Advance one step with `loss_w` watts dissipated in the winding.
  void step(double loss_w);
  double winding_c() const { return ambient_ + rise_[0]; }
  double housing_c() const { return ambient_ + rise_[1]; }

private:
  double ambient_;
  double rise_[2] = {0, 0};  // K above ambient
  double ad_[2][2];          // exp(A dt)
  double bd_[2];             // A^-1 (exp(A dt) - I) B
};

}  // namespace vdrive::plant
