#include "grid/Grid.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "core/Error.hpp"

namespace gf {

Grid::Grid(MPI_Comm comm, PetscInt nx, PetscInt ny, double Lx, double Ly, bool periodic_x)
    : comm_(comm) {
  if (nx < 8 || ny < 8) throw InputError("grid: nx and ny must be >= 8");
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  box_.nx = nx;
  box_.ny = ny;
  box_.Lx = Lx;
  box_.Ly = Ly;
  box_.hx = Lx / nx;
  box_.hy = Ly / ny;
  box_.periodic_x = periodic_x;

  // Periodic x: the ghost exchange wraps (cell -1 <- cell nx-1, ...), see Grid.hpp.
  const DMBoundaryType bx = periodic_x ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_GHOSTED;
  const DMBoundaryType bt = DM_BOUNDARY_GHOSTED;
  // The processor grid: PETSc's choice (it splits the longer side: 2 ranks on case A's 4n x n
  // cut it at x = Lx/2, which leaves all the granular cells, and all the plastic work, on rank
  // 0) unless -da_processors_x / -da_processors_y ask for another, e.g. 1 x 2 (cut in y).
  PetscInt pxo = PETSC_DECIDE, pyo = PETSC_DECIDE;
  GF_PETSC(PetscOptionsGetInt(nullptr, nullptr, "-da_processors_x", &pxo, nullptr));
  GF_PETSC(PetscOptionsGetInt(nullptr, nullptr, "-da_processors_y", &pyo, nullptr));
  auto fits = [&](PetscInt v) { return v == PETSC_DECIDE || (v >= 1 && size_ % v == 0); };
  if (!fits(pxo) || !fits(pyo) ||
      (pxo != PETSC_DECIDE && pyo != PETSC_DECIDE && pxo * pyo != size_)) {
    auto show = [](PetscInt v) {
      return v == PETSC_DECIDE ? std::string("unset") : std::to_string(v);
    };
    throw InputError("grid: -da_processors_x = " + show(pxo) + ", -da_processors_y = " +
                     show(pyo) + " do not fit the " + std::to_string(size_) +
                     " MPI ranks (each must divide it, their product must equal it)");
  }
  // PETSc refuses a split whose parts are thinner than the stencil: the user's grid and ranks
  // (setup/ checks this first; this is the last word if its prediction differs).
  try {
    GF_PETSC(DMDACreate2d(comm, bx, bt, DMDA_STENCIL_BOX, nx, ny, pxo, pyo, 1, kGhost, nullptr,
                          nullptr, &dm_cell_));
    GF_PETSC(DMSetUp(dm_cell_));
  } catch (const PetscFailure& e) {
    throw InputError("grid: " + std::to_string(nx) + " x " + std::to_string(ny) +
                     " cells cannot be split over " + std::to_string(size_) +
                     " MPI ranks with a stencil of " + std::to_string(kGhost) +
                     " cells: use fewer ranks or a larger grid (" + e.what() + ")");
  }
  // All other DMs copy the cell DM's parallel layout so that (i, j) is owned by the same rank.
  PetscInt px, py;
  const PetscInt *lx, *ly;
  GF_PETSC(DMDAGetInfo(dm_cell_, nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
                       nullptr, nullptr, nullptr, nullptr, nullptr));
  GF_PETSC(DMDAGetOwnershipRanges(dm_cell_, &lx, &ly, nullptr));
  for (PetscInt r = 0; r < px; ++r)
    if (lx[r] < kGhost) throw InputError("grid: too many ranks in x for nx = " + std::to_string(nx));
  for (PetscInt r = 0; r < py; ++r)
    if (ly[r] < kGhost) throw InputError("grid: too many ranks in y for ny = " + std::to_string(ny));

  auto make = [&](PetscInt dof, DMDAStencilType st, PetscInt w, DM* dm) {
    GF_PETSC(DMDACreate2d(comm, bx, bt, st, nx, ny, px, py, dof, w, lx, ly, dm));
    GF_PETSC(DMSetUp(*dm));
  };
  make(2, DMDA_STENCIL_BOX, kGhost, &dm_vel_);
  make(3, DMDA_STENCIL_BOX, 1, &dm_ten_);
  make(1, DMDA_STENCIL_STAR, 1, &dm_pres_);
  make(2, DMDA_STENCIL_BOX, 1, &dm_visc_);
  // Nodes (cell corners) 0..nx x 0..ny (0..nx-1 in x when periodic: node nx is node 0): the
  // node copy of the plastic tensor (rheology.plastic_grid = "cell_node"). Node (i, j) is owned
  // by the rank that owns cell (i, j); the last rank of a row/column also owns the wall nodes.
  {
    std::vector<PetscInt> nlx(lx, lx + px), nly(ly, ly + py);
    if (!periodic_x) nlx.back() += 1;
    nly.back() += 1;
    GF_PETSC(DMDACreate2d(comm, bx, bt, DMDA_STENCIL_BOX, periodic_x ? nx : nx + 1, ny + 1, px, py,
                          3, 1, nlx.data(), nly.data(), &dm_node_));
    GF_PETSC(DMSetUp(dm_node_));
  }
  // Cell centres. A periodic DMDA spaces its coordinates by (xmax - xmin)/nx, not /(nx - 1).
  GF_PETSC(DMDASetUniformCoordinates(dm_cell_, 0.5 * box_.hx,
                                     periodic_x ? Lx + 0.5 * box_.hx : Lx - 0.5 * box_.hx,
                                     0.5 * box_.hy, Ly - 0.5 * box_.hy, 0, 0));
  GF_PETSC(DMDAGetCorners(dm_cell_, &box_.xs, &box_.ys, nullptr, &box_.xm, &box_.ym, nullptr));
  MPI_Comm_split(comm, static_cast<int>(box_.xs), -static_cast<int>(box_.ys), &comm_column_);
}

Grid::~Grid() {
  if (comm_column_ != MPI_COMM_NULL) MPI_Comm_free(&comm_column_);
  DMDestroy(&dm_visc_);
  DMDestroy(&dm_node_);
  DMDestroy(&dm_pres_);
  DMDestroy(&dm_ten_);
  DMDestroy(&dm_vel_);
  DMDestroy(&dm_cell_);
}

double Grid::sum(double local) const {
  double g = 0;
  MPI_Allreduce(&local, &g, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return g;
}
double Grid::max(double local) const {
  double g = 0;
  MPI_Allreduce(&local, &g, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return g;
}
long long Grid::sum(long long local) const {
  long long g = 0;
  MPI_Allreduce(&local, &g, 1, MPI_LONG_LONG, MPI_SUM, comm_);
  return g;
}

void to_local(DM dm, Vec global, Vec local) {
  GF_PETSC(DMGlobalToLocalBegin(dm, global, INSERT_VALUES, local));
  GF_PETSC(DMGlobalToLocalEnd(dm, global, INSERT_VALUES, local));
}

void fill_velocity_ghosts(const Grid& g, Vel** vel) {
  const Box& b = g.box();
  const PetscInt G = Grid::kGhost;
  // Ghost range of this rank's local array. Outside-domain points exist only on ranks that
  // touch the wall, and those own at least kGhost cells there, so mirrors are local.
  const PetscInt gx0 = b.xs - G, gx1 = b.xe() + G, gy0 = b.ys - G, gy1 = b.ye() + G;
  // With periodic x the x ghosts are wrapped copies from the exchange: never outside.
  for (PetscInt j = gy0; j < gy1; ++j)
    for (PetscInt i = gx0; i < gx1; ++i) {
      const bool outx = !b.periodic_x && (i < 0 || i >= b.nx), outy = j < 0 || j >= b.ny;
      if (!outx && !outy) continue;
      const PetscInt im = !outx ? i : (i < 0 ? -1 - i : 2 * b.nx - 1 - i);
      const PetscInt jm = j < 0 ? -1 - j : (j >= b.ny ? 2 * b.ny - 1 - j : j);
      // Normal components beyond a wall are zero (the wall face i = nx / j = ny is eq. 20);
      // tangential ones are even mirrors, finite but never used by wall-aware kernels.
      vel[j][i].u = outx ? 0.0 : vel[jm][i].u;
      vel[j][i].v = outy ? 0.0 : vel[j][im].v;
    }
  // Wall faces stored in the owned range: i = 0 (u, unless periodic) and j = 0 (v).
  if (b.xs == 0 && !b.periodic_x)
    for (PetscInt j = gy0; j < gy1; ++j) vel[j][0].u = 0.0;
  if (b.ys == 0)
    for (PetscInt i = gx0; i < gx1; ++i) vel[0][i].v = 0.0;
}

}  // namespace gf
