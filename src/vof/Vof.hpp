#pragma once
// The conservative volume fraction of the granular phase (interface.method = "clsvof"):
//
//  * c, cell centred on grid.dm_cell(), the granular volume fraction of each cell, 0 <= c <= 1:
//    the granular mass is rho_s sum c hx hy, and the density of a cell rho_f (1 - c) + rho_s c;
//  * transport by the direction-split geometric scheme of Weymouth & Yue (2010, "Conservative
//    Volume-of-Fluid method for free-surface simulations on Cartesian-grids", J. Comput. Phys.
//    229:2853-2865): one sweep per direction, in alternating order from step to step (Strang-like),
//      c^{k+1} = c^k - (F_{i+1/2} - F_{i-1/2}) + c_c (s_{i+1/2} - s_{i-1/2}),  s = u dt / h,
//    F the granular volume (in cell units) that crosses the face in the sweep, cut out of the
//    upwind cell's PLIC interface (vof/Plic.hpp) as the strip of width |s| next to the face, and
//    c_c = 1 where c^n > 1/2, else 0, frozen over the sweeps of one step. Summed over the sweeps
//    the c_c terms are c_c dt div(u), which vanishes for a solenoidal u: the granular volume is
//    then conserved to round-off (the fluxes cancel in pairs, the walls carry none), and
//    0 <= c <= 1 holds for |s| <= 1/2 (their section 3);
//  * the coupling with the level set of CLSVOF (Sussman & Puckett 2000, J. Comput. Phys.
//    162:301-337): the interface normals come from the level set phi (grad phi, phi > 0 in the
//    air), the position of the interface in each cell from c; phi is then rebuilt as the signed
//    distance to that PLIC interface (rebuild_distance), so that phi, which granflow keeps for
//    normals, the height fractions of the viscosity and the front measures, never drifts from
//    the conserved mass.
//
// Conventions of grid/Grid.hpp (global [j][i] indices, walls carry u.n = 0, periodic x wraps).
#include <petscdmda.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/Error.hpp"
#include "grid/Grid.hpp"
#include "vof/Plic.hpp"

namespace gf::vof {

// Fractions within this of 0 or 1 count as an empty or a full cell (no interface in it).
inline constexpr double kCut = 1e-12;
// A cell holds granular mass where c > kMass (the yield-stress support, the Coulomb faces).
inline constexpr double kMass = 1e-9;

// ---------------------------------------------------------------------------------------------
// 1. The initial fraction: c of each owned cell from a signed distance d(x, y) (m, < 0 granular:
// the exact distance of the initial shape). A cell whose centre is further than its half
// diagonal from the interface is full or empty; a cut cell is split into 8 x 8 sub-squares and
// each sub-square's fraction is the PLIC area of d's tangent plane at its centre (exact for a
// straight interface, the sub-squares resolve corners and curvature).
template <class D>
void init_fraction(const Grid& g, Vec c, const D& d) {
  const Box& b = g.box();
  PetscScalar** ca;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), c, &ca));
  constexpr int M = 8;
  const double half_diag = 0.5 * std::hypot(b.hx, b.hy);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double d0 = d(b.xc(i), b.yc(j));
      if (std::abs(d0) > half_diag) {
        ca[j][i] = d0 < 0 ? 1.0 : 0.0;
        continue;
      }
      const double wx = b.hx / M, wy = b.hy / M;
      double sum = 0;
      for (int q = 0; q < M; ++q)
        for (int r = 0; r < M; ++r) {
          const double x = b.xf(i) + (r + 0.5) * wx, y = b.yf(j) + (q + 0.5) * wy;
          const double dc = d(x, y);
          // The tangent plane d(x) ~ dc + grad d . (x - x_c): granular where it is <= 0, i.e.
          // m1 X + m2 Y <= alpha in the sub-square's unit coordinates.
          const double gx = (d(x + 0.25 * wx, y) - d(x - 0.25 * wx, y)) / (0.5 * wx);
          const double gy = (d(x, y + 0.25 * wy) - d(x, y - 0.25 * wy)) / (0.5 * wy);
          const Line l{gx * wx, gy * wy, 0.5 * (gx * wx + gy * wy) - dc};
          sum += line_area(l.m1, l.m2, l.alpha);
        }
      ca[j][i] = sum / (M * M);
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), c, &ca));
}

// ---------------------------------------------------------------------------------------------
// 2. Interface reconstruction and transport.

// Where the normals of the PLIC reconstruction come from.
enum class Normals {
  LevelSet,  // grad phi (CLSVOF, Sussman & Puckett 2000), Youngs' c where phi is flat
  Youngs,    // -grad c by Youngs' 3 x 3 stencil (Youngs 1982)
};

// The PLIC line of cell (i, j) from c (and phi) read through LOCAL (ghosted) arrays; cells beyond
// a wall are replaced by the cell itself in the stencils (no ghost extrapolation).
// Returns false for a cell that is not cut (c <= kCut or c >= 1 - kCut).
bool reconstruct(const Box& b, const PetscScalar* const* c, const PetscScalar* const* phi,
                 Normals src, PetscInt i, PetscInt j, Line& l);

// One step of the Weymouth & Yue transport. Keeps what the consistent momentum transport
// (ops::momentum_transport) needs of the step: the granular volume flux of each sweep through
// each face, the fraction at the start of the step and the c_c field.
class Advector {
 public:
  explicit Advector(const Grid& g);
  ~Advector();
  Advector(const Advector&) = delete;
  Advector& operator=(const Advector&) = delete;

  // c (global, dm_cell) from t to t + dt with the face velocity vel (global, dm_vel; solenoidal
  // for the volume to be conserved). The first sweep is x on even steps, y on odd ones.
  // phi (global, dm_cell): the level set for the normals (Normals::LevelSet), or nullptr.
  // Collective.
  void step(Vec c, Vec vel, Vec phi, double dt, long long step, Normals src);

  // After step(): the first sweep's direction (0 = x, 1 = y); the fluxes F (dm_vel: .u = the x
  // sweep's F on the u-faces, .v = the y sweep's on the v-faces; signed along +x / +y, in cell
  // volumes); c^n and c_c (dm_cell). Owned entries.
  int first_dir() const { return first_dir_; }
  Vec flux() const { return flux_; }
  Vec c_start() const { return c0_; }
  Vec cc() const { return cc_; }
  // The largest |F| removed by clipping c to [0, 1] in the last step (collective): round-off for
  // |s| <= 1/2, more if the step broke the CFL bound of the scheme.
  double clipped() const { return clipped_; }

 private:
  const Grid& g_;
  Vec c0_ = nullptr, cc_ = nullptr, flux_ = nullptr;
  Vec lc_ = nullptr, lphi_ = nullptr, lvel_ = nullptr;
  int first_dir_ = 0;
  double clipped_ = 0;
  void sweep(int dir, Vec c, double dt, bool have_phi, Normals src);
};

// phi <- the signed distance (m, < 0 granular) to the PLIC interface of c, the normals from phi
// itself (Normals::LevelSet) or from c (Youngs), within kBand cells of a cut cell or of a face
// between a full and an empty cell; further away +-(kBand + 1) h with the sign of c - 1/2. The
// centre of a cut cell lies on the granular side of its own line exactly when c > 1/2 (a straight
// line through the centre of a square halves it), so the sign is that of 1/2 - c everywhere.
// Collective.
inline constexpr int kBand = 3;
void rebuild_distance(const Grid& g, Vec c, Vec phi, Normals src);

// ---------------------------------------------------------------------------------------------
// 3. Properties and supports from c.

// rho = rho_air (1 - c) + rho_gran c at the cells; eta the harmonic mean weighted by the air
// fraction 1 - c (the volume-fraction form of section 3.1's height-fraction mean), at the cells
// and (eta_node, a dm_cell Vec) at the nodes, from the mean c of the node's in-domain cells.
void update_properties(const Grid& g, Vec c, double rho_air, double rho_gran, double eta_air,
                       double eta_gran, Vec rho, Vec eta, Vec eta_node);
// The same with a granular viscosity field (mu(I), eq. 11); interior nodes only (as
// levelset::mix_viscosity).
void mix_viscosity(const Grid& g, Vec c, double eta_air, Vec eta_gran, Vec eta, Vec eta_node);
// The yield-stress support of rheology::yield_stress: weight c where the cell holds granular
// mass (c > kMass), -1 elsewhere.
void yield_support(const Grid& g, Vec c, Vec w);
// A phase field with the sign convention of phi (< 0 where the cell holds granular mass):
// kMass - c. What the Coulomb walls and the granular mask read instead of phi.
void phase_field(const Grid& g, Vec c, Vec ph);

// ---------------------------------------------------------------------------------------------
// 4. Diagnostics (collective).

// sum c hx hy, m^2 per metre.
double volume(const Grid& g, Vec c);
// The potential energy of the two phases in the gravity field g, J/m: each cell's granular mass
// rho_gran c hx hy at the centroid of its PLIC polygon and its air mass at the centroid of the
// rest (the normals as reconstruct(), from phi or c), -sum m (g . x). Second order where the
// cell-centred sum -sum rho_c (g . x_c) hx hy of a sharp fraction is first order (a column top
// half-way down a cell holds its water h/4 below the cell centre): with the cell-centred sum
// the released energy of the dam break lagged its kinetic energy by 2 % (16 cells per a) and
// 1 % (32) at T = 0.1.
double potential_energy(const Grid& g, Vec c, Vec phi, Normals src, double rho_air,
                        double rho_gran, const std::array<double, 2>& gravity);

// sum |c - c_exact| hx hy, m^2 (the usual L1 error of a volume fraction).
double l1_error(const Grid& g, Vec c, Vec c_exact);

}  // namespace gf::vof
