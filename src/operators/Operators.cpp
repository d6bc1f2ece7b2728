#include "operators/Operators.hpp"

namespace gf::ops {

namespace {

// van Leer's limited slope: the harmonic mean of the two one-sided differences, 0 at extrema.
inline double van_leer(double a, double b) { return a * b > 0 ? 2 * a * b / (a + b) : 0.0; }

// The transported velocity component at a flux point between the samples q0 and q1, by a
// MUSCL reconstruction from the upwind side (advecting velocity a). qm1 / q2 are the next
// samples upstream on each side; where one lies beyond a wall (have_m1 / have_2 false) the
// reconstruction drops to first-order upwind: no ghost extrapolation.
inline double muscl(double qm1, double q0, double q1, double q2, bool have_m1, bool have_2,
                    double a) {
  if (a >= 0) return have_m1 ? q0 + 0.5 * van_leer(q0 - qm1, q1 - q0) : q0;
  return have_2 ? q1 - 0.5 * van_leer(q2 - q1, q1 - q0) : q1;
}

}  // namespace

void convection(const Box& b, const Vel* const* vel, Vel** out) {
  const double hx = b.hx, hy = b.hy;
  const PetscInt ny = b.ny;
  // x-momentum: the flux of u through the cell centre c (between u-faces c and c+1) and through
  // the node (i, jn) (between u(i, jn-1) and u(i, jn)). u-face indices 0..nx exist (0 and nx are
  // walls, u = 0; with periodic x every face exists, read from the wrapped ghosts); rows 0..ny-1.
  auto fx_u = [&](PetscInt c, PetscInt j) {
    const double a = 0.5 * (vel[j][c].u + vel[j][c + 1].u);
    const bool m1 = b.has_uface(c - 1), p2 = b.has_uface(c + 2);
    const double q = muscl(m1 ? vel[j][c - 1].u : 0.0, vel[j][c].u, vel[j][c + 1].u,
                           p2 ? vel[j][c + 2].u : 0.0, m1, p2, a);
    return a * q;
  };
  auto fy_u = [&](PetscInt i, PetscInt jn) {
    if (jn == 0 || jn == ny) return 0.0;  // wall: v = 0
    const double a = 0.5 * (vel[jn][i - 1].v + vel[jn][i].v);
    const double q = muscl(jn >= 2 ? vel[jn - 2][i].u : 0.0, vel[jn - 1][i].u, vel[jn][i].u,
                           jn + 1 <= ny - 1 ? vel[jn + 1][i].u : 0.0, jn >= 2, jn + 1 <= ny - 1, a);
    return a * q;
  };
  // y-momentum: the flux of v through the node (in, j) (between v(in-1, j) and v(in, j)) and
  // through the cell centre c (between v-faces c and c+1).
  auto fx_v = [&](PetscInt in, PetscInt j) {
    if (b.wall_u(in)) return 0.0;  // wall: u = 0
    const double a = 0.5 * (vel[j - 1][in].u + vel[j][in].u);
    const bool m2 = b.has_cell_x(in - 2), p1 = b.has_cell_x(in + 1);
    const double q = muscl(m2 ? vel[j][in - 2].v : 0.0, vel[j][in - 1].v, vel[j][in].v,
                           p1 ? vel[j][in + 1].v : 0.0, m2, p1, a);
    return a * q;
  };
  auto fy_v = [&](PetscInt i, PetscInt c) {
    const double a = 0.5 * (vel[c][i].v + vel[c + 1][i].v);
    const double q = muscl(c >= 1 ? vel[c - 1][i].v : 0.0, vel[c][i].v, vel[c + 1][i].v,
                           c + 2 <= ny ? vel[c + 2][i].v : 0.0, c >= 1, c + 2 <= ny, a);
    return a * q;
  };
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      out[j][i].u = b.wall_u(i) ? 0.0
                             : (fx_u(i, j) - fx_u(i - 1, j)) / hx + (fy_u(i, j + 1) - fy_u(i, j)) / hy;
      out[j][i].v = (j == 0) ? 0.0
                             : (fx_v(i + 1, j) - fx_v(i, j)) / hx + (fy_v(i, j) - fy_v(i, j - 1)) / hy;
    }
}

void divergence(const Box& b, const Vel* const* vel, PetscScalar** div) {
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      div[j][i] = (vel[j][i + 1].u - vel[j][i].u) / b.hx + (vel[j + 1][i].v - vel[j][i].v) / b.hy;
}

}  // namespace gf::ops
