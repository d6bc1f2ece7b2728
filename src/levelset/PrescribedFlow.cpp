// Prescribed flows and initial shapes for the level-set verification (see PrescribedFlow.hpp).
#include "levelset/PrescribedFlow.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/Error.hpp"

namespace gf::levelset {

namespace {

// Signed distances at the cell centres. With periodic x the shape repeats with period Lx: the
// signed distance to the union of its images x - Lx, x, x + Lx (exact for a shape inside the
// domain, whose images do not overlap) is the smallest of the three.
template <class F>
void fill_cells(const Grid& g, Vec phi, const F& f) {
  const Box& b = g.box();
  PetscScalar** p;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), phi, &p));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double x = b.xc(i), y = b.yc(j);
      p[j][i] = b.periodic_x ? std::min({f(x - b.Lx, y), f(x, y), f(x + b.Lx, y)}) : f(x, y);
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), phi, &p));
}

double segment_distance(double x, double y, double ax, double ay, double bx, double by) {
  const double ex = bx - ax, ey = by - ay;
  const double t = std::clamp(((x - ax) * ex + (y - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
  return std::hypot(x - ax - t * ex, y - ay - t * ey);
}

}  // namespace

void rotation_velocity(const Grid& g, Vec vel, double omega, double cx, double cy,
                       double r_solid, double r_still) {
  if (!(r_solid > 0 && r_still > r_solid))
    throw InputError("rotation_velocity: need 0 < r_solid < r_still");
  const double r1 = r_solid, d = r_still - r_solid;
  // Angular velocity omega g(r), g = 1 - (3 t^2 - 2 t^3), t = (r - r1)/d clipped to [0, 1]; the
  // stream function psi(r) = -omega int_0^r s g(s) ds in closed form.
  auto psi = [=](double x, double y) {
    const double r = std::hypot(x - cx, y - cy);
    if (r <= r1) return -omega * 0.5 * r * r;
    const double t = std::min((r - r1) / d, 1.0), t2 = t * t, t4 = t2 * t2;
    return -omega * (0.5 * r1 * r1 + d * (r1 * (t - t2 * t + 0.5 * t4) +
                                          d * (0.5 * t2 - 0.75 * t4 + 0.4 * t4 * t)));
  };
  velocity_from_stream_function(g, vel, psi);
}

void rotation_velocity(const Grid& g, Vec vel, double omega, double cx, double cy) {
  const Box& b = g.box();
  const double r_still = std::min({cx, b.Lx - cx, cy, b.Ly - cy});
  rotation_velocity(g, vel, omega, cx, cy, 0.85 * r_still, r_still);
}

void single_vortex_velocity(const Grid& g, Vec vel, double t, double T) {
  const Box& b = g.box();
  if (std::abs(b.Lx - 1) > 1e-12 || std::abs(b.Ly - 1) > 1e-12)
    throw InputError("single_vortex_velocity: the domain must be the unit square");
  const double pi = std::numbers::pi, c = std::cos(pi * t / T) / pi;
  auto psi = [=](double x, double y) {
    const double sx = std::sin(pi * x), sy = std::sin(pi * y);
    return sx * sx * sy * sy * c;
  };
  velocity_from_stream_function(g, vel, psi);
}

double circle_distance(double x, double y, double cx, double cy, double r) {
  return std::hypot(x - cx, y - cy) - r;
}

double zalesak_distance(double x, double y, double cx, double cy, double r, double slot_width,
                        double slot_depth) {
  const double hw = 0.5 * slot_width;
  const double y_top = cy - r + slot_depth;              // slot ceiling
  const double y_bot = cy - std::sqrt(r * r - hw * hw);  // where the slot walls meet the circle
  const double rho = std::hypot(x - cx, y - cy);
  const bool inside = rho < r && !(std::abs(x - cx) < hw && y < y_top);
  // Boundary = circle minus its lower arc between the slot walls, two slot walls, the ceiling.
  double d_arc;
  if (rho == 0) {
    d_arc = r;
  } else {
    const double qx = cx + r * (x - cx) / rho, qy = cy + r * (y - cy) / rho;  // radial foot
    if (std::abs(qx - cx) >= hw || qy > cy)
      d_arc = std::abs(rho - r);
    else  // the foot falls in the removed arc: nearest point is an end of the kept arc
      d_arc = std::min(std::hypot(x - (cx - hw), y - y_bot), std::hypot(x - (cx + hw), y - y_bot));
  }
  const double d = std::min({d_arc, segment_distance(x, y, cx - hw, y_bot, cx - hw, y_top),
                             segment_distance(x, y, cx + hw, y_bot, cx + hw, y_top),
                             segment_distance(x, y, cx - hw, y_top, cx + hw, y_top)});
  return inside ? -d : d;
}

double rectangle_distance(double x, double y, double x0, double x1, double y0, double y1) {
  const double dx = std::abs(x - 0.5 * (x0 + x1)) - 0.5 * (x1 - x0);
  const double dy = std::abs(y - 0.5 * (y0 + y1)) - 0.5 * (y1 - y0);
  return std::hypot(std::max(dx, 0.0), std::max(dy, 0.0)) + std::min(std::max(dx, dy), 0.0);
}

void init_circle(const Grid& g, Vec phi, double cx, double cy, double r) {
  fill_cells(g, phi, [=](double x, double y) { return circle_distance(x, y, cx, cy, r); });
}

void init_zalesak(const Grid& g, Vec phi, double cx, double cy, double r, double slot_width,
                  double slot_depth) {
  fill_cells(g, phi, [=](double x, double y) {
    return zalesak_distance(x, y, cx, cy, r, slot_width, slot_depth);
  });
}

void init_rectangle(const Grid& g, Vec phi, double x0, double x1, double y0, double y1) {
  fill_cells(g, phi, [=](double x, double y) { return rectangle_distance(x, y, x0, x1, y0, y1); });
}

double trapezoid_distance(double x, double y, double x0, double x1, double h, double slope_deg) {
  const double run = h / std::tan(slope_deg * std::numbers::pi / 180);
  const double xl = x0 + run, xr = x1 - run;  // ends of the top
  const double d = std::min({segment_distance(x, y, x0, 0.0, xl, h),
                             segment_distance(x, y, xl, h, xr, h),
                             segment_distance(x, y, xr, h, x1, 0.0)});
  const bool inside = y < h && x > x0 + y / h * run && x < x1 - y / h * run;
  return inside ? -d : d;
}

void init_trapezoid(const Grid& g, Vec phi, double x0, double x1, double h, double slope_deg) {
  fill_cells(g, phi, [=](double x, double y) { return trapezoid_distance(x, y, x0, x1, h, slope_deg); });
}

void init_layer(const Grid& g, Vec phi, double height) {
  fill_cells(g, phi, [=](double, double y) { return y - height; });
}

}  // namespace gf::levelset
