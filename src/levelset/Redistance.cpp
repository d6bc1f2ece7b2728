// Redistancing of the level set (section 3.1, ref [42]: C. Min, "On reinitializing level set
// functions", J. Comput. Phys. 229 (2010) 2764-2772). The level set is brought back to a signed
// distance by marching to steady state the Hamilton-Jacobi equation
//   (R1)  d(phi)/dtau + sgn(phi0) (|grad phi| - 1) = 0,  phi(tau = 0) = phi0,
// whose steady states are distance functions sharing phi0's zero level. Discretisation:
//   (R2)  Godunov Hamiltonian: for sgn > 0, |phi_x|^2 = max((a^+)^2, (b^-)^2), and for sgn < 0,
//         |phi_x|^2 = max((a^-)^2, (b^+)^2), with a = D-x phi, b = D+x phi (same in y);
//   (R3)  ENO2 one-sided differences
//         D+x phi_i = (phi_{i+1} - phi_i)/h - h/2 minmod(Dxx phi_i, Dxx phi_{i+1}),
//         D-x phi_i = (phi_i - phi_{i-1})/h + h/2 minmod(Dxx phi_i, Dxx phi_{i-1});
//   (R4)  subcell fix: where phi0_i phi0_{i+1} < 0 the interface lies at distance dx+ from x_i,
//         found as the root of the quadratic ENO interpolant of phi0 (linear if its second
//         difference vanishes), and
//         D+x phi_i = (0 - phi_i)/dx+ - dx+/2 minmod(Dxx phi_i, Dxx phi_{i+1})
//         (mirror for D-x), so that phi is pinned to 0 at the interface found from phi0;
//   (R5)  TVD-RK2 (Heun) in pseudo time. Because dx+ may be much smaller than h, the pseudo-time
//         step is local, dtau_ij = cfl min(h, dx+-, dy+-): only the steady state matters and (R4)
//         is a relaxation with rate 1/dx+ that an explicit step must resolve.
// Walls (no ghost points): a one-sided difference that would need a cell outside the domain is
// dropped from (R2) (no information enters through a wall: the distance to an interface inside a
// convex domain is carried by characteristics that leave through the walls), and the ENO
// correction in (R3) is dropped (first order) when one of its second differences would need such
// a cell. That is wrong next to a contact line where the interface meets the wall at a shallow
// angle (the toe of a pile, the front of a deposit): the distance of a wall-row cell to the
// interface is then carried by characteristics that come through the wall, and without them the
// cell gets its distance along the wall instead (1/sin(15 deg) = 3.9 times too large at a 15 deg
// toe), which lowers its granular mass at every redistancing. With set_wall_extrapolation(true)
// phi is continued linearly beyond the wall (two virtual cells, line_at): the interface continues
// through the wall at its contact angle, the subcell fix (R4) finds it there, and the ENO
// correction vanishes on the virtual cells (their second differences are zero). A periodic x
// direction has no walls: the stencils read the wrapped ghosts.
#include <algorithm>
#include <cmath>

#include "core/Error.hpp"
#include "levelset/GhostGuard.hpp"
#include "levelset/LevelSet.hpp"

namespace gf::levelset {

namespace {

inline double minmod(double a, double b) {
  if (a * b <= 0) return 0.0;
  return std::abs(a) < std::abs(b) ? a : b;
}

// A grid line as the redistancing stencils see it: detail::Line's cells, plus (extrap) up to two
// virtual cells beyond each wall holding the linear extrapolation of phi (line_at).
struct Line {
  PetscInt n;
  bool periodic;
  bool extrap;
  bool has(PetscInt k) const {
    return periodic || (k >= 0 && k < n) || (extrap && k >= -2 && k < n + 2);
  }
};
inline Line x_line(const Box& b, bool extrap) { return {b.nx, b.periodic_x, extrap}; }
inline Line y_line(const Box& b, bool extrap) { return {b.ny, false, extrap}; }

// phi at cell m of a line whose in-domain values are f(0 .. n-1): beyond a wall, the straight
// line through the two cells next to it. An interface that meets the wall at an angle then
// continues through it at the same angle, so the cells next to a contact line keep their
// distance to it (the wall rows see the interface below them); only read where Line::has allows.
template <class F>
inline double line_at(const F& f, PetscInt m, const Line& L) {
  if (L.periodic || (m >= 0 && m < L.n)) return f(m);
  if (m < 0) return f(0) + static_cast<double>(m) * (f(1) - f(0));
  return f(L.n - 1) + static_cast<double>(m - L.n + 1) * (f(L.n - 1) - f(L.n - 2));
}

// Undivided second difference of the line at cell k, if its three cells are in the domain.
template <class At>
inline bool d2(const At& at, PetscInt k, const Line& n, double& out) {
  if (!n.has(k - 1) || !n.has(k + 1)) return false;
  out = at(k - 1) - 2 * at(k) + at(k + 1);
  return true;
}

// (R4) ENO minmod of the second differences at cells k1, k2; 0 (first order) near walls.
template <class At>
inline double eno_d2(const At& at, PetscInt k1, PetscInt k2, const Line& n) {
  double a, b;
  if (!d2(at, k1, n, a) || !d2(at, k2, n, b)) return 0.0;
  return minmod(a, b);
}

// Distance (m) from cell c to the interface towards its neighbour c + dir, given that phi0
// changes sign between them: the root in (0, 1) of the quadratic ENO interpolant
//   p(s) = p_c + (p_n - p_c) s + (D/2) s (s - 1),  D = minmod(Dxx phi0_c, Dxx phi0_n),
// in units of h (Min 2010, sec. 3); linear interpolation where D vanishes or is unavailable.
template <class At>
inline double interface_distance(const At& at, PetscInt c, int dir, const Line& n, double h) {
  const double pc = at(c), pn = at(c + dir);
  const double D = eno_d2(at, c, c + dir, n);
  double s = pc / (pc - pn);  // linear
  const double A = 0.5 * D, B = pn - pc - 0.5 * D, C = pc;
  if (std::abs(A) > 1e-10 * (std::abs(pc) + std::abs(pn))) {
    const double disc = std::max(B * B - 4 * A * C, 0.0);
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    // p(0) p(1) < 0, so exactly one root lies in (0, 1); take the candidate closest to it.
    const double r1 = q / A, r2 = q != 0 ? C / q : r1;
    auto off = [](double r) { return r < 0 ? -r : (r > 1 ? r - 1 : 0.0); };
    s = off(r1) <= off(r2) ? r1 : r2;
  }
  s = std::clamp(s, 1e-12, 1.0);
  return s * h;
}

// Index of owned cell (i, j) in the per-cell arrays.
inline std::size_t cell_index(const Box& b, PetscInt i, PetscInt j) {
  return static_cast<std::size_t>((j - b.ys) * b.xm + (i - b.xs));
}

// One direction's contribution |phi_x|^2 to (R2), with (R3)/(R4). at(k): phi along the line,
// c: the cell, dm/dp: subcell distances towards c-1 / c+1 (< 0: no interface that way).
template <class At>
inline double godunov_1d(const At& at, PetscInt c, const Line& n, double h, double dm, double dp,
                         double sgn) {
  const double pc = at(c);
  double term = 0;
  if (n.has(c - 1)) {  // a = D-x phi_c
    const double m = eno_d2(at, c, c - 1, n);
    const double a = dm > 0 ? pc / dm + 0.5 * dm * m / (h * h) : (pc - at(c - 1) + 0.5 * m) / h;
    const double up = sgn > 0 ? std::max(a, 0.0) : std::min(a, 0.0);
    term = std::max(term, up * up);
  }
  if (n.has(c + 1)) {  // b = D+x phi_c
    const double m = eno_d2(at, c, c + 1, n);
    const double bb = dp > 0 ? -pc / dp - 0.5 * dp * m / (h * h) : (at(c + 1) - pc - 0.5 * m) / h;
    const double up = sgn > 0 ? std::min(bb, 0.0) : std::max(bb, 0.0);
    term = std::max(term, up * up);
  }
  return term;
}

}  // namespace

Redistancer::Redistancer(const Grid& g, int iterations, double cfl)
    : g_(g), iters_(iterations), cfl_(cfl) {
  if (iterations < 0) throw InputError("redistancing: iterations must be >= 0");
  if (!(cfl > 0 && cfl <= 1)) throw InputError("redistancing: cfl must be in (0, 1]");
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &loc_));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &stage_));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &rhs_));
  detail::poison_outside_ghosts(g.dm_cell(), loc_, g.box());
  const std::size_t n = static_cast<std::size_t>(g.box().xm * g.box().ym);
  for (auto* v : {&sgn_, &dtau_, &dxm_, &dxp_, &dym_, &dyp_}) v->assign(n, 0.0);
}

Redistancer::~Redistancer() {
  VecDestroy(&rhs_);
  VecDestroy(&stage_);
  VecDestroy(&loc_);
}

const PetscScalar* const* Redistancer::ghosted(Vec phi) {
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), phi, INSERT_VALUES, loc_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), phi, INSERT_VALUES, loc_));
  const PetscScalar* const* p;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), loc_, &p));
  return p;
}

void Redistancer::prepare(Vec phi0) {
  const Box& b = g_.box();
  const PetscScalar* const* p = ghosted(phi0);
  const double h = std::min(b.hx, b.hy);
  const Line lx = x_line(b, wall_extrap_), ly = y_line(b, wall_extrap_);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const std::size_t k = cell_index(b, i, j);
      const double pc = p[j][i];
      sgn_[k] = pc > 0 ? 1.0 : (pc < 0 ? -1.0 : 0.0);
      auto atx = [&](PetscInt m) { return line_at([&](PetscInt q) { return p[j][q]; }, m, lx); };
      auto aty = [&](PetscInt m) { return line_at([&](PetscInt q) { return p[q][i]; }, m, ly); };
      // Distance to the interface towards neighbour c + dir of a line, if phi0 changes sign.
      auto dist = [&](const auto& at, const Line& L, PetscInt c, int dir, double hh) {
        return L.has(c + dir) && pc * at(c + dir) < 0 ? interface_distance(at, c, dir, L, hh) : -1;
      };
      dxm_[k] = dist(atx, lx, i, -1, b.hx);
      dxp_[k] = dist(atx, lx, i, 1, b.hx);
      dym_[k] = dist(aty, ly, j, -1, b.hy);
      dyp_[k] = dist(aty, ly, j, 1, b.hy);
      double hl = h;
      for (double d : {dxm_[k], dxp_[k], dym_[k], dyp_[k]})
        if (d > 0) hl = std::min(hl, d);
      dtau_[k] = cfl_ * hl;
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), loc_, &p));
}

void Redistancer::eval_rhs(Vec phi) {
  const Box& b = g_.box();
  const PetscScalar* const* p = ghosted(phi);
  PetscScalar** r;
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), rhs_, &r));
  const Line lx = x_line(b, wall_extrap_), ly = y_line(b, wall_extrap_);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const std::size_t k = cell_index(b, i, j);
      const double s = sgn_[k];
      if (s == 0) {  // a node exactly on the interface stays there
        r[j][i] = 0;
        continue;
      }
      auto atx = [&](PetscInt m) { return line_at([&](PetscInt q) { return p[j][q]; }, m, lx); };
      auto aty = [&](PetscInt m) { return line_at([&](PetscInt q) { return p[q][i]; }, m, ly); };
      const double gx = godunov_1d(atx, i, lx, b.hx, dxm_[k], dxp_[k], s);
      const double gy = godunov_1d(aty, j, ly, b.hy, dym_[k], dyp_[k], s);
      r[j][i] = -dtau_[k] * s * (std::sqrt(gx + gy) - 1.0);  // (R1) times the local step
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), rhs_, &r));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), loc_, &p));
}

double Redistancer::distance_defect(Vec phi) {
  const Box& b = g_.box();
  const PetscScalar* const* p = ghosted(phi);
  const double band = 3 * std::max(b.hx, b.hy);
  const Line lx = x_line(b, false), ly = y_line(b, false);
  double worst = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (std::abs(p[j][i]) >= band) continue;
      const bool xm = lx.has(i - 1), xp = lx.has(i + 1), ym = ly.has(j - 1), yp = ly.has(j + 1);
      const double gx = (p[j][xp ? i + 1 : i] - p[j][xm ? i - 1 : i]) / ((xp + xm) * b.hx);
      const double gy = (p[yp ? j + 1 : j][i] - p[ym ? j - 1 : j][i]) / ((yp + ym) * b.hy);
      worst = std::max(worst, std::abs(std::hypot(gx, gy) - 1.0));
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), loc_, &p));
  return g_.max(worst);
}

int Redistancer::run(Vec phi) {
  prepare(phi);
  last_iters_ = 0;
  for (int it = 0; it < iters_; ++it) {
    // (R5) Heun: phi1 = phi + dtau L(phi); phi2 = phi1 + dtau L(phi1); phi <- (phi + phi2)/2.
    eval_rhs(phi);
    GF_PETSC(VecWAXPY(stage_, 1.0, rhs_, phi));
    eval_rhs(stage_);
    GF_PETSC(VecAXPY(stage_, 1.0, rhs_));
    GF_PETSC(VecAXPY(stage_, -1.0, phi));  // phi2 - phi
    GF_PETSC(VecAXPY(phi, 0.5, stage_));
    ++last_iters_;
    if (tol_ > 0) {  // max change over the band |phi| < band_ (what the properties see)
      const double band = band_ > 0 ? band_ : 3 * std::max(g_.hx(), g_.hy());
      const PetscScalar *p, *d;
      PetscInt n;
      GF_PETSC(VecGetLocalSize(phi, &n));
      GF_PETSC(VecGetArrayRead(phi, &p));
      GF_PETSC(VecGetArrayRead(stage_, &d));
      double change = 0;
      for (PetscInt k = 0; k < n; ++k)
        if (std::abs(p[k]) < band) change = std::max(change, 0.5 * std::abs(d[k]));
      GF_PETSC(VecRestoreArrayRead(stage_, &d));
      GF_PETSC(VecRestoreArrayRead(phi, &p));
      if (g_.max(change) < tol_) break;
    }
  }
  return last_iters_;
}

}  // namespace gf::levelset
