// A case: from the registry (setup/Schema.cpp) to the typed CaseConfig, checked
// (setup/Checks.cpp), resolved and written back. See setup/Case.hpp.
#include "setup/Case.hpp"

#include <cmath>
#include <fstream>

#include "core/Error.hpp"
#include "setup/Checks.hpp"
#include "setup/Names.hpp"

namespace gf {

using namespace setup_detail;
using Shape = CaseConfig::Shape;
using Prescribed = CaseConfig::Prescribed;

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
         air == o.air && rheology == o.rheology && levelset == o.levelset && interface == o.interface && initial == o.initial &&
         flow == o.flow && walls == o.walls && periodic_x == o.periodic_x && side_walls == o.side_walls && gate == o.gate && output == o.output && collapse == o.collapse &&
         solver == o.solver &&
         probes == o.probes;
}

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

namespace {

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
  rh.anderson_depth = static_cast<int>(p.get_int("rheology.anderson_depth"));
  rh.anderson_reset_ratio = p.get_real("rheology.anderson_reset_ratio");
  rh.fp_monitor = p.get_bool("rheology.fp_monitor");
  rh.newton = p.get_string("rheology.solver") == "newton";
  rh.newton_coupled = p.get_string("rheology.newton_pressure") == "coupled";
  rh.newton_wall_iterate = p.get_string("rheology.newton_wall_load") == "iterate";
  rh.newton_tol = p.get_real("rheology.newton_tol");
  rh.newton_max_iter = static_cast<int>(p.get_int("rheology.newton_max_iter"));

  c.levelset.enabled = p.get_bool("levelset.enabled");
  c.levelset.eps_cells = p.get_real("levelset.eps_cells");
  c.levelset.redistance_every = static_cast<int>(p.get_int("levelset.redistance_every"));
  c.levelset.redistance_iters = static_cast<int>(p.get_int("levelset.redistance_iters"));
  c.levelset.redistance_tol = p.get_real("levelset.redistance_tol");
  c.levelset.redistance_interval = p.get_real("levelset.redistance_interval");
  c.levelset.redistance_wall_extrapolate =
      p.get_string("levelset.redistance_wall") == "extrapolate";
  c.levelset.redistance_cfl = p.get_real("levelset.redistance_cfl");
  c.interface.method =
      enum_of<interface::Method>(kInterfaceMethods, p.get_string("interface.method"));
  c.interface.normals = enum_of<vof::Normals>(kInterfaceNormals, p.get_string("interface.normals"));

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
  c.side_walls.width = p.get_real("boundary.side_walls.width");
  c.side_walls.friction_angle_deg = p.get_real("boundary.side_walls.friction_angle");
  c.side_walls.earth_pressure = p.get_real("boundary.side_walls.earth_pressure");
  c.side_walls.eta_b = p.get_real("boundary.side_walls.eta_b");
  c.side_walls.hydrostatic = p.get_string("boundary.side_walls.normal_stress") == "hydrostatic";
  c.gate.x = p.get_real("boundary.gate.x");
  c.gate.height = p.get_real("boundary.gate.height");
  c.gate.speed = p.get_real("boundary.gate.speed");
  c.gate.friction_angle_deg = p.get_real("boundary.gate.friction_angle");
  c.gate.eta_b = p.get_real("boundary.gate.eta_b");

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

CaseConfig resolve(Params& p, InputErrors& errors) {
  CaseConfig c = fill(p);
  check_case(p, c, errors);
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

std::string write_resolved_case(const CaseConfig& c, const std::string& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return path + ": cannot write the resolved case";
  out << c.resolved_toml;
  out.close();
  return out ? "" : path + ": writing the resolved case failed";
}

}  // namespace gf
