#pragma once
// The prescribed flows of the level-set benchmarks (section 3.1's transport and redistancing
// checked alone): the velocity is set at every step by a formula, the momentum equations are not
// solved, and only the interface moves. Kept here at the edge, beside the case that asks for it
// (flow.prescribed), so that the two-phase stepper has no branch for it.
//   rotation:      solid-body rotation with omega about (cx, cy) (Zalesak's disk);
//   single_vortex: LeVeque's vortex, reversed at t = period/2, back at t = period.
// Both bring the interface back to its start after one period, so the initial level set is the
// exact answer (ModelTraits::returns_to_start; summary.json area_change_pct and
// interface_l1_error_m2).
#include <memory>

#include "grid/Grid.hpp"
#include "interface/Interface.hpp"
#include "stepper/TimeStepper.hpp"

namespace gf {

enum class PrescribedFlow { None, Rotation, SingleVortex };

struct KinematicConfig {
  PrescribedFlow flow = PrescribedFlow::Rotation;
  double omega = 0, cx = 0, cy = 0;  // rad/s, m, m: rotation
  double period = 1;                 // s: single vortex
  levelset::RedistanceConfig redistance;
  interface::Method method = interface::Method::LevelSet;  // interface.method
  vof::Normals normals = vof::Normals::LevelSet;
  double eps = 0;                          // m, for the properties (eq. 25)
  double rho_air = 1.2, rho_gran = 1550;   // kg/m^3
  double eta_air = 1.8e-5, eta_gran = 0.5;  // Pa s
};

class KinematicStepper : public TimeStepper {
 public:
  KinematicStepper(const Grid& g, const KinematicConfig& cfg);
  ~KinematicStepper() override;
  const ModelTraits& traits() const override { return traits_; }
  void initialize(State& s) override;
  void resume(State& s) override {}
  StepStats step(State& s, double dt) override;
  void derived_fields(State& s, Vec Dnorm, Vec Snorm, Vec yielded) override;
  Vec kappa() const override { return kappa_; }

 private:
  const Grid& g_;
  KinematicConfig cfg_;
  ModelTraits traits_;
  interface::Interface interface_;
  Vec kappa_ = nullptr;  // no yield stress: zero
  void prescribe_velocity(State& s, double t) const;
};

}  // namespace gf
