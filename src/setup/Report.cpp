// The `granflow check` report: scales, numbers and the cost estimate (setup/Report.hpp).
#include "setup/Report.hpp"

#include <petscsys.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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
  if (rh.yield != Yield::None && rh.newton) {
    os << "           plastic step (eq. 31) solved exactly, theta = 0: semismooth Newton to a "
          "residual < "
       << g4(rh.newton_tol) << ", at most " << rh.newton_max_iter << " iterations; r_factor = "
       << g4(rh.r_factor) << " (does not change the answer); "
       << (rh.newton_coupled ? "with the pressure in the same system (newton_pressure = coupled)"
                             : "then the projection of eq. 32 (newton_pressure = projection)")
       << "; wall load "
       << (rh.newton_wall_iterate ? "from the iterate (newton_wall_load = iterate)"
                                  : "from the step's start (newton_wall_load = step_start)")
       << "\n";
  } else if (rh.yield != Yield::None) {
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
  if (c.side_walls.width > 0) {
    const auto& sw = c.side_walls;
    os << "side walls channel width W = " << g4(sw.width) << " m: grains ";
    if (sw.friction_angle_deg > 0)
      os << format_number(sw.friction_angle_deg) << " deg (tan " << g4(sw.tan_friction())
         << "), body force up to (2/W) tan K p = " << g4(2 / sw.width * sw.tan_friction() *
                                                        sw.earth_pressure)
         << (sw.hydrostatic ? " p_hyd" : " p") << " /m (K = " << g4(sw.earth_pressure) << ")";
    else
      os << "no friction";
    os << "; air Navier slip eta_b = " << g4(sw.eta_b) << " Pa s/m\n";
  }
  if (c.gate.x > 0) {
    const auto& gt = c.gate;
    const double hx = c.hx;
    os << "gate       at x = " << g4(std::round(gt.x / hx) * hx) << " m, " << g4(gt.height)
       << " m high, lifted at " << g4(gt.speed) << " m/s";
    if (gt.speed > 0) os << " (clear of its height after " << g4(gt.height / gt.speed) << " s)";
    os << "; grains " << (gt.friction_angle_deg > 0 ? format_number(gt.friction_angle_deg) + " deg" : "frictionless")
       << ", air Navier slip eta_b = " << g4(gt.eta_b) << " Pa s/m\n";
  }
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

double memory_estimate_bytes(const CaseConfig& c, int nranks) {
  const double cells = static_cast<double>(c.nx) * c.ny;
  return std::max(nranks, 1) * kBytesPerRank +
         cells * (c.rheology.node_copy ? kBytesPerCellNodeCopy : kBytesPerCell);
}

namespace {

std::string gib(double bytes) { return g4(bytes / (1024.0 * 1024 * 1024)) + " GiB"; }

// PETSc's processor grid for an M x N DMDA on `size` ranks (DMSetUp_DA_2D, PETSc 3.18): the
// counts asked for, else the most square split, the longer side cut more often.
std::array<long long, 2> petsc_processor_grid(long long M, long long N, int size, int px,
                                              int py) {
  long long m = px, n = py;
  if (m <= 0 || n <= 0) {
    if (n > 0)
      m = size / n;
    else if (m > 0)
      n = size / m;
    else {
      m = static_cast<long long>(0.5 + std::sqrt(static_cast<double>(M) * size / N));
      if (m == 0) m = 1;
      while (m > 0) {
        n = size / m;
        if (m * n == size) break;
        --m;
      }
      if (M > N && m < n) std::swap(m, n);
    }
  }
  return {std::max(m, 1LL), std::max(n, 1LL)};
}

}  // namespace

std::vector<std::string> resource_problems(const CaseConfig& c, int nranks,
                                           double available_bytes, int da_px, int da_py) {
  std::vector<std::string> out;
  nranks = std::max(nranks, 1);
  const double cells = static_cast<double>(c.nx) * c.ny;
  const std::string grid = "grid.n = " + std::to_string(c.ny) + " (" + std::to_string(c.nx) +
                           " x " + std::to_string(c.ny) + " = " + g4(cells) + " cells)";
  // PETSc indexes with PetscInt: the global size of every field, and each rank's nonzeros of
  // a matrix (its row pointers), must fit.
  const double max_int = static_cast<double>(std::numeric_limits<PetscInt>::max());
  const std::string bits = std::to_string(8 * sizeof(PetscInt)) + "-bit";
  const double node_values = 3.0 * (c.nx + 1.0) * (c.ny + 1.0);  // S at the nodes, 3 each
  if (node_values > max_int)
    out.push_back(grid + ": the largest field (the plastic tensor at the nodes, 3 values per "
                  "node) has " + g4(node_values) + " values, beyond PETSc's " + bits +
                  " index limit " + g4(max_int) + ": at most about " + g4(max_int / 3) +
                  " cells (this PETSc is built with " + bits + " PetscInt)");
  const double nnz_rank = 36.0 * cells / nranks;  // viscous matrix: 2 unknowns x 18 per row
  if (node_values <= max_int && nnz_rank > max_int)
    out.push_back(grid + " on " + std::to_string(nranks) + " rank(s): each rank's part of the "
                  "viscous matrix has " + g4(nnz_rank) + " nonzeros (36 per cell), beyond "
                  "PETSc's " + bits + " index limit " + g4(max_int) + ": use at least " +
                  std::to_string(static_cast<long long>(std::ceil(36.0 * cells / max_int))) +
                  " ranks or a smaller grid.n");
  // Each rank's part of the grid must be at least as wide as the stencil (kGhost = 3 cells for
  // WENO5): PETSc refuses thinner parts.
  const auto [m, n] = petsc_processor_grid(c.nx, c.ny, nranks, da_px, da_py);
  const long long ghost = 3;
  const auto thin = [&](long long cells_side, long long parts, const char* side,
                        const char* key) {
    if (cells_side / parts < ghost)
      out.push_back(grid + " on " + std::to_string(nranks) + " ranks: the processor grid " +
                    std::to_string(m) + " x " + std::to_string(n) + " cuts " + side + " into " +
                    std::to_string(parts) + " parts of " + std::to_string(cells_side / parts) +
                    " cells, thinner than the stencil (" + std::to_string(ghost) +
                    " cells): use at most " + std::to_string(cells_side / ghost) +
                    " parts there (fewer ranks, -da_processors_" + key + "), or a larger grid");
  };
  if (m * n == nranks) {  // otherwise the grid says that the processor grid does not fit
    thin(c.nx, m, "nx", "x");
    thin(c.ny, n, "ny", "y");
  }
  const double need = memory_estimate_bytes(c, nranks);
  if (available_bytes > 0 && need > available_bytes)
    out.push_back(grid + " on " + std::to_string(nranks) + " rank(s) needs about " + gib(need) +
                  " of memory (" + g4((c.rheology.node_copy ? kBytesPerCellNodeCopy
                                                              : kBytesPerCell) / 1024) +
                  " KiB per cell and " + g4(kBytesPerRank / (1024 * 1024)) +
                  " MiB per rank, the measured peak of case A), more than the " +
                  gib(available_bytes) + " available on the machine(s) of the ranks: use a "
                  "smaller grid.n (memory grows as grid.n^2), or more machines");
  return out;
}

double initial_dt(const CaseConfig& c) {
  if (c.time.dt > 0) return c.time.dt;
  const double U = velocity_scale(c);
  const double h = std::min(c.hx, c.hy);
  return U > 0 ? std::min(c.time.cfl * h / U, c.time.dt_max) : c.time.dt_max;
}

std::string describe_case(const CaseConfig& c, int nranks, double available_bytes) {
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
    os << (c.interface.method == interface::Method::Clsvof
               ? "two phases (clsvof: conserved volume fraction + level set), initial "
               : "two phases (level set), initial ")
       << to_string(c.initial.shape) << "\n";
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
  plastic = plastic || (c.side_walls.width > 0 && c.side_walls.friction_angle_deg > 0);
  const double per = plastic ? kSecondsPerCellStepPlastic : kSecondsPerCellStep;
  const double seconds = static_cast<double>(cells) * steps * per / nranks;
  os << "estimate   " << g4(steps) << " steps (" << (capped ? "time.max_steps" : "t_end / first dt")
     << "); run time about " << g4(seconds) << " s (" << g4(seconds / 3600) << " h) on " << nranks
     << (nranks == 1 ? " rank" : " ranks")
     << "\n           (an estimate: " << g4(per) << " s per cell per step on one core"
     << (plastic ? " with the fixed point of eq. 31" : "") << ", perfect scaling assumed;\n"
        "           adaptive steps and solver iterations change the real cost)\n";
  os << "memory     about " << gib(memory_estimate_bytes(c, nranks)) << " on " << nranks
     << (nranks == 1 ? " rank" : " ranks") << " ("
     << g4((c.rheology.node_copy ? kBytesPerCellNodeCopy : kBytesPerCell) / 1024)
     << " KiB per cell + " << g4(kBytesPerRank / (1024 * 1024)) << " MiB per rank)";
  if (available_bytes > 0) os << "; " << gib(available_bytes) << " available";
  os << "\n";
  for (const auto& w : c.warnings) os << "warning    " << w << "\n";
  return os.str();
}

}  // namespace gf
