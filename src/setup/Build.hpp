#pragma once
// From a validated case (setup/Case.hpp) to the objects of a run: the model's time stepper
// (the two-phase flow, or a prescribed flow of the level-set benchmarks), the schedule of the
// simulation, the initial level set and velocity. The only place that maps case keys onto
// solver structures.
#include <functional>
#include <memory>
#include <string>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "setup/Case.hpp"
#include "sim/Simulation.hpp"
#include "stepper/Stepper.hpp"
#include "stepper/TimeStepper.hpp"

namespace gf {

PhysicsConfig physics_from_case(const CaseConfig& c);
// The model of the case: Stepper (physics_from_case), or KinematicStepper for flow.prescribed.
std::unique_ptr<TimeStepper> make_stepper(const Grid& g, const CaseConfig& c);
RunConfig run_from_case(const CaseConfig& c, const std::string& out_dir);
// The signed distance of initial.shape (m, < 0 granular), with its periodic images in x.
std::function<double(double, double)> initial_distance(const CaseConfig& c);
// phi at t = 0 from initial.shape (a signed distance; phi = -1 m everywhere for a one-phase run).
void initial_levelset(const Grid& g, const CaseConfig& c, Vec phi);
// The granular volume fraction at t = 0 (vof::init_fraction of initial_distance; 1 everywhere
// for a one-phase run): the conserved field of interface.method = "clsvof".
void initial_fraction(const Grid& g, const CaseConfig& c, Vec frac);
// The velocity at t = 0 from initial.velocity into vel (and vel_old, the same field, so that a
// BDF2 history read before the first step sees a fluid already in motion rather than at rest).
// none: zero. vortex: the stream function, sampled at the nodes (i hx, j hy),
//   walls:      psi = A (Lx/pi) sin^2(pi x/Lx) sin^2(pi y/Ly),
//   periodic x: psi = A (Ly/pi) sin(2 pi x/Lx) sin^2(pi y/Ly)   (two counter-rotating cells
//               per period, u = A sin(2 pi x/Lx) sin(2 pi y/Ly); the shear across the seam
//               x = 0 = Lx is largest, v = -2 A (Ly/Lx) sin^2(pi y/Ly) there, where the wall
//               form, periodic as well, would leave the fluid at rest),
// and u = (psi(i, j+1) - psi(i, j))/hy, v = -(psi(i+1, j) - psi(i, j))/hx: the discrete
// divergence of every cell is zero to round-off, the normal velocity on every wall is zero, and
// psi has a double zero on the walls, so the tangential velocity vanishes there too (no slip).
void initial_velocity(const Grid& g, const CaseConfig& c, Vec vel, Vec vel_old);

}  // namespace gf
