#pragma once
// The prognostic and derived fields of the two-phase model, as PETSc global vectors on the
// grid's DMs. A model's state is what a checkpoint must hold to continue a run exactly.
#include <petscvec.h>

#include "grid/Grid.hpp"

namespace gf {

// Owning wrapper around a PETSc Vec (destroyed with the object).
class Field {
 public:
  Field() = default;
  Field(DM dm, const char* name);
  ~Field();
  Field(const Field&) = delete;
  Field& operator=(const Field&) = delete;
  Field(Field&& o) noexcept : v_(o.v_) { o.v_ = nullptr; }
  Field& operator=(Field&& o) noexcept;
  operator Vec() const { return v_; }
  Vec vec() const { return v_; }

 private:
  Vec v_ = nullptr;
};

struct State {
  explicit State(const Grid& g);
  // Prognostic: level set, velocity at t^n and t^{n-1}, pressure p^n, plastic tensor S^n.
  Field phi;      // dm_cell, m (signed distance; > 0 air, < 0 granular)
  // dm_cell, the granular volume fraction of each cell, 0..1: with interface.method = "clsvof"
  // the conserved field that carries the granular mass (vof/Vof.hpp), phi being rebuilt from it;
  // unused (0) with the level set alone.
  Field frac;
  Field vel;      // dm_vel, m/s, u^n (divergence free)
  Field vel_old;  // dm_vel, m/s, u^{n-1}
  Field p;        // dm_cell, Pa
  Field S;        // dm_ten, dimensionless (Sxx, Sxy, Syy), |S| <= 1 (eq. 29)
  Field S_node;   // dm_node, the node copy of S (rheology.plastic_grid = "cell_node"), else 0
  Field s_wall;   // dm_vel, dimensionless, |s_t| <= 1: Coulomb wall stress direction (eq. 30),
                  // stored on the wall faces (momentum/Momentum.hpp, wall storage)
  // dm_vel, m/s: the last step's prediction u~ (before the projection), where the exact plastic
  // step (rheology.solver = newton) starts its Newton iteration (checkpointed with it); else 0.
  Field vel_pred;
  Field s_side;   // dm_vel read as a cell-centred vector, |s| <= 1: the direction of the side
                  // walls' friction (boundary/SideWalls.hpp); 0 without side walls
  // Derived from phi (refreshed by the stepper): density and viscosity at cell centres.
  Field rho;      // dm_cell, kg/m^3, eq. 25
  Field eta;      // dm_cell, Pa s, harmonic mean with the height fraction (section 3.1)
  double t = 0;        // s
  double dt = 0;       // s, the step that led to t
  double dt_old = 0;   // s, the step before (variable-step BDF2)
  long long step = 0;
};

}  // namespace gf
