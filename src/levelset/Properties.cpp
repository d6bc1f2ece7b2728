// Phase properties derived from the level set (section 3.1) and level-set diagnostics.
//  * density, eq. 25: rho = rho_air H_eps(phi) + rho_gran (1 - H_eps(phi)) at cell centres;
//  * viscosity: harmonic mean weighted by the height fraction
//      theta(x) = int_K(x) phi^+ / int_K(x) |phi|,  |K(x)| ~ h,
//    which is 1 where K lies in the air and 0 where it lies in the granular phase.
// The integrals over K use phi bilinearly interpolated between cell centres. A bilinear function
// on a rectangle takes its extreme values at the corners, so on every piece of K covered by one
// bilinear patch the sign can be decided exactly from four values: single-signed pieces are
// integrated exactly (mean of the corners times the area), and only pieces cut by the zero level
// are sub-sampled.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/Error.hpp"
#include "grid/Local.hpp"
#include "levelset/Heaviside.hpp"
#include "levelset/LevelSet.hpp"

namespace gf::levelset {

namespace {

constexpr int kThetaSamples = 8;  // midpoint samples per direction and per cut patch (theta)
constexpr int kL1Samples = 16;    // same for the interface error

// The bilinear interpolant of cell-centre values on the patch whose lower-left centre is
// (i0, j0). In the half cells along a wall the patch is the nearest in-domain one, i.e. phi is
// linearly extrapolated from in-domain centres (no ghost cell outside the domain is read). With
// periodic x there is no wall in x: the patch may start at cell -1 or end at cell nx (the wrapped
// ghosts), and x may lie outside [0, Lx] by up to half a cell (the dual cell of node 0).
struct Patch {
  const Box* b;
  PetscInt i0, j0;
  double f00, f10, f01, f11;

  Patch(const Box& box, const PetscScalar* const* p, double x, double y) : b(&box) {
    const auto ix = static_cast<PetscInt>(std::floor(x / box.hx - 0.5));
    i0 = box.periodic_x ? ix : std::clamp<PetscInt>(ix, 0, box.nx - 2);
    j0 = std::clamp<PetscInt>(static_cast<PetscInt>(std::floor(y / box.hy - 0.5)), 0, box.ny - 2);
    f00 = p[j0][i0];
    f10 = p[j0][i0 + 1];
    f01 = p[j0 + 1][i0];
    f11 = p[j0 + 1][i0 + 1];
  }
  double operator()(double x, double y) const {
    const double tx = x / b->hx - 0.5 - i0, ty = y / b->hy - 0.5 - j0;
    return (1 - tx) * ((1 - ty) * f00 + ty * f01) + tx * ((1 - ty) * f10 + ty * f11);
  }
};

// Calls f(xa, xb, ya, yb) for the pieces of [x0, x1] x [y0, y1] cut by the lines through cell
// centres, so that each piece lies in a single bilinear patch.
template <class F>
void for_each_piece(const Box& b, double x0, double x1, double y0, double y1, const F& f) {
  double xs[4], ys[4];
  int nxp = 0, nyp = 0;
  xs[nxp++] = x0;
  for (PetscInt k = static_cast<PetscInt>(std::floor(x0 / b.hx - 0.5)) + 1; b.xc(k) < x1; ++k)
    if (b.xc(k) > x0 && nxp < 3) xs[nxp++] = b.xc(k);
  xs[nxp++] = x1;
  ys[nyp++] = y0;
  for (PetscInt k = static_cast<PetscInt>(std::floor(y0 / b.hy - 0.5)) + 1; b.yc(k) < y1; ++k)
    if (b.yc(k) > y0 && nyp < 3) ys[nyp++] = b.yc(k);
  ys[nyp++] = y1;
  for (int q = 0; q + 1 < nyp; ++q)
    for (int r = 0; r + 1 < nxp; ++r) f(xs[r], xs[r + 1], ys[q], ys[q + 1]);
}

// theta over a rectangle of the domain: returns int phi^+ / int |phi|.
double theta_rect(const Box& b, const PetscScalar* const* p, double x0, double x1, double y0,
                  double y1) {
  double pos = 0, abs = 0;
  for_each_piece(b, x0, x1, y0, y1, [&](double xa, double xb, double ya, double yb) {
    const Patch P(b, p, 0.5 * (xa + xb), 0.5 * (ya + yb));
    const double c[4] = {P(xa, ya), P(xb, ya), P(xa, yb), P(xb, yb)};
    const double area = (xb - xa) * (yb - ya);
    const double lo = std::min({c[0], c[1], c[2], c[3]}), hi = std::max({c[0], c[1], c[2], c[3]});
    if (lo >= 0 || hi <= 0) {  // one sign: the exact integral of a bilinear function
      const double mean = 0.25 * (c[0] + c[1] + c[2] + c[3]);
      pos += area * std::max(mean, 0.0);
      abs += area * std::abs(mean);
      return;
    }
    const int M = kThetaSamples;
    const double dx = (xb - xa) / M, dy = (yb - ya) / M, dA = dx * dy;
    for (int q = 0; q < M; ++q)
      for (int r = 0; r < M; ++r) {
        const double v = P(xa + (r + 0.5) * dx, ya + (q + 0.5) * dy);
        pos += dA * std::max(v, 0.0);
        abs += dA * std::abs(v);
      }
  });
  return abs > 0 ? pos / abs : 0.5;  // phi == 0 on all of K: the interface itself
}

}  // namespace

double height_fraction_cell(const Box& b, const PetscScalar* const* phi_local, PetscInt i,
                            PetscInt j) {
  return theta_rect(b, phi_local, b.xf(i), b.xf(i + 1), b.yf(j), b.yf(j + 1));
}

double height_fraction_node(const Box& b, const PetscScalar* const* phi_local, PetscInt i,
                            PetscInt j) {
  // The dual cell [x_i - hx/2, x_i + hx/2] x [...] around the node, clipped to the domain (not
  // in a periodic x: the node 0 is interior, its dual cell straddles the wrapped seam).
  const double x0 = b.periodic_x ? (i - 0.5) * b.hx : std::max(0.0, (i - 0.5) * b.hx);
  const double x1 = b.periodic_x ? (i + 0.5) * b.hx : std::min(b.Lx, (i + 0.5) * b.hx);
  const double y0 = std::max(0.0, (j - 0.5) * b.hy), y1 = std::min(b.Ly, (j + 0.5) * b.hy);
  return theta_rect(b, phi_local, x0, x1, y0, y1);
}

double harmonic_viscosity(double theta, double eta_air, double eta_gran) {
  // Section 3.1 with the air fraction theta: 1/eta = theta/eta_air + (1 - theta)/eta_gran.
  // (The paper's printed 1/eta = theta/eta_s + (1 - theta)/eta_f swaps the phases with respect
  // to its own definition of theta as the phi^+ = air fraction; see LevelSet.hpp.)
  return 1.0 / (theta / eta_air + (1.0 - theta) / eta_gran);
}

void update_properties(const Grid& g, Vec phi, const Props& pr, Vec rho, Vec eta, Vec eta_node) {
  const Box& b = g.box();
  const LocalCells p(g.dm_cell(), phi);
  PetscScalar **r, **e;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta, &e));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      r[j][i] = density(p[j][i], pr.eps, pr.rho_air, pr.rho_gran);  // eq. 25
      e[j][i] = harmonic_viscosity(height_fraction_cell(b, p.array(), i, j), pr.eta_air,
                                   pr.eta_gran);
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta, &e));
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), rho, &r));
  if (!eta_node) return;
  // Shear stresses live at the nodes: their viscosity is the harmonic mean with the height
  // fraction of the dual cell around the node (section 3.1).
  PetscScalar** en;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta_node, &en));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      en[j][i] = harmonic_viscosity(height_fraction_node(b, p.array(), i, j), pr.eta_air,
                                    pr.eta_gran);
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta_node, &en));
}

void mix_viscosity(const Grid& g, Vec phi, double eta_air, Vec eta_gran, Vec eta, Vec eta_node) {
  const Box& b = g.box();
  const LocalCells es(g.dm_cell(), eta_gran);
  std::optional<LocalCells> ph;
  if (phi) ph.emplace(g.dm_cell(), phi);
  PetscScalar **ec, **en;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta, &ec));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta_node, &en));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double thc = ph ? height_fraction_cell(b, ph->array(), i, j) : 0.0;
      ec[j][i] = harmonic_viscosity(thc, eta_air, es[j][i]);
      if (!b.wall_u(i) && j >= 1) {  // interior node: mean of the four surrounding cells
        const double esn = 0.25 * (es[j][i] + es[j][i - 1] + es[j - 1][i] + es[j - 1][i - 1]);
        const double thn = ph ? height_fraction_node(b, ph->array(), i, j) : 0.0;
        en[j][i] = harmonic_viscosity(thn, eta_air, esn);
      }
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta_node, &en));
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta, &ec));
}

void granular_fraction(const Grid& g, Vec phi, double eps, Vec c) {
  const Box& b = g.box();
  const PetscScalar** ph;
  PetscScalar** ca;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), phi, &ph));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), c, &ca));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) ca[j][i] = 1.0 - heaviside(ph[j][i], eps);
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), c, &ca));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), phi, &ph));
}

void yield_support(const Grid& g, Vec phi, double support, Vec w) {
  const Box& b = g.box();
  const PetscScalar** ph;
  PetscScalar** wa;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), phi, &ph));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), w, &wa));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double p = ph[j][i];
      wa[j][i] = p < support ? (support > 0 ? 1.0 - heaviside(p, support) : 1.0) : -1.0;
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), w, &wa));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), phi, &ph));
}

double granular_area(const Grid& g, Vec phi, double eps) {
  const Box& b = g.box();
  const PetscScalar* const* p;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), phi, &p));
  double s = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) s += 1.0 - heaviside(p[j][i], eps);
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), phi, &p));
  return g.sum(s * b.hx * b.hy);
}

double interface_l1_error(const Grid& g, Vec phi, Vec phi_exact) {
  const Box& b = g.box();
  const LocalCells p(g.dm_cell(), phi), q(g.dm_cell(), phi_exact);
  double err = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      for_each_piece(b, b.xf(i), b.xf(i + 1), b.yf(j), b.yf(j + 1),
                     [&](double xa, double xb, double ya, double yb) {
        const double xm = 0.5 * (xa + xb), ym = 0.5 * (ya + yb);
        const Patch P(b, p.array(), xm, ym), Q(b, q.array(), xm, ym);
        const double cp[4] = {P(xa, ya), P(xb, ya), P(xa, yb), P(xb, yb)};
        const double cq[4] = {Q(xa, ya), Q(xb, ya), Q(xa, yb), Q(xb, yb)};
        const double p_lo = std::min({cp[0], cp[1], cp[2], cp[3]});
        const double p_hi = std::max({cp[0], cp[1], cp[2], cp[3]});
        const double q_lo = std::min({cq[0], cq[1], cq[2], cq[3]});
        const double q_hi = std::max({cq[0], cq[1], cq[2], cq[3]});
        const bool p_air = p_lo > 0, p_gran = p_hi <= 0, q_air = q_lo > 0, q_gran = q_hi <= 0;
        if ((p_air || p_gran) && (q_air || q_gran)) {  // H_0 constant on the piece for both
          if (p_air != q_air) err += (xb - xa) * (yb - ya);
          return;
        }
        const int M = kL1Samples;
        const double dx = (xb - xa) / M, dy = (yb - ya) / M;
        int differ = 0;
        for (int s = 0; s < M; ++s)
          for (int r = 0; r < M; ++r) {
            const double x = xa + (r + 0.5) * dx, y = ya + (s + 0.5) * dy;
            differ += (P(x, y) > 0) != (Q(x, y) > 0);
          }
        err += differ * dx * dy;
      });
  return g.sum(err);
}

}  // namespace gf::levelset
