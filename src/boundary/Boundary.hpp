#pragma once
// Per-side wall conditions for the tangential velocity (section 2.2). The normal velocity is
// zero on every side (eq. 20) by construction of the MAC storage (grid/Grid.hpp).
//
// On a wall, the viscous flux of tangential momentum through the wall face, per unit length,
// is eta d(u_t)/dn = c (U_wall - u_c), where u_c is the tangential velocity at the first face
// centre, a distance d = h/2 from the wall, and c depends on the condition:
//   free slip (eq. 21)          d(u_t)/dn = 0                  -> c = 0
//   no slip (u_t = U_wall)      eta (U_wall - u_c) / d          -> c = eta / d
//   Navier slip (eq. 24)        eta d(u_t)/dn + eta_b u_t = 0   -> with the wall value
//        u_w = eta u_c / (eta + eta_b d), the flux is -eta_b u_w  -> c = eta eta_b / (eta + eta_b d)
// (Navier with eta_b -> infinity is no slip, eta_b = 0 is free slip.)
namespace gf {

enum class WallType { FreeSlip, NoSlip, Navier };

struct WallBC {
  WallType type = WallType::FreeSlip;
  double eta_b = 1.0;     // Pa s / m, Navier coefficient (eq. 24)
  double velocity = 0.0;  // m/s, tangential wall velocity (a moving lid); + along +x or +y
};

struct Boundaries {
  WallBC left, right, bottom, top;
};

// The coefficient c of the wall flux c (U_wall - u_c), Pa s / m.
inline double wall_coefficient(const WallBC& w, double eta, double d) {
  switch (w.type) {
    case WallType::FreeSlip: return 0.0;
    case WallType::NoSlip: return eta / d;
    case WallType::Navier: return eta * w.eta_b / (eta + w.eta_b * d);
  }
  return 0.0;
}


}  // namespace gf
