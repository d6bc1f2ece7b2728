// Transport of the level set, eq. 26: d(phi)/dt + div(u phi) = 0, written in conservative form
// as the paper asks ("nonlinear terms are written in conservative form in level-set and momentum
// equations"), discretised by finite volumes with WENO5 face values (refs [39, 40]) and the
// TVD-RK3 scheme of Shu & Osher (ref [41]).
#include <algorithm>
#include <cmath>

#include "core/Error.hpp"
#include "levelset/GhostGuard.hpp"
#include "levelset/LevelSet.hpp"

namespace gf::levelset {

namespace {

// Jiang & Shu (1996) regularisation of the smoothness indicators. The indicators are computed on
// phi in metres, so eps carries the units of phi^2; taking eps = 1e-6 h^2 makes the weights the
// same as those of the classical eps = 1e-6 applied to phi measured in cells (phi / h), i.e. the
// scheme is invariant under a change of length unit or of grid size for a distance function.
constexpr double kWenoEps = 1e-6;

// Upwind WENO5 value at the right edge of cell 3 of (v1 .. v5) = phi at cells c-2 .. c+2, where
// the face lies between c and c+1 and the flow goes from c to c+1 (Jiang & Shu 1996, eqs. 2.8-2.10
// and 3.2-3.4): three quadratic candidates, nonlinear weights from the smoothness indicators.
inline double weno5(double v1, double v2, double v3, double v4, double v5, double eps) {
  const double q0 = (2 * v1 - 7 * v2 + 11 * v3) / 6;
  const double q1 = (-v2 + 5 * v3 + 2 * v4) / 6;
  const double q2 = (2 * v3 + 5 * v4 - v5) / 6;
  const double s0 = 13.0 / 12 * (v1 - 2 * v2 + v3) * (v1 - 2 * v2 + v3) +
                    0.25 * (v1 - 4 * v2 + 3 * v3) * (v1 - 4 * v2 + 3 * v3);
  const double s1 = 13.0 / 12 * (v2 - 2 * v3 + v4) * (v2 - 2 * v3 + v4) +
                    0.25 * (v2 - v4) * (v2 - v4);
  const double s2 = 13.0 / 12 * (v3 - 2 * v4 + v5) * (v3 - 2 * v4 + v5) +
                    0.25 * (3 * v3 - 4 * v4 + v5) * (3 * v3 - 4 * v4 + v5);
  const double a0 = 0.1 / ((eps + s0) * (eps + s0));
  const double a1 = 0.6 / ((eps + s1) * (eps + s1));
  const double a2 = 0.3 / ((eps + s2) * (eps + s2));
  return (a0 * q0 + a1 * q1 + a2 * q2) / (a0 + a1 + a2);
}

// Upwind WENO3 value at the right edge of cell c from (v1, v2, v3) = phi at c-1, c, c+1: two
// linear candidates (the ENO2 stencils) with ideal weights 1/3, 2/3 (Jiang & Shu 1996, sec. 2).
inline double weno3(double v1, double v2, double v3, double eps) {
  const double q0 = -0.5 * v1 + 1.5 * v2;
  const double q1 = 0.5 * v2 + 0.5 * v3;
  const double s0 = (v2 - v1) * (v2 - v1);
  const double s1 = (v3 - v2) * (v3 - v2);
  const double a0 = (1.0 / 3) / ((eps + s0) * (eps + s0));
  const double a1 = (2.0 / 3) / ((eps + s1) * (eps + s1));
  return (a0 * q0 + a1 * q1) / (a0 + a1);
}

// Face value for the interior face f (between cells f-1 and f, 1 <= f <= n-1, or any f on a
// periodic line) of a grid line of n cells, upwind for the velocity sign. at(k) reads phi at cell
// k of the line (0 <= k < n only, or the wrapped ghosts of a periodic line).
// The stencil is the largest of WENO5 / WENO3 / first-order upwind whose cells all lie inside
// the domain: the downwind cell always exists for an interior face, so WENO3 needs one more cell
// upstream and WENO5 two more upstream and one more downstream. First-order upwind is used only
// at the face next to a wall when the flow leaves that wall (no second upstream cell), where the
// normal velocity is itself O(h) (u.n = 0 on the wall), so the flux error there is O(h^2).
template <class At>
inline double face_value(PetscInt f, const detail::Line& L, double vel, double eps, const At& at) {
  if (vel > 0) {  // upwind cell c = f - 1, flow towards +
    const PetscInt c = f - 1;
    if (L.has(c - 2) && L.has(c + 2)) return weno5(at(c - 2), at(c - 1), at(c), at(c + 1), at(c + 2), eps);
    if (L.has(c - 1)) return weno3(at(c - 1), at(c), at(c + 1), eps);
    return at(c);
  }
  const PetscInt c = f;  // upwind cell c = f, flow towards -: the mirror image
  if (L.has(c + 2) && L.has(c - 2)) return weno5(at(c + 2), at(c + 1), at(c), at(c - 1), at(c - 2), eps);
  if (L.has(c + 1)) return weno3(at(c + 1), at(c), at(c - 1), eps);
  return at(c);
}

}  // namespace

void weno5_rhs(const Box& b, const PetscScalar* const* phi, const Vel* const* vel,
               PetscScalar** rhs) {
  const double epsx = kWenoEps * b.hx * b.hx, epsy = kWenoEps * b.hy * b.hy;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) rhs[j][i] = 0.0;

  // x-faces: face f is the left face of cell f. Each face flux F is computed once and given to
  // both neighbours, -(F_{i+1} - F_i)/hx, in the same order (left face first) on every rank so
  // that results do not depend on the parallel layout. Faces f = 0 and f = nx are walls, or,
  // with periodic x, the same interior face (computed from the wrapped ghosts by both owners).
  const detail::Line lx = detail::x_line(b), ly = detail::y_line(b);
  const PetscInt f0 = b.periodic_x ? b.xs : std::max<PetscInt>(b.xs, 1);
  const PetscInt f1 = b.periodic_x ? b.xe() : std::min(b.xe(), b.nx - 1);
  for (PetscInt j = b.ys; j < b.ye(); ++j) {
    const PetscScalar* row = phi[j];
    auto at = [row](PetscInt k) { return row[k]; };
    for (PetscInt f = f0; f <= f1; ++f) {
      const double u = vel[j][f].u;
      if (u == 0.0) continue;
      const double F = u * face_value(f, lx, u, epsx, at) / b.hx;
      if (f < b.xe()) rhs[j][f] += F;       // inflow through the left face of cell f
      if (f - 1 >= b.xs) rhs[j][f - 1] -= F;  // outflow through the right face of cell f-1
    }
  }
  // y-faces: face f is the bottom face of cell (i, f); faces 0 and ny are walls.
  for (PetscInt i = b.xs; i < b.xe(); ++i) {
    auto at = [phi, i](PetscInt k) { return phi[k][i]; };
    for (PetscInt f = std::max<PetscInt>(b.ys, 1); f <= std::min(b.ye(), b.ny - 1); ++f) {
      const double v = vel[f][i].v;
      if (v == 0.0) continue;
      const double G = v * face_value(f, ly, v, epsy, at) / b.hy;
      if (f < b.ye()) rhs[f][i] += G;
      if (f - 1 >= b.ys) rhs[f - 1][i] -= G;
    }
  }
}

// ---------------------------------------------------------------------------------------------

Advector::Advector(const Grid& g) : g_(g) {
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &phi_loc_));
  GF_PETSC(DMCreateLocalVector(g.dm_vel(), &vel_loc_));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &stage_));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &rhs_));
  detail::poison_outside_ghosts(g.dm_cell(), phi_loc_, g.box());
}

Advector::~Advector() {
  VecDestroy(&rhs_);
  VecDestroy(&stage_);
  VecDestroy(&vel_loc_);
  VecDestroy(&phi_loc_);
}

void Advector::eval_rhs(Vec phi) {
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), phi, INSERT_VALUES, phi_loc_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), phi, INSERT_VALUES, phi_loc_));
  const PetscScalar* const* p;
  const Vel* const* v;
  PetscScalar** r;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), phi_loc_, &p));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), vel_loc_, &v));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), rhs_, &r));
  weno5_rhs(g_.box(), p, v, r);
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), rhs_, &r));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), vel_loc_, &v));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), phi_loc_, &p));
}

void Advector::step(Vec phi, Vec vel, double dt) {
  // The face velocity is frozen over the step (the paper advects phi^n with u^n, section 3.3);
  // its ghost faces i = nx, j = ny are the walls.
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_vel(), vel, INSERT_VALUES, vel_loc_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_vel(), vel, INSERT_VALUES, vel_loc_));
  Vel** va;
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), vel_loc_, &va));
  fill_velocity_ghosts(g_, va);
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), vel_loc_, &va));

  // Shu & Osher (1988) TVD-RK3 with L = -div(u .):
  //   phi1 = phi + dt L(phi)
  //   phi2 = 3/4 phi + 1/4 (phi1 + dt L(phi1))
  //   phi  = 1/3 phi + 2/3 (phi2 + dt L(phi2))
  eval_rhs(phi);
  GF_PETSC(VecWAXPY(stage_, dt, rhs_, phi));     // stage_ = phi1
  eval_rhs(stage_);
  GF_PETSC(VecAXPY(stage_, dt, rhs_));            // phi1 + dt L(phi1)
  GF_PETSC(VecAXPBY(stage_, 0.75, 0.25, phi));    // stage_ = phi2
  eval_rhs(stage_);
  GF_PETSC(VecAXPY(stage_, dt, rhs_));            // phi2 + dt L(phi2)
  GF_PETSC(VecAXPBY(phi, 2.0 / 3, 1.0 / 3, stage_));
}

double max_cfl_dt(const Grid& g, Vec vel, double cfl) {
  const Box& b = g.box();
  Vec loc;
  GF_PETSC(DMGetLocalVector(g.dm_vel(), &loc));
  GF_PETSC(DMGlobalToLocalBegin(g.dm_vel(), vel, INSERT_VALUES, loc));
  GF_PETSC(DMGlobalToLocalEnd(g.dm_vel(), vel, INSERT_VALUES, loc));
  Vel** v;
  GF_PETSC(DMDAVecGetArray(g.dm_vel(), loc, &v));
  fill_velocity_ghosts(g, v);
  // Per cell: the larger of its two faces in each direction (the RK3/WENO5 stability bound of a
  // 2D upwind scheme is on the sum of the directional Courant numbers).
  double rate = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double u = std::max(std::abs(v[j][i].u), std::abs(v[j][i + 1].u));
      const double w = std::max(std::abs(v[j][i].v), std::abs(v[j + 1][i].v));
      rate = std::max(rate, u / b.hx + w / b.hy);
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_vel(), loc, &v));
  GF_PETSC(DMRestoreLocalVector(g.dm_vel(), &loc));
  rate = g.max(rate);
  return rate > 0 ? cfl / rate : 1e300;
}

}  // namespace gf::levelset
