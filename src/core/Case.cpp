// The case schema (every parameter declared once), the cross-field checks, and the
// `granflow check` report. See Case.hpp.
#include "core/Case.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <map>
#include <ostream>
#include <sstream>

#include "core/Error.hpp"

namespace gf {

namespace {

// Names as written in case files, indexed by the enumerators of CaseConfig: the schema's
// choices and the string -> enum conversion both come from these, so they cannot drift.
const std::vector<std::string> kDtModes{"adaptive", "fixed"};
const std::vector<std::string> kShapes{"none",   "rectangle", "layer",
                                       "circle", "zalesak",   "trapezoid"};
const std::vector<std::string> kPrescribed{"none", "rotation", "single_vortex"};
const std::vector<std::string> kInitialVelocities{"none", "vortex"};
const std::vector<std::string> kInitialStresses{"zero", "equilibrium"};
const std::vector<std::string> kInitialPressures{"projection", "hydrostatic"};
const std::vector<std::string> kWalls{"free_slip", "no_slip", "navier"};
const std::vector<std::string> kProbeFields{"phi", "rho",    "u",      "v",     "speed",
                                            "p",   "eta",    "D_norm", "S_norm", "kappa"};
const std::vector<std::string> kSides{"left", "right", "bottom", "top"};
const std::vector<std::string> kYields{"none", "bingham", "dp", "hp"};
const std::vector<std::string> kPlasticGrids{"cell", "cell_node"};
const std::vector<std::string> kYieldSupports{"phase", "mass"};
const std::vector<std::string> kRedistanceWalls{"drop", "extrapolate"};
const std::vector<std::string> kViscosities{"constant", "mu_i"};

// Counts are stored as int; these bounds keep them (and nx * ny) far from overflow.
constexpr double kMaxCellsPerSide = 100000;

template <class E>
E enum_of(const std::vector<std::string>& names, const std::string& s) {
  const auto it = std::find(names.begin(), names.end(), s);
  // The registry has already checked s against the same list.
  return static_cast<E>(it == names.end() ? 0 : it - names.begin());
}

Range closed(double lo, double hi) {
  Range r = Range::ge(lo);
  r.hi = hi;
  return r;
}

// lo <= x < hi
Range closed_open(double lo, double hi) {
  Range r = closed(lo, hi);
  r.hi_open = true;
  return r;
}

// Compact number for reports: 4 significant digits.
std::string g4(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string probe_name_rule(const std::string& s) {
  const bool ok = !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
  });
  return ok ? "" : "must be made of letters, digits, _ and - only ([A-Za-z0-9_-]+)";
}

}  // namespace

const char* to_string(CaseConfig::DtMode v) { return kDtModes[static_cast<int>(v)].c_str(); }
const char* to_string(CaseConfig::Shape v) { return kShapes[static_cast<int>(v)].c_str(); }
const char* to_string(CaseConfig::Prescribed v) { return kPrescribed[static_cast<int>(v)].c_str(); }
const char* to_string(CaseConfig::InitialVelocity v) {
  return kInitialVelocities[static_cast<int>(v)].c_str();
}
const char* to_string(CaseConfig::Wall v) { return kWalls[static_cast<int>(v)].c_str(); }
const char* to_string(CaseConfig::ProbeField v) {
  return kProbeFields[static_cast<int>(v)].c_str();
}
const char* to_string(CaseConfig::Side v) { return kSides[static_cast<int>(v)].c_str(); }
const char* to_string(CaseConfig::Yield v) { return kYields[static_cast<int>(v)].c_str(); }
const char* to_string(CaseConfig::Viscosity v) { return kViscosities[static_cast<int>(v)].c_str(); }

bool CaseConfig::operator==(const CaseConfig& o) const {
  return title == o.title && domain == o.domain && nx == o.nx && ny == o.ny && hx == o.hx &&
         hy == o.hy && time == o.time && gravity == o.gravity && granular == o.granular &&
         air == o.air && rheology == o.rheology && levelset == o.levelset && initial == o.initial &&
         flow == o.flow && walls == o.walls && periodic_x == o.periodic_x && output == o.output && collapse == o.collapse &&
         solver == o.solver &&
         probes == o.probes;
}

// ------------------------------------------------------------------------------------------
// The schema: the one place where each parameter is declared. Defaults are case A of the
// paper (section 4.1: column 0.20 x 0.14 m in a 0.8 x 0.2 m box, rho_s = 1550, eta_0 = 0.5).
// ------------------------------------------------------------------------------------------

Params case_params() {
  Params p;
  p.add_string("title", "granflow case",
               "One line saying what this case is; copied to the output.");

  p.add_real("domain.Lx", "m", 0.8, Range::gt(0),
             "Domain length: Omega = (0, Lx) x (0, Ly); x = 0 is the back wall.");
  p.add_real("domain.Ly", "m", 0.2, Range::gt(0), "Domain height; y = 0 is the bottom.");

  p.add_int("grid.n", "cells", 64, closed(8, kMaxCellsPerSide), "Number of cells in y (ny).");
  p.add_int("grid.nx", "cells", 0, closed(8, kMaxCellsPerSide).or_zero(),
            "Number of cells in x; 0 = round(Lx/Ly * n), i.e. (near) square cells.");

  p.add_real("time.t_end", "s", 1.0, Range::gt(0), "Simulated end time.");
  p.add_enum("time.dt_mode", "adaptive", kDtModes,
             "adaptive: dt = cfl h / max|u| every step, within [dt_min, dt_max]; "
             "fixed: the same dt every step.");
  p.add_real("time.dt", "s", 0.0, Range::ge(0),
             "The fixed step (dt_mode = fixed) or the first step (adaptive); 0 = automatic: "
             "cfl h / U with the velocity scale U of `granflow check`, capped by dt_max.");
  p.add_real("time.cfl", "", 0.5, Range::open_closed(0, 1),
             "CFL number of the adaptive step (and of the automatic first step).");
  p.add_real("time.dt_max", "s", 1e-3, Range::gt(0), "Largest adaptive time step.");
  p.add_real("time.dt_min", "s", 1e-9, Range::gt(0),
             "An adaptive step below this stops the run as failed (a collapsing dt means "
             "the flow is blowing up).");
  p.add_int("time.max_steps", "steps", 0, Range::ge(0),
            "Stop after this many steps (of this run: a restart counts from the checkpoint); "
            "0 = unlimited.");
  p.add_real("time.max_speed", "m/s", 100.0, Range::gt(0),
             "A speed above this anywhere stops the run as blown up (exit code 4), before "
             "it turns into NaN: no flow of this solver (granular collapses, dam breaks: a "
             "few m/s) comes near it.");

  p.add_real2("physics.gravity", "m/s^2", {0.0, -9.81}, Range::any(), "Gravity (gx, gy).");

  p.add_real("phase.granular.rho", "kg/m^3", 1550, Range::gt(0),
             "Density rho_s of the granular phase (bulk: grain density x volume fraction).");
  p.add_real("phase.granular.eta", "Pa s", 0.5, Range::gt(0),
             "Viscosity eta_0 of the granular phase.");
  p.add_real("phase.air.rho", "kg/m^3", 1.2, Range::gt(0), "Density rho_f of the air.");
  p.add_real("phase.air.eta", "Pa s", 1.8e-5, Range::gt(0), "Viscosity eta_f of the air.");

  // Viscoplastic rheology of the granular phase (sections 2.1-2.2, 3.2-3.3). The air is
  // always Newtonian (kappa = 0, eq. 18).
  p.add_enum("rheology.yield", "none", kYields,
             "Yield stress kappa of the granular phase: none = Newtonian granular phase "
             "(eta = phase.granular.eta); bingham = constant yield stress tau_y; dp = "
             "Drucker-Prager kappa = tan(alpha) p^+ with the current pressure (eq. 19); hp = "
             "kappa = tan(alpha) p_hyd, the weight of the granular column above the point "
             "(eq. 15).");
  p.add_real("rheology.tau_y", "Pa", 0.0, Range::ge(0), "bingham: yield stress tau_y.");
  p.add_real("rheology.friction_angle", "degrees", 25.5, Range::open(0, 90),
             "Internal friction angle alpha, mu_s = tan(alpha); used by dp, hp and mu_i.");
  p.add_enum("rheology.viscosity", "constant", kViscosities,
             "Viscosity eta_s of the granular phase: constant = phase.granular.eta; mu_i = "
             "eq. 11, eta = (mu_inf - tan alpha) p / (2|D u| + I0 sqrt(p) / (d sqrt(rho_s))), "
             "clipped to [eta_min, eta_max]; needs yield = dp (with it, the mu(I) rheology).");
  p.add_real("rheology.mu_inf", "", 0.73, Range::gt(0),
             "mu_i: limiting friction coefficient mu_inf of eq. 11 (> tan alpha).");
  p.add_real("rheology.I0", "", 0.279, Range::gt(0), "mu_i: inertial number scale I0 of eq. 11.");
  p.add_real("rheology.d", "m", 0.0, Range::ge(0),
             "mu_i: particle diameter d of eq. 11; 0 = not given (an error with mu_i).");
  p.add_real("rheology.eta_min", "Pa s", 1e-3, Range::ge(0),
             "mu_i: floor of the mu(I) viscosity (where p -> 0); how often it acts is reported.");
  p.add_real("rheology.eta_max", "Pa s", 1.2, Range::gt(0),
             "mu_i: cap of the mu(I) viscosity (where |D u| -> 0); 1.2 Pa s is the bound "
             "observed in the paper; how often it acts is reported.");
  p.add_real("rheology.r_factor", "", 0.5, Range::gt(0),
             "Fixed point of eq. 31: the augmentation of the projection is r = r_factor (2 eta "
             "+ rho a0 h^2/dt) / kappa^2, a local choice (the paper: any r > 0). With theta > 0 "
             "the converged step depends on r / theta: where S stays inside the yield surface "
             "the material deforms with D = theta (S - S^n) / (r kappa), like an elastic solid "
             "that a larger r makes stiffer; the stresses there move with it (case A's peak "
             "granular pressure by up to 6 %, docs/VALIDATION.md \"Augmentation r\"). 1 "
             "oscillates on case A, 0.5 converges.");
  p.add_enum("rheology.plastic_grid", "cell", kPlasticGrids,
             "Where the plastic tensor S lives: cell = at the cell centres only, the shear rate "
             "there the mean of the four node shear rates (the paper, section 3.4); cell_node = "
             "a copy at the cell centres and one at the nodes, each carrying half of the plastic "
             "stress, so that the node shear rates and the cell normal rates are both seen "
             "exactly: the cell-only strain rate has near-null modes (u alternating row by row) "
             "that the yield stress cannot stop (docs/RHEOLOGY.md, cessation).");
  p.add_enum("rheology.yield_support", "phase", kYieldSupports,
             "Where the yield stress kappa and the Coulomb wall friction act: phase = where "
             "phi < 0 (the paper: kappa = 0 in the air, eq. 18; friction where phi < 0, eq. 22); "
             "mass = where phi < eps, i.e. wherever eq. 25 gives the cell granular mass "
             "(1 - H_eps > 0). With phase, the smeared band 0 < phi < eps is heavy but has "
             "neither yield stress nor wall friction: on a slope or at a shallow front it slides "
             "as a thin gravity current, so a pile whose slopes are below the friction angle "
             "does not stay at rest (docs/RHEOLOGY.md, pile at rest).");
  p.add_real("rheology.theta_per_dt", "1/s", 10.0, Range::gt(0),
             "Fixed point of eq. 31: pseudo-relaxation theta = theta_per_dt dt (theta = 10 dt "
             "in section 4.1.3), capped at 0.5.");
  p.add_real("rheology.fp_tol", "", 1e-4, Range::gt(0),
             "Fixed point of eq. 31: stop when the largest change of S and s_t in one "
             "iteration is below this.");
  p.add_real("rheology.fp_tol_u", "m/s", 0.0, Range::ge(0),
             "Fixed point of eq. 31: if > 0, also stop when the largest change of the velocity "
             "u~ in one iteration is below this (0: only fp_tol).");
  p.add_int("rheology.fp_max_iter", "", 50, closed(1, 1e6),
            "Fixed point of eq. 31: most iterations per time step.");
  p.add_real("rheology.fp_fail_change", "", 1.0, Range::gt(0),
             "Fixed point of eq. 31: a step that reaches fp_max_iter with its last change still "
             "above this has not converged (S or s_t oscillates; a sign flip is a change of 2) "
             "and stops the run as failed; below it, a step at the cap is a counted warning "
             "(case A at n = 32: 75 capped steps of 1060, the largest last change 0.12).");

  p.add_bool("levelset.enabled", true,
             "Two phases separated by the level set phi (< 0 granular, > 0 air). false: a "
             "single phase, phi ignored, the whole domain is the granular (heavy) fluid, "
             "e.g. a lid-driven cavity.");
  p.add_real("levelset.eps_cells", "cells", 1.5, Range::open_closed(0, 5),
             "Half-width eps of the smoothed Heaviside H_eps (section 3.1, eq. 25), in cells: "
             "eps = eps_cells h; the paper does not give it. A trade-off "
             "(docs/LEVELSET_VOLUME.md): cells with 0 < phi < eps are heavy but have no yield "
             "stress (kappa is sharp in sign(phi)), and after a collapse stops that band slides "
             "along the deposit and takes level-set volume with it, so the paper's cases use "
             "1.0 (case A, n = 64: volume change -0.5 % against -3.0 % with 1.5); but a narrower "
             "band puts a large yield stress at a free surface (Bingham) next to light faces, "
             "and the Coulomb block then slides 22-35 % too fast with 1.0 (2 % with 1.5).");
  p.add_int("levelset.redistance_every", "steps", 5, closed(0, 1e6),
            "Redistance phi every this many steps; 0 = never. Ignored when "
            "levelset.redistance_interval > 0.");
  p.add_real("levelset.redistance_interval", "s", 0.0, Range::ge(0),
             "> 0: redistance phi once every this many seconds of simulated time (in the step "
             "that reaches each multiple of it) instead of every redistance_every steps, so that "
             "a change of the time step does not change how often phi is redistanced. Each "
             "redistancing moves the zero level a little and where the interface meets a wall "
             "at a shallow angle that erodes granular volume: case B at n = 64 with dt = 1e-4 s "
             "gives runout 1.236 m redistanced every 5e-3 s and 0.970 m every 5 steps "
             "(docs/VALIDATION.md, time step). 0 = count steps.");
  p.add_real("levelset.redistance_tol", "", 0.0, Range::ge(0),
             "Redistance (when redistance_every or redistance_interval says so) only if phi has "
             "drifted from a signed distance near the interface: max | |grad phi| - 1 | over "
             "|phi| < 3h above this. "
             "0 = always. Each redistancing moves the zero level slightly, most where it meets a "
             "wall at a shallow angle; with a tolerance a deposit at rest is left alone.");
  p.add_enum("levelset.redistance_wall", "drop", kRedistanceWalls,
             "Redistancing next to a wall: drop = the differences that would need a cell beyond "
             "the wall are left out (information only leaves through walls); extrapolate = phi "
             "is continued linearly beyond the wall, so that an interface keeps its angle with "
             "the wall: where it meets the wall at a shallow angle (a pile's toe, a deposit's "
             "front) drop gives the wall-row cells their distance along the wall and erodes the "
             "granular mass there at every redistancing (docs/RHEOLOGY.md, pile at rest).");
  p.add_int("levelset.redistance_iters", "", 10, closed(1, 1000),
            "Pseudo-time iterations per redistancing.");
  p.add_real("levelset.redistance_cfl", "", 0.5, Range::open_closed(0, 1),
             "CFL number of the redistancing pseudo-time steps.");

  p.add_enum("initial.shape", "rectangle", kShapes,
             "Initial granular region (phi < 0): none; rectangle [x0, x1] x [y0, y1] (the "
             "column); layer 0 <= y <= height; circle (cx, cy, radius); zalesak: the circle "
             "with a vertical slot slot_width wide cut slot_depth up from its bottom, "
             "centred on cx (Zalesak's disc); trapezoid: a pile on the bottom, base [x0, x1], "
             "height `height`, both sides sloping at `slope`.");
  p.add_real("initial.x0", "m", 0.0, Range::any(), "rectangle: left edge.");
  p.add_real("initial.x1", "m", 0.2, Range::any(), "rectangle: right edge (the gate).");
  p.add_real("initial.y0", "m", 0.0, Range::any(), "rectangle: bottom edge.");
  p.add_real("initial.y1", "m", 0.14, Range::any(), "rectangle: top edge (column height).");
  p.add_real("initial.height", "m", 0.1, Range::gt(0), "layer: thickness of the layer.");
  p.add_real("initial.cx", "m", 0.5, Range::any(), "circle, zalesak: centre x.");
  p.add_real("initial.cy", "m", 0.75, Range::any(), "circle, zalesak: centre y.");
  p.add_real("initial.radius", "m", 0.15, Range::gt(0), "circle, zalesak: radius.");
  p.add_real("initial.slot_width", "m", 0.05, Range::gt(0), "zalesak: slot width.");
  p.add_real("initial.slot_depth", "m", 0.25, Range::gt(0),
             "zalesak: slot depth, from the bottom of the disc.");
  p.add_real("initial.slope", "degrees", 20.0, Range::open(0, 90),
             "trapezoid: angle of both sides of the pile with the horizontal.");
  p.add_enum("initial.velocity", "none", kInitialVelocities,
             "Initial velocity: none = at rest; vortex = one divergence-free cell from the "
             "stream function psi = A (Lx/pi) sin^2(pi x/Lx) sin^2(pi y/Ly) (with "
             "boundary.periodic_x: psi = A (Ly/pi) sin(2 pi x/Lx) sin^2(pi y/Ly)) sampled at "
             "the nodes, u = dpsi/dy, v = -dpsi/dx by node differences: exactly divergence "
             "free, zero normal velocity on the walls, and zero tangential velocity on the walls "
             "(compatible with no_slip). A cessation test for viscoplastic fluids.");
  p.add_real("initial.velocity_amplitude", "m/s", 0.0, Range::any(),
             "vortex: amplitude A: the peak of v with walls (u peaks at A Lx/Ly), the peak of "
             "u with periodic_x (v peaks at 2 A Ly/Lx).");

  p.add_enum("initial.stress", "zero", kInitialStresses,
             "Initial plastic stress S (and wall stress s_t): zero (the paper: the column is "
             "released with S = 0, and eq. 31's relaxation theta (S^n - S) builds the stresses "
             "over the first steps, while the material moves a little); equilibrium: before "
             "t = 0, pseudo-steps of eq. 31-32 from rest, each one's velocity discarded and its "
             "S, s_t and p kept, until the granular velocity one step makes is below "
             "initial.stress_tol (a statically admissible stress state where one exists: a "
             "pile, a block held by friction); summary.json: initial_stress_steps, initial_stress_speed_mps.");
  p.add_enum("initial.pressure", "projection", kInitialPressures,
             "Initial pressure p^0: projection (the pressure of a fluid released from rest: "
             "the projection of u* = g, which is below the column's weight near its free "
             "sides); hydrostatic (the column at rest behind its gate, the paper's 'initial "
             "static state' of Figs. 5 and 18: p^0 = int_y^Ly rho |g_y| ds in each column of "
             "cells). Only the first step's yield stress (eq. 19, from p^n) sees the "
             "difference: the projection of that step sets p^1.");
  p.add_int("initial.stress_max_steps", "steps", 1000, closed(1, 1e6),
            "equilibrium: pseudo-steps at most; a warning if the tolerance is not reached.");
  p.add_real("initial.stress_tol", "m/s", 1e-7, Range::gt(0),
             "equilibrium: the largest granular velocity (cells with phi < -eps) the last "
             "pseudo-step may make.");

  p.add_enum("flow.prescribed", "none", kPrescribed,
             "none: solve the momentum equations. Otherwise a level-set-only test with a "
             "prescribed velocity: rotation (solid body, omega about (cx, cy)); "
             "single_vortex (LeVeque's vortex, reversed at t = period/2, back at t = period).");
  p.add_real("flow.omega", "rad/s", 1.0, Range::any(),
             "rotation: angular velocity (counter-clockwise > 0).");
  p.add_real("flow.cx", "m", 0.5, Range::any(), "rotation: centre x.");
  p.add_real("flow.cy", "m", 0.5, Range::any(), "rotation: centre y.");
  p.add_real("flow.period", "s", 8.0, Range::gt(0), "single_vortex: period T.");

  for (const auto& side : kSides) {
    // The back wall (left) and the bottom are rough in the paper's column collapses: Navier
    // slip with eta_b = 1 (eq. 24); the open side and the top only bound the air.
    const bool rough = side == "left" || side == "bottom";
    const std::string b = "boundary." + side + ".";
    p.add_enum(b + "type", rough ? "navier" : "free_slip", kWalls,
               "Tangential condition on the " + side +
                   " wall (the normal velocity is 0): "
                   "free_slip (eq. 21), no_slip, or navier slip (eq. 24).");
    p.add_real(b + "eta_b", "Pa s/m", 1.0, Range::ge(0),
               "navier: slip coefficient eta_b of eq. 24 (0 = free slip, large = no slip).");
    p.add_real(b + "velocity", "m/s", 0.0, Range::any(),
               "Tangential wall velocity (no_slip, navier), e.g. a cavity lid; along +x on "
               "bottom/top, +y on left/right.");
    p.add_real(b + "friction_angle", "degrees", 0.0, closed_open(0, 90),
               "Wall friction angle alpha_b; 0 = none. Where the granular phase (phi < 0) "
               "touches this wall, Coulomb friction kappa_b = tan(alpha_b) (-T_n)^+ (eqs. "
               "22-23, 30) replaces `type`; where air touches it, `type` applies.");
  }

  p.add_bool("boundary.periodic_x", false,
             "The domain repeats in x (period Lx): no left/right walls; the boundary.left / "
             "boundary.right settings are then ignored (a non-zero friction_angle or velocity "
             "there is an error, any other setting a warning). The initial shapes must still "
             "lie inside the domain. For plane Poiseuille, inclined-layer and Bagnold flows.");

  p.add_real("output.interval", "s", 0.01, Range::gt(0),
             "Simulated time between diagnostics and probe samples.");
  p.add_real("output.vtk_interval", "s", 0.05, Range::ge(0),
             "Simulated time between VTK snapshots; 0 = no VTK.");
  p.add_real("output.progress_interval", "s", 2.0, Range::ge(0),
             "Wall-clock time between progress lines; 0 = none.");
  p.add_int("output.checkpoint_interval_steps", "steps", 0, Range::ge(0),
            "Write a checkpoint (OUT/checkpoint, for `granflow run --restart OUT`) every this "
            "many steps; 0 = none. A checkpoint is also written at the end of the run and on "
            "SIGINT/SIGTERM.");
  p.add_real("output.checkpoint_wall_s", "s", 600.0, Range::ge(0),
             "Write a checkpoint every this much wall-clock time, so that a run killed hard "
             "(SIGKILL, a node failure) loses at most this much work; 0 = none.");
  p.add_real("output.volume_warn_pct", "%", 1.0, Range::gt(0),
             "A change of the granular volume (diagnostics.csv volume_change_pct) beyond this "
             "is a warning: printed once, and the rows counted in summary.json "
             "(warnings_volume_drift_rows).");

  // Column-collapse measures (diagnostics/Collapse.hpp; profiles.csv, structure.csv,
  // deposit.csv and the collapse keys of summary.json). They read the state only.
  p.add_real_list("collapse.cutoffs", "", {0.075, 0.0075}, Range::open(0, 1),
                  "Basal deposit of section 4.2.5: the granular material whose speed is at most "
                  "cutoff x (the largest max granular |u| of the run so far), one deposit per "
                  "value (the paper uses 7.5 % and 0.75 %).");
  // Case A's deposit (our choice, the paper gives no slopes for it): a plateau on the back
  // wall to x ~ 0.04 m, then one slope to the gate and a flatter one beyond it.
  p.add_real2("collapse.slope_back_range", "m", {0.05, 0.15}, Range::ge(0),
              "Final deposit: the back slope is the least-squares slope of h(x) over the "
              "columns with x in this range (and x < front).");
  p.add_real2("collapse.slope_front_range", "m", {0.2, 0.8}, Range::ge(0),
              "Final deposit: the front slope is the least-squares slope of h(x) over the "
              "columns with x in this range (and x < front).");
  p.add_real("collapse.front_fit_length", "m", 0.02, Range::gt(0),
             "Final deposit: the front angle is the least-squares slope of h(x) over the "
             "columns within this distance behind the front.");
  p.add_real("collapse.speed_window", "s", 0.05, Range::gt(0),
             "Stages: the front speed at an output time is the least-squares slope of "
             "front_x(t) over the outputs within +- half this window.");
  p.add_real("collapse.plateau_fraction", "", 0.9, Range::open(0, 1),
             "Stages: the constant-speed phase [t1, t2] is the run of outputs around the "
             "fastest one whose front speed is >= this fraction of the largest.");
  p.add_real("collapse.stop_distance", "m", 1e-3, Range::gt(0),
             "Stages: t3 is the first output after which the front advances less than this.");
  p.add_real("collapse.rest_speed", "m/s", 1e-3, Range::gt(0),
             "Stages: tf is the first output from which the max granular |u| (outside the "
             "smeared interface band) stays below this to the end of the run.");

  p.add_real("solver.pressure_rtol", "", 1e-10, Range::open(0, 1),
             "Relative residual tolerance of the pressure solve (eq. 32).");
  p.add_real("solver.viscous_rtol", "", 1e-10, Range::open(0, 1),
             "Relative residual tolerance of the viscous solve (eq. 31).");
  p.add_int("solver.viscous_local_margin", "cells", 6, closed(0, 1000),
             "After the first viscous solve of a step, solve the fixed point's viscous problems "
             "only on the granular cells widened by this many cells, the others frozen, and end "
             "with one full solve (Predictor::begin_local); 0 = full solves throughout. "
             "summary.json: visc_polish_its_total, what the closing solves had to add.");
  p.add_string("solver.petsc_options", "",
               "Extra PETSc options, e.g. \"-pres_pc_type gamg\"; applied before the command "
               "line's, which therefore win.");

  Params probe;
  probe.add_string("name", std::nullopt, "Probe name, unique; used in output file names.",
                   probe_name_rule, "[A-Za-z0-9_-]+");
  probe.add_real("x0", "m", std::nullopt, Range::any(), "Segment start, x.");
  probe.add_real("y0", "m", std::nullopt, Range::any(), "Segment start, y.");
  probe.add_real("x1", "m", std::nullopt, Range::any(), "Segment end, x.");
  probe.add_real("y1", "m", std::nullopt, Range::any(), "Segment end, y.");
  probe.add_int("points", "", 101, closed(2, 1e6),
                "Samples along the segment, both ends included.");
  probe.add_string_list("fields", {"phi", "u", "v", "p"}, kProbeFields,
                        "Fields sampled: phi, rho (kg/m^3), u, v, speed (m/s), p (Pa), eta "
                        "(Pa s) and the plastic fields D_norm (|D(u)|, 1/s), S_norm (|S|, "
                        "< 1 where rigid) and kappa (yield stress, Pa), all cell centred.");
  p.add_table_array("probe", std::move(probe),
                    "A line probe: samples fields along a segment every output.interval.");
  return p;
}

void print_case_help(std::ostream& os) {
  os << "Case file parameters (TOML; units SI). Every key is optional unless marked "
        "required; unknown keys are errors.\n\n";
  case_params().print_help(os);
}

// ------------------------------------------------------------------------------------------
// Registry -> CaseConfig, and the checks that involve more than one key.
// ------------------------------------------------------------------------------------------

namespace {

using Shape = CaseConfig::Shape;
using Prescribed = CaseConfig::Prescribed;

// The top of the initial granular region, m (0 if there is none).
double granular_top(const CaseConfig& c) {
  if (!c.levelset.enabled) return c.domain.Ly;
  switch (c.initial.shape) {
    case Shape::Rectangle:
      return c.initial.y1;
    case Shape::Layer:
    case Shape::Trapezoid:
      return c.initial.height;
    case Shape::Circle:
    case Shape::Zalesak:
      return c.initial.cy + c.initial.radius;
    case Shape::None:
      return 0.0;
  }
  return 0.0;
}

CaseConfig fill(const Params& p) {
  CaseConfig c;
  c.source = p.source();
  c.title = p.get_string("title");
  c.domain = {p.get_real("domain.Lx"), p.get_real("domain.Ly")};
  c.ny = static_cast<int>(p.get_int("grid.n"));
  c.nx = static_cast<int>(p.get_int("grid.nx"));
  if (c.nx == 0) c.nx = static_cast<int>(std::lround(c.domain.Lx / c.domain.Ly * c.ny));
  c.hx = c.domain.Lx / std::max(c.nx, 1);
  c.hy = c.domain.Ly / c.ny;

  c.time.t_end = p.get_real("time.t_end");
  c.time.dt_mode = enum_of<CaseConfig::DtMode>(kDtModes, p.get_string("time.dt_mode"));
  c.time.dt = p.get_real("time.dt");
  c.time.cfl = p.get_real("time.cfl");
  c.time.dt_max = p.get_real("time.dt_max");
  c.time.dt_min = p.get_real("time.dt_min");
  c.time.max_steps = p.get_int("time.max_steps");
  c.time.max_speed = p.get_real("time.max_speed");

  c.gravity = p.get_real2("physics.gravity");
  c.granular = {p.get_real("phase.granular.rho"), p.get_real("phase.granular.eta")};
  c.air = {p.get_real("phase.air.rho"), p.get_real("phase.air.eta")};

  auto& rh = c.rheology;
  rh.yield = enum_of<CaseConfig::Yield>(kYields, p.get_string("rheology.yield"));
  rh.tau_y = p.get_real("rheology.tau_y");
  rh.friction_angle_deg = p.get_real("rheology.friction_angle");
  rh.viscosity = enum_of<CaseConfig::Viscosity>(kViscosities, p.get_string("rheology.viscosity"));
  rh.mu_inf = p.get_real("rheology.mu_inf");
  rh.I0 = p.get_real("rheology.I0");
  rh.d = p.get_real("rheology.d");
  rh.eta_min = p.get_real("rheology.eta_min");
  rh.eta_max = p.get_real("rheology.eta_max");
  rh.r_factor = p.get_real("rheology.r_factor");
  rh.theta_per_dt = p.get_real("rheology.theta_per_dt");
  rh.node_copy = p.get_string("rheology.plastic_grid") == "cell_node";
  rh.yield_on_mass = p.get_string("rheology.yield_support") == "mass";
  rh.fp_tol = p.get_real("rheology.fp_tol");
  rh.fp_tol_u = p.get_real("rheology.fp_tol_u");
  rh.fp_max_iter = static_cast<int>(p.get_int("rheology.fp_max_iter"));
  rh.fp_fail_change = p.get_real("rheology.fp_fail_change");

  c.levelset.enabled = p.get_bool("levelset.enabled");
  c.levelset.eps_cells = p.get_real("levelset.eps_cells");
  c.levelset.redistance_every = static_cast<int>(p.get_int("levelset.redistance_every"));
  c.levelset.redistance_iters = static_cast<int>(p.get_int("levelset.redistance_iters"));
  c.levelset.redistance_tol = p.get_real("levelset.redistance_tol");
  c.levelset.redistance_interval = p.get_real("levelset.redistance_interval");
  c.levelset.redistance_wall_extrapolate =
      p.get_string("levelset.redistance_wall") == "extrapolate";
  c.levelset.redistance_cfl = p.get_real("levelset.redistance_cfl");

  auto& in = c.initial;
  in.shape = enum_of<Shape>(kShapes, p.get_string("initial.shape"));
  in.x0 = p.get_real("initial.x0");
  in.x1 = p.get_real("initial.x1");
  in.y0 = p.get_real("initial.y0");
  in.y1 = p.get_real("initial.y1");
  in.height = p.get_real("initial.height");
  in.cx = p.get_real("initial.cx");
  in.cy = p.get_real("initial.cy");
  in.radius = p.get_real("initial.radius");
  in.slot_width = p.get_real("initial.slot_width");
  in.slot_depth = p.get_real("initial.slot_depth");
  in.slope_deg = p.get_real("initial.slope");
  in.velocity =
      enum_of<CaseConfig::InitialVelocity>(kInitialVelocities, p.get_string("initial.velocity"));
  in.velocity_amplitude = p.get_real("initial.velocity_amplitude");
  in.stress_equilibrium = p.get_string("initial.stress") == "equilibrium";
  in.pressure_hydrostatic = p.get_string("initial.pressure") == "hydrostatic";
  in.stress_max_steps = static_cast<int>(p.get_int("initial.stress_max_steps"));
  in.stress_tol = p.get_real("initial.stress_tol");

  c.flow.prescribed = enum_of<Prescribed>(kPrescribed, p.get_string("flow.prescribed"));
  c.flow.omega = p.get_real("flow.omega");
  c.flow.cx = p.get_real("flow.cx");
  c.flow.cy = p.get_real("flow.cy");
  c.flow.period = p.get_real("flow.period");

  for (std::size_t s = 0; s < kSides.size(); ++s) {
    const std::string b = "boundary." + kSides[s] + ".";
    c.walls[s].type = enum_of<CaseConfig::Wall>(kWalls, p.get_string(b + "type"));
    c.walls[s].eta_b = p.get_real(b + "eta_b");
    c.walls[s].velocity = p.get_real(b + "velocity");
    c.walls[s].friction_angle_deg = p.get_real(b + "friction_angle");
  }
  c.periodic_x = p.get_bool("boundary.periodic_x");

  c.output.interval = p.get_real("output.interval");
  c.output.vtk_interval = p.get_real("output.vtk_interval");
  c.output.progress_interval = p.get_real("output.progress_interval");
  c.output.checkpoint_interval_steps = p.get_int("output.checkpoint_interval_steps");
  c.output.checkpoint_wall_s = p.get_real("output.checkpoint_wall_s");
  c.output.volume_warn_pct = p.get_real("output.volume_warn_pct");

  auto& co = c.collapse;
  co.cutoffs = p.get_real_list("collapse.cutoffs");
  co.slope_back_range = p.get_real2("collapse.slope_back_range");
  co.slope_front_range = p.get_real2("collapse.slope_front_range");
  co.front_fit_length = p.get_real("collapse.front_fit_length");
  co.speed_window = p.get_real("collapse.speed_window");
  co.plateau_fraction = p.get_real("collapse.plateau_fraction");
  co.stop_distance = p.get_real("collapse.stop_distance");
  co.rest_speed = p.get_real("collapse.rest_speed");

  c.solver.pressure_rtol = p.get_real("solver.pressure_rtol");
  c.solver.viscous_rtol = p.get_real("solver.viscous_rtol");
  c.solver.viscous_local_margin = static_cast<int>(p.get_int("solver.viscous_local_margin"));
  c.solver.petsc_options = p.get_string("solver.petsc_options");

  for (const Params& item : p.items("probe")) {
    CaseConfig::Probe pr;
    pr.name = item.get_string("name");
    pr.x0 = item.get_real("x0");
    pr.y0 = item.get_real("y0");
    pr.x1 = item.get_real("x1");
    pr.y1 = item.get_real("y1");
    pr.points = static_cast<int>(item.get_int("points"));
    for (const auto& f : item.get_string_list("fields"))
      pr.fields.push_back(enum_of<CaseConfig::ProbeField>(kProbeFields, f));
    c.probes.push_back(std::move(pr));
  }
  return c;
}

// Cross-field validation. A check runs only if every key it reads holds an accepted value:
// a rejected value was reported already and now holds its default, so checking it again
// would only report a consequence of the first error. Nothing runs without a readable file.
void check(const Params& p, CaseConfig& c, InputErrors& errors) {
  const auto ok = [&](std::initializer_list<std::string> keys) {
    if (!p.file_ok()) return false;
    for (const auto& k : keys)
      if (!p.valid(k)) return false;
    return true;
  };
  const double Lx = c.domain.Lx, Ly = c.domain.Ly;
  const auto m = [](double v) { return format_number(v) + " m"; };

  // Grid.
  if (ok({"grid.n", "grid.nx", "domain.Lx", "domain.Ly"}) && p.get_int("grid.nx") == 0) {
    const double nx = std::round(Lx / Ly * c.ny);
    if (nx < 8 || nx > kMaxCellsPerSide)
      errors.add(p.where("grid.n") + ": gives grid.nx = round(Lx/Ly * n) = " + format_number(nx) +
                 ", outside [8, " + format_number(kMaxCellsPerSide) +
                 "]: change grid.n or set grid.nx");
  }
  if (ok({"grid.n", "grid.nx", "domain.Lx", "domain.Ly"}) && c.nx >= 8 &&
      std::abs(c.hx / c.hy - 1.0) > 0.01)
    c.warnings.push_back("cells are not square: hx = " + m(c.hx) + ", hy = " + m(c.hy));

  // Collapse measures: a fit range must not be empty.
  for (const char* key : {"collapse.slope_back_range", "collapse.slope_front_range"})
    if (ok({key}) && p.get_real2(key)[0] >= p.get_real2(key)[1])
      errors.add(p.where(key) + ": must be [lo, hi] with lo < hi (m)");

  // Time.
  if (ok({"time.dt_min", "time.dt_max"}) && c.time.dt_min >= c.time.dt_max)
    errors.add(p.where("time.dt_min") +
               ": must be < time.dt_max = " + format_number(c.time.dt_max) + " (s)");
  if (ok({"time.dt", "time.dt_min", "time.dt_max", "time.dt_mode"}) &&
      c.time.dt_mode == CaseConfig::DtMode::Adaptive && c.time.dt > 0) {
    if (c.time.dt > c.time.dt_max)
      errors.add(p.where("time.dt") + ": the first adaptive step must be <= time.dt_max = " +
                 format_number(c.time.dt_max) + " (s)");
    else if (c.time.dt < c.time.dt_min)
      errors.add(p.where("time.dt") + ": the first adaptive step must be >= time.dt_min = " +
                 format_number(c.time.dt_min) + " (s)");
  }
  if (ok({"time.dt", "time.t_end"}) && c.time.dt > c.time.t_end)
    c.warnings.push_back("time.dt = " + format_number(c.time.dt) + " s is longer than " +
                         "time.t_end = " + format_number(c.time.t_end) + " s: a single step");
  if (ok({"output.interval", "time.t_end"}) && c.output.interval > c.time.t_end)
    c.warnings.push_back("output.interval = " + format_number(c.output.interval) +
                         " s is longer than time.t_end: diagnostics only at the start and end");

  // Level set, initial shape and prescribed flow must agree.
  const bool momentum = c.flow.prescribed == Prescribed::None;
  if (ok({"flow.prescribed", "levelset.enabled"}) && !momentum && !c.levelset.enabled)
    errors.add(p.where("flow.prescribed") +
               ": a prescribed flow only advects the level set: needs levelset.enabled = true");
  if (ok({"initial.shape", "levelset.enabled"})) {
    if (c.levelset.enabled && c.initial.shape == Shape::None)
      errors.add(p.where("initial.shape") +
                 ": levelset.enabled = true needs an initial granular region: one of "
                 "rectangle, layer, circle, zalesak (or set levelset.enabled = false)");
    if (!c.levelset.enabled && c.initial.shape != Shape::None)
      errors.add(p.where("initial.shape") +
                 ": levelset.enabled = false makes the whole domain granular, so the shape "
                 "would be ignored: must be \"none\"");
  }

  // Initial geometry: inside the domain and, when momentum is solved, clear of the top wall
  // by the smeared interface half-width plus one cell (otherwise the heavy phase would be in
  // contact with the lid and the air above it would be under-resolved).
  const bool geom_ok = ok({"initial.shape", "levelset.enabled", "flow.prescribed", "domain.Lx",
                           "domain.Ly", "grid.n", "levelset.eps_cells"}) &&
                       c.levelset.enabled;
  const double top_margin = momentum ? (c.levelset.eps_cells + 1) * c.hy : 0.0;
  const double y_top = Ly - top_margin;
  const std::string y_top_text = momentum
                                     ? "Ly - (levelset.eps_cells + 1) hy = " + m(y_top) +
                                           " so the smeared interface does not touch the top wall"
                                     : "domain.Ly = " + m(Ly);
  const auto inside = [&](const char* key, double v, double lo, double hi, const char* what,
                          const std::string& lo_text, const std::string& hi_text) {
    if (v < lo)
      errors.add(p.where(key) + ": " + what + " must lie inside the domain: must be >= " + lo_text);
    else if (v > hi)
      errors.add(p.where(key) + ": " + what + " must lie inside the domain: must be <= " + hi_text);
  };
  if (geom_ok && c.initial.shape == Shape::Rectangle &&
      ok({"initial.x0", "initial.x1", "initial.y0", "initial.y1"})) {
    const auto& in = c.initial;
    inside("initial.x0", in.x0, 0, Lx, "the column", "0 m", "domain.Lx = " + m(Lx));
    inside("initial.y0", in.y0, 0, Ly, "the column", "0 m", "domain.Ly = " + m(Ly));
    if (in.x1 <= in.x0)
      errors.add(p.where("initial.x1") + ": must be > initial.x0 = " + m(in.x0));
    else
      inside("initial.x1", in.x1, 0, Lx, "the column", "0 m", "domain.Lx = " + m(Lx));
    if (in.y1 <= in.y0)
      errors.add(p.where("initial.y1") + ": must be > initial.y0 = " + m(in.y0));
    else if (in.y1 > Ly)
      errors.add(p.where("initial.y1") +
                 ": the column must lie inside the domain: must be <= domain.Ly = " + m(Ly));
    else if (in.y1 > y_top)
      errors.add(p.where("initial.y1") + ": the column touches the top: must be <= " + y_top_text);
  }
  if (geom_ok && c.initial.shape == Shape::Layer && ok({"initial.height"}) &&
      c.initial.height > y_top)
    errors.add(p.where("initial.height") + ": the layer " +
               (c.initial.height > Ly ? "must lie inside the domain" : "touches the top") +
               ": must be <= " + y_top_text);
  if (geom_ok && c.initial.shape == Shape::Trapezoid &&
      ok({"initial.x0", "initial.x1", "initial.height", "initial.slope"})) {
    const auto& in = c.initial;
    const double run = in.height / std::tan(in.slope_deg * std::numbers::pi / 180);
    if (in.x0 < 0)
      errors.add(p.where("initial.x0") + ": the pile must lie inside the domain: must be >= 0");
    if (in.x1 > Lx)
      errors.add(p.where("initial.x1") +
                 ": the pile must lie inside the domain: must be <= domain.Lx = " + m(Lx));
    if (in.x1 - in.x0 <= 2 * run)
      errors.add(p.where("initial.x1") + ": the pile has no top: needs x1 - x0 > 2 height / "
                 "tan(slope) = " + m(2 * run));
    if (in.height > y_top)
      errors.add(p.where("initial.height") + ": the pile " +
                 (in.height > Ly ? "must lie inside the domain" : "touches the top") +
                 ": must be <= " + y_top_text);
  }
  const bool disc = c.initial.shape == Shape::Circle || c.initial.shape == Shape::Zalesak;
  if (geom_ok && disc && ok({"initial.cx", "initial.cy", "initial.radius"})) {
    const auto& in = c.initial;
    const std::string r = ", initial.radius = " + format_number(in.radius);
    if (in.cx - in.radius < 0)
      errors.add(p.where("initial.cx") + r +
                 ": the disc must lie inside the domain: needs cx - radius >= 0");
    if (in.cx + in.radius > Lx)
      errors.add(
          p.where("initial.cx") + r +
          ": the disc must lie inside the domain: needs cx + radius <= domain.Lx = " + m(Lx));
    if (in.cy - in.radius < 0)
      errors.add(p.where("initial.cy") + r +
                 ": the disc must lie inside the domain: needs cy - radius >= 0");
    if (in.cy + in.radius > y_top)
      errors.add(p.where("initial.cy") + r + ": the disc " +
                 (in.cy + in.radius > Ly ? "must lie inside the domain" : "touches the top") +
                 ": needs cy + radius <= " + y_top_text);
  }
  if (geom_ok && c.initial.shape == Shape::Zalesak &&
      ok({"initial.radius", "initial.slot_width", "initial.slot_depth"})) {
    const auto& in = c.initial;
    if (in.slot_width >= 2 * in.radius)
      errors.add(p.where("initial.slot_width") +
                 ": must be < 2 initial.radius = " + m(2 * in.radius));
    if (in.slot_depth >= 2 * in.radius)
      errors.add(p.where("initial.slot_depth") + ": must be < 2 initial.radius = " +
                 m(2 * in.radius) + " (the slot would cut the disc in two)");
    if (in.slot_width < 2 * std::min(c.hx, c.hy))
      c.warnings.push_back("initial.slot_width = " + m(in.slot_width) +
                           " spans fewer than 2 cells: the slot is not resolved");
  }

  // Solid-body rotation: the centre inside the domain, and the shape's orbit too.
  if (geom_ok && c.flow.prescribed == Prescribed::Rotation &&
      ok({"flow.cx", "flow.cy", "initial.x0", "initial.x1", "initial.y0", "initial.y1",
          "initial.height", "initial.cx", "initial.cy", "initial.radius"})) {
    const auto& f = c.flow;
    if (f.cx <= 0 || f.cx >= Lx)
      errors.add(p.where("flow.cx") +
                 ": the rotation centre must lie inside the domain: must be in (0, " + m(Lx) + ")");
    else if (f.cy <= 0 || f.cy >= Ly)
      errors.add(p.where("flow.cy") +
                 ": the rotation centre must lie inside the domain: must be in (0, " + m(Ly) + ")");
    else {
      const auto& in = c.initial;
      double reach = 0;  // farthest point of the shape from the centre
      const auto corner = [&](double x, double y) {
        reach = std::max(reach, std::hypot(x - f.cx, y - f.cy));
      };
      if (in.shape == Shape::Rectangle) {
        corner(in.x0, in.y0);
        corner(in.x1, in.y0);
        corner(in.x0, in.y1);
        corner(in.x1, in.y1);
      }
      if (in.shape == Shape::Layer) {
        corner(0, 0);
        corner(Lx, 0);
        corner(0, in.height);
        corner(Lx, in.height);
      }
      if (disc) reach = std::hypot(in.cx - f.cx, in.cy - f.cy) + in.radius;
      const double room = std::min({f.cx, Lx - f.cx, f.cy, Ly - f.cy});
      if (reach > room)
        errors.add(p.where("initial.shape") + ": rotating about (flow.cx, flow.cy) = (" +
                   format_number(f.cx) + ", " + format_number(f.cy) +
                   ") carries it out of the domain: it reaches " + m(reach) +
                   " from the centre, the nearest wall is " + m(room) + " away");
    }
  }

  // Periodic x: there are no left/right walls. A wall speed or a friction angle there would be
  // physics silently dropped (an error); their type and eta_b are only ignored (a warning).
  const bool periodic = ok({"boundary.periodic_x"}) && c.periodic_x;
  const auto x_wall = [](std::size_t s) { return s == CaseConfig::kLeft || s == CaseConfig::kRight; };
  if (periodic)
    for (std::size_t s : {std::size_t{CaseConfig::kLeft}, std::size_t{CaseConfig::kRight}}) {
      const std::string b = "boundary." + kSides[s] + ".";
      const std::string why = ": boundary.periodic_x = true: there is no " + kSides[s] + " wall";
      if (ok({b + "velocity"}) && c.walls[s].velocity != 0)
        errors.add(p.where(b + "velocity") + why + " to move: must be 0");
      if (ok({b + "friction_angle"}) && c.walls[s].friction_angle_deg != 0)
        errors.add(p.where(b + "friction_angle") + why + " to rub on: must be 0");
      for (const char* k : {"type", "eta_b"})
        if (p.is_set(b + k))
          c.warnings.push_back(b + k + " is set but boundary.periodic_x = true: there is no " +
                               kSides[s] + " wall, ignored");
    }

  // Walls. A free-slip wall carries no tangential stress, so a wall velocity would be
  // silently ignored there.
  for (std::size_t s = 0; s < kSides.size(); ++s) {
    if (periodic && x_wall(s)) continue;  // reported above
    const std::string b = "boundary." + kSides[s] + ".";
    if (ok({b + "type", b + "velocity"}) && c.walls[s].type == CaseConfig::Wall::FreeSlip &&
        c.walls[s].velocity != 0)
      errors.add(p.where(b + "velocity") +
                 ": a free-slip wall cannot drive the flow: must be 0, "
                 "or set " +
                 b + "type = \"no_slip\" or \"navier\"");
    if (p.is_set(b + "eta_b") && c.walls[s].type != CaseConfig::Wall::Navier)
      c.warnings.push_back(b + "eta_b is set but " + b + "type = " + to_string(c.walls[s].type) +
                           " does not use it");
  }
  // Rheology. Each error names the key to change, and the value that makes it wrong.
  {
    using Yield = CaseConfig::Yield;
    using Visc = CaseConfig::Viscosity;
    const auto& rh = c.rheology;
    const bool mu_i = rh.viscosity == Visc::MuI;
    const bool yield_ok = ok({"rheology.yield"}), visc_ok = ok({"rheology.viscosity"});
    if (yield_ok && rh.yield == Yield::Bingham && ok({"rheology.tau_y"}) && rh.tau_y <= 0)
      errors.add(p.where("rheology.tau_y") +
                 ": rheology.yield = \"bingham\" needs a yield stress: must be > 0 (Pa)");
    if (visc_ok && mu_i) {
      if (ok({"rheology.d"}) && rh.d <= 0)
        errors.add(p.where("rheology.d") +
                   ": mu(I) without d: rheology.viscosity = \"mu_i\" needs the particle "
                   "diameter (eq. 11): must be > 0 (m)");
      if (ok({"rheology.mu_inf", "rheology.friction_angle"}) && rh.mu_inf <= rh.tan_alpha())
        errors.add(p.where("rheology.mu_inf") +
                   ": rheology.viscosity = \"mu_i\" needs mu_inf > tan(rheology.friction_angle) "
                   "= tan(" +
                   format_number(rh.friction_angle_deg) + " deg) = " + g4(rh.tan_alpha()) +
                   " (otherwise the eq. 11 viscosity is <= 0)");
      if (yield_ok && rh.yield != Yield::DruckerPrager)
        errors.add(p.where("rheology.viscosity") +
                   ": the mu(I) rheology is Drucker-Prager with the eq. 11 viscosity: needs "
                   "rheology.yield = \"dp\", not \"" +
                   to_string(rh.yield) + "\"");
      if (ok({"rheology.eta_min", "rheology.eta_max"}) && rh.eta_min >= rh.eta_max)
        errors.add(p.where("rheology.eta_min") +
                   ": must be < rheology.eta_max = " + format_number(rh.eta_max) + " (Pa s)");
    }
    // Pressure-dependent models need a weight: with g = 0 the granular phase has no
    // (lithostatic) pressure, so kappa (and the mu(I) viscosity) would vanish.
    const bool pressure_model =
        yield_ok && (rh.yield == Yield::DruckerPrager || rh.yield == Yield::Hydrostatic);
    if (ok({"physics.gravity"}) && momentum && (pressure_model || (visc_ok && mu_i))) {
      const std::string model =
          pressure_model ? std::string("rheology.yield = \"") + to_string(rh.yield) + "\""
                         : std::string("rheology.viscosity = \"mu_i\"");
      if (c.gravity[0] == 0 && c.gravity[1] == 0)
        errors.add(p.where("physics.gravity") + ": " + model +
                   (pressure_model ? " scales the yield stress" : " scales the viscosity") +
                   " with the pressure of the grains' weight: needs non-zero gravity");
      else if (rh.yield == Yield::Hydrostatic && c.gravity[1] >= 0)
        errors.add(p.where("physics.gravity") +
                   ": rheology.yield = \"hp\" weighs the granular column above the point "
                   "(eq. 15): needs gravity pointing down, gy < 0");
    }
    // Keys of a model that is not selected: legal, but usually a slip.
    if (yield_ok && visc_ok) {
      std::vector<std::pair<std::string, std::string>> unused_keys;  // key, why unused
      const std::string y = std::string("rheology.yield = ") + to_string(rh.yield);
      if (rh.yield != Yield::Bingham) unused_keys.push_back({"rheology.tau_y", y});
      if (!pressure_model) unused_keys.push_back({"rheology.friction_angle", y});
      if (!mu_i)
        for (const char* k : {"rheology.mu_inf", "rheology.I0", "rheology.d", "rheology.eta_min",
                              "rheology.eta_max"})
          unused_keys.push_back({k, "rheology.viscosity = constant"});
      if (rh.yield == Yield::None)
        for (const char* k : {"rheology.r_factor", "rheology.theta_per_dt", "rheology.fp_tol",
                              "rheology.plastic_grid", "rheology.yield_support",
                              "rheology.fp_max_iter"})
          unused_keys.push_back({k, y + " (no plastic fixed point)"});
      for (const auto& [k, why] : unused_keys)
        if (p.is_set(k)) c.warnings.push_back(k + " is set but " + why + " does not use it");
    }
    if (c.levelset.redistance_interval > 0 && p.is_set("levelset.redistance_every"))
      c.warnings.push_back("levelset.redistance_every is set but levelset.redistance_interval = " +
                           format_number(c.levelset.redistance_interval) +
                           " s replaces it (redistancing by simulated time)");
    if (yield_ok && rh.yield != Yield::None && !momentum)
      c.warnings.push_back(std::string("rheology.yield = ") + to_string(rh.yield) +
                           " is ignored: flow.prescribed = " + to_string(c.flow.prescribed) +
                           " does not solve the momentum equations");
    for (std::size_t s = 0; s < kSides.size(); ++s) {
      if (periodic && x_wall(s)) continue;
      const std::string k = "boundary." + kSides[s] + ".friction_angle";
      if (yield_ok && ok({k}) && c.walls[s].friction_angle_deg > 0 && rh.yield == Yield::None)
        c.warnings.push_back(k + " = " + format_number(c.walls[s].friction_angle_deg) +
                             " with rheology.yield = none: Coulomb wall friction on a Newtonian "
                             "granular phase (legal, but unusual)");
    }
  }

  // Initial velocity.
  using IV = CaseConfig::InitialVelocity;
  if (ok({"initial.velocity", "initial.velocity_amplitude"})) {
    if (c.initial.velocity == IV::Vortex && c.initial.velocity_amplitude == 0)
      errors.add(p.where("initial.velocity_amplitude") +
                 ": initial.velocity = \"vortex\" needs an amplitude: must be non-zero (m/s)");
    if (c.initial.velocity == IV::None && p.is_set("initial.velocity_amplitude"))
      c.warnings.push_back(
          "initial.velocity_amplitude is set but initial.velocity = none does not use it");
  }
  if (ok({"initial.velocity", "flow.prescribed"}) && !momentum && c.initial.velocity != IV::None)
    errors.add(p.where("initial.velocity") + ": flow.prescribed = " +
               to_string(c.flow.prescribed) +
               " sets the velocity at every step: must be \"none\"");

  if (ok({"physics.gravity"}) && momentum && c.gravity[0] == 0 && c.gravity[1] == 0 &&
      c.initial.velocity == IV::None &&
      std::all_of(c.walls.begin(), c.walls.end(), [](const auto& w) { return w.velocity == 0; }))
    c.warnings.push_back("no gravity and no moving wall: nothing drives the flow");

  // Keys given for a shape or a flow that does not use them: legal, but usually a slip.
  const auto unused = [&](const std::vector<std::string>& keys,
                          const std::vector<std::string>& used, const std::string& chooser,
                          const std::string& choice) {
    for (const auto& k : keys)
      if (p.is_set(k) && std::find(used.begin(), used.end(), k) == used.end())
        c.warnings.push_back(k + " is set but " + chooser + " = " + choice + " does not use it");
  };
  const std::vector<std::string> shape_keys{
      "initial.x0", "initial.x1", "initial.y0",     "initial.y1",         "initial.height",
      "initial.cx", "initial.cy", "initial.radius", "initial.slot_width", "initial.slot_depth",
      "initial.slope"};
  std::vector<std::string> shape_used;
  switch (c.initial.shape) {
    case Shape::Rectangle:
      shape_used = {"initial.x0", "initial.x1", "initial.y0", "initial.y1"};
      break;
    case Shape::Layer:
      shape_used = {"initial.height"};
      break;
    case Shape::Circle:
      shape_used = {"initial.cx", "initial.cy", "initial.radius"};
      break;
    case Shape::Zalesak:
      shape_used = {"initial.cx", "initial.cy", "initial.radius", "initial.slot_width",
                    "initial.slot_depth"};
      break;
    case Shape::Trapezoid:
      shape_used = {"initial.x0", "initial.x1", "initial.height", "initial.slope"};
      break;
    case Shape::None:
      break;
  }
  unused(shape_keys, shape_used, "initial.shape", to_string(c.initial.shape));
  std::vector<std::string> flow_used;
  if (c.flow.prescribed == Prescribed::Rotation) flow_used = {"flow.omega", "flow.cx", "flow.cy"};
  if (c.flow.prescribed == Prescribed::SingleVortex) flow_used = {"flow.period"};
  unused({"flow.omega", "flow.cx", "flow.cy", "flow.period"}, flow_used, "flow.prescribed",
         to_string(c.flow.prescribed));

  // Probes: unique names, segments of non-zero length inside the closed domain.
  const auto& items = p.items("probe");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Params& it = items[i];
    const CaseConfig::Probe& pr = c.probes[i];
    if (it.valid("name"))
      for (std::size_t j = 0; j < i; ++j)
        if (items[j].valid("name") && c.probes[j].name == pr.name) {
          errors.add(it.where("name") + ": probe names must be unique: already used by probe[" +
                     std::to_string(j + 1) + "]");
          break;
        }
    if (!ok({"domain.Lx", "domain.Ly"})) continue;
    const std::pair<const char*, double> xs[] = {{"x0", pr.x0}, {"x1", pr.x1}};
    const std::pair<const char*, double> ys[] = {{"y0", pr.y0}, {"y1", pr.y1}};
    bool all_ok = true;
    for (const auto& [k, v] : xs)
      if (it.valid(k) && (v < 0 || v > Lx)) {
        errors.add(it.where(k) +
                   ": the probe must lie inside the domain: must be in [0, domain.Lx = " +
                   format_number(Lx) + "] (m)");
        all_ok = false;
      }
    for (const auto& [k, v] : ys)
      if (it.valid(k) && (v < 0 || v > Ly)) {
        errors.add(it.where(k) +
                   ": the probe must lie inside the domain: must be in [0, domain.Ly = " +
                   format_number(Ly) + "] (m)");
        all_ok = false;
      }
    if (all_ok && it.valid("x0") && it.valid("x1") && it.valid("y0") && it.valid("y1") &&
        pr.x0 == pr.x1 && pr.y0 == pr.y1)
      errors.add(it.where("x1") +
                 ": the segment has zero length: (x1, y1) must differ from "
                 "(x0, y0) = (" +
                 format_number(pr.x0) + ", " + format_number(pr.y0) + ")");
  }
}

CaseConfig resolve(Params& p, InputErrors& errors) {
  CaseConfig c = fill(p);
  check(p, c, errors);
  if (p.get_int("grid.nx") == 0)
    p.annotate("grid.nx", "resolved: nx = round(Lx/Ly * n) = " + std::to_string(c.nx));
  c.resolved_toml = p.to_toml(
      "granflow resolved case: every parameter with the value used (defaults filled in,\n"
      "--set overrides applied). Units SI. Running this file gives the same case.");
  return c;
}

}  // namespace

CaseConfig load_case(const std::string& path, const std::vector<std::string>& overrides) {
  Params p = case_params();
  InputErrors errors;
  p.load(path, overrides, errors);
  CaseConfig c = resolve(p, errors);
  errors.throw_if_any();
  return c;
}

CaseConfig load_case_string(const std::string& text, const std::string& source,
                            const std::vector<std::string>& overrides) {
  Params p = case_params();
  InputErrors errors;
  p.load_string(text, source, overrides, errors);
  CaseConfig c = resolve(p, errors);
  errors.throw_if_any();
  return c;
}

const std::vector<std::string>& restart_changeable_keys() {
  static const std::vector<std::string> keys{
      "time.t_end",          "time.max_steps", "time.dt_mode",
      "time.dt",             "time.cfl",       "time.dt_max",
      "time.dt_min",         "time.max_speed", "output.progress_interval",
      "output.checkpoint_interval_steps",      "output.checkpoint_wall_s",
      "output.volume_warn_pct",                "solver.petsc_options",
      "rheology.fp_fail_change"};
  return keys;
}

namespace {
// key -> value text of a resolved case: "section.key" for [section] tables, "probe[k].key"
// for the k-th [[probe]]; comments and blank lines skipped.
std::vector<std::pair<std::string, std::string>> resolved_entries(const std::string& toml) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(toml);
  std::string line, section;
  std::map<std::string, int> array_count;
  const auto trim = [](std::string x) {
    const auto a = x.find_first_not_of(" \t"), b = x.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : x.substr(a, b - a + 1);
  };
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("[[", 0) == 0) {
      const std::string name = trim(line.substr(2, line.find("]]") - 2));
      section = name + "[" + std::to_string(++array_count[name]) + "]";
      continue;
    }
    if (line[0] == '[') {
      section = trim(line.substr(1, line.find(']') - 1));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim(line.substr(0, eq));
    out.emplace_back(section.empty() ? key : section + "." + key, trim(line.substr(eq + 1)));
  }
  return out;
}
}  // namespace

std::vector<std::string> case_differences(const std::string& checkpoint_toml,
                                          const std::string& now_toml,
                                          const std::vector<std::string>& ignore) {
  const auto a = resolved_entries(checkpoint_toml), b = resolved_entries(now_toml);
  const auto skip = [&](const std::string& k) {
    return std::find(ignore.begin(), ignore.end(), k) != ignore.end();
  };
  const auto value = [](const auto& list, const std::string& k) -> const std::string* {
    for (const auto& [key, v] : list)
      if (key == k) return &v;
    return nullptr;
  };
  std::vector<std::string> diffs;
  for (const auto& [k, v] : a) {
    if (skip(k)) continue;
    const std::string* w = value(b, k);
    if (!w)
      diffs.push_back(k + ": " + v + " at the checkpoint, absent now");
    else if (*w != v)
      diffs.push_back(k + ": " + v + " at the checkpoint, " + *w + " now");
  }
  for (const auto& [k, v] : b)
    if (!skip(k) && !value(a, k)) diffs.push_back(k + ": absent at the checkpoint, " + v + " now");
  return diffs;
}

std::string write_resolved_case(const CaseConfig& c, const std::string& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return path + ": cannot write the resolved case";
  out << c.resolved_toml;
  out.close();
  return out ? "" : path + ": writing the resolved case failed";
}

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
    // Peak speed of the initial vortex (sim/Setup.hpp): max(|u|, |v|) of its stream function.
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
