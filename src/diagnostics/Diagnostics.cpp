#include "diagnostics/Diagnostics.hpp"

#include <mpi.h>

#include <cmath>
#include <limits>

#include "core/Error.hpp"
#include "grid/Local.hpp"
#include "levelset/Heaviside.hpp"

namespace gf::diag {

namespace {

// Global maximum that is NaN on every rank if any rank saw a NaN. MPI_MAX on NaN is not
// specified by MPI, so the NaN travels as a separate flag in the same reduction.
double max_nan_aware(const Grid& g, double local_max, bool local_nan) {
  double in[2] = {local_max, local_nan ? 1.0 : 0.0}, out[2] = {0, 0};
  MPI_Allreduce(in, out, 2, MPI_DOUBLE, MPI_MAX, g.comm());
  return out[1] > 0 ? std::numeric_limits<double>::quiet_NaN() : out[0];
}

// Folds one value into a running (max, saw-NaN) pair.
struct MaxAcc {
  double m = -std::numeric_limits<double>::infinity();
  bool nan = false;
  void add(double x) {
    if (std::isnan(x)) nan = true;
    else if (x > m) m = x;
  }
};

}  // namespace

double max_speed(const Grid& g, Vec vel) {
  const Box& b = g.box();
  LocalVelocity v(g, vel);
  MaxAcc acc;
  acc.m = 0.0;  // a speed is never negative; 0 also covers a rank that owns no cells
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      double uc, vc;
      cell_centre_velocity(v, i, j, uc, vc);
      acc.add(std::sqrt(uc * uc + vc * vc));
    }
  return max_nan_aware(g, acc.m, acc.nan);
}

double kinetic_energy(const Grid& g, Vec vel, Vec rho) {
  const Box& b = g.box();
  LocalVelocity v(g, vel);
  LocalCells r(g.dm_cell(), rho);
  double local = 0.0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double uu = 0.5 * (v[j][i].u * v[j][i].u + v[j][i + 1].u * v[j][i + 1].u);
      const double vv = 0.5 * (v[j][i].v * v[j][i].v + v[j + 1][i].v * v[j + 1][i].v);
      local += 0.5 * r[j][i] * (uu + vv);
    }
  return g.sum(local) * b.hx * b.hy;
}

double max_divergence(const Grid& g, Vec vel) {
  const Box& b = g.box();
  // The ghost exchange brings u_{i+1} / v_{j+1} owned by the right / upper neighbour; the
  // wall faces i = nx / j = ny are not stored and come as zeros from fill_velocity_ghosts
  // (with periodic x, the face nx is the wrapped face 0 from the ghost exchange).
  LocalVelocity v(g, vel);
  MaxAcc acc;
  acc.m = 0.0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double d =
          (v[j][i + 1].u - v[j][i].u) / b.hx + (v[j + 1][i].v - v[j][i].v) / b.hy;
      acc.add(std::fabs(d));
    }
  return max_nan_aware(g, acc.m, acc.nan);
}

double granular_volume(const Grid& g, Vec phi, double eps) {
  const Box& b = g.box();
  const PetscScalar** p = nullptr;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), phi, &p));
  double local = 0.0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      // heaviside() maps NaN to the middle branch, which returns NaN: it is not lost.
      local += 1.0 - levelset::heaviside(p[j][i], eps);
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), phi, &p));
  return g.sum(local) * b.hx * b.hy;
}

double max_in_granular(const Grid& g, Vec field, Vec phi) {
  const Box& b = g.box();
  const PetscScalar **f = nullptr, **p = nullptr;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), field, &f));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), phi, &p));
  MaxAcc acc;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      if (p[j][i] < 0) acc.add(f[j][i]);
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), phi, &p));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), field, &f));
  const double m = max_nan_aware(g, acc.m, acc.nan);
  // -inf means no rank found a granular cell (an empty or fully fluidised domain).
  return m == -std::numeric_limits<double>::infinity() ? 0.0 : m;
}

std::array<double, 2> granular_mean_velocity(const Grid& g, Vec vel, Vec phi, double eps) {
  const Box& b = g.box();
  LocalVelocity v(g, vel);
  const PetscScalar** ph;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), phi, &ph));
  double acc[3] = {0, 0, 0}, tot[3] = {0, 0, 0};
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double w = 1.0 - levelset::heaviside(ph[j][i], eps);
      double uc, vc;
      cell_centre_velocity(v, i, j, uc, vc);
      acc[0] += w * uc;
      acc[1] += w * vc;
      acc[2] += w;
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), phi, &ph));
  MPI_Allreduce(acc, tot, 3, MPI_DOUBLE, MPI_SUM, g.comm());
  if (tot[2] <= 0) return {0.0, 0.0};
  return {tot[0] / tot[2], tot[1] / tot[2]};
}

std::array<double, 2> granular_mean_velocity(const Grid& g, Vec vel, Vec fraction) {
  const Box& b = g.box();
  LocalVelocity v(g, vel);
  const PetscScalar** w;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), fraction, &w));
  double acc[3] = {0, 0, 0}, tot[3] = {0, 0, 0};
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      double uc, vc;
      cell_centre_velocity(v, i, j, uc, vc);
      acc[0] += w[j][i] * uc;
      acc[1] += w[j][i] * vc;
      acc[2] += w[j][i];
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), fraction, &w));
  MPI_Allreduce(acc, tot, 3, MPI_DOUBLE, MPI_SUM, g.comm());
  if (tot[2] <= 0) return {0.0, 0.0};
  return {tot[0] / tot[2], tot[1] / tot[2]};
}

double potential_energy(const Grid& g, Vec rho, const std::array<double, 2>& gravity) {
  const Box& b = g.box();
  const PetscScalar** r;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), rho, &r));
  double local = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      local -= r[j][i] * (gravity[0] * b.xc(i) + gravity[1] * b.yc(j));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), rho, &r));
  return g.sum(local) * b.hx * b.hy;
}

namespace {
// The lowest linear index j nx + i over the ranks of a local candidate (-1: none here).
CellIndex lowest_cell(const Grid& g, long long local) {
  const long long none = std::numeric_limits<long long>::max();
  long long in = local < 0 ? none : local, out = none;
  MPI_Allreduce(&in, &out, 1, MPI_LONG_LONG, MPI_MIN, g.comm());
  if (out == none) return {};
  return {static_cast<PetscInt>(out % g.nx()), static_cast<PetscInt>(out / g.nx())};
}
}  // namespace

CellIndex first_nonfinite(const Grid& g, Vec field) {
  const Box& b = g.box();
  PetscInt n = 0;
  GF_PETSC(VecGetLocalSize(field, &n));
  const PetscInt cells = b.xm * b.ym;
  const PetscInt dof = cells > 0 ? n / cells : 1;
  const PetscScalar* a;
  GF_PETSC(VecGetArrayRead(field, &a));
  long long first = -1;
  // Owned values are stored i-fastest from (xs, ys), dof per cell: the first bad value in
  // storage order is the first bad cell in (j, i) order.
  for (PetscInt k = 0; k < n; ++k)
    if (!std::isfinite(a[k])) {
      const PetscInt c = k / dof;
      first = static_cast<long long>(b.ys + c / b.xm) * b.nx + (b.xs + c % b.xm);
      break;
    }
  GF_PETSC(VecRestoreArrayRead(field, &a));
  return lowest_cell(g, first);
}

SpeedAt max_speed_at(const Grid& g, Vec vel) {
  SpeedAt r;
  r.speed = max_speed(g, vel);
  const Box& b = g.box();
  LocalVelocity v(g, vel);
  long long at = -1;
  for (PetscInt j = b.ys; j < b.ye() && at < 0; ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      double uc, vc;
      cell_centre_velocity(v, i, j, uc, vc);
      const double s = std::sqrt(uc * uc + vc * vc);
      // The same expression as in max_speed, so the comparison is exact (NaN: none matches).
      if (s == r.speed) {
        at = static_cast<long long>(j) * b.nx + i;
        break;
      }
    }
  r.at = lowest_cell(g, at);
  return r;
}

}  // namespace gf::diag
