// The conservative volume fraction (vof/Vof.hpp): PLIC reconstruction, the direction-split
// transport of Weymouth & Yue (2010), the CLSVOF distance rebuild of Sussman & Puckett (2000),
// the properties and supports from c.
#include "vof/Vof.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/Error.hpp"
#include "grid/Local.hpp"

namespace gf::vof {

namespace {

// f at (i + di, j + dj), or at (i, j) where that cell lies beyond a wall: the stencils of the
// normals drop to one side at a wall instead of reading a ghost outside the domain.
inline double at(const Box& b, const PetscScalar* const* f, PetscInt i, PetscInt j, int di,
                 int dj) {
  PetscInt ii = i + di, jj = j + dj;
  if (!b.has_cell_x(ii)) ii = i;
  if (jj < 0 || jj >= b.ny) jj = j;
  return f[jj][ii];
}

// Youngs' (1982) gradient of f in cell units (d f / dX, d f / dY): central differences over the
// 3 x 3 block, weights 1 2 1 across.
inline void youngs(const Box& b, const PetscScalar* const* f, PetscInt i, PetscInt j, double& gx,
                   double& gy) {
  auto v = [&](int di, int dj) { return at(b, f, i, j, di, dj); };
  gx = ((v(1, 1) + 2 * v(1, 0) + v(1, -1)) - (v(-1, 1) + 2 * v(-1, 0) + v(-1, -1))) / 8;
  gy = ((v(1, 1) + 2 * v(0, 1) + v(-1, 1)) - (v(1, -1) + 2 * v(0, -1) + v(-1, -1))) / 8;
}

inline double harmonic(double air_fraction, double eta_air, double eta_gran) {
  return 1.0 / (air_fraction / eta_air + (1.0 - air_fraction) / eta_gran);
}

// The mean c of the in-domain cells around node (i, j) (at (i hx, j hy)).
inline double node_fraction(const Box& b, const PetscScalar* const* c, PetscInt i, PetscInt j) {
  double s = 0;
  int n = 0;
  for (PetscInt jj = j - 1; jj <= j; ++jj)
    for (PetscInt ii = i - 1; ii <= i; ++ii)
      if (jj >= 0 && jj < b.ny && b.has_cell_x(ii)) {
        s += c[jj][ii];
        ++n;
      }
  return n ? s / n : 0.0;
}

}  // namespace

bool reconstruct(const Box& b, const PetscScalar* const* c, const PetscScalar* const* phi,
                 Normals src, PetscInt i, PetscInt j, Line& l) {
  const double cv = c[j][i];
  if (cv <= kCut || cv >= 1 - kCut) return false;
  double m1 = 0, m2 = 0;
  bool have = false;
  if (src == Normals::LevelSet && phi) {
    // grad phi points into the air, the direction of (m1, m2); in cell units d phi / dX = hx
    // d phi / dx. A distance function has |grad phi| = 1; where the level set is flat across
    // the cell (a sheet thinner than a cell, whose two sides phi cannot tell apart), the
    // fraction's own gradient takes over.
    youngs(b, phi, i, j, m1, m2);
    have = std::hypot(m1 / b.hx, m2 / b.hy) > 0.5;
  }
  if (!have) {
    youngs(b, c, i, j, m1, m2);
    m1 = -m1;
    m2 = -m2;
    have = std::abs(m1) + std::abs(m2) > 1e-12;
  }
  if (!have) {  // no direction at all (an isolated speck): a horizontal line, granular below
    m1 = 0;
    m2 = 1;
  }
  l = Line{m1, m2, line_alpha(m1, m2, cv)};
  return true;
}

// ---------------------------------------------------------------------------------------------
// Transport.

Advector::Advector(const Grid& g) : g_(g) {
  for (Vec* v : {&c0_, &cc_}) GF_PETSC(DMCreateGlobalVector(g.dm_cell(), v));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &flux_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lc_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lphi_));
  GF_PETSC(DMCreateLocalVector(g.dm_vel(), &lvel_));
  GF_PETSC(VecSet(flux_, 0.0));
}

Advector::~Advector() {
  for (Vec* v : {&c0_, &cc_, &flux_, &lc_, &lphi_, &lvel_}) VecDestroy(v);
}

void Advector::step(Vec c, Vec vel, Vec phi, double dt, long long step, Normals src) {
  GF_PETSC(VecCopy(c, c0_));
  // c_c of Weymouth & Yue: the step function of c^n, frozen over both sweeps, so that the
  // dilatation terms c_c (s_{i+1/2} - s_{i-1/2}) of the two sweeps sum to c_c dt div u = 0.
  {
    const PetscScalar* a;
    PetscScalar* h;
    PetscInt n;
    GF_PETSC(VecGetLocalSize(c, &n));
    GF_PETSC(VecGetArrayRead(c, &a));
    GF_PETSC(VecGetArray(cc_, &h));
    for (PetscInt k = 0; k < n; ++k) h[k] = a[k] > 0.5 ? 1.0 : 0.0;
    GF_PETSC(VecRestoreArray(cc_, &h));
    GF_PETSC(VecRestoreArrayRead(c, &a));
  }
  to_local(g_.dm_vel(), vel, lvel_);
  {
    Vel** lv;
    GF_PETSC(DMDAVecGetArray(g_.dm_vel(), lvel_, &lv));
    fill_velocity_ghosts(g_, lv);
    GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), lvel_, &lv));
  }
  if (phi) to_local(g_.dm_cell(), phi, lphi_);
  // Alternating order (x then y on even steps): the splitting error of one step is undone by
  // the next, as in Strang splitting (Weymouth & Yue 2010, section 2; Basilisk's vof.h).
  first_dir_ = static_cast<int>(step % 2);
  clipped_ = 0;
  sweep(first_dir_, c, dt, phi != nullptr, src);
  sweep(1 - first_dir_, c, dt, phi != nullptr, src);
  clipped_ = g_.max(clipped_);
}

void Advector::sweep(int dir, Vec c, double dt, bool have_phi, Normals src) {
  const Box& b = g_.box();
  to_local(g_.dm_cell(), c, lc_);
  const PetscScalar **lc, **lp = nullptr, **ccv;
  const Vel** lv;
  PetscScalar** ca;
  Vel** fl;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lc_, &lc));
  if (have_phi) GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lphi_, &lp));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), lvel_, &lv));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), cc_, &ccv));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), c, &ca));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), flux_, &fl));
  const double h = dir == 0 ? b.hx : b.hy;
  // The granular volume F (cell units) through a face in this sweep: the strip of width |s|
  // along the face in the upwind cell, cut out of that cell's PLIC interface.
  auto face_flux = [&](PetscInt di, PetscInt dj, double s) {
    // (di, dj): the upwind cell
    const double cd = lc[dj][di];
    if (cd <= kCut || cd >= 1 - kCut) return cd * s;
    Line l;
    reconstruct(b, lc, lp, src, di, dj, l);
    const double a = std::abs(s);
    double F;
    if (dir == 0)
      F = s > 0 ? rect_area(l, 1 - a, 1, 0, 1) : rect_area(l, 0, a, 0, 1);
    else
      F = s > 0 ? rect_area(l, 0, 1, 1 - a, 1) : rect_area(l, 0, 1, 0, a);
    return s > 0 ? F : -F;
  };
  if (dir == 0) {
    std::vector<double> F(b.xm + 1), S(b.xm + 1);
    for (PetscInt j = b.ys; j < b.ye(); ++j) {
      for (PetscInt i = b.xs; i <= b.xe(); ++i) {
        const std::size_t k = i - b.xs;
        if (b.wall_u(i)) {
          F[k] = S[k] = 0;
          continue;
        }
        const double s = lv[j][i].u * dt / h;
        S[k] = s;
        F[k] = s == 0 ? 0.0 : face_flux(s > 0 ? i - 1 : i, j, s);
      }
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const std::size_t k = i - b.xs;
        fl[j][i].u = F[k];
        const double v = lc[j][i] - (F[k + 1] - F[k]) + ccv[j][i] * (S[k + 1] - S[k]);
        const double vc = std::clamp(v, 0.0, 1.0);
        clipped_ = std::max(clipped_, std::abs(v - vc));
        ca[j][i] = vc;
      }
    }
  } else {
    std::vector<double> F(b.ym + 1), S(b.ym + 1);
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      for (PetscInt j = b.ys; j <= b.ye(); ++j) {
        const std::size_t k = j - b.ys;
        if (j == 0 || j == b.ny) {
          F[k] = S[k] = 0;
          continue;
        }
        const double s = lv[j][i].v * dt / h;
        S[k] = s;
        F[k] = s == 0 ? 0.0 : face_flux(i, s > 0 ? j - 1 : j, s);
      }
      for (PetscInt j = b.ys; j < b.ye(); ++j) {
        const std::size_t k = j - b.ys;
        fl[j][i].v = F[k];
        const double v = lc[j][i] - (F[k + 1] - F[k]) + ccv[j][i] * (S[k + 1] - S[k]);
        const double vc = std::clamp(v, 0.0, 1.0);
        clipped_ = std::max(clipped_, std::abs(v - vc));
        ca[j][i] = vc;
      }
    }
  }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), flux_, &fl));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), c, &ca));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), cc_, &ccv));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), lvel_, &lv));
  if (have_phi) GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lphi_, &lp));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lc_, &lc));
}

// ---------------------------------------------------------------------------------------------
// The distance rebuild.

void rebuild_distance(const Grid& g, Vec c, Vec phi, Normals src) {
  const Box& b = g.box();
  const DM dm = g.dm_cell();
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  // 1. The lines of the owned cut cells (alpha NaN: no line), then exchanged so that every
  //    cell sees the segments within kBand cells (the ghost width).
  Vec m1, m2, al;
  GF_PETSC(DMGetGlobalVector(dm, &m1));
  GF_PETSC(DMGetGlobalVector(dm, &m2));
  GF_PETSC(DMGetGlobalVector(dm, &al));
  {
    const LocalCells lc(dm, c), lp(dm, phi);
    PetscScalar **a1, **a2, **aa;
    GF_PETSC(DMDAVecGetArray(dm, m1, &a1));
    GF_PETSC(DMDAVecGetArray(dm, m2, &a2));
    GF_PETSC(DMDAVecGetArray(dm, al, &aa));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        Line l;
        if (reconstruct(b, lc.array(), lp.array(), src, i, j, l)) {
          a1[j][i] = l.m1;
          a2[j][i] = l.m2;
          aa[j][i] = l.alpha;
        } else {
          a1[j][i] = a2[j][i] = 0;
          aa[j][i] = kNone;
        }
      }
    GF_PETSC(DMDAVecRestoreArray(dm, al, &aa));
    GF_PETSC(DMDAVecRestoreArray(dm, m2, &a2));
    GF_PETSC(DMDAVecRestoreArray(dm, m1, &a1));
  }
  {
    const LocalCells A(dm, m1), B(dm, m2), C(dm, al), lc(dm, c);
    // 2. The segments of every cell of the ghosted range [xs - kBand, xe + kBand) x
    //    [ys - kBand, ye + kBand) (within the domain, or its periodic images in x): its PLIC
    //    segment, and its right and top faces where they separate a full cell from an empty one
    //    (a column aligned with the grid has no cut cell at all; walls are not interfaces).
    struct Segs {
      int n = 0;
      double x[3][4];
    };
    const PetscInt K = kBand, W = b.xm + 2 * K, H = b.ym + 2 * K;
    std::vector<Segs> segs(static_cast<std::size_t>(W * H));
    std::vector<char> mark(segs.size(), 0), near(segs.size(), 0), rowm(segs.size(), 0);
    auto at = [&](PetscInt i, PetscInt j) { return (j - b.ys + K) * W + (i - b.xs + K); };
    auto in_domain = [&](PetscInt i, PetscInt j) { return j >= 0 && j < b.ny && b.has_cell_x(i); };
    const PetscInt i0 = b.xs - K, i1 = b.xe() + K, j0 = b.ys - K, j1 = b.ye() + K;
    for (PetscInt jj = j0; jj < j1; ++jj)
      for (PetscInt ii = i0; ii < i1; ++ii) {
        if (!in_domain(ii, jj)) continue;
        Segs& sg = segs[at(ii, jj)];
        const double x0 = b.xf(ii), y0 = b.yf(jj);
        if (!std::isnan(C[jj][ii])) {
          const Line l{A[jj][ii], B[jj][ii], C[jj][ii]};
          double xa, ya, xb, yb;
          if (line_segment(l, xa, ya, xb, yb)) {
            double* q = sg.x[sg.n++];
            q[0] = x0 + xa * b.hx, q[1] = y0 + ya * b.hy, q[2] = x0 + xb * b.hx,
            q[3] = y0 + yb * b.hy;
          }
        }
        const double cv = lc[jj][ii];
        const bool full = cv >= 1 - kCut, empty = cv <= kCut;
        if (full || empty) {
          auto opposite = [&](double cn) { return (full && cn <= kCut) || (empty && cn >= 1 - kCut); };
          if (ii + 1 < i1 && in_domain(ii + 1, jj) && opposite(lc[jj][ii + 1])) {
            double* q = sg.x[sg.n++];
            q[0] = x0 + b.hx, q[1] = y0, q[2] = x0 + b.hx, q[3] = y0 + b.hy;
          }
          if (jj + 1 < j1 && in_domain(ii, jj + 1) && opposite(lc[jj + 1][ii])) {
            double* q = sg.x[sg.n++];
            q[0] = x0, q[1] = y0 + b.hy, q[2] = x0 + b.hx, q[3] = y0 + b.hy;
          }
        }
        mark[at(ii, jj)] = sg.n > 0;
      }
    // 3. Which owned cells have a segment within kBand cells: a separable dilation of the marks
    //    (rows, then columns), so that the cells far from the interface skip the search.
    for (PetscInt jj = j0; jj < j1; ++jj)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        char m = 0;
        for (PetscInt ii = i - K; ii <= i + K && !m; ++ii) m = mark[at(ii, jj)];
        rowm[at(i, jj)] = m;
      }
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        char m = 0;
        for (PetscInt jj = j - K; jj <= j + K && !m; ++jj) m = rowm[at(i, jj)];
        near[at(i, j)] = m;
      }
    // 4. The distance of each owned cell centre to the nearest segment, the sign of 1/2 - c.
    PetscScalar** out;
    GF_PETSC(DMDAVecGetArray(dm, phi, &out));
    const double far = (kBand + 1) * std::max(b.hx, b.hy);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const double sign = lc[j][i] > 0.5 ? -1.0 : 1.0;
        if (!near[at(i, j)]) {
          out[j][i] = sign * far;
          continue;
        }
        const double px = b.xc(i), py = b.yc(j);
        double best = far;
        for (PetscInt jj = j - K; jj <= j + K; ++jj)
          for (PetscInt ii = i - K; ii <= i + K; ++ii) {
            if (!mark[at(ii, jj)]) continue;
            const Segs& sg = segs[at(ii, jj)];
            for (int q = 0; q < sg.n; ++q)
              best = std::min(best, segment_distance(px, py, sg.x[q][0], sg.x[q][1],
                                                     sg.x[q][2], sg.x[q][3]));
          }
        out[j][i] = sign * best;
      }
    GF_PETSC(DMDAVecRestoreArray(dm, phi, &out));
  }
  GF_PETSC(DMRestoreGlobalVector(dm, &al));
  GF_PETSC(DMRestoreGlobalVector(dm, &m2));
  GF_PETSC(DMRestoreGlobalVector(dm, &m1));
}

// ---------------------------------------------------------------------------------------------
// Properties and supports.

void update_properties(const Grid& g, Vec c, double rho_air, double rho_gran, double eta_air,
                       double eta_gran, Vec rho, Vec eta, Vec eta_node) {
  const Box& b = g.box();
  const LocalCells lc(g.dm_cell(), c);
  PetscScalar **r, **e, **en = nullptr;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta, &e));
  if (eta_node) GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta_node, &en));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double cv = lc[j][i];
      r[j][i] = rho_air * (1 - cv) + rho_gran * cv;
      e[j][i] = harmonic(1 - cv, eta_air, eta_gran);
      if (en) en[j][i] = harmonic(1 - node_fraction(b, lc.array(), i, j), eta_air, eta_gran);
    }
  if (eta_node) GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta_node, &en));
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta, &e));
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), rho, &r));
}

void mix_viscosity(const Grid& g, Vec c, double eta_air, Vec eta_gran, Vec eta, Vec eta_node) {
  const Box& b = g.box();
  const LocalCells lc(g.dm_cell(), c), es(g.dm_cell(), eta_gran);
  PetscScalar **ec, **en;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta, &ec));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta_node, &en));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      ec[j][i] = harmonic(1 - lc[j][i], eta_air, es[j][i]);
      if (!b.wall_u(i) && j >= 1) {  // interior node: mean of the four surrounding cells
        const double esn = 0.25 * (es[j][i] + es[j][i - 1] + es[j - 1][i] + es[j - 1][i - 1]);
        en[j][i] = harmonic(1 - node_fraction(b, lc.array(), i, j), eta_air, esn);
      }
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta_node, &en));
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta, &ec));
}

void yield_support(const Grid& g, Vec c, Vec w) {
  const PetscScalar* a;
  PetscScalar* o;
  PetscInt n;
  GF_PETSC(VecGetLocalSize(c, &n));
  GF_PETSC(VecGetArrayRead(c, &a));
  GF_PETSC(VecGetArray(w, &o));
  for (PetscInt k = 0; k < n; ++k) o[k] = a[k] > kMass ? a[k] : -1.0;
  GF_PETSC(VecRestoreArray(w, &o));
  GF_PETSC(VecRestoreArrayRead(c, &a));
}

void phase_field(const Grid& g, Vec c, Vec ph) {
  GF_PETSC(VecCopy(c, ph));
  GF_PETSC(VecScale(ph, -1.0));
  GF_PETSC(VecShift(ph, kMass));
}

double volume(const Grid& g, Vec c) {
  const Box& b = g.box();
  PetscScalar s;
  GF_PETSC(VecSum(c, &s));
  return s * b.hx * b.hy;
}

double potential_energy(const Grid& g, Vec c, Vec phi, Normals src, double rho_air,
                        double rho_gran, const std::array<double, 2>& gravity) {
  const Box& b = g.box();
  const LocalCells lc(g.dm_cell(), c), lp(g.dm_cell(), phi);
  double local = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double cv = lc[j][i], xc = b.xc(i), yc = b.yc(j);
      double xg = xc, yg = yc, xa = xc, ya = yc;
      Line l;
      if (reconstruct(b, lc.array(), lp.array(), src, i, j, l)) {
        double X, Y;
        line_centroid(l, X, Y);
        xg = b.xf(i) + X * b.hx;
        yg = b.yf(j) + Y * b.hy;
        // The air's centroid: the cell's centre of mass is the centre.
        xa = (xc - cv * xg) / (1 - cv);
        ya = (yc - cv * yg) / (1 - cv);
      }
      const double mg = rho_gran * cv, ma = rho_air * (1 - cv);
      local -= mg * (gravity[0] * xg + gravity[1] * yg) + ma * (gravity[0] * xa + gravity[1] * ya);
    }
  return g.sum(local) * b.hx * b.hy;
}

double l1_error(const Grid& g, Vec c, Vec c_exact) {
  const Box& b = g.box();
  Vec d;
  GF_PETSC(VecDuplicate(c, &d));
  GF_PETSC(VecWAXPY(d, -1.0, c_exact, c));
  PetscReal n1;
  GF_PETSC(VecNorm(d, NORM_1, &n1));
  VecDestroy(&d);
  return n1 * b.hx * b.hy;
}

}  // namespace gf::vof
