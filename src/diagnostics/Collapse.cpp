#include "diagnostics/Collapse.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/Error.hpp"
#include "diagnostics/Diagnostics.hpp"
#include "grid/Local.hpp"

namespace gf::diag {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double cell_speed(const LocalVelocity& v, PetscInt i, PetscInt j) {
  double uc, vc;
  cell_centre_velocity(v, i, j, uc, vc);
  return std::sqrt(uc * uc + vc * vc);
}

// Column arrays are reduced over the whole communicator: every column is then known on every
// rank, whatever the decomposition (in x, in y or both), and the scans along x below run
// identically everywhere. Their length is nx, small next to the fields.
void allreduce(const Grid& g, std::vector<double>& a, MPI_Op op) {
  MPI_Allreduce(MPI_IN_PLACE, a.data(), static_cast<int>(a.size()), MPI_DOUBLE, op, g.comm());
}

}  // namespace

std::vector<double> surface_heights(const Grid& g, Vec phi) {
  const Box& b = g.box();
  const PetscInt nx = b.nx, ny = b.ny;
  LocalCells p(g.dm_cell(), phi);
  // [0, nx): this rank's candidate for h_i (the highest crossing among its rows; the global
  // top is the largest); [nx, 2 nx): 1 if the column holds a NaN (MPI_MAX on NaN itself is
  // not specified).
  std::vector<double> buf(2 * nx, 0.0);
  for (PetscInt i = b.xs; i < b.xe(); ++i) {
    double cand = 0.0;
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      if (std::isnan(p[j][i])) buf[nx + i] = 1.0;
    for (PetscInt j = b.ye() - 1; j >= b.ys; --j) {
      if (!(p[j][i] < 0)) continue;
      if (j == ny - 1) {
        cand = b.Ly;
      } else {
        const double a = p[j][i], c = p[j + 1][i];  // j + 1 may be a ghost row (inside)
        // c < 0: the column continues on the rank above, whose candidate is higher.
        cand = c >= 0 ? b.yc(j) + b.hy * a / (a - c) : b.yc(j + 1);
      }
      break;
    }
    if (cand == 0.0 && b.ys == 0) {
      // A layer thinner than hy/2: the zero of the line through the centres 0 and 1.
      const double a = p[0][i], c = p[1][i];
      if (a >= 0 && c > a && 1.5 * a - 0.5 * c < 0) cand = b.yc(0) - b.hy * a / (c - a);
    }
    buf[i] = cand;
  }
  allreduce(g, buf, MPI_MAX);
  std::vector<double> h(buf.begin(), buf.begin() + nx);
  for (PetscInt i = 0; i < nx; ++i)
    if (buf[nx + i] > 0) h[i] = kNaN;
  return h;
}

double front_position(const Grid& g, Vec phi) {
  const Box& b = g.box();
  const PetscInt nx = b.nx;
  LocalCells p(g.dm_cell(), phi);
  // phi extrapolated to the bottom; only the ranks owning row 0 contribute (row 1 is in their
  // ghost layer), the others add zeros.
  std::vector<double> pb(nx, 0.0);
  if (b.ys == 0)
    for (PetscInt i = b.xs; i < b.xe(); ++i) pb[i] = 1.5 * p[0][i] - 0.5 * p[1][i];
  allreduce(g, pb, MPI_SUM);  // a NaN survives the sum
  for (PetscInt i = 0; i < nx; ++i)
    if (std::isnan(pb[i])) return kNaN;
  for (PetscInt k = nx - 1; k >= 0; --k) {
    if (!(pb[k] < 0)) continue;
    if (k == nx - 1) return b.Lx;
    return b.xc(k) + b.hx * pb[k] / (pb[k] - pb[k + 1]);
  }
  return 0.0;
}

double max_granular_speed(const Grid& g, Vec vel, Vec phi, double eps) {
  const Box& b = g.box();
  LocalVelocity v(g, vel);
  LocalCells p(g.dm_cell(), phi);
  double acc[2] = {0.0, 0.0};  // max speed, saw-NaN flag
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (!(p[j][i] < -eps)) continue;
      const double s = cell_speed(v, i, j);
      if (std::isnan(s)) acc[1] = 1.0;
      else acc[0] = std::max(acc[0], s);
    }
  MPI_Allreduce(MPI_IN_PLACE, acc, 2, MPI_DOUBLE, MPI_MAX, g.comm());
  return acc[1] > 0 ? kNaN : acc[0];
}

std::vector<BasalDeposit> basal_deposits(const Grid& g, Vec vel, const std::vector<double>& h,
                                         double front_x, double gate_x, double U,
                                         const std::vector<double>& cutoffs) {
  const Box& b = g.box();
  const PetscInt nx = b.nx, ny = b.ny;
  const std::size_t K = cutoffs.size();
  LocalVelocity v(g, vel);
  // 1. j*: the lowest cell of each column faster than c U (ny if none), per cut-off.
  std::vector<int> first(K * nx, static_cast<int>(ny));
  for (PetscInt i = b.xs; i < b.xe(); ++i)
    for (PetscInt j = b.ys; j < b.ye(); ++j) {
      const double s = cell_speed(v, i, j);
      for (std::size_t k = 0; k < K; ++k)
        if (s > cutoffs[k] * U && j < first[k * nx + i]) first[k * nx + i] = static_cast<int>(j);
    }
  MPI_Allreduce(MPI_IN_PLACE, first.data(), static_cast<int>(first.size()), MPI_INT, MPI_MIN,
                g.comm());
  // 2. y* by the rank that owns cell j* (j* - 1 is in its ghost layer), and the bottom-row
  // speeds by the ranks owning row 0; all values are >= 0, the other ranks contribute 0.
  std::vector<double> buf((K + 1) * nx, 0.0);
  for (PetscInt i = b.xs; i < b.xe(); ++i) {
    for (std::size_t k = 0; k < K; ++k) {
      const PetscInt js = first[k * nx + i];
      const double thr = cutoffs[k] * U;
      double y = 0.0;
      if (js == ny) {
        y = b.Ly;
      } else if (js >= b.ys && js < b.ye() && js > 0) {
        const double lo = cell_speed(v, i, js - 1), hi = cell_speed(v, i, js);
        y = b.yc(js - 1) + b.hy * (thr - lo) / (hi - lo);
      }
      buf[k * nx + i] = y;
    }
    if (b.ys == 0) buf[K * nx + i] = cell_speed(v, i, 0);
  }
  allreduce(g, buf, MPI_MAX);
  const double* s0 = buf.data() + K * nx;

  std::vector<BasalDeposit> out(K);
  for (std::size_t k = 0; k < K; ++k) {
    BasalDeposit& d = out[k];
    d.cutoff = cutoffs[k];
    const double thr = cutoffs[k] * U;
    d.h_deposit.resize(nx);
    for (PetscInt i = 0; i < nx; ++i) d.h_deposit[i] = std::min(h[i], buf[k * nx + i]);
    // The deposit front along the bottom row, from the back wall.
    double xd = b.Lx;
    for (PetscInt i = 0; i < nx; ++i)
      if (s0[i] > thr) {
        xd = i == 0 ? 0.0 : b.xc(i - 1) + b.hx * (thr - s0[i - 1]) / (s0[i] - s0[i - 1]);
        break;
      }
    d.x_deposit = std::min(xd, front_x);
    d.L = front_x - gate_x;
    d.L_d = d.x_deposit - gate_x;
    d.L_h = d.L - d.L_d;
    for (PetscInt i = 0; i < nx; ++i) {
      const double w = std::clamp((b.xf(i + 1) - gate_x) / b.hx, 0.0, 1.0);
      d.A += w * h[i] * b.hx;
      d.A_d += w * d.h_deposit[i] * b.hx;
    }
  }
  return out;
}

double backwall_height(const std::vector<double>& h) {
  if (h.empty()) return kNaN;
  if (h.size() < 2 || !(h[0] > 0 && h[1] > 0)) return h[0];
  return 1.5 * h[0] - 0.5 * h[1];
}

namespace {
// Least-squares slope of the points (x_k, y_k) with keep(k), NaN with fewer than two distinct x.
template <class Keep>
double ls_fit(const std::vector<double>& x, const std::vector<double>& y, Keep keep) {
  double n = 0, sx = 0, sy = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (keep(k)) {
      n += 1;
      sx += x[k];
      sy += y[k];
    }
  if (n < 2) return kNaN;
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (keep(k)) {
      sxx += (x[k] - mx) * (x[k] - mx);
      sxy += (x[k] - mx) * (y[k] - my);
    }
  return sxx > 0 ? sxy / sxx : kNaN;
}
}  // namespace

double fit_slope_deg(const std::vector<double>& x, const std::vector<double>& h, double lo,
                     double hi, double front) {
  const double m = ls_fit(x, h, [&](std::size_t i) {
    return x[i] >= lo && x[i] <= hi && x[i] < front && h[i] > 0;
  });
  return std::atan(-m) * 180.0 / std::numbers::pi;
}

double ls_slope(const std::vector<double>& t, const std::vector<double>& y, double lo, double hi) {
  return ls_fit(t, y, [&](std::size_t k) { return t[k] >= lo && t[k] <= hi; });
}

Stages detect_stages(const std::vector<double>& t, const std::vector<double>& front,
                     const std::vector<double>& umax, const StageRule& r) {
  Stages s{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  const std::size_t n = t.size();
  if (n < 2) return s;
  // Outputs are not exactly evenly spaced (the last step lands on t_end): a relative slack.
  const double tiny = 1e-9 * std::max(1.0, std::fabs(t.back()));
  const double half = 0.5 * r.speed_window + tiny;
  std::vector<double> V(n);
  std::size_t kmax = n;
  for (std::size_t k = 0; k < n; ++k) {
    V[k] = ls_slope(t, front, t[k] - half, t[k] + half);
    if (!std::isnan(V[k]) && (kmax == n || V[k] > V[kmax])) kmax = k;
  }
  if (kmax < n && V[kmax] > 0) {
    const double lim = r.plateau_fraction * V[kmax];
    std::size_t a = kmax, b = kmax;
    while (a > 0 && V[a - 1] >= lim) --a;
    while (b + 1 < n && V[b + 1] >= lim) ++b;
    s.t1 = t[a];
    s.t2 = t[b];
    s.max_front_speed = V[kmax];
    s.front_speed = b > a ? ls_slope(t, front, t[a] - tiny, t[b] + tiny) : V[kmax];
  }
  // t3: the first output after which the front advances less than stop_distance.
  for (std::size_t k = 0; k + 1 < n; ++k) {
    bool still = true;
    for (std::size_t m = k + 1; m < n && still; ++m)
      still = front[m] - front[k] < r.stop_distance;
    if (still) {
      s.t3 = t[k];
      break;
    }
  }
  // tf: the first output of the final run of outputs at rest.
  std::size_t k = n;
  while (k > 0 && umax[k - 1] < r.rest_speed) --k;
  if (k < n) s.tf = t[k];
  return s;
}

}  // namespace gf::diag
