// The case schema: the one place where each parameter is declared, with its unit, default,
// allowed range and help text (core/Params.hpp). See setup/Case.hpp.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <ostream>

#include "setup/Case.hpp"
#include "setup/Names.hpp"

namespace gf {

using namespace setup_detail;

namespace {

// A probe's name is its file name (probes/<name>.csv) and a word of the checkpoint header.
// File names are limited to 255 bytes (NAME_MAX), and a name is also a column label in plots:
// kMaxProbeName characters are plenty and leave room for the folder and the suffix.
constexpr std::size_t kMaxProbeName = 64;

std::string probe_name_rule(const std::string& s) {
  const bool ok = !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
  });
  if (!ok) return "must be made of letters, digits, _ and - only ([A-Za-z0-9_-]+)";
  if (s.size() > kMaxProbeName)
    return "is " + std::to_string(s.size()) + " characters long: at most " +
           std::to_string(kMaxProbeName) + " (it becomes the file name probes/<name>.csv)";
  return "";
}

// Text that is printed (the title on the terminal and in the log, the PETSc options in
// command.txt): one line without control characters, so that an ESC sequence or a carriage
// return in a case file cannot rewrite the user's terminal or hide a line of the log.
std::string printable_rule(const std::string& s) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    const unsigned char c = static_cast<unsigned char>(s[k]);
    if (c < 0x20 || c == 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "0x%02X", static_cast<unsigned>(c));
      return std::string("must be one line of printable text: character ") +
             std::to_string(k + 1) + " is the control character " + b +
             (c == 0x1b ? " (ESC)" : c == '\r' ? " (CR)" : c == '\n' ? " (line feed)" : "");
    }
  }
  return "";
}

}  // namespace

// ------------------------------------------------------------------------------------------
// The schema: the one place where each parameter is declared. Defaults are case A of the
// paper (section 4.1: column 0.20 x 0.14 m in a 0.8 x 0.2 m box, rho_s = 1550, eta_0 = 0.5).
// ------------------------------------------------------------------------------------------

namespace {

// The title, the domain, the grid and the time stepping.
void declare_domain_time(Params& p) {
  p.add_string("title", "granflow case",
               "One line saying what this case is; copied to the output.", printable_rule,
               "one line of printable text (no control characters)");

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
}

// Gravity, the two phases and the rheology of the granular one with its fixed point (sections 2.1-2.2, 3.2-3.3).
void declare_physics(Params& p) {
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
  p.add_enum("rheology.solver", "fixed_point", kPlasticSolvers,
             "How each step's plastic problem (eq. 31) is solved: fixed_point = the paper's "
             "iteration (relaxation theta = theta_per_dt dt, Anderson acceleration, stops at "
             "fp_tol or fp_max_iter); newton = exactly, with theta = 0, by a primal-dual "
             "semismooth Newton method (one direct solve per iteration, to newton_tol; "
             "momentum/ExactPlasticStep.hpp): the rigid zones are rigid and the step does not "
             "depend on r_factor. Newton is not yet available with plastic_grid = cell_node "
             "or the gate.");
  p.add_enum("rheology.newton_pressure", "projection", kNewtonPressures,
             "rheology.solver = newton: projection = the plastic step, then the projection of "
             "eq. 32 (which can set a rigid zone moving again: a held block or pile moves in "
             "its first steps); coupled = the pressure in the same Newton system (eqs. 31 and "
             "32 solved together: divergence-free and at rest from the first step, but on a "
             "collapse such as case A many steps reached newton_max_iter at 160, and each such "
             "step takes newton_max_iter iterations: lower it there; the rigid zones' "
             "pressure is not unique; docs/RHEOLOGY.md).");
  p.add_enum("rheology.newton_wall_load", "step_start", kNewtonWallLoads,
             "rheology.solver = newton: the normal load of the Coulomb walls' friction "
             "kappa_b = tan(alpha_b) (-T_n)^+ (eq. 22): step_start = from p^n, S^n and u^n, "
             "frozen for the step as kappa is, so that the step's velocity is unique; iterate "
             "= refreshed from the Newton iterate's S and D(u~) (the paper's kappa_b^{n+1}: "
             "in a rigid zone S is not unique, and case A at n = 16 then had 294 of its 1060 "
             "steps reach newton_max_iter at 160; docs/newton_knobs.md).");
  // 5e-8 (2026-12-08, sixteenth session; 1e-7 from 2026-12-07, 1e-6 before; docs/RHEOLOGY.md):
  // a dead zone's and a collapse's peak granular pressure keep each step's residual
  // (p^{n+1} = p^n + psi), and the knob criterion (1e-4) needs it small. Whole runs of
  // cases A and B at n = 64 (to 0.2 s, then continued to the end by --restart, one time grid):
  // r_factor / 4, x 4 and newton_tol / 4, x 4 move runout, front, back wall and peak granular
  // pressure by at most 4.4e-5 (A) and 4.2e-5 (B), the stage times by at most 4.1e-6; the
  // defaults' runs cap no step (0 of 1062, 0 of 1360), the knob runs three of their 9,688 at
  // 1000 (A newton_tol / 4: two, 3.4e-8 left; B r_factor x 4: one at 0.87 s, 1.4e-7 left). At
  // 1e-7, case B's newton_tol x 4 moved its peak by 1.15e-4; 5e-8 costs 1.24 (A) and 1.36 (B)
  // times 1e-7's iterations (docs/newton_knobs_n64_tol5e-8_whole.md).
  p.add_real("rheology.newton_tol", "", 5e-8, Range::gt(0),
             "rheology.solver = newton: stop when max |S - P(S + r kappa D)| over the cells and "
             "|s_t - P_b(s_t + r_b kappa_b u_t)| over the Coulomb wall faces are below this "
             "(-exactpd_rigid_tol_factor f: the rigid cells and sticking faces to f times it; "
             "a dead zone's pressure keeps their residual from step to step: at 1e-6 a factor "
             "4 in r_factor or newton_tol moved cases A's and B's peak granular pressure by up "
             "to 3.7e-4, at 1e-7 by up to 1.15e-4, at 5e-8 by up to 4.4e-5, for 3.2 to 3.4 "
             "times the iterations of 1e-6; docs/RHEOLOGY.md).");
  // 1000: a step that converges never reaches the cap, so the figures of the runs that capped no
  // step are the same; the steps that reached 160 were converging slowly, not stuck
  // (docs/RHEOLOGY.md, thirteenth session). The five knob runs at n = 64 that capped steps at 160
  // cap none at 1000: case A newton_tol / 4, r_factor x 4 and r_factor / 4 (4, 5 and 1 of 1061
  // at 160; the hardest step 267, 385 and 180 iterations), case B r_factor x 4 and newton_tol / 4
  // (2 and 1 of 1360; 289 and 177), for -2.1 to +5.3 % iterations in all. Case A's r_factor / 4
  // run then moves the peak granular pressure by 2.2e-4 (5e-6 when its step ended at the cap).
  // (All at newton_tol 1e-6. At 1e-7 two of eight knob runs to 0.2 s capped one step each at
  // 1000; at 5e-8, see newton_tol above: docs/RHEOLOGY.md, fourteenth and sixteenth sessions.)
  // (160, not 100, since 2026-12-06: case A at n = 128 capped 2 of its first 13 steps at 100.)
  p.add_int("rheology.newton_max_iter", "", 1000, closed(1, 1e6),
            "rheology.solver = newton: most Newton iterations per time step (a step that "
            "reaches it is counted as capped, like the fixed point's).");
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
  p.add_int("rheology.anderson_depth", "", 5, closed(0, 100),
            "Fixed point of eq. 31: depth m of the Anderson acceleration of the iterates (Walker "
            "& Ni 2011); 0 = the plain (Picard) iteration of the paper. Same fixed point either "
            "way; 5 reaches a tolerance in far fewer viscous solves (docs/RHEOLOGY.md).");
  p.add_real("rheology.anderson_reset_ratio", "", 1.0, Range::gt(0),
             "Fixed point of eq. 31: the Anderson history is dropped when the change grows by "
             "more than this factor from one iteration to the next (1: at any growth; the "
             "projections make the map non-smooth, and a stale history then misleads).");
  p.add_bool("rheology.fp_monitor", false,
             "Fixed point of eq. 31: log one line per iteration (its change, the change of u~, "
             "how many values moved) to stderr and granflow.log, for convergence studies.");
}

// The level set (section 3.1).
void declare_levelset(Params& p) {
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
}

// The interface method (interface/Interface.hpp).
void declare_interface(Params& p) {
  p.add_enum("interface.method", "clsvof", kInterfaceMethods,
             "How the interface moves and where the mass is. clsvof (default): the granular "
             "volume fraction c is transported by the conservative geometric scheme of "
             "Weymouth & Yue (2010) with the normals of the level set (CLSVOF, Sussman & "
             "Puckett 2000), phi is rebuilt every step as the distance to c's interface "
             "(levelset.redistance_* then do not apply, eps_cells only sets the band left out "
             "of max_speed_granular), rho = rho_f (1 - c) + rho_s c, the momentum is "
             "transported with the mass fluxes of c (BDF1 in time), and the yield stress and "
             "the wall friction act wherever c > 0, the wall load including the wall cells' "
             "own weight: the granular volume is conserved to round-off, deposits stay where "
             "they stop and the water dam break gains no energy (docs/INTERFACE.md). "
             "level_set: the paper's level set (section 3.1: eq. 26, the Heaviside density of "
             "eq. 25, redistancing, BDF2 with the velocity convected); its granular volume "
             "int (1 - H_eps(phi)) is not conserved (docs/LEVELSET_VOLUME.md): the scheme of "
             "the paper's figures.");
  p.add_enum("interface.normals", "level_set", kInterfaceNormals,
             "clsvof: the normals of the PLIC interface: level_set = grad phi (CLSVOF), youngs = "
             "-grad c by Youngs' 3 x 3 stencil (plain VOF).");
}

// The initial state and the prescribed flows of the level-set benchmarks.
void declare_initial(Params& p) {
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
}

// The walls (section 2.2).
void declare_walls(Params& p) {
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

  // The side walls of a channel (issue 21, boundary/SideWalls.hpp): both experiments of the
  // paper ran between plexiglass walls 10 cm apart, which the paper's 2D model leaves out.
  p.add_real("boundary.side_walls.width", "m", 0.0, Range::ge(0),
             "Channel width W between the two side walls (the planes z = +-W/2 of the 2D "
             "model); 0 = no side walls (the paper's model). Their friction acts on the grains "
             "as a body force up to (2/W) tan(alpha_w) K p (N/m^3) against the velocity, with "
             "stick and slide (Coulomb, through the projection of eq. 30), and on the air as "
             "Navier slip.");
  p.add_real("boundary.side_walls.friction_angle", "degrees", 0.0, closed_open(0, 90),
             "Friction angle alpha_w of the grains on the side walls; 0 = none.");
  p.add_real("boundary.side_walls.earth_pressure", "-", 1.0, Range::open(0, 10),
             "K: the side walls' normal stress is K p. 1: the plane model's out-of-plane "
             "stress, the isotropic closure of Jop, Forterre & Pouliquen (2005).");
  p.add_enum("boundary.side_walls.normal_stress", "pressure", {"pressure", "hydrostatic"},
             "The side walls' normal stress, times K: pressure (the model's p, the in-plane mean "
             "stress: the out-of-plane stress of the plane model; indeterminate in rigid "
             "zones) or hydrostatic (the weight of the grains above, rho |g_y| times the "
             "granular depth, as eq. 15).");
  p.add_real("boundary.side_walls.eta_b", "Pa s/m", 1.0, Range::ge(0),
             "Navier slip coefficient of the air on the side walls (eq. 24), in series with the "
             "air's shear across the half-width; 0 = none.");

  // The gate of the dam break (issue 21, boundary/Gate.hpp).
  p.add_real("boundary.gate.x", "m", 0.0, Range::ge(0),
             "Position of the gate, a thin vertical plate that holds the column at t <= 0 and "
             "is lifted from t = 0 (moved to the nearest vertical grid line, at least two "
             "cells from the left and right walls); 0 = no gate (the paper: the whole column released "
             "at t = 0).");
  p.add_real("boundary.gate.height", "m", 0.0, Range::ge(0),
             "Height of the plate: it covers y in [speed t, height] and leaves the channel "
             "through the open top above height (as the experiments' plate rises out of the "
             "channel); must be below domain.Ly, so that the air above it connects both sides.");
  p.add_real("boundary.gate.speed", "m/s", 0.0, Range::ge(0),
             "Lifting speed of the gate (its lower edge at y = speed t); 0 = never lifted.");
  p.add_real("boundary.gate.friction_angle", "degrees", 0.0, closed_open(0, 90),
             "Friction angle of the grains on the plate (Coulomb, against their velocity "
             "relative to the plate); 0 = frictionless.");
  p.add_real("boundary.gate.eta_b", "Pa s/m", 1.0, Range::ge(0),
             "Navier slip coefficient of the air on the plate (eq. 24).");

  p.add_bool("boundary.periodic_x", false,
             "The domain repeats in x (period Lx): no left/right walls; the boundary.left / "
             "boundary.right settings are then ignored (a non-zero friction_angle or velocity "
             "there is an error, any other setting a warning). The initial shapes must still "
             "lie inside the domain. For plane Poiseuille, inclined-layer and Bagnold flows.");
}

// The outputs and the column-collapse measures.
void declare_output(Params& p) {
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
}

// The linear solvers and the line probes.
void declare_solver(Params& p) {
  p.add_real("solver.pressure_rtol", "", 1e-10, Range::open(0, 1),
             "Relative residual tolerance of the pressure solve (eq. 32).");
  p.add_real("solver.viscous_rtol", "", 1e-10, Range::open(0, 1),
             "Relative residual tolerance of the viscous solve (eq. 31).");
  p.add_int("solver.viscous_local_margin", "cells", 6, closed(0, 1000),
             "After the first viscous solve of a step, solve the fixed point's viscous problems "
             "only on the granular cells widened by this many cells, the others frozen, and end "
             "with one full solve (Predictor::begin_local); 0 = full solves throughout. "
             "summary.json: visc_polish_its_total, what the closing solves had to add. With "
             "rheology.solver = newton (newton_pressure = projection): the Newton systems after "
             "the first of each step, on the same rows (at least 2 cells of margin), the step "
             "converged only when the rows outside also hold the momentum equation to "
             "solver.viscous_rtol.");
  p.add_string("solver.petsc_options", "",
               "Extra PETSc options, e.g. \"-pres_pc_type gamg\"; applied before the command "
               "line's, which therefore win.",
               printable_rule, "one line of printable text (no control characters)");

  Params probe;
  probe.add_string("name", std::nullopt, "Probe name, unique; used in output file names.",
                   probe_name_rule,
                   "[A-Za-z0-9_-]+, at most " + std::to_string(kMaxProbeName) + " characters");
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
}

}  // namespace


Params case_params() {
  Params p;
  declare_domain_time(p);
  declare_physics(p);
  declare_levelset(p);
  declare_interface(p);
  declare_initial(p);
  declare_walls(p);
  declare_output(p);
  declare_solver(p);
  return p;
}

void print_case_help(std::ostream& os) {
  os << "Case file parameters (TOML; units SI). Every key is optional unless marked "
        "required; unknown keys are errors.\n\n";
  case_params().print_help(os);
}

}  // namespace gf
