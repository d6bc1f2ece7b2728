#pragma once
// The interface stage of a time step (section 3.1): phi^{n+1} from eq. 26 with the solenoidal
// u^n (WENO5 + TVD-RK3, Advector), redistanced (Min 2010, Redistancer) when due: every
// redistance_every steps, or, with redistance_interval > 0, in the step that reaches each
// multiple of the interval; with redistance_tol > 0 only if phi has drifted from a distance.
// Shared by the two-phase flow (stepper/) and the prescribed flows of the level-set benchmarks.
#include <petscvec.h>

#include <memory>

#include "grid/Grid.hpp"
#include "levelset/LevelSet.hpp"

namespace gf::levelset {

struct RedistanceConfig {
  int every = 5;          // steps, 0 = never
  double interval = 0;    // s; > 0: in the step reaching each multiple of it (not by `every`)
  double tol = 0;         // > 0: only when max | |grad phi| - 1 | near phi = 0 exceeds it
  bool wall_extrapolate = false;  // levelset.redistance_wall = "extrapolate"
  int iters = 10;         // pseudo-time iterations
  double cfl = 0.5;       // pseudo-time CFL
};

class InterfaceStage {
 public:
  InterfaceStage(const Grid& g, const RedistanceConfig& rc);
  // Whether the step from t (step number `step`, 0 for the first) of length dt redistances phi.
  bool redistance_due(double t, long long step, double dt) const;
  // Advances phi (global Vec) by dt with the face velocity vel; returns whether phi was
  // redistanced. Collective.
  bool advance(Vec phi, Vec vel, double t, long long step, double dt);

 private:
  RedistanceConfig rc_;
  Advector advector_;
  Redistancer redistancer_;
};

}  // namespace gf::levelset
