#pragma once
// The regularised Heaviside function of section 3.1 (used in eq. 25):
//   H_eps(phi) = 0 for phi < -eps, 1 for phi > eps,
//              = (1 + phi/eps + sin(pi phi/eps)/pi) / 2 in between.
// phi > 0 is air, phi < 0 the granular phase, so rho = rho_f H + rho_s (1 - H).
#include <cmath>
#include <numbers>

namespace gf::levelset {

inline double heaviside(double phi, double eps) {
  if (phi < -eps) return 0.0;
  if (phi > eps) return 1.0;
  return 0.5 * (1.0 + phi / eps + std::sin(std::numbers::pi * phi / eps) / std::numbers::pi);
}

// Eq. 25.
inline double density(double phi, double eps, double rho_air, double rho_gran) {
  const double H = heaviside(phi, eps);
  return rho_air * H + rho_gran * (1.0 - H);
}

}  // namespace gf::levelset
