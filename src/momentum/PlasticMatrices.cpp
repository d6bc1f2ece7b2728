// The plastic operators of eq. 31 as matrices, by probing their kernels (see PlasticMatrices.hpp).
#include "momentum/PlasticMatrices.hpp"

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/Error.hpp"

namespace gf::momentum {

PlasticMatrices::~PlasticMatrices() {
  MatDestroy(&B);
  MatDestroy(&C);
  VecDestroy(&d0);
}

namespace {

// The colour of a column i in x: its residue modulo 3, except in the last nx mod 3 columns,
// which get colours of their own (3, 4), so that any three consecutive columns have three
// colours also across the periodic seam (column nx - 1 next to column 0).
struct Colours {
  PetscInt nx, ny, base;
  bool periodic;
  Colours(const Box& b) : nx(b.nx), ny(b.ny), base(b.nx - b.nx % 3), periodic(b.periodic_x) {}
  int nxc() const { return 3 + static_cast<int>(nx % 3); }
  PetscInt wrap(PetscInt i) const { return periodic ? (i % nx + nx) % nx : i; }
  int cx(PetscInt i) const {
    const PetscInt w = wrap(i);
    return w < base ? static_cast<int>(w % 3) : static_cast<int>(3 + (w - base));
  }
  static int cy(PetscInt j) { return static_cast<int>(j % 3); }
};

// Global indices of (i, j, c) of a DMDA, i and j unwrapped global indices within the ghost
// width of this rank (with periodic x, i = -1 is column nx - 1).
class Indexer {
 public:
  explicit Indexer(DM dm) {
    GF_PETSC(DMDAGetGhostCorners(dm, &gxs_, &gys_, nullptr, &gxm_, &gym_, nullptr));
    GF_PETSC(DMDAGetInfo(dm, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, &dof_,
                         nullptr, nullptr, nullptr, nullptr, nullptr));
    GF_PETSC(DMGetLocalToGlobalMapping(dm, &map_));
  }
  PetscInt global(PetscInt i, PetscInt j, PetscInt c) const {
    if (i < gxs_ || i >= gxs_ + gxm_ || j < gys_ || j >= gys_ + gym_)
      throw std::logic_error("plastic matrices: point (" + std::to_string(i) + ", " +
                             std::to_string(j) + ") outside the ghost region");
    const PetscInt loc = ((j - gys_) * gxm_ + (i - gxs_)) * dof_ + c;
    PetscInt out;
    GF_PETSC(ISLocalToGlobalMappingApply(map_, 1, &loc, &out));
    return out;
  }

 private:
  PetscInt gxs_ = 0, gys_ = 0, gxm_ = 0, gym_ = 0, dof_ = 1;
  ISLocalToGlobalMapping map_ = nullptr;
};

Mat create_matrix(MPI_Comm comm, Vec rows, Vec cols, PetscInt nnz) {
  PetscInt m, n;
  GF_PETSC(VecGetLocalSize(rows, &m));
  GF_PETSC(VecGetLocalSize(cols, &n));
  Mat M;
  GF_PETSC(MatCreate(comm, &M));
  GF_PETSC(MatSetSizes(M, m, n, PETSC_DETERMINE, PETSC_DETERMINE));
  GF_PETSC(MatSetType(M, MATAIJ));
  GF_PETSC(MatSeqAIJSetPreallocation(M, nnz, nullptr));
  GF_PETSC(MatMPIAIJSetPreallocation(M, nnz, nullptr, nnz, nullptr));
  GF_PETSC(MatSetOption(M, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  return M;
}

// The faces of one velocity component inside a box of rows/columns, as the unknowns a probe can
// reach: u-faces that are not left/right walls, v-faces above the bottom wall and below the top.
bool is_unknown(const Box& b, int q, PetscInt i, PetscInt j) {
  if (j < 0 || j >= b.ny) return false;
  if (!b.has_cell_x(i) && !(q == 0 && b.has_uface(i))) return false;
  return q == 0 ? !b.wall_u(i) : j >= 1;
}

// The one point of colour (cx, cy) in the window [x0, x1] x [y0, y1] that pass(i, j) accepts;
// false if there is none, throws if there are two (the colouring would be ambiguous).
template <class Pass>
bool find_point(const Colours& col, int cx, int cy, PetscInt x0, PetscInt x1, PetscInt y0,
                PetscInt y1, const Pass& pass, PetscInt& xi, PetscInt& yj) {
  int found = 0;
  for (PetscInt y = y0; y <= y1; ++y)
    for (PetscInt x = x0; x <= x1; ++x)
      if (y >= 0 && Colours::cy(y) == cy && col.cx(x) == cx && pass(x, y)) {
        xi = x;
        yj = y;
        ++found;
      }
  if (found > 1) throw std::logic_error("plastic matrices: ambiguous colouring");
  return found == 1;
}

void unexplained(const char* what, PetscInt i, PetscInt j, double v) {
  throw std::logic_error(std::string("plastic matrices: ") + what + " at (" + std::to_string(i) +
                         ", " + std::to_string(j) + ") responds (" + std::to_string(v) +
                         ") to a probe no point of its stencil carries: the kernel's stencil "
                         "changed, widen the windows in PlasticMatrices.cpp");
}

}  // namespace

void assemble_plastic_matrices(const Grid& g, Predictor& pred, Vec eta, PlasticMatrices& out) {
  const Box& b = g.box();
  const Colours col(b);
  pred.clear_plastic_region();
  MatDestroy(&out.B);
  MatDestroy(&out.C);
  VecDestroy(&out.d0);
  Vec vel, D, kappa, S, zero_vel, force;
  GF_PETSC(DMGetGlobalVector(g.dm_vel(), &vel));
  GF_PETSC(DMGetGlobalVector(g.dm_vel(), &zero_vel));
  GF_PETSC(DMGetGlobalVector(g.dm_vel(), &force));
  GF_PETSC(DMGetGlobalVector(g.dm_ten(), &D));
  GF_PETSC(DMGetGlobalVector(g.dm_ten(), &S));
  GF_PETSC(DMGetGlobalVector(g.dm_cell(), &kappa));
  GF_PETSC(VecSet(zero_vel, 0.0));
  GF_PETSC(DMCreateGlobalVector(g.dm_ten(), &out.d0));
  pred.strain_rate(zero_vel, eta, out.d0);
  const Indexer iv(g.dm_vel()), it(g.dm_ten());

  // B: a cell's D reads the u-faces i..i+1 x j-1..j+1 and the v-faces i-1..i+1 x j..j+1.
  out.B = create_matrix(g.comm(), out.d0, vel, 12);
  for (int q = 0; q < 2; ++q)
    for (int cx = 0; cx < col.nxc(); ++cx)
      for (int cy = 0; cy < 3; ++cy) {
        Vel** v;
        GF_PETSC(DMDAVecGetArray(g.dm_vel(), vel, &v));
        for (PetscInt j = b.ys; j < b.ye(); ++j)
          for (PetscInt i = b.xs; i < b.xe(); ++i) {
            const bool on = is_unknown(b, q, i, j) && col.cx(i) == cx && Colours::cy(j) == cy;
            (q == 0 ? v[j][i].u : v[j][i].v) = on ? 1.0 : 0.0;
            (q == 0 ? v[j][i].v : v[j][i].u) = 0.0;
          }
        GF_PETSC(DMDAVecRestoreArray(g.dm_vel(), vel, &v));
        pred.strain_rate(vel, eta, D);
        GF_PETSC(VecAXPY(D, -1.0, out.d0));
        const PetscScalar* const* const* d;
        GF_PETSC(DMDAVecGetArrayDOFRead(g.dm_ten(), D, &d));
        auto pass = [&](PetscInt x, PetscInt y) { return is_unknown(b, q, x, y); };
        for (PetscInt j = b.ys; j < b.ye(); ++j)
          for (PetscInt i = b.xs; i < b.xe(); ++i) {
            PetscInt fx = 0, fy = 0;
            const bool has = q == 0 ? find_point(col, cx, cy, i, i + 1, j - 1, j + 1, pass, fx, fy)
                                    : find_point(col, cx, cy, i - 1, i + 1, j, j + 1, pass, fx, fy);
            for (int k = 0; k < 3; ++k) {
              const double val = d[j][i][k];
              if (val == 0.0) continue;
              if (!has) unexplained("the strain rate of cell", i, j, val);
              const PetscInt r = it.global(i, j, k), c = iv.global(fx, fy, q);
              GF_PETSC(MatSetValue(out.B, r, c, val, INSERT_VALUES));
            }
          }
        GF_PETSC(DMDAVecRestoreArrayDOFRead(g.dm_ten(), D, &d));
      }
  GF_PETSC(MatAssemblyBegin(out.B, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(out.B, MAT_FINAL_ASSEMBLY));

  // C: a u-face (i, j) reads the cells i-1..i x j-1..j+1, a v-face (i, j) the cells
  // i-1..i+1 x j-1..j. kappa = 1 and no Coulomb traction (kappa_b = 0): the probe is kappa S.
  out.C = create_matrix(g.comm(), vel, out.d0, 18);
  GF_PETSC(VecSet(kappa, 1.0));
  Vec kb, sw;
  GF_PETSC(DMGetGlobalVector(g.dm_vel(), &kb));
  GF_PETSC(DMGetGlobalVector(g.dm_vel(), &sw));
  GF_PETSC(VecSet(kb, 0.0));
  GF_PETSC(VecSet(sw, 0.0));
  auto cell = [&](PetscInt x, PetscInt y) { return y >= 0 && y < b.ny && b.has_cell_x(x); };
  for (int k = 0; k < 3; ++k)
    for (int cx = 0; cx < col.nxc(); ++cx)
      for (int cy = 0; cy < 3; ++cy) {
        PetscScalar*** s;
        GF_PETSC(DMDAVecGetArrayDOF(g.dm_ten(), S, &s));
        for (PetscInt j = b.ys; j < b.ye(); ++j)
          for (PetscInt i = b.xs; i < b.xe(); ++i)
            for (int m = 0; m < 3; ++m)
              s[j][i][m] = (m == k && col.cx(i) == cx && Colours::cy(j) == cy) ? 1.0 : 0.0;
        GF_PETSC(DMDAVecRestoreArrayDOF(g.dm_ten(), S, &s));
        GF_PETSC(VecSet(force, 0.0));
        pred.add_plastic(kappa, S, kb, sw, force);
        const Vel* const* f;
        GF_PETSC(DMDAVecGetArrayRead(g.dm_vel(), force, &f));
        for (PetscInt j = b.ys; j < b.ye(); ++j)
          for (PetscInt i = b.xs; i < b.xe(); ++i)
            for (int q = 0; q < 2; ++q) {
              const double val = q == 0 ? f[j][i].u : f[j][i].v;
              if (val == 0.0) continue;
              PetscInt cxi = 0, cyj = 0;
              const bool has = q == 0 ? find_point(col, cx, cy, i - 1, i, j - 1, j + 1, cell, cxi, cyj)
                                      : find_point(col, cx, cy, i - 1, i + 1, j - 1, j, cell, cxi, cyj);
              if (!has) unexplained("the plastic force on the face", i, j, val);
              const PetscInt r = iv.global(i, j, q), c = it.global(cxi, cyj, k);
              GF_PETSC(MatSetValue(out.C, r, c, val, INSERT_VALUES));
            }
        GF_PETSC(DMDAVecRestoreArrayRead(g.dm_vel(), force, &f));
      }
  GF_PETSC(MatAssemblyBegin(out.C, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(out.C, MAT_FINAL_ASSEMBLY));

  GF_PETSC(DMRestoreGlobalVector(g.dm_vel(), &sw));
  GF_PETSC(DMRestoreGlobalVector(g.dm_vel(), &kb));
  GF_PETSC(DMRestoreGlobalVector(g.dm_cell(), &kappa));
  GF_PETSC(DMRestoreGlobalVector(g.dm_ten(), &S));
  GF_PETSC(DMRestoreGlobalVector(g.dm_ten(), &D));
  GF_PETSC(DMRestoreGlobalVector(g.dm_vel(), &force));
  GF_PETSC(DMRestoreGlobalVector(g.dm_vel(), &zero_vel));
  GF_PETSC(DMRestoreGlobalVector(g.dm_vel(), &vel));
}

}  // namespace gf::momentum
