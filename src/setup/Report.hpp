#pragma once
// What `granflow check` tells a user before any computation: the grid, the model, the velocity
// scale and the first time step, the dimensionless numbers, and the estimated steps and cost.
#include <string>
#include <vector>

#include "setup/Case.hpp"

namespace gf {

// The report of `granflow check`: grid, h, first dt, dimensionless numbers, estimated steps,
// run time and memory on `nranks` ranks (with the memory the machines of the ranks have
// available, bytes, when known: > 0).
std::string describe_case(const CaseConfig& c, int nranks, double available_bytes = 0);

// Memory model of describe_case and resource_problems, from the peak resident memory of case A
// (Drucker-Prager, Coulomb walls, the fixed point with Anderson mixing, a probe) measured at
// grid.n = 64 and 256 (16384 and 262144 cells) on 1 rank: 88.6 and 715.1 MiB, i.e. 2.6 KiB per
// cell; 3.2 KiB with rheology.plastic_grid = "cell_node" (97.9 and 858.0 MiB); 2 ranks at
// n = 256: 780 MiB in all, the fixed cost of a process about 50 MiB. A cell holds the state
// (16 values: phi, u^n, u^{n-1}, p, S, the node copy of S, s_t, rho, eta), the step's work
// fields and Anderson's history, the viscous matrix (2 unknowns with a 3 x 3 stencil: 36
// nonzeros, 432 bytes in AIJ) with its copy for the local solves and its preconditioner, and
// the pressure matrix with its multigrid hierarchy. Newtonian runs use less (the water dam
// break: 2.3 KiB): an upper bound for them.
inline constexpr double kBytesPerCell = 2700;
inline constexpr double kBytesPerCellNodeCopy = 3300;
inline constexpr double kBytesPerRank = 50.0 * 1024 * 1024;
// The estimated peak memory of the run on `nranks` ranks, bytes (all ranks together).
double memory_estimate_bytes(const CaseConfig& c, int nranks);

// What makes the case impossible to run on `nranks` ranks although every key is in its
// range, each a message naming the key, the value and the limit: a field or a rank's part of
// the viscous matrix beyond PETSc's index range (32-bit PetscInt), a rank's part of the grid
// narrower than the stencil (3 cells, WENO5), more memory than available (bytes; 0 = unknown,
// not checked). `da_px`, `da_py`: the processor grid asked for (-da_processors_x/y; 0 = PETSc
// decides).
std::vector<std::string> resource_problems(const CaseConfig& c, int nranks,
                                           double available_bytes, int da_px = 0, int da_py = 0);
// Cost model of describe_case: wall seconds per cell per time step on one core. An estimate
// (measured orders of magnitude, not a promise): Newtonian phases (one viscous and one pressure
// solve per step), and a viscoplastic phase or Coulomb walls, whose fixed point of eq. 31 costs
// 20-30 viscous solves per step (case A at n = 64: ~85 s for 1061 steps, docs/PERFORMANCE.md).
inline constexpr double kSecondsPerCellStep = 1.5e-6;
inline constexpr double kSecondsPerCellStepPlastic = 5e-6;

// The velocity scale U of the case, m/s: |omega| R or the vortex peak for a prescribed flow;
// otherwise the largest of sqrt(|g| H) (H = top of the initial granular region, two-phase
// runs) and the wall speeds. 0 if nothing drives the flow.
double velocity_scale(const CaseConfig& c);
// The first time step, s: time.dt if > 0, else min(cfl min(hx, hy) / U, dt_max) (dt_max if
// U = 0).
double initial_dt(const CaseConfig& c);

}  // namespace gf
