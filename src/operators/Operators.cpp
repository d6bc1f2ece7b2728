#include "operators/Operators.hpp"

#include "core/Error.hpp"

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

void momentum_transport(const Box& b, double dt, double rho_air, double rho_gran,
                        const Vel* const* adv, const PetscScalar* const* c_a,
                        const PetscScalar* const* c_b, const PetscScalar* const* cc,
                        const Vel* const* F, const Vel* const* q, Vel** out) {
  const double drho = rho_gran - rho_air;
  const PetscInt ny = b.ny;
  auto rho = [&](double c) { return rho_air + drho * c; };
  // The CFL numbers, mass fluxes and dilatation masses of the two sweeps (see the header).
  auto s_x = [&](PetscInt i, PetscInt j) { return b.wall_u(i) ? 0.0 : adv[j][i].u * dt / b.hx; };
  auto s_y = [&](PetscInt i, PetscInt j) {
    return (j <= 0 || j >= ny) ? 0.0 : adv[j][i].v * dt / b.hy;
  };
  auto Mx = [&](PetscInt i, PetscInt j) {
    return b.wall_u(i) ? 0.0 : rho_air * s_x(i, j) + drho * F[j][i].u;
  };
  auto My = [&](PetscInt i, PetscInt j) {
    return (j <= 0 || j >= ny) ? 0.0 : rho_air * s_y(i, j) + drho * F[j][i].v;
  };
  auto D = [&](PetscInt i, PetscInt j) {
    return rho(cc[j][i]) * (s_x(i + 1, j) - s_x(i, j) + s_y(i, j + 1) - s_y(i, j));
  };
  // The density after the step of the control volume of u-face (i, j) and of v-face (i, j);
  // a wall face's control volume is its one cell.
  auto rb_u = [&](PetscInt i, PetscInt j) {
    const PetscInt il = b.has_cell_x(i - 1) ? i - 1 : i, ir = b.has_cell_x(i) ? i : i - 1;
    return 0.5 * (rho(c_b[j][il]) + rho(c_b[j][ir]));
  };
  auto rb_v = [&](PetscInt i, PetscInt j) {
    const PetscInt jl = j >= 1 ? j - 1 : j, jr = j < ny ? j : j - 1;
    return 0.5 * (rho(c_b[jl][i]) + rho(c_b[jr][i]));
  };
  // The side's contribution M q_side: q_side upwind of M by MUSCL with van Leer's limiter (as
  // convection()), the samples qm1, q0 | q1, q2 across the side (have_* whether the outer two
  // exist), rb0 / rb1 the densities after the step of the control volumes of q0 / q1. The
  // upwind control volume gives up M q_side and keeps rho_b q' = ... - M (q_up + corr): the
  // MUSCL correction corr moves its velocity by M corr / rho_b, which at a density jump (a
  // heavy outflow leaving a control volume that has become light, M / rho_b >> 1) would
  // overshoot without bound (measured: 1.3 m/s beyond the bounds of a 0.4 m/s rotation in one
  // step). It is scaled down where the upwind control volume's local Courant number M / rho_b
  // exceeds kLambda (in a region of uniform density M / rho_b is the CFL number, <= 1/2:
  // untouched); q_side stays between q0 and q1, so the receiving side stays bounded as well.
  constexpr double kLambda = 0.5;
  auto side = [&](double m, double qm1, double q0, double q1, double q2, bool have_m1,
                  bool have_2, double rb0, double rb1) {
    if (m == 0.0) return 0.0;
    double q, corr, rb;
    if (m > 0) {
      q = q0;
      corr = have_m1 ? 0.5 * van_leer(q0 - qm1, q1 - q0) : 0.0;
      rb = rb0;
    } else {
      q = q1;
      corr = have_2 ? -0.5 * van_leer(q2 - q1, q1 - q0) : 0.0;
      rb = rb1;
    }
    const double lam = std::abs(m) / rb;
    if (lam > kLambda) corr *= kLambda / lam;
    return m * (q + corr);
  };
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      // ---- u on the u-face (i, j): its control volume is half of cells (i-1, j) and (i, j).
      if (b.wall_u(i)) {
        out[j][i].u = 0.0;
      } else {
        // x-sides at the centres of cells i-1 and i, between u-faces c and c+1
        auto fx = [&](PetscInt c) {
          const double m = 0.5 * (Mx(c, j) + Mx(c + 1, j));
          const bool m1 = b.has_uface(c - 1), p2 = b.has_uface(c + 2);
          return side(m, m1 ? q[j][c - 1].u : 0.0, q[j][c].u, q[j][c + 1].u,
                      p2 ? q[j][c + 2].u : 0.0, m1, p2, rb_u(c, j), rb_u(c + 1, j));
        };
        // y-sides at the nodes (i, jn), between u(i, jn-1) and u(i, jn); walls carry none
        auto fy = [&](PetscInt jn) {
          if (jn <= 0 || jn >= ny) return 0.0;
          const double m = 0.5 * (My(i - 1, jn) + My(i, jn));
          return side(m, jn >= 2 ? q[jn - 2][i].u : 0.0, q[jn - 1][i].u, q[jn][i].u,
                      jn + 1 <= ny - 1 ? q[jn + 1][i].u : 0.0, jn >= 2, jn + 1 <= ny - 1,
                      rb_u(i, jn - 1), rb_u(i, jn));
        };
        const double flux = fx(i) - fx(i - 1) + fy(j + 1) - fy(j);
        const double Df = 0.5 * (D(i - 1, j) + D(i, j));
        const double ra = 0.5 * (rho(c_a[j][i - 1]) + rho(c_a[j][i]));
        const double rb = 0.5 * (rho(c_b[j][i - 1]) + rho(c_b[j][i]));
        out[j][i].u = (ra * q[j][i].u - flux + Df * q[j][i].u) / rb;
      }
      // ---- v on the v-face (i, j): half of cells (i, j-1) and (i, j).
      if (j == 0) {
        out[j][i].v = 0.0;
      } else {
        // x-sides at the nodes (in, j), between v(in-1, j) and v(in, j); walls carry none
        auto fx = [&](PetscInt in) {
          if (b.wall_u(in)) return 0.0;
          const double m = 0.5 * (Mx(in, j - 1) + Mx(in, j));
          const bool m2 = b.has_cell_x(in - 2), p1 = b.has_cell_x(in + 1);
          return side(m, m2 ? q[j][in - 2].v : 0.0, q[j][in - 1].v, q[j][in].v,
                      p1 ? q[j][in + 1].v : 0.0, m2, p1, rb_v(in - 1, j), rb_v(in, j));
        };
        // y-sides at the centres of cells j-1 and j, between v-faces c and c+1
        auto fy = [&](PetscInt c) {
          const double m = 0.5 * (My(i, c) + My(i, c + 1));
          return side(m, c >= 1 ? q[c - 1][i].v : 0.0, q[c][i].v, q[c + 1][i].v,
                      c + 2 <= ny ? q[c + 2][i].v : 0.0, c >= 1, c + 2 <= ny, rb_v(i, c),
                      rb_v(i, c + 1));
        };
        const double flux = fx(i + 1) - fx(i) + fy(j) - fy(j - 1);
        const double Df = 0.5 * (D(i, j - 1) + D(i, j));
        const double ra = 0.5 * (rho(c_a[j - 1][i]) + rho(c_a[j][i]));
        const double rb = 0.5 * (rho(c_b[j - 1][i]) + rho(c_b[j][i]));
        out[j][i].v = (ra * q[j][i].v - flux + Df * q[j][i].v) / rb;
      }
    }
}

void divergence(const Box& b, const Vel* const* vel, PetscScalar** div) {
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      div[j][i] = (vel[j][i + 1].u - vel[j][i].u) / b.hx + (vel[j + 1][i].v - vel[j][i].v) / b.hy;
}

void set_pressure_level(const Grid& g, Vec p) {
  const Box& b = g.box();
  double top_sum = 0;
  {
    const PetscScalar** pa;
    GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), p, &pa));
    if (b.ye() == b.ny)
      for (PetscInt i = b.xs; i < b.xe(); ++i)
        top_sum += 1.5 * pa[b.ny - 1][i] - 0.5 * pa[b.ny - 2][i];
    GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), p, &pa));
  }
  GF_PETSC(VecShift(p, -g.sum(top_sum) / b.nx));
}

}  // namespace gf::ops
