#pragma once
// What `granflow check` tells a user before any computation: the grid, the model, the velocity
// scale and the first time step, the dimensionless numbers, and the estimated steps and cost.
#include <string>

#include "setup/Case.hpp"

namespace gf {

// The report of `granflow check`: grid, h, first dt, dimensionless numbers, estimated steps
// and run time on `nranks` ranks.
std::string describe_case(const CaseConfig& c, int nranks);
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
