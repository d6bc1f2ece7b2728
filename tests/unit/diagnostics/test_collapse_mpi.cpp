// Column-collapse measures (diagnostics/Collapse.hpp) against exact answers, on 1 and 2 ranks.
//
// The level sets are piecewise-linear functions of (x, y) whose zero set is known exactly: the
// measures interpolate phi (and the speed) linearly between cell centres, so they are exact to
// round-off wherever the samples they use lie on one linear piece, and only the columns next to
// a kink carry an O(h) error. The wide grid is split in x on 2 ranks, the tall one in y, so that
// the column scans and the sub-cell interpolations cross a rank boundary in both directions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/Error.hpp"
#include "diagnostics/Collapse.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"

namespace {

using gf::Grid;
namespace diag = gf::diag;
constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
double deg(double a) { return a * kPi / 180; }

template <class F>
void set_cells(const Grid& g, Vec v, F f) {
  const gf::Box& b = g.box();
  PetscScalar** a;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), v, &a));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = f(b.xc(i), b.yc(j));
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), v, &a));
}

// u(x, y) on the left faces (0 on the wall face x = 0), v = 0.
template <class F>
void set_u(const Grid& g, Vec vel, F u) {
  const gf::Box& b = g.box();
  gf::Vel** a;
  GF_PETSC(DMDAVecGetArray(g.dm_vel(), vel, &a));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = {i == 0 ? 0.0 : u(b.xf(i), b.yc(j)), 0.0};
  GF_PETSC(DMDAVecRestoreArray(g.dm_vel(), vel, &a));
}

// Signed distance to the line y = c - t x, negative below it.
double below_line(double x, double y, double c, double t) {
  return (y + t * x - c) / std::sqrt(1 + t * t);
}

// A deposit with two slopes, as case B's (section 4.2.2): h(x) = max(H - t1 x, c - t2 x), 29 deg
// at the back, 7 deg at the front, kink at xk, front at c / t2. The granular region is the union
// of the regions below the two lines: phi = min of their distances (exact outside, and its zero
// set is exactly the surface).
struct TwoSlopes {
  double H = 0.1, xk = 0.08, t1 = std::tan(deg(29)), t2 = std::tan(deg(7));
  double c = H - (t1 - t2) * xk;
  double h(double x) const { return std::max({H - t1 * x, c - t2 * x, 0.0}); }
  double phi(double x, double y) const { return std::min(below_line(x, y, H, t1), below_line(x, y, c, t2)); }
  double front() const { return c / t2; }
  // Exact area of the mass beyond x = a (a in the 7 deg part).
  double area_beyond(double a) const { return 0.5 * (c - t2 * a) * (front() - a); }
};

TEST(Collapse, TwoSlopeDepositProfileFrontAndSlopes) {
  Grid g(PETSC_COMM_WORLD, 128, 32, 0.8, 0.2);
  gf::State s(g);
  const TwoSlopes d;
  set_cells(g, s.phi, [&](double x, double y) { return d.phi(x, y); });
  const auto h = diag::surface_heights(g, s.phi);
  ASSERT_EQ(h.size(), 128u);
  const double hx = g.hx();
  int exact_cols = 0;
  for (PetscInt i = 0; i < g.nx(); ++i) {
    const double x = g.box().xc(i);
    // Columns whose crossing samples straddle the kink are off by O(h) (a kink inside one cell).
    if (std::fabs(x - d.xk) < 2 * hx) {
      EXPECT_NEAR(h[i], d.h(x), g.hy()) << "column " << i;
    } else {
      EXPECT_NEAR(h[i], d.h(x), 1e-13) << "column " << i << " x = " << x;
      ++exact_cols;
    }
  }
  EXPECT_GT(exact_cols, 120);
  // The front (phi extrapolated to y = 0, linear along x) is exact, and so is the back wall.
  EXPECT_NEAR(diag::front_position(g, s.phi), d.front(), 1e-13);
  EXPECT_NEAR(diag::backwall_height(h), d.H, 1e-13);
  // The thin tip (< hy/2 thick, no granular cell centre) is measured too.
  const double x_tip = g.box().xc(static_cast<PetscInt>(d.front() / hx) - 1);
  ASSERT_LT(d.h(x_tip), 0.5 * g.hy());
  // Slopes and the front angle: exact on ranges that avoid the kink.
  std::vector<double> x(g.nx());
  for (PetscInt i = 0; i < g.nx(); ++i) x[i] = g.box().xc(i);
  EXPECT_NEAR(diag::fit_slope_deg(x, h, 0.0, 0.06, d.front()), 29.0, 1e-10);
  EXPECT_NEAR(diag::fit_slope_deg(x, h, 0.12, 0.8, d.front()), 7.0, 1e-10);
  EXPECT_NEAR(diag::fit_slope_deg(x, h, d.front() - 0.02, d.front(), d.front()), 7.0, 1e-10);
  EXPECT_TRUE(std::isnan(diag::fit_slope_deg(x, h, 0.9, 1.0, d.front())));  // no column

  // At rest everything is deposit, and the area beyond the gate is the integral of h to
  // O(h^2) (midpoint rule; the tip column is the only non-linear one).
  GF_PETSC(VecSet(s.vel, 0.0));
  const double gate = 0.2;
  const auto dep = diag::basal_deposits(g, s.vel, h, d.front(), gate, 0.0, {0.075, 0.0075});
  ASSERT_EQ(dep.size(), 2u);
  for (const auto& b : dep) {
    EXPECT_NEAR(b.A, d.area_beyond(gate), 2 * hx * hx);
    EXPECT_DOUBLE_EQ(b.A_d, b.A);
    EXPECT_DOUBLE_EQ(b.x_deposit, d.front());
    EXPECT_NEAR(b.L, d.front() - gate, 1e-13);
    EXPECT_DOUBLE_EQ(b.L_h, 0.0);
    for (PetscInt i = 0; i < g.nx(); ++i) EXPECT_DOUBLE_EQ(b.h_deposit[i], h[i]);
  }
}

// A shear flow u = a y + b x through the two-slope deposit: the cell-centre speed is linear in x
// and y away from the back wall, so the deposit height y* = (cU - b x)/a, its front along the
// bottom row x_d = (cU - a y_0)/b and the areas are exact.
TEST(Collapse, ShearFlowDepositAndFlowingLayer) {
  Grid g(PETSC_COMM_WORLD, 128, 32, 0.8, 0.2);
  gf::State s(g);
  const TwoSlopes d;
  set_cells(g, s.phi, [&](double x, double y) { return d.phi(x, y); });
  const double a = 5.0, b = 1.0;  // 1/s
  set_u(g, s.vel, [&](double x, double y) { return a * y + b * x; });
  const gf::Box& bx = g.box();
  // U over the granular cells (eps = 0: phi < 0); column 0 has the wall face u = 0.
  double U = 0;
  for (PetscInt j = 0; j < g.ny(); ++j)
    for (PetscInt i = 0; i < g.nx(); ++i) {
      const double x = bx.xc(i), y = bx.yc(j);
      if (!(d.phi(x, y) < 0)) continue;
      const double sp = i == 0 ? 0.5 * (a * y + b * bx.hx) : a * y + b * x;
      U = std::max(U, sp);
    }
  ASSERT_NEAR(diag::max_granular_speed(g, s.vel, s.phi, 0.0), U, 1e-13);
  // Outside the band phi < -eps only: fewer cells, a smaller maximum.
  EXPECT_LT(diag::max_granular_speed(g, s.vel, s.phi, 0.01), U);

  const auto h = diag::surface_heights(g, s.phi);
  const double front = diag::front_position(g, s.phi), gate = 0.2;
  const std::vector<double> cuts{0.5, 0.7};
  const auto dep = diag::basal_deposits(g, s.vel, h, front, gate, U, cuts);
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const double thr = cuts[k] * U;
    const auto& D = dep[k];
    double A = 0, Ad = 0;
    int layered = 0;
    for (PetscInt i = 1; i + 1 < g.nx(); ++i) {
      const double x = bx.xc(i);
      const double y0 = bx.yc(0);
      const double ystar = a * y0 + b * x > thr ? 0.0 : std::min((thr - b * x) / a, g.box().Ly);
      EXPECT_NEAR(D.h_deposit[i], std::min(h[i], ystar), 1e-12) << "cut " << cuts[k] << " col " << i;
      if (h[i] > D.h_deposit[i] && D.h_deposit[i] > 0) ++layered;
      const double w = std::clamp((bx.xf(i + 1) - gate) / bx.hx, 0.0, 1.0);
      A += w * h[i] * bx.hx;
      Ad += w * D.h_deposit[i] * bx.hx;
    }
    EXPECT_GT(layered, 5);  // a deposit under a flowing layer: the case the test is about
    const double xd = std::min((thr - a * bx.yc(0)) / b, front);
    EXPECT_NEAR(D.x_deposit, xd, 1e-12);
    EXPECT_NEAR(D.L_d, xd - gate, 1e-12);
    EXPECT_NEAR(D.L_h, front - xd, 1e-12);
    EXPECT_NEAR(D.A, A, 1e-14);  // columns 0 and nx - 1 lie behind the gate / beyond the front
    EXPECT_NEAR(D.A_d, Ad, 1e-14);
  }
}

// A tall grid (split in y on 2 ranks): the surface and the deposit top cross the rank boundary
// y = 0.4, and the front reaches the right wall.
TEST(Collapse, TallGridCrossesRankBoundaries) {
  Grid g(PETSC_COMM_WORLD, 16, 64, 0.2, 0.8);
  gf::State s(g);
  const double c = 0.41, t = 0.1;  // surface from 0.41 at x = 0 to 0.39 at x = 0.2
  set_cells(g, s.phi, [&](double x, double y) { return below_line(x, y, c, t); });
  const auto h = diag::surface_heights(g, s.phi);
  for (PetscInt i = 0; i < g.nx(); ++i) EXPECT_NEAR(h[i], c - t * g.box().xc(i), 1e-13);
  EXPECT_DOUBLE_EQ(diag::front_position(g, s.phi), 0.2);  // reaches the right wall: Lx
  EXPECT_NEAR(diag::backwall_height(h), c, 1e-13);

  const double a = 2.0;
  set_u(g, s.vel, [&](double, double y) { return a * y; });
  const double U = diag::max_granular_speed(g, s.vel, s.phi, 0.0);
  const double cut = a * 0.4 / U;  // y* = 0.4 in every interior column: on the rank boundary
  const auto dep = diag::basal_deposits(g, s.vel, h, 0.2, 0.1, U, {cut});
  for (PetscInt i = 1; i + 1 < g.nx(); ++i)
    EXPECT_NEAR(dep[0].h_deposit[i], std::min(h[i], 0.4), 1e-12) << "column " << i;
}

TEST(Collapse, NaNIsNotHidden) {
  Grid g(PETSC_COMM_WORLD, 32, 8, 0.8, 0.2);
  gf::State s(g);
  set_cells(g, s.phi, [](double x, double y) { return x > 0.5 && x < 0.53 && y < 0.03 ? kNaN : x - 0.3; });
  EXPECT_TRUE(std::isnan(diag::front_position(g, s.phi)));
  const auto h = diag::surface_heights(g, s.phi);
  EXPECT_TRUE(std::any_of(h.begin(), h.end(), [](double v) { return std::isnan(v); }));
  EXPECT_DOUBLE_EQ(h[0], 0.2);  // a granular column to the top: Ly
}

// A synthetic front: the speed rises linearly to V over [0, T1], stays at V to T2, falls
// linearly to 0 at T3 and the front then recedes by 5 mm (a lost tip must not move t3).
struct SyntheticFront {
  double V = 1.0, T1 = 0.1, T2 = 0.35, T3 = 0.45, x0 = 0.2;
  double x(double t) const {
    if (t <= T1) return x0 + 0.5 * V * t * t / T1;
    const double x1 = x0 + 0.5 * V * T1;
    if (t <= T2) return x1 + V * (t - T1);
    const double x2 = x1 + V * (T2 - T1), D = T3 - T2;
    if (t <= T3) return x2 + V * (t - T2) - 0.5 * V * (t - T2) * (t - T2) / D;
    const double x3 = x2 + 0.5 * V * D;
    return t <= 0.6 ? x3 : x3 - 0.005 * std::min(1.0, (t - 0.6) / 0.2);
  }
};

TEST(CollapseStages, SyntheticFrontGivesTheKnownStages) {
  const SyntheticFront f;
  const double dt = 0.01;
  std::vector<double> t, x, u;
  for (int k = 0; k <= 100; ++k) {
    t.push_back(k * dt);
    x.push_back(f.x(k * dt));
    // The max granular speed decays exponentially after T3, from 1 m/s with 0.05 s.
    u.push_back(k * dt < f.T3 ? 1.0 : std::exp(-(k * dt - f.T3) / 0.05));
  }
  diag::StageRule r;  // window 0.05 s, 90 %, 1 mm, 1 mm/s
  const auto st = diag::detect_stages(t, x, u, r);
  // Away from the kinks the centred 5-point least-squares slope of a parabola is its
  // derivative. Next to them the window mixes the two phases: at 0.09 s (V = 0.9 on the ramp)
  // it reads 0.89 V, at 0.10 s 0.955 V; at 0.35 s 0.955 V and at 0.36 s (V = 0.9 on the
  // deceleration) 0.89 V. So the rule gives t1 = 0.10 s and t2 = 0.35 s, here T1 and T2, and
  // the front moves at exactly V in between.
  EXPECT_NEAR(st.t1, 0.10, 1e-12);
  EXPECT_NEAR(st.t2, 0.35, 1e-12);
  EXPECT_NEAR(st.max_front_speed, f.V, 1e-12);
  EXPECT_NEAR(st.front_speed, f.V, 1e-12);
  // t3: the first output within 1 mm of the runout, T3 - sqrt(2 delta (T3 - T2) / V) = 0.4359 s.
  const double t3_exact = f.T3 - std::sqrt(2 * r.stop_distance * (f.T3 - f.T2) / f.V);
  EXPECT_NEAR(st.t3, std::ceil(t3_exact / dt) * dt, 1e-12);
  // tf: exp(-(t - T3)/0.05) < 1e-3 from t = T3 + 0.05 ln 1000 = 0.7954 s.
  EXPECT_NEAR(st.tf, 0.80, 1e-12);

  // A front still advancing at the end, a flow still moving: no t3, no tf.
  std::vector<double> x2 = x, u2 = u;
  x2.back() += 0.01;
  u2.back() = 0.1;
  const auto st2 = diag::detect_stages(t, x2, u2, r);
  EXPECT_TRUE(std::isnan(st2.t3));
  EXPECT_TRUE(std::isnan(st2.tf));
  // A plateau fraction of 0.55 widens the constant phase: t1 is the first output with
  // V >= 0.55 V on the ramp, 0.06 s (0.05 s reads 0.5 V).
  r.plateau_fraction = 0.55;
  EXPECT_NEAR(diag::detect_stages(t, x, u, r).t1, 0.06, 1e-12);
}

}  // namespace
