#pragma once
// From a validated case (core/Case.hpp) to the objects of a run: the physics of the stepper,
// the schedule of the simulation, the initial level set. The only place that maps case keys
// onto solver structures.
#include "core/Case.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "sim/Simulation.hpp"
#include "stepper/Stepper.hpp"

namespace gf {

PhysicsConfig physics_from_case(const CaseConfig& c);
RunConfig run_from_case(const CaseConfig& c, const std::string& out_dir);
// phi at t = 0 from initial.shape (a signed distance; phi = -1 m everywhere for a one-phase run).
void initial_levelset(const Grid& g, const CaseConfig& c, Vec phi);

}  // namespace gf
