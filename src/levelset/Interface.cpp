#include "levelset/Interface.hpp"

#include <cmath>

#include "core/Profile.hpp"

namespace gf::levelset {

InterfaceStage::InterfaceStage(const Grid& g, const RedistanceConfig& rc)
    : rc_(rc), advector_(g), redistancer_(g, rc.iters, rc.cfl) {
  redistancer_.set_wall_extrapolation(rc.wall_extrapolate);
}

bool InterfaceStage::redistance_due(double t, long long step, double dt) const {
  if (rc_.interval > 0) {
    // The step from t to t + dt redistances if it reaches the next multiple of the interval
    // (k I with t < k I <= t + dt; the relative slack absorbs the round-off of summed dts, so a
    // dt that divides the interval gives every (interval / dt)-th step, like redistance_every).
    const double slack = 1e-9 * rc_.interval;
    const auto k_before = std::floor((t + slack) / rc_.interval);
    const auto k_after = std::floor((t + dt + slack) / rc_.interval);
    return k_after > k_before;
  }
  return rc_.every > 0 && (step + 1) % rc_.every == 0;
}

bool InterfaceStage::advance(Vec phi, Vec vel, double t, long long step, double dt) {
  {
    prof::Scope ps(prof::Advect);
    advector_.step(phi, vel, dt);  // eq. 26
  }
  if (!redistance_due(t, step, dt)) return false;
  prof::Scope ps(prof::Redistance);
  // levelset.redistance_tol: only when transport has made phi drift from a distance. Each
  // redistancing moves the zero level a little (most where it meets a wall at a shallow angle);
  // a deposit at rest, whose phi does not change, should not be eroded by it.
  if (rc_.tol > 0 && !(redistancer_.distance_defect(phi) > rc_.tol)) return false;
  redistancer_.run(phi);
  return true;
}

}  // namespace gf::levelset
