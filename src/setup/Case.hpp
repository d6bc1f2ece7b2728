#pragma once
// A case: every input of a run, read once from a TOML case file plus `--set` overrides,
// validated (per key by the registry, across keys in setup/Checks.cpp), and stored in plain
// typed members, in the physics layers' own types, so that no solver ever looks a parameter up
// by name.
//
// The keys, units, defaults, ranges and help texts are declared in one place, case_params()
// in setup/Schema.cpp; `granflow check --list` prints them (print_case_help).
#include <array>
#include <cmath>
#include <iosfwd>
#include <numbers>
#include <string>
#include <vector>

#include "boundary/Boundary.hpp"
#include "core/Params.hpp"
#include "interface/Interface.hpp"
#include "rheology/Rheology.hpp"
#include "setup/Kinematic.hpp"

namespace gf {

struct CaseConfig {
  enum class DtMode { Adaptive, Fixed };
  enum class Shape { None, Rectangle, Layer, Circle, Zalesak, Trapezoid };
  using Prescribed = PrescribedFlow;  // setup/Kinematic.hpp
  // Initial velocity field (initial.velocity): none = rest; vortex = a divergence-free cell
  // from a stream function (setup/Build.hpp), amplitude initial.velocity_amplitude.
  enum class InitialVelocity { None, Vortex };
  using Wall = WallType;  // boundary/Boundary.hpp
  // Probe fields; DNorm, SNorm, Kappa are the cell-centred plastic fields |D(u)| (1/s), |S|
  // and the yield stress kappa (Pa), the same as the VTK output (appended: order kept).
  enum class ProbeField { Phi, Rho, U, V, Speed, P, Eta, DNorm, SNorm, Kappa };
  // None: Newtonian granular phase; Bingham: kappa = tau_y; DruckerPrager ("dp"): kappa =
  // tan(alpha) p^+ (eq. 19); Hydrostatic ("hp"): kappa = tan(alpha) p_hyd (eq. 15).
  using Yield = rheology::Yield;
  // Constant: eta_s = phase.granular.eta; MuI: the mu(I) viscosity of eq. 11.
  using Viscosity = rheology::Viscosity;
  enum Side { kLeft = 0, kRight = 1, kBottom = 2, kTop = 3 };

  struct Domain {
    double Lx = 0, Ly = 0;  // m
    bool operator==(const Domain&) const = default;
  };
  struct Time {
    double t_end = 0;  // s
    DtMode dt_mode = DtMode::Adaptive;
    double dt = 0;                  // s; fixed step, or the first adaptive step; 0 = automatic
    double cfl = 0;                 // -
    double dt_max = 0, dt_min = 0;  // s; below dt_min the run stops as failed
    long long max_steps = 0;        // 0 = unlimited
    double max_speed = 0;           // m/s; above it the run stops as blown up
    bool operator==(const Time&) const = default;
  };
  struct Phase {
    double rho = 0;  // kg/m^3
    double eta = 0;  // Pa s
    bool operator==(const Phase&) const = default;
  };
  struct LevelSet {
    bool enabled = true;       // false: single phase, the whole domain is "granular"
    double eps_cells = 0;      // smearing half-width of H_eps, in cells (eps = eps_cells h)
    int redistance_every = 0;  // steps; 0 = never
    double redistance_tol = 0;  // -, redistance only above this distance defect (0: always)
    double redistance_interval = 0;  // s; > 0: redistance by simulated time, not by steps
    bool redistance_wall_extrapolate = false;  // levelset.redistance_wall = "extrapolate"
    int redistance_iters = 0;
    double redistance_cfl = 0;  // pseudo-time CFL
    bool operator==(const LevelSet&) const = default;
  };
  // interface.method: the paper's level set, or the mass-conserving CLSVOF (interface/).
  struct InterfaceChoice {
    interface::Method method = interface::Method::LevelSet;
    vof::Normals normals = vof::Normals::LevelSet;  // clsvof: the PLIC normals
    bool operator==(const InterfaceChoice&) const = default;
  };
  struct Initial {
    Shape shape = Shape::None;
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // m, rectangle (the granular column)
    double height = 0;                      // m, layer
    double cx = 0, cy = 0, radius = 0;      // m, circle and Zalesak disc
    double slot_width = 0, slot_depth = 0;  // m, Zalesak slot
    double slope_deg = 0;                   // degrees, trapezoid side slopes (a pile)
    InitialVelocity velocity = InitialVelocity::None;
    double velocity_amplitude = 0;  // m/s, peak speed scale of the initial vortex
    bool stress_equilibrium = false;  // initial.stress = "equilibrium"
    bool pressure_hydrostatic = false;  // initial.pressure = "hydrostatic"
    int stress_max_steps = 0;         // pseudo-steps at most
    double stress_tol = 0;            // m/s
    bool operator==(const Initial&) const = default;
  };
  struct Flow {
    Prescribed prescribed = Prescribed::None;  // != None: level set only, momentum not solved
    double omega = 0;                          // rad/s, rotation
    double cx = 0, cy = 0;                     // m, rotation centre
    double period = 0;                         // s, single-vortex period T
    bool operator==(const Flow&) const = default;
  };
  struct WallConfig {
    Wall type = Wall::FreeSlip;
    double eta_b = 0;     // Pa s/m, Navier coefficient (eq. 24)
    double velocity = 0;  // m/s, tangential wall velocity (+x on bottom/top, +y on left/right)
    // degrees, in [0, 90); 0 = none. Where the granular phase (phi < 0) touches the wall,
    // Coulomb friction kappa_b = tan(alpha_b) (-T_n)^+ (eqs. 22-23, 30) replaces `type`;
    // where air touches it, `type` applies.
    double friction_angle_deg = 0;
    double tan_friction() const { return std::tan(friction_angle_deg * std::numbers::pi / 180); }
    bool operator==(const WallConfig&) const = default;
  };
  // The viscoplastic rheology of the granular phase (sections 2.1-2.2, 3.2-3.3).
  struct Rheology {
    Yield yield = Yield::None;
    double tau_y = 0;               // Pa, Bingham yield stress
    double friction_angle_deg = 0;  // degrees, internal friction alpha (dp, hp, mu_i)
    Viscosity viscosity = Viscosity::Constant;
    double mu_inf = 0, I0 = 0;        // -, eq. 11
    double d = 0;                     // m, particle diameter (0 = not given)
    double eta_min = 0, eta_max = 0;  // Pa s, floor and cap of the mu(I) viscosity
    // Fixed point of eq. 31.
    double r_factor = 0;      // -, r = r_factor (2 eta + rho a0 h^2/dt) / kappa^2
    double theta_per_dt = 0;  // 1/s, theta = min(theta_per_dt dt, 0.5)
    bool node_copy = false;   // rheology.plastic_grid = "cell_node": S also at the nodes
    bool yield_on_mass = false;  // rheology.yield_support = "mass": kappa where phi < eps
    double fp_tol = 0;        // -, on the max change of S and s_t in one iteration
    double fp_tol_u = 0;      // m/s, on the max change of u~ in one iteration (0: off)
    int fp_max_iter = 0;
    double fp_fail_change = 1.0;  // -, a capped step ending above this change is a failure
    int anderson_depth = 0;       // -, Anderson acceleration of the fixed point (0 = Picard)
    double anderson_reset_ratio = 0;  // -, the history is dropped when the change grows more
    bool fp_monitor = false;      // a log line per fixed-point iteration
    bool newton = false;          // rheology.solver = "newton": theta = 0, solved exactly
    bool newton_coupled = false;  // rheology.newton_pressure = "coupled"
    bool newton_wall_iterate = false;  // rheology.newton_wall_load = "iterate"
    double newton_tol = 0;        // -, on max |S - P(S + r kappa D)| and the walls'
    int newton_max_iter = 0;
    // mu_s = tan(alpha).
    double tan_alpha() const { return std::tan(friction_angle_deg * std::numbers::pi / 180); }
    bool operator==(const Rheology&) const = default;
  };
  struct Output {
    double interval = 0;           // s (simulated), diagnostics and probes
    double vtk_interval = 0;       // s (simulated), 0 = no VTK
    double progress_interval = 0;  // s (wall clock), 0 = no progress lines
    long long checkpoint_interval_steps = 0;  // steps, 0 = none
    double checkpoint_wall_s = 0;             // s (wall clock), 0 = none
    double volume_warn_pct = 0;               // %, granular volume drift counted as a warning
    bool operator==(const Output&) const = default;
  };
  // The column-collapse measures of diagnostics/Collapse.hpp (section 4 of the paper): the
  // deposit cut-offs of section 4.2.5 and the rules that read the final deposit and the four
  // stages of the front from the output history.
  struct Collapse {
    std::vector<double> cutoffs;                 // -, fractions of the max granular |u|
    std::array<double, 2> slope_back_range{};    // m, x range of the back slope fit
    std::array<double, 2> slope_front_range{};   // m, x range of the front slope fit
    double front_fit_length = 0;                 // m, behind the front: the front angle fit
    double speed_window = 0;                     // s, width of the front speed fit
    double plateau_fraction = 0;                 // -, of the max front speed: constant phase
    double stop_distance = 0;                    // m, front moves less: stopped
    double rest_speed = 0;                       // m/s, max granular |u| below: at rest
    bool operator==(const Collapse&) const = default;
  };
  struct Solver {
    double pressure_rtol = 0, viscous_rtol = 0;
    int viscous_local_margin = 0;  // cells, 0 = off
    std::string petsc_options;  // applied before the command-line options
    bool operator==(const Solver&) const = default;
  };
  struct Probe {
    std::string name;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // m, the segment sampled
    int points = 0;                         // samples, end points included
    std::vector<ProbeField> fields;
    bool operator==(const Probe&) const = default;
  };

  std::string title;
  Domain domain;
  int nx = 0, ny = 0;     // cells; nx derived from grid.nx (0 = round(Lx/Ly ny))
  double hx = 0, hy = 0;  // m, Lx/nx and Ly/ny
  Time time;
  std::array<double, 2> gravity{};  // m/s^2
  Phase granular, air;
  Rheology rheology;
  LevelSet levelset;
  InterfaceChoice interface;
  Initial initial;
  Flow flow;
  std::array<WallConfig, 4> walls{};  // indexed by Side
  bool periodic_x = false;            // boundary.periodic_x: no left/right walls, x repeats
  // boundary.side_walls: the channel's side walls (boundary/SideWalls.hpp).
  struct SideWalls {
    double width = 0;               // m, 0 = none
    double friction_angle_deg = 0;  // degrees, 0 = none
    double earth_pressure = 1;      // -, K
    bool hydrostatic = false;       // normal_stress = "hydrostatic": K p_hyd instead of K p
    double eta_b = 0;               // Pa s/m, the air's Navier coefficient
    double tan_friction() const { return std::tan(friction_angle_deg * std::numbers::pi / 180); }
    bool operator==(const SideWalls&) const = default;
  } side_walls;
  // boundary.gate: the gate of the dam break (boundary/Gate.hpp).
  struct Gate {
    double x = 0, height = 0, speed = 0;  // m, m, m/s; x = 0: none
    double friction_angle_deg = 0;        // degrees
    double eta_b = 0;                     // Pa s/m
    double tan_friction() const { return std::tan(friction_angle_deg * std::numbers::pi / 180); }
    bool operator==(const Gate&) const = default;
  } gate;
  Output output;
  Collapse collapse;
  Solver solver;
  std::vector<Probe> probes;

  // Not part of the physics (and not compared by operator==):
  std::string source;                 // the case file as given
  std::string resolved_toml;          // every key with its value, for the output folder
  std::vector<std::string> warnings;  // legal but probably unintended settings

  bool operator==(const CaseConfig& o) const;  // all physics/numerics members above
};

// Reads, validates and resolves a case. `overrides` are "key=value" strings (--set).
// Throws InputError listing every problem found, one per line.
CaseConfig load_case(const std::string& path, const std::vector<std::string>& overrides);
// Same from TOML text in memory; `source` names it in messages.
CaseConfig load_case_string(const std::string& text, const std::string& source,
                            const std::vector<std::string>& overrides);

// The declaration of every case parameter (the schema), with defaults loaded.
Params case_params();
// The `granflow check --list` listing.
void print_case_help(std::ostream& os);

// The top of the initial granular region, m (Ly for a one-phase run, 0 if there is none).
double granular_top(const CaseConfig& c);

// Writes c.resolved_toml to `path`. Returns an error message, empty on success.
[[nodiscard]] std::string write_resolved_case(const CaseConfig& c, const std::string& path);

// Names as written in case files.
const char* to_string(CaseConfig::DtMode v);
const char* to_string(CaseConfig::Shape v);
const char* to_string(CaseConfig::Prescribed v);
const char* to_string(CaseConfig::InitialVelocity v);
const char* to_string(CaseConfig::Wall v);
const char* to_string(CaseConfig::ProbeField v);
const char* to_string(CaseConfig::Yield v);
const char* to_string(CaseConfig::Viscosity v);
const char* to_string(CaseConfig::Side v);

}  // namespace gf
