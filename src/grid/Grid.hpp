#pragma once
// The uniform MAC grid on Omega = (0, Lx) x (0, Ly), distributed by PETSc DMDA
// (paper section 3.4: velocities on cell faces, p, phi and S at cell centres).
//
// Storage convention (all DMs share one parallel layout, nx x ny cells):
//  * cell-centred scalars (phi, p, rho, eta, S components): index (i, j) is cell i, j,
//    centre ((i + 1/2) hx, (j + 1/2) hy);
//  * velocity (dm_vel, dof 2, struct Vel): (i, j).u is the x-velocity on the LEFT face of cell
//    (i, j), at (i hx, (j + 1/2) hy); (i, j).v is the y-velocity on the BOTTOM face, at
//    ((i + 1/2) hx, j hy). Because u.n = 0 on every side (eq. 20), the wall faces i = 0,
//    i = nx (u) and j = 0, j = ny (v) carry zero normal velocity: faces i = 0 / j = 0 are
//    stored and kept at 0, faces i = nx / j = ny live in the ghost layer of local vectors
//    (DM_BOUNDARY_GHOSTED) and are filled with 0 by fill_velocity_ghosts().
//  * periodic x (Box::periodic_x, boundary.periodic_x): every DM is DM_BOUNDARY_PERIODIC in x,
//    so the x ghosts of local vectors hold the wrapped values (cell -1 is cell nx-1, face nx is
//    face 0) and kernels read them with unwrapped indices; the u-face i = 0 is then an ordinary
//    interior face (the same as face nx), there are no left/right walls, and the node (0, j) is
//    an interior node. MatSetValuesStencil wraps column indices -1 / nx likewise. Kernels ask
//    the Box (wall_u, has_cell_x, has_uface) instead of testing i == 0 / i + 1 < nx.
// Arrays from DMDAVecGetArray are indexed [j][i] with global indices.
#include <petscdmda.h>

#include <array>

namespace gf {

struct Vel {
  PetscScalar u, v;
};

// The owned index range of this rank and the global sizes: what every kernel loops over.
struct Box {
  PetscInt xs = 0, ys = 0, xm = 0, ym = 0;  // owned cells [xs, xs+xm) x [ys, ys+ym)
  PetscInt nx = 0, ny = 0;                  // global cells
  double hx = 0, hy = 0;                    // cell size, m
  double Lx = 0, Ly = 0;                    // domain size, m
  bool periodic_x = false;                  // the domain repeats in x: no left/right walls
  PetscInt xe() const { return xs + xm; }
  // x-direction topology (see the storage convention above). For i within the ghost width:
  //  wall_u(i): the u-face i is a left/right wall (i <= 0 or i >= nx, never if periodic);
  //  has_cell_x(i): cell column i exists (in the domain, or its periodic image);
  //  has_uface(i): u-face i exists (0 <= i <= nx, walls included, or its periodic image).
  bool wall_u(PetscInt i) const { return !periodic_x && (i <= 0 || i >= nx); }
  bool has_cell_x(PetscInt i) const { return periodic_x || (i >= 0 && i < nx); }
  bool has_uface(PetscInt i) const { return periodic_x || (i >= 0 && i <= nx); }
  PetscInt ye() const { return ys + ym; }
  double xc(PetscInt i) const { return (i + 0.5) * hx; }  // cell centre x, m
  double yc(PetscInt j) const { return (j + 0.5) * hy; }  // cell centre y, m
  double xf(PetscInt i) const { return i * hx; }          // left face x, m
  double yf(PetscInt j) const { return j * hy; }          // bottom face y, m
};

class Grid {
 public:
  static constexpr PetscInt kGhost = 3;  // WENO5 needs 3 cells on each side

  // periodic_x: DM_BOUNDARY_PERIODIC in x for every DM (boundary.periodic_x).
  Grid(MPI_Comm comm, PetscInt nx, PetscInt ny, double Lx, double Ly, bool periodic_x = false);
  ~Grid();
  Grid(const Grid&) = delete;
  Grid& operator=(const Grid&) = delete;

  MPI_Comm comm() const { return comm_; }
  const Box& box() const { return box_; }
  PetscInt nx() const { return box_.nx; }
  PetscInt ny() const { return box_.ny; }
  bool periodic_x() const { return box_.periodic_x; }
  double hx() const { return box_.hx; }
  double hy() const { return box_.hy; }
  int rank() const { return rank_; }
  int size() const { return size_; }

  DM dm_cell() const { return dm_cell_; }  // dof 1, box stencil, width 3: fields
  DM dm_vel() const { return dm_vel_; }    // dof 2 (Vel), box stencil, width 3: velocity
  DM dm_ten() const { return dm_ten_; }    // dof 3, box stencil, width 1: S = (Sxx, Sxy, Syy)
  DM dm_pres() const { return dm_pres_; }  // dof 1, star stencil, width 1: pressure matrix
  DM dm_visc() const { return dm_visc_; }  // dof 2, box stencil, width 1: viscous matrix
  // dof 3, box stencil, width 1, (nx+1) x (ny+1) nodes (nx x (ny+1) if periodic in x): the node
  // copy of S. Node (i, j) = (i hx, j hy); owned ranges as the cells', plus the last wall row.
  DM dm_node() const { return dm_node_; }
  // The ranks that own the same x range (a process column), ordered from the top down: for
  // sums along vertical columns (the hydrostatic pressure of eq. 15).
  MPI_Comm comm_column() const { return comm_column_; }

  // Collective sums and maxima over all ranks.
  double sum(double local) const;
  double max(double local) const;
  long long sum(long long local) const;

 private:
  MPI_Comm comm_;
  MPI_Comm comm_column_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  Box box_;
  DM dm_cell_ = nullptr, dm_vel_ = nullptr, dm_ten_ = nullptr, dm_pres_ = nullptr,
     dm_visc_ = nullptr, dm_node_ = nullptr;
};

// Ghost exchange of a global Vec into a local (ghosted) Vec of the same DM.
void to_local(DM dm, Vec global, Vec local);

// Sets the normal velocity on the four walls of a LOCAL (ghosted) velocity array to zero:
// faces i = 0 and i = nx for u, j = 0 and j = ny for v (eq. 20). Tangential ghost values
// outside the domain are set to NaN-free copies (mirror), never used by kernels that drop
// order at walls, but kept finite so no NaN can leak. With periodic x the x ghosts hold the
// wrapped values of the ghost exchange and are left alone (only the bottom/top are walls).
void fill_velocity_ghosts(const Grid& g, Vel** vel);

}  // namespace gf
