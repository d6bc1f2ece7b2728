#pragma once
// The interface of the two-phase model, by either of its two methods (interface.method):
//
//  * level_set: the paper's (section 3.1). phi^{n+1} from eq. 26 (WENO5 + TVD-RK3), redistanced
//    when due (Min 2010); rho from the smeared Heaviside of eq. 25, eta the harmonic mean with the
//    height fraction; the granular volume is int (1 - H_eps(phi)), which the scheme does not
//    conserve (docs/LEVELSET_VOLUME.md).
//  * clsvof: a coupled level set and volume of fluid (Sussman & Puckett 2000). The granular
//    volume fraction c is transported by the conservative direction-split geometric scheme of
//    Weymouth & Yue (2010), with the PLIC normals of the level set advected beside it (eq. 26);
//    phi is then rebuilt as the signed distance to that PLIC interface (vof/Vof.hpp). The mass
//    is c's, conserved to round-off for a solenoidal velocity; rho = rho_f (1 - c) + rho_s c and
//    eta the harmonic mean with the air fraction 1 - c; the yield stress and the wall friction
//    act wherever c > 0 (the support of the mass). phi keeps the normals, the distances of the
//    collapse measures and the sign the rest of granflow reads.
//
// This layer owns the choice; the stepper (and the prescribed flows of the benchmarks) call it
// in the order of section 3.3 and never branch on the method themselves.
#include <petscvec.h>

#include <memory>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "levelset/Interface.hpp"
#include "levelset/LevelSet.hpp"
#include "vof/Vof.hpp"

namespace gf::interface {

enum class Method { LevelSet, Clsvof };

struct Config {
  Method method = Method::LevelSet;
  levelset::RedistanceConfig redistance;  // level_set only
  levelset::Props props;                  // densities, viscosities, eps (eq. 25)
  // level_set: the yield stress and the wall friction act where phi < yield_support (0: the
  // paper; eps: rheology.yield_support = "mass"). clsvof: where the cell holds granular mass.
  double yield_support = 0;
  vof::Normals normals = vof::Normals::LevelSet;  // clsvof: the PLIC normals
};

class Interface {
 public:
  Interface(const Grid& g, const Config& cfg);
  ~Interface();
  Interface(const Interface&) = delete;
  Interface& operator=(const Interface&) = delete;

  Method method() const { return cfg_.method; }
  bool conservative() const { return cfg_.method == Method::Clsvof; }
  const Config& config() const { return cfg_; }

  // At t = 0, from the initial phi and c: clsvof rebuilds phi as the distance to c's PLIC
  // interface (the normals of the initial phi), so that phi is c's from the start; the level
  // set keeps its phi. Collective.
  void initialize(State& s) const;

  // Step 1 of section 3.3: the interface from t^n to t^n + dt with the solenoidal face velocity
  // vel (u^n in the paper's scheme); s.t and s.step are those of t^n. Returns whether phi was
  // redistanced (level_set). Collective.
  bool advance(State& s, Vec vel, double dt);

  // Step 2: rho, eta at the cells and eta at the nodes (eta_node may be null).
  void properties(const State& s, Vec rho, Vec eta, Vec eta_node) const;
  // The harmonic means with a cell field of granular viscosity (mu(I), eq. 11).
  void mix_viscosity(const State& s, double eta_air, Vec eta_gran, Vec eta, Vec eta_node) const;
  // The granular volume fraction of each cell: 1 - H_eps(phi) (eq. 25) or c (eq. 15's weight).
  void granular_fraction(const State& s, Vec out) const;
  // The support of the yield stress, for rheology::yield_stress (weight >= 0 where kappa acts).
  void yield_support(const State& s, Vec w) const;
  // A field with phi's sign convention, < support_offset() where the cell counts as granular for
  // the Coulomb walls and the granular mask of the fixed point: phi itself (level_set), or
  // vof::kMass - c (clsvof, offset 0). Refreshed here and returned (valid until the next call).
  Vec phase(const State& s);
  double phase_offset() const { return conservative() ? 0.0 : cfg_.yield_support; }

  // The granular volume, m^2 per metre (collective): int (1 - H_eps(phi)) or sum c hx hy.
  double volume(const State& s) const;

  // clsvof, after advance(): the sweeps of the step (for the consistent momentum transport).
  const vof::Advector& sweeps() const { return *vof_; }

 private:
  const Grid& g_;
  Config cfg_;
  std::unique_ptr<levelset::InterfaceStage> ls_;  // level_set
  std::unique_ptr<levelset::Advector> phi_adv_;   // clsvof: phi for the normals
  std::unique_ptr<vof::Advector> vof_;            // clsvof
  Vec phase_ = nullptr;
};

}  // namespace gf::interface
