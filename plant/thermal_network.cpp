#include "plant/thermal_network.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace vdrive::plant {

ThermalNetwork::ThermalNetwork(const MotorParams& m, double step_s) : ambient_(m.ambient_c) {
  const double cw = m.winding_capacity_j_per_k, ch = m.housing_capacity_j_per_k;
  const double gwh = 1.0 / m.winding_to_housing_k_per_w, gha = 1.0 / m.housing_to_ambient_k_per_w;
  Eigen::Matrix2d a;
  a << -gwh / cw, gwh / cw,
        gwh / ch, -(gwh + gha) / ch;
  const Eigen::Vector2d b(1.0 / cw, 0.0);
  const Eigen::Matrix2d ad = (a * step_s).exp();
  const Eigen::Vector2d bd = a.fullPivLu().solve((ad - Eigen::Matrix2d::Identity()) * b);
  for (int r = 0; r < 2; ++r) {
    bd_[r] = bd(r);
    for (int c = 0; c < 2; ++c) ad_[r][c] = ad(r, c);
  }
}

void ThermalNetwork::step(double loss_w) {
  const double w = ad_[0][0] * rise_[0] + ad_[0][1] * rise_[1] + bd_[0] * loss_w;
  const double h = ad_[1][0] * rise_[0] + ad_[1][1] * rise_[1] + bd_[1] * loss_w;
  rise_[0] = w;
  rise_[1] = h;
}

}  // namespace vdrive::plant
