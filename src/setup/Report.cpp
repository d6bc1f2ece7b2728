// The `granflow check` report: scales, numbers and the cost estimate (setup/Report.hpp).
#include "setup/Report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "setup/Names.hpp"

namespace gf {

using namespace setup_detail;
using Shape = CaseConfig::Shape;
using Prescribed = CaseConfig::Prescribed;

// ------------------------------------------------------------------------------------------
// Scales and the `granflow check` report.
// ------------------------------------------------------------------------------------------

namespace {

struct Scale {
  double U = 0;     // m/s
  std::string why;  // how U was obtained
};

Scale velocity_scale_of(const CaseConfig& c) {
  const double Lx = c.domain.Lx, Ly = c.domain.Ly;
  if (c.flow.prescribed == Prescribed::Rotation) {
    // The fastest point of a solid-body rotation is the domain corner farthest from the centre.
    const double R = std::max(
        {std::hypot(c.flow.cx, c.flow.cy), std::hypot(Lx - c.flow.cx, c.flow.cy),
         std::hypot(c.flow.cx, Ly - c.flow.cy), std::hypot(Lx - c.flow.cx, Ly - c.flow.cy)});
    return {std::abs(c.flow.omega) * R, "|omega| x the farthest corner distance " + g4(R) + " m"};
  }
  if (c.flow.prescribed == Prescribed::SingleVortex)
    // LeVeque's field has peak speed 1 on the unit square; scaled to the domain: L per second.
    return {std::max(Lx, Ly), "single vortex: max(Lx, Ly) / (1 s), the peak of the standard field"};
  Scale s;
  const double H = granular_top(c);
  const double g = std::hypot(c.gravity[0], c.gravity[1]);
  if (c.levelset.enabled && H > 0 && g > 0) {
    s.U = std::sqrt(g * H);
    s.why = "sqrt(|g| H), H = " + format_number(H) + " m, the top of the initial granular region";
  }
  for (std::size_t k = 0; k < c.walls.size(); ++k)
    if (std::abs(c.walls[k].velocity) > s.U) {
      s.U = std::abs(c.walls[k].velocity);
      s.why = std::string("the ") + kSides[k] + " wall speed";
    }
  if (c.initial.velocity == CaseConfig::InitialVelocity::Vortex) {
    // Peak speed of the initial vortex (setup/Build.hpp): max(|u|, |v|) of its stream function.
    const double A = std::abs(c.initial.velocity_amplitude);
    const double U = c.periodic_x ? A * std::max(1.0, 2 * Ly / Lx) : A * std::max(1.0, Lx / Ly);
    if (U > s.U) {
      s.U = U;
      s.why = "the peak speed of the initial vortex (initial.velocity_amplitude)";
    }
  }
  return s;
}

// The lines "rheology ..." and "walls ..." of the report: the model, its parameters, the
// fixed point's relaxation at the first step, and the wall friction.
std::string rheology_text(const CaseConfig& c, double dt) {
  using Yield = CaseConfig::Yield;
  const auto& rh = c.rheology;
  std::ostringstream os;
  const std::string alpha =
      "alpha = " + format_number(rh.friction_angle_deg) + " deg, tan alpha = " + g4(rh.tan_alpha());
  os << "rheology   ";
  switch (rh.yield) {
    case Yield::None:
      os << "Newtonian granular phase (rheology.yield = none)";
      break;
    case Yield::Bingham:
      os << "Bingham (bingham): kappa = tau_y = " << g4(rh.tau_y) << " Pa";
      break;
    case Yield::DruckerPrager:
      os << "Drucker-Prager (dp): kappa = tan(alpha) p^+ (eq. 19), " << alpha;
      break;
    case Yield::Hydrostatic:
      os << "hydrostatic Drucker-Prager (hp): kappa = tan(alpha) p_hyd (eq. 15), " << alpha;
      break;
  }
  os << "\n           viscosity ";
  if (rh.viscosity == CaseConfig::Viscosity::MuI)
    os << "mu(I) (eq. 11): mu_inf = " << g4(rh.mu_inf) << ", I0 = " << g4(rh.I0)
       << ", d = " << g4(rh.d) << " m, clipped to [" << g4(rh.eta_min) << ", " << g4(rh.eta_max)
       << "] Pa s\n";
  else
    os << "constant: eta = phase.granular.eta = " << g4(c.granular.eta) << " Pa s\n";
  if (rh.yield != Yield::None) {
    const double theta = rh.theta_per_dt * dt;
    os << "           fixed point (eq. 31): theta = theta_per_dt x first dt = "
       << g4(rh.theta_per_dt) << " /s x " << g4(dt)
       << " s = " << (theta > 0.5 ? g4(theta) + ", capped at 0.5" : g4(theta))
       << "\n           r_factor = " << g4(rh.r_factor) << ", stop at a change < " << g4(rh.fp_tol)
       << " or after " << rh.fp_max_iter << " iterations\n"
       << "           plastic tensor S at the " << (rh.node_copy ? "cell centres and the nodes (half each)" : "cell centres") << "\n";
  }
  std::string friction;
  for (std::size_t k = 0; k < c.walls.size(); ++k)
    if (c.walls[k].friction_angle_deg > 0)
      friction += (friction.empty() ? "" : ", ") + kSides[k] + " " +
                  format_number(c.walls[k].friction_angle_deg) + " deg (tan " +
                  g4(c.walls[k].tan_friction()) + ")";
  os << "walls      ";
  for (std::size_t k = 0; k < c.walls.size(); ++k)
    if (!c.periodic_x || k >= CaseConfig::kBottom)
      os << (k && !(c.periodic_x && k == CaseConfig::kBottom) ? ", " : "") << kSides[k] << " "
         << to_string(c.walls[k].type);
  if (c.periodic_x) os << "; periodic in x (no left/right walls)";
  os << "\n           Coulomb friction where the granular phase touches: "
     << (friction.empty() ? "none" : friction) << "\n";
  return os.str();
}

// The rheology's scales for the "numbers" lines: for a pressure-dependent yield stress, the
// pressure bound rho_s |g| H_c of the column and the yield stress it gives; the Bingham
// number Bi = kappa H / (eta U) (yield stress over viscous stress eta U / H) with kappa = tau_y
// (bingham) or tan(alpha) rho_s |g| H (dp, hp); for mu(I), the inertial number
// I = 2 d |D| / sqrt(p / rho_s) at |D| = U / H, p = rho_s |g| H.
void rheology_numbers(const CaseConfig& c, double U, std::vector<std::string>& numbers) {
  using Yield = CaseConfig::Yield;
  const auto& rh = c.rheology;
  const double H = granular_top(c);
  const double g = std::hypot(c.gravity[0], c.gravity[1]);
  if (H <= 0 || rh.yield == Yield::None) return;
  const double rho = c.granular.rho;
  const double p_max = rho * g * H;
  double kappa = rh.tau_y;
  if (rh.yield == Yield::DruckerPrager || rh.yield == Yield::Hydrostatic) {
    if (g <= 0) return;
    kappa = rh.tan_alpha() * p_max;
    numbers.push_back("pressure scale rho_s |g| H = " + g4(p_max) +
                      " Pa (bound of p in the granular column, H = " + g4(H) + " m)");
    numbers.push_back("yield stress scale tan(alpha) rho_s |g| H = " + g4(kappa) + " Pa");
  }
  if (U <= 0) return;
  double eta = c.granular.eta;
  std::string eta_text = "eta_gran";
  if (rh.viscosity == CaseConfig::Viscosity::MuI && rh.d > 0 && g > 0) {
    const double D = U / H;
    const double I = 2 * rh.d * D / std::sqrt(g * H);
    const double den = 2 * D + rh.I0 * std::sqrt(p_max) / (rh.d * std::sqrt(rho));
    const double raw = (rh.mu_inf - rh.tan_alpha()) * p_max / den;
    eta = std::clamp(raw, rh.eta_min, rh.eta_max);
    eta_text = "eta(I)";
    numbers.push_back("inertial number I = 2 d (U/H) / sqrt(|g| H) = " + g4(I));
    numbers.push_back("mu(I) viscosity there eta(I) = " + g4(eta) + " Pa s" +
                      (raw > rh.eta_max   ? " (capped by eta_max)"
                       : raw < rh.eta_min ? " (floored at eta_min)"
                                          : ""));
  }
  if (eta > 0)
    numbers.push_back("Bingham number Bi = kappa H / (" + eta_text +
                      " U) = " + g4(kappa * H / (eta * U)) + " (yield over viscous stress)");
}

}  // namespace

double velocity_scale(const CaseConfig& c) { return velocity_scale_of(c).U; }

double initial_dt(const CaseConfig& c) {
  if (c.time.dt > 0) return c.time.dt;
  const double U = velocity_scale(c);
  const double h = std::min(c.hx, c.hy);
  return U > 0 ? std::min(c.time.cfl * h / U, c.time.dt_max) : c.time.dt_max;
}

std::string describe_case(const CaseConfig& c, int nranks) {
  std::ostringstream os;
  nranks = std::max(nranks, 1);
  const long long cells = static_cast<long long>(c.nx) * c.ny;
  const double h = std::min(c.hx, c.hy);
  const Scale sc = velocity_scale_of(c);

  os << "case       " << c.title << " (" << c.source << ")\n";
  os << "grid       " << c.nx << " x " << c.ny << " = " << cells << " cells on "
     << format_number(c.domain.Lx) << " m x " << format_number(c.domain.Ly) << " m; ";
  if (std::abs(c.hx - c.hy) <= 1e-12 * h)
    os << "h = " << format_number(c.hx) << " m\n";
  else
    os << "hx = " << format_number(c.hx) << " m, hy = " << format_number(c.hy) << " m\n";

  os << "model      ";
  if (c.flow.prescribed != Prescribed::None)
    os << "level set advected by the prescribed " << to_string(c.flow.prescribed)
       << " flow (momentum not solved)\n";
  else if (c.levelset.enabled)
    os << "two phases (level set), initial " << to_string(c.initial.shape) << "\n";
  else
    os << "single phase (the granular fluid fills the domain)\n";

  const double dt = initial_dt(c);
  if (c.flow.prescribed == Prescribed::None) os << rheology_text(c, dt);

  os << "velocity   U = " << g4(sc.U) << " m/s"
     << (sc.why.empty() ? " (nothing drives the flow)" : " = " + sc.why) << "\n";

  os << "time step  first dt = " << g4(dt) << " s (" << to_string(c.time.dt_mode) << "): ";
  if (c.time.dt > 0)
    os << "time.dt as given\n";
  else if (sc.U > 0 && c.time.cfl * h / sc.U > c.time.dt_max)
    os << "cfl h / U = " << g4(c.time.cfl * h / sc.U) << " s, capped by time.dt_max\n";
  else if (sc.U > 0)
    os << "cfl h / U with cfl = " << g4(c.time.cfl) << "\n";
  else
    os << "time.dt_max (no velocity scale)\n";

  std::vector<std::string> numbers;
  if (c.levelset.enabled && c.flow.prescribed == Prescribed::None)
    numbers.push_back("density ratio rho_gran/rho_air = " + g4(c.granular.rho / c.air.rho) +
                      "; viscosity ratio eta_gran/eta_air = " + g4(c.granular.eta / c.air.eta));
  if (c.flow.prescribed == Prescribed::None) {
    const double H = granular_top(c);
    if (c.levelset.enabled && H > 0)
      numbers.push_back("Re = rho_gran U H / eta_gran = " +
                        g4(c.granular.rho * sc.U * H / c.granular.eta) + " (H = " + g4(H) + " m)");
    for (std::size_t k = 0; k < c.walls.size(); ++k)
      if (c.walls[k].velocity != 0) {
        // A moving wall of length L drives a cavity: Re = rho U L / eta with its speed.
        const bool horizontal = k == CaseConfig::kBottom || k == CaseConfig::kTop;
        const double L = horizontal ? c.domain.Lx : c.domain.Ly;
        const double U = std::abs(c.walls[k].velocity);
        numbers.push_back(
            "cavity Re = rho U L / eta = " + g4(c.granular.rho * U * L / c.granular.eta) + " (" +
            kSides[k] + " wall, U = " + g4(U) + " m/s, L = " + g4(L) + " m)");
      }
  }
  if (c.flow.prescribed == Prescribed::None) rheology_numbers(c, sc.U, numbers);
  for (std::size_t k = 0; k < numbers.size(); ++k)
    os << (k == 0 ? "numbers    " : "           ") << numbers[k] << "\n";

  double steps = std::ceil(c.time.t_end / dt - 1e-9);
  const bool capped = c.time.max_steps > 0 && steps > static_cast<double>(c.time.max_steps);
  if (capped) steps = static_cast<double>(c.time.max_steps);
  bool plastic = c.rheology.yield != CaseConfig::Yield::None;
  for (const auto& w : c.walls) plastic = plastic || w.friction_angle_deg > 0;
  const double per = plastic ? kSecondsPerCellStepPlastic : kSecondsPerCellStep;
  const double seconds = static_cast<double>(cells) * steps * per / nranks;
  os << "estimate   " << g4(steps) << " steps (" << (capped ? "time.max_steps" : "t_end / first dt")
     << "); run time about " << g4(seconds) << " s (" << g4(seconds / 3600) << " h) on " << nranks
     << (nranks == 1 ? " rank" : " ranks")
     << "\n           (an estimate: " << g4(per) << " s per cell per step on one core"
     << (plastic ? " with the fixed point of eq. 31" : "") << ", perfect scaling assumed;\n"
        "           adaptive steps and solver iterations change the real cost)\n";
  for (const auto& w : c.warnings) os << "warning    " << w << "\n";
  return os.str();
}

}  // namespace gf
