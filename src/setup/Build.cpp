#include "setup/Build.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "core/Error.hpp"
#include "levelset/PrescribedFlow.hpp"
#include "setup/Kinematic.hpp"
#include "setup/Report.hpp"
#include "vof/Vof.hpp"

namespace gf {

namespace {
levelset::RedistanceConfig redistance_from_case(const CaseConfig& c) {
  levelset::RedistanceConfig r;
  r.every = c.levelset.redistance_every;
  r.iters = c.levelset.redistance_iters;
  r.cfl = c.levelset.redistance_cfl;
  r.tol = c.levelset.redistance_tol;
  r.interval = c.levelset.redistance_interval;
  r.wall_extrapolate = c.levelset.redistance_wall_extrapolate;
  return r;
}
// m, the half-width of the smeared Heaviside of eq. 25.
double eps_of(const CaseConfig& c) { return c.levelset.eps_cells * std::max(c.hx, c.hy); }
}  // namespace

PhysicsConfig physics_from_case(const CaseConfig& c) {
  PhysicsConfig p;
  p.rho_gran = c.granular.rho;
  p.eta_gran = c.granular.eta;
  p.rho_air = c.air.rho;
  p.eta_air = c.air.eta;
  p.gravity = c.gravity;
  p.levelset = c.levelset.enabled;
  p.eps = eps_of(c);
  p.redistance = redistance_from_case(c);
  auto wall = [&](CaseConfig::Side s) {
    const auto& w = c.walls[s];
    return WallBC{w.type, w.eta_b, w.velocity};
  };
  p.bc.left = wall(CaseConfig::kLeft);
  p.bc.right = wall(CaseConfig::kRight);
  p.bc.bottom = wall(CaseConfig::kBottom);
  p.bc.top = wall(CaseConfig::kTop);
  p.pressure_rtol = c.solver.pressure_rtol;
  p.viscous_rtol = c.solver.viscous_rtol;
  p.initial_pressure_hydrostatic = c.initial.pressure_hydrostatic;
  const auto& rh = c.rheology;
  p.rheo.yield = rh.yield;
  p.rheo.tau_y = rh.tau_y;
  p.rheo.tan_alpha = rh.tan_alpha();
  p.rheo.viscosity = rh.viscosity;
  p.rheo.mu_inf = rh.mu_inf;
  p.rheo.I0 = rh.I0;
  p.rheo.d = rh.d;
  p.rheo.eta_min = rh.eta_min;
  p.rheo.eta_max = rh.eta_max;
  p.rheo.r_factor = rh.r_factor;
  p.rheo.theta_per_dt = rh.theta_per_dt;
  p.rheo.node_copy = rh.node_copy;
  p.rheo.fp_tol = rh.fp_tol;
  p.rheo.fp_tol_u = rh.fp_tol_u;
  p.rheo.fp_max_iter = rh.fp_max_iter;
  p.fp.anderson_depth = rh.anderson_depth;
  p.fp.anderson_reset_ratio = rh.anderson_reset_ratio;
  p.fp.monitor = rh.fp_monitor;
  p.newton = rh.newton;
  p.newton_coupled = rh.newton_coupled;
  p.newton_opt.tol = rh.newton_tol;
  p.newton_opt.max_outer = rh.newton_max_iter;
  p.newton_opt.refresh_kappa_b = rh.newton_wall_iterate;
  p.newton_opt.local_margin = c.solver.viscous_local_margin;
  p.newton_opt.momentum_rtol = c.solver.viscous_rtol;
  p.fp.local_margin = c.solver.viscous_local_margin;
  p.yield_support = rh.yield_on_mass && c.levelset.enabled ? p.eps : 0.0;
  p.interface_method = c.interface.method;
  p.normals = c.interface.normals;
  for (int sd = 0; sd < 4; ++sd)
    p.wall_tan_b[sd] = c.walls[sd].friction_angle_deg > 0 ? c.walls[sd].tan_friction() : 0.0;
  const auto& sw = c.side_walls;
  p.side.width = sw.width;
  p.side.tan_w = sw.friction_angle_deg > 0 ? sw.tan_friction() : 0.0;
  p.side.earth_pressure = sw.earth_pressure;
  p.side.hydrostatic = sw.hydrostatic;
  // The air's drag only in a two-phase run (in a one-phase run every cell is granular).
  p.side.eta_b = c.levelset.enabled ? sw.eta_b : 0.0;
  p.side.eta_air = c.air.eta;
  p.gate.x = c.gate.x;
  p.gate.height = c.gate.height;
  p.gate.speed = c.gate.speed;
  p.gate.tan_g = c.gate.friction_angle_deg > 0 ? c.gate.tan_friction() : 0.0;
  p.gate.eta_b = c.gate.eta_b;
  return p;
}

std::unique_ptr<TimeStepper> make_stepper(const Grid& g, const CaseConfig& c) {
  if (c.flow.prescribed == PrescribedFlow::None)
    return std::make_unique<Stepper>(g, physics_from_case(c));
  KinematicConfig k;
  k.flow = c.flow.prescribed;
  k.omega = c.flow.omega;
  k.cx = c.flow.cx;
  k.cy = c.flow.cy;
  k.period = c.flow.period;
  k.redistance = redistance_from_case(c);
  k.method = c.interface.method;
  k.normals = c.interface.normals;
  k.eps = eps_of(c);
  k.rho_air = c.air.rho;
  k.rho_gran = c.granular.rho;
  k.eta_air = c.air.eta;
  k.eta_gran = c.granular.eta;
  return std::make_unique<KinematicStepper>(g, k);
}

RunConfig run_from_case(const CaseConfig& c, const std::string& out_dir) {
  RunConfig r;
  r.t_end = c.time.t_end;
  r.dt_fixed = c.time.dt_mode == CaseConfig::DtMode::Fixed;
  r.dt = r.dt_fixed ? c.time.dt : initial_dt(c);
  r.cfl = c.time.cfl;
  r.stress_equilibrium = c.initial.stress_equilibrium;
  r.stress_max_steps = c.initial.stress_max_steps;
  r.stress_tol = c.initial.stress_tol;
  r.dt_max = c.time.dt_max;
  r.dt_min = c.time.dt_min;
  r.max_steps = c.time.max_steps;
  r.max_speed = c.time.max_speed;
  r.speed_scale = velocity_scale(c);
  r.checkpoint_interval_steps = c.output.checkpoint_interval_steps;
  r.checkpoint_wall_s = c.output.checkpoint_wall_s;
  r.volume_warn_pct = c.output.volume_warn_pct;
  r.fp_fail_change = c.rheology.fp_fail_change;
  r.newton = c.rheology.newton;
  r.output_interval = c.output.interval;
  r.vtk_interval = c.output.vtk_interval;
  r.progress_interval = c.output.progress_interval;
  for (const auto& pr : c.probes) {
    io::ProbeSpec s{pr.name, pr.x0, pr.y0, pr.x1, pr.y1, pr.points, {}};
    for (auto f : pr.fields) s.fields.emplace_back(to_string(f));
    r.probes.push_back(std::move(s));
  }
  auto& co = r.collapse;
  co.cutoffs = c.collapse.cutoffs;
  co.slope_back_range = c.collapse.slope_back_range;
  co.slope_front_range = c.collapse.slope_front_range;
  co.front_fit_length = c.collapse.front_fit_length;
  co.stages = {c.collapse.speed_window, c.collapse.plateau_fraction, c.collapse.stop_distance,
               c.collapse.rest_speed};
  co.rho_s = c.granular.rho;
  co.gravity = std::hypot(c.gravity[0], c.gravity[1]);
  co.eps = c.levelset.enabled ? eps_of(c) : 0.0;  // as eq. 25
  r.out_dir = out_dir;
  r.title = c.title;
  return r;
}

std::function<double(double, double)> initial_distance(const CaseConfig& c) {
  const auto& in = c.initial;
  std::function<double(double, double)> d;
  switch (in.shape) {
    case CaseConfig::Shape::None: return [](double, double) { return 1.0; };  // all air
    case CaseConfig::Shape::Rectangle: {
      // A side of the column lying on a wall is not an interface: extend the rectangle beyond
      // that wall so that phi is the distance to the free sides only (otherwise H_eps smears
      // granular volume away along the walls: 2 % of the column at n = 32). With periodic x
      // the sides x = 0 and x = Lx are interfaces with the periodic image (unless the
      // rectangle spans the whole period, then it is a layer: extend it as well).
      const double Lx = c.domain.Lx, Ly = c.domain.Ly;
      const bool span = in.x0 <= 0 && in.x1 >= Lx;
      const bool ext_x0 = in.x0 <= 0 && (!c.periodic_x || span);
      const bool ext_x1 = in.x1 >= Lx && (!c.periodic_x || span);
      const double x0 = ext_x0 ? -Lx : in.x0, x1 = ext_x1 ? 2 * Lx : in.x1;
      const double y0 = in.y0 <= 0 ? -Ly : in.y0, y1 = in.y1 >= Ly ? 2 * Ly : in.y1;
      d = [=](double x, double y) { return levelset::rectangle_distance(x, y, x0, x1, y0, y1); };
      break;
    }
    case CaseConfig::Shape::Layer:
      d = [h = in.height](double, double y) { return y - h; };
      break;
    case CaseConfig::Shape::Circle:
      d = [=](double x, double y) { return levelset::circle_distance(x, y, in.cx, in.cy, in.radius); };
      break;
    case CaseConfig::Shape::Trapezoid:
      d = [=](double x, double y) {
        return levelset::trapezoid_distance(x, y, in.x0, in.x1, in.height, in.slope_deg);
      };
      break;
    case CaseConfig::Shape::Zalesak:
      d = [=](double x, double y) {
        return levelset::zalesak_distance(x, y, in.cx, in.cy, in.radius, in.slot_width,
                                          in.slot_depth);
      };
      break;
  }
  if (!c.periodic_x) return d;
  // With periodic x the shape repeats with period Lx: the distance to the nearest image.
  const double Lx = c.domain.Lx;
  return [=](double x, double y) { return std::min({d(x - Lx, y), d(x, y), d(x + Lx, y)}); };
}

void initial_levelset(const Grid& g, const CaseConfig& c, Vec phi) {
  if (!c.levelset.enabled) {
    GF_PETSC(VecSet(phi, -1.0));
    return;
  }
  const auto d = initial_distance(c);
  const Box& b = g.box();
  PetscScalar** p;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), phi, &p));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) p[j][i] = d(b.xc(i), b.yc(j));
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), phi, &p));
}

void initial_fraction(const Grid& g, const CaseConfig& c, Vec frac) {
  if (!c.levelset.enabled) {
    GF_PETSC(VecSet(frac, 1.0));
    return;
  }
  vof::init_fraction(g, frac, initial_distance(c));
}

void initial_velocity(const Grid& g, const CaseConfig& c, Vec vel, Vec vel_old) {
  GF_PETSC(VecSet(vel, 0.0));
  if (c.initial.velocity == CaseConfig::InitialVelocity::Vortex) {
    const Box& b = g.box();
    const double A = c.initial.velocity_amplitude, pi = std::numbers::pi;
    const double Lx = b.Lx, Ly = b.Ly;
    auto sq = [](double x) { return x * x; };
    if (b.periodic_x)
      levelset::velocity_from_stream_function(g, vel, [=](double x, double y) {
        return A * (Ly / pi) * std::sin(2 * pi * x / Lx) * sq(std::sin(pi * y / Ly));
      });
    else
      levelset::velocity_from_stream_function(g, vel, [=](double x, double y) {
        return A * (Lx / pi) * sq(std::sin(pi * x / Lx)) * sq(std::sin(pi * y / Ly));
      });
  }
  GF_PETSC(VecCopy(vel, vel_old));
}

}  // namespace gf
