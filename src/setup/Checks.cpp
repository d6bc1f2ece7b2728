// The checks of a case that involve more than one key (setup/Case.hpp). A check runs only if
// every key it reads holds an accepted value: a rejected value was reported already and now
// holds its default, so checking it again would only report a consequence of the first error.
// Nothing runs without a readable file. Errors name the key to change, its value and what is
// allowed; legal but probably unintended settings become warnings.
#include "setup/Checks.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>

#include "setup/Names.hpp"
#include "setup/Report.hpp"

namespace gf {

using namespace setup_detail;

namespace {

using Shape = CaseConfig::Shape;
using Prescribed = CaseConfig::Prescribed;

std::string m(double v) { return format_number(v) + " m"; }
bool x_wall(std::size_t s) { return s == CaseConfig::kLeft || s == CaseConfig::kRight; }

class CaseChecks {
 public:
  CaseChecks(const Params& p, CaseConfig& c, InputErrors& errors)
      : p(p), c(c), errors(errors), Lx(c.domain.Lx), Ly(c.domain.Ly) {
    momentum = c.flow.prescribed == Prescribed::None;
    geom_ok = ok({"initial.shape", "levelset.enabled", "flow.prescribed", "domain.Lx",
                  "domain.Ly", "grid.n", "levelset.eps_cells"}) &&
              c.levelset.enabled;
    disc = c.initial.shape == Shape::Circle || c.initial.shape == Shape::Zalesak;
    periodic = ok({"boundary.periodic_x"}) && c.periodic_x;
  }
  void run() {
    grid();
    time();
    phase();
    geometry();
    rotation();
    periodic_walls();
    walls();
    rheology();
    initial_velocity();
    unused_keys();
    probes();
  }

 private:
  const Params& p;
  CaseConfig& c;
  InputErrors& errors;
  const double Lx, Ly;
  bool momentum = true;  // the momentum equations are solved (no prescribed flow)
  bool geom_ok = false;  // the initial shape's keys are all valid, and there is a level set
  bool disc = false;     // the initial shape is a circle or Zalesak's disc
  bool periodic = false;  // boundary.periodic_x

  bool ok(std::initializer_list<std::string> keys) const {
    if (!p.file_ok()) return false;
    for (const auto& k : keys)
      if (!p.valid(k)) return false;
    return true;
  }
  void grid();
  void time();
  void fixed_step();
  void counts();
  void phase();
  void geometry();
  void rotation();
  void periodic_walls();
  void walls();
  void rheology();
  void initial_velocity();
  void unused_keys();
  void probes();
};

// The grid and the collapse measures' fit ranges.
void CaseChecks::grid() {
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
}

// The time-step controls.
void CaseChecks::time() {
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
  fixed_step();
  counts();
}

// A fixed step: it must exist, and it must not be far beyond the stability limits that the
// adaptive step respects (Simulation::choose_dt): the convective CFL number U dt / h <= 1 with
// the case's velocity scale U (the report's), and, when momentum is solved under gravity, the
// gravity limit dt <= sqrt(h / |g|) (the time to fall one cell from rest, up to sqrt 2).
void CaseChecks::fixed_step() {
  if (!ok({"time.dt", "time.dt_mode", "grid.n", "grid.nx", "domain.Lx", "domain.Ly",
           "physics.gravity"}) ||
      c.time.dt_mode != CaseConfig::DtMode::Fixed)
    return;
  const double dt = c.time.dt;
  if (dt <= 0) {
    errors.add(p.where("time.dt") + ": time.dt_mode = \"fixed\" needs the step: must be > 0 "
               "(s), or use time.dt_mode = \"adaptive\"");
    return;
  }
  const double h = std::min(c.hx, c.hy);
  const double U = velocity_scale(c);
  const double g = std::hypot(c.gravity[0], c.gravity[1]);
  double limit = std::numeric_limits<double>::infinity();
  std::string why;
  if (U > 0) {
    limit = h / U;
    why = "CFL number U dt / h = " + g4(U * dt / h) + " (U = " + g4(U) + " m/s, h = " +
          format_number(h) + " m)";
  }
  if (momentum && g > 0 && std::sqrt(h / g) < limit) {
    limit = std::sqrt(h / g);
    why = "dt / sqrt(h / |g|) = " + g4(dt / limit) + " (the gravity limit sqrt(h / |g|) = " +
          g4(limit) + " s, h = " + format_number(h) + " m, |g| = " + g4(g) + " m/s^2)";
  }
  if (!(dt > limit)) return;
  // Up to kFarBeyond times the limit a run may survive (U is an estimate, the flow may stay
  // slower): a warning. Beyond, no step of the explicit convection or of the fall from rest
  // can be stable: refused.
  constexpr double kFarBeyond = 10;
  if (dt > kFarBeyond * limit)
    errors.add(p.where("time.dt") + ": with time.dt_mode = \"fixed\" the step is " +
               g4(dt / limit) + " times the stability limit, " + why +
               ": must be <= " + g4(kFarBeyond * limit) + " s (" + format_number(kFarBeyond) +
               " times the limit " + g4(limit) + " s); stable steps are <= " + g4(limit) +
               " s, or use time.dt_mode = \"adaptive\"");
  else
    c.warnings.push_back("time.dt = " + format_number(dt) + " s (fixed) is beyond the stability "
                         "limit " + g4(limit) + " s: " + why + " > 1; the run may blow up: try "
                         "time.dt <= " + g4(limit) + " s or time.dt_mode = \"adaptive\"");
}

// The number of steps and outputs to t_end: bounded, so that a slip of the exponent
// (output.interval = 1e-300, time.t_end = 1e308) is an error here instead of a run that never
// ends or writes without end.
void CaseChecks::counts() {
  if (!ok({"time.t_end", "time.dt", "time.dt_mode", "time.dt_max", "output.interval",
           "output.vtk_interval"}))
    return;
  const double T = c.time.t_end;
  // The message names both keys, where each was given: either may be the slip.
  const auto too_many = [&](const std::string& key, double per, double limit,
                            const std::string& what, const std::string& why) {
    const double n = T / per;
    if (!(n > limit)) return;
    errors.add(p.where(key) + " with " + p.where("time.t_end") + ": time.t_end / " + key +
               " = " + g4(n) + " " + what +
               ", more than " + g4(limit) + " (" + why + "): needs " + key + " >= " +
               g4(T / limit) + " s or time.t_end <= " + g4(limit * per) + " s");
  };
  // 1e9 steps: beyond any run (even the smallest grid takes about 1e-4 s per step: more than a
  // day), and the loop's time tolerance, 1e-12 t_end, must stay far below one step.
  const bool fixed = c.time.dt_mode == CaseConfig::DtMode::Fixed;
  if (!fixed || c.time.dt > 0)
    too_many(fixed ? "time.dt" : "time.dt_max", fixed ? c.time.dt : c.time.dt_max, kMaxSteps,
             fixed ? "steps" : "steps at least (the adaptive step is at most time.dt_max)",
             "no run can take them: at 1e-4 s per step on the smallest grid that is over a day");
  // A diagnostics row (~0.5 kB, plus a row per probe point) every output.interval.
  too_many("output.interval", c.output.interval, kMaxOutputs, "diagnostics outputs",
           "a row of diagnostics.csv and of every probe each: gigabytes of tables");
  // A VTK file holds 11 values per cell: 1e5 files are 1e5 times the size of the state.
  if (c.output.vtk_interval > 0)
    too_many("output.vtk_interval", c.output.vtk_interval, kMaxVtkOutputs, "VTK files",
             "each holds 11 values per cell");
}

// The level set, the initial shape and a prescribed flow must agree.
void CaseChecks::phase() {
  // Level set, initial shape and prescribed flow must agree.
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
}

// The initial shape inside the domain.
void CaseChecks::geometry() {
  // Initial geometry: inside the domain and, when momentum is solved, clear of the top wall
  // by the smeared interface half-width plus one cell (otherwise the heavy phase would be in
  // contact with the lid and the air above it would be under-resolved).
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
}

// A solid-body rotation's centre and the shape's orbit inside the domain.
void CaseChecks::rotation() {
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
}

// Periodic x: no left/right walls.
void CaseChecks::periodic_walls() {
  // Periodic x: there are no left/right walls. A wall speed or a friction angle there would be
  // physics silently dropped (an error); their type and eta_b are only ignored (a warning).
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
}

// The wall conditions.
void CaseChecks::walls() {
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
  // The side walls: a friction angle without a width would be physics silently dropped.
  const std::string sw = "boundary.side_walls.";
  if (ok({sw + "width", sw + "friction_angle"}) && c.side_walls.width == 0 &&
      c.side_walls.friction_angle_deg > 0)
    errors.add(p.where(sw + "friction_angle") + ": " + sw + "friction_angle = " +
               format_number(c.side_walls.friction_angle_deg) + " deg needs the channel's width: " +
               "set " + sw + "width > 0 (m), or friction_angle = 0");
  // The gate: two cells from the left and right walls (its Coulomb faces are stored where the walls
  // are not), below the top, with a height.
  const std::string gt = "boundary.gate.";
  if (ok({gt + "x", gt + "height", "domain.Lx", "domain.Ly", "grid.n", "grid.nx"}) && c.gate.x > 0 &&
      c.hx > 0) {
    const double hx = c.hx;
    const double xg = std::round(c.gate.x / hx) * hx;
    if (xg < 2 * hx || xg > Lx - 2 * hx)
      errors.add(p.where(gt + "x") + ": " + gt + "x = " + m(c.gate.x) + " lies on the grid line x = " +
                 g4(xg) + " m" + ": must be at least two cells (" + m(2 * hx) + ") from the side walls x = 0 and " +
                 m(Lx));
    if (c.gate.height <= 0 || c.gate.height >= Ly)
      errors.add(p.where(gt + "height") + ": " + gt + "height = " + m(c.gate.height) +
                 ": must be > 0 and below domain.Ly = " + m(Ly) +
                 " (the air above the plate joins both sides)");
    if (std::abs(xg - c.gate.x) > 1e-9 * Lx)
      c.warnings.push_back(gt + "x = " + format_number(c.gate.x) + " m is moved to the grid line x = " +
                           g4(xg) + " m (a column ending at x would leave a gap of " +
                           g4(std::abs(xg - c.gate.x)) + " m to the plate)");
  } else if (ok({gt + "x"}) && c.gate.x == 0) {
    for (const char* k : {"height", "speed", "friction_angle", "eta_b"})
      if (p.is_set(gt + k))
        c.warnings.push_back(gt + k + " is set but " + gt + "x = 0: there is no gate, ignored");
  }
  // The exact solver does not cover these yet: say so rather than drop the physics.
  // (The side walls are: ExactPlasticStep's NewtonSide.)
  if (ok({"rheology.solver", gt + "x", "rheology.plastic_grid"}) && c.rheology.newton) {
    const std::string what = c.gate.x > 0         ? gt + "x = " + m(c.gate.x)
                             : c.rheology.node_copy ? std::string("rheology.plastic_grid = \"cell_node\"")
                                                    : std::string();
    if (!what.empty())
      errors.add(p.where("rheology.solver") + ": rheology.solver = \"newton\" is not available with " +
                 what + " yet: use rheology.solver = \"fixed_point\" (the default)");
  }
  if (ok({sw + "width"}) && c.side_walls.width == 0)
    for (const char* k : {"earth_pressure", "eta_b", "normal_stress"})
      if (p.is_set(sw + k))
        c.warnings.push_back(sw + k + " is set but " + sw + "width = 0: there are no side walls, "
                             "ignored");
}

// The rheology's keys together.
void CaseChecks::rheology() {
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
                              "rheology.fp_max_iter", "rheology.newton_pressure",
                              "rheology.newton_wall_load"})
          unused_keys.push_back({k, y + " (no plastic fixed point)"});
      if (rh.newton)
        for (const char* k : {"rheology.theta_per_dt", "rheology.fp_tol", "rheology.fp_tol_u",
                              "rheology.fp_max_iter", "rheology.anderson_depth",
                              "rheology.anderson_reset_ratio", "rheology.fp_monitor"})
          unused_keys.push_back({k, "rheology.solver = newton (theta = 0, no fixed point)"});
      else
        for (const char* k : {"rheology.newton_tol", "rheology.newton_max_iter",
                              "rheology.newton_pressure", "rheology.newton_wall_load"})
          unused_keys.push_back({k, "rheology.solver = fixed_point"});
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
}

// The initial velocity.
void CaseChecks::initial_velocity() {
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
}

// Keys of a shape or a flow that is not selected.
void CaseChecks::unused_keys() {
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
}

// The line probes.
void CaseChecks::probes() {
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

}  // namespace

void check_case(const Params& p, CaseConfig& c, InputErrors& errors) {
  CaseChecks(p, c, errors).run();
}

}  // namespace gf
