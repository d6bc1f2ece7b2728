#include "sim/Simulation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/Error.hpp"
#include "diagnostics/Diagnostics.hpp"
#include "io/Csv.hpp"
#include "io/Json.hpp"
#include "io/Vtk.hpp"
#include "levelset/LevelSet.hpp"

namespace gf {

Simulation::Simulation(const Grid& g, State& s, Stepper& stepper, const RunConfig& rc)
    : g_(g), s_(s), stepper_(stepper), rc_(rc) {}

double Simulation::choose_dt(double umax, double dt_prev) const {
  double dt;
  if (rc_.dt_fixed) {
    dt = rc_.dt;
  } else {
    const double h = std::min(g_.hx(), g_.hy());
    dt = rc_.dt_max;
    if (umax > 0) dt = std::min(dt, rc_.cfl * h / umax);
    const auto& gr = stepper_.config().gravity;
    const double gmag = std::hypot(gr[0], gr[1]);
    // A fluid starting from rest accelerates by |g|: it must not cross more than a cell
    // fraction in one step (sqrt(h/|g|) is the time to fall one cell from rest, times sqrt 2).
    if (gmag > 0 && stepper_.config().prescribed == PrescribedFlow::None)
      dt = std::min(dt, rc_.cfl * std::sqrt(h / gmag));
    if (dt_prev > 0) dt = std::min(dt, 1.2 * dt_prev);
    else if (rc_.dt > 0) dt = std::min(dt, rc_.dt);
  }
  const double remaining = rc_.t_end - s_.t;
  if (dt > remaining) dt = remaining;
  return dt;
}

namespace {
double wall_now() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}
}  // namespace

RunSummary Simulation::run() {
  namespace fs = std::filesystem;
  const bool root = g_.rank() == 0;
  if (root) fs::create_directories(rc_.out_dir);
  MPI_Barrier(g_.comm());
  const auto& cfg = stepper_.config();

  io::CsvWriter csv(rc_.out_dir + "/diagnostics.csv",
                    {"t", "dt", "step", "granular_volume", "volume_change_pct", "max_speed",
                     "granular_u", "granular_v", "kinetic_energy", "max_divergence", "visc_its", "pres_its", "fp_iters",
                     "fp_change", "left_stick_m", "left_slide_m", "bottom_stick_m",
                     "bottom_slide_m", "left_normal_N", "left_friction_N", "bottom_normal_N",
                     "bottom_friction_N", "front_x", "backwall_h", "max_p_granular",
                     "max_speed_granular"},
                    g_.comm());
  // Column-collapse measures and their files (profiles.csv, structure.csv, deposit.csv).
  diag::CollapseMonitor collapse(g_, rc_.collapse, rc_.out_dir, cfg.levelset);
  io::ProbeWriter probes(g_, rc_.out_dir, rc_.probes);
  Field dnorm(g_.dm_cell(), "D_norm"), snorm(g_.dm_cell(), "S_norm"),
      yielded(g_.dm_cell(), "yielded");
  std::unique_ptr<io::VtkSeries> vtk;
  if (rc_.vtk_interval > 0) vtk = std::make_unique<io::VtkSeries>(g_, rc_.out_dir, "fields");
  // Cell-centred velocity (2 interleaved components, reusing the dm_vel layout) and |u|.
  Field ucell(g_.dm_vel(), "u_cell"), speed(g_.dm_cell(), "speed");

  const double eps = cfg.levelset ? cfg.eps : 0.0;
  auto volume = [&]() {
    return cfg.levelset ? diag::granular_volume(g_, s_.phi, eps) : g_.box().Lx * g_.box().Ly;
  };
  const double vol0 = volume();
  RunSummary sum;
  StepStats last;
  double max_div_run = 0;
  long long fp_capped_steps = 0;  // steps whose fixed point stopped at its cap (a warning)
  int max_fp_iters = 0;
  long long mu_floor_max = 0, mu_cap_max = 0;  // mu(I): most granular cells at the bounds

  auto write_diag = [&]() {
    const double vol = volume();
    const double vchange = vol0 > 0 ? 100.0 * (vol - vol0) / vol0 : 0.0;
    const double div = diag::max_divergence(g_, s_.vel);
    max_div_run = std::max(max_div_run, div);
    const auto gu = diag::granular_mean_velocity(g_, s_.vel, s_.phi, eps);
    // Where the granular material sticks to / slides on the back wall and the bottom (eqs. 22-23).
    const auto wc = stepper_.wall_contact(s_);
    const auto &stick = wc.stick_m, &slide = wc.slide_m;
    const auto col = collapse.sample(s_.t, s_.phi, s_.vel, s_.p);
    csv.row({s_.t, s_.dt, static_cast<double>(s_.step), vol, vchange,
             diag::max_speed(g_, s_.vel), gu[0], gu[1], diag::kinetic_energy(g_, s_.vel, s_.rho), div,
             static_cast<double>(last.visc_its), static_cast<double>(last.pres_its),
             static_cast<double>(last.fp_iters), last.fp_change, stick[0], slide[0], stick[2],
             slide[2], wc.normal_N[0], wc.friction_N[0], wc.normal_N[2], wc.friction_N[2],
             col.front_x, col.backwall_h, col.max_p_granular, col.max_speed_granular});
    // The plastic fields only when a probe samples them (one extra strain-rate evaluation).
    io::NamedCellFields extra;
    if (probes.samples("D_norm") || probes.samples("S_norm")) {
      stepper_.derived_fields(s_, dnorm, snorm, yielded);
      extra = {{"D_norm", dnorm}, {"S_norm", snorm}};
    }
    if (probes.samples("kappa")) extra.emplace_back("kappa", stepper_.kappa());
    probes.write(s_.t, s_.phi, s_.rho, s_.vel, s_.p, s_.eta, extra);
    sum.volume_change_pct = vchange;
  };
  auto write_vtk = [&]() {
    if (!vtk) return;
    io::cell_velocity(g_, s_.vel, ucell, nullptr, speed);
    stepper_.derived_fields(s_, dnorm, snorm, yielded);
    vtk->write(s_.t, {{"phi", s_.phi, 1}, {"rho", s_.rho, 1}, {"u", ucell, 2},
                      {"speed", speed, 1}, {"p", s_.p, 1}, {"eta", s_.eta, 1},
                      {"D_norm", dnorm, 1}, {"S_norm", snorm, 1}, {"yielded", yielded, 1},
                      {"kappa", stepper_.kappa(), 1}});
  };

  stepper_.initialize(s_);
  // A prescribed flow that returns the interface to its start (one turn, a reversed vortex)
  // has the initial level set as exact answer: keep it for the interface error at the end.
  Field phi0(g_.dm_cell(), "phi0");
  const bool prescribed = cfg.prescribed != PrescribedFlow::None;
  if (prescribed) GF_PETSC(VecCopy(s_.phi, phi0));
  write_diag();
  write_vtk();
  double next_out = s_.t + rc_.output_interval;
  double next_vtk = s_.t + rc_.vtk_interval;
  const double t0 = wall_now();
  double last_progress = t0;
  const long long step0 = s_.step;
  const double tiny = 1e-12 * std::max(1.0, rc_.t_end);
  double dt_prev = 0;
  while (s_.t < rc_.t_end - tiny && (rc_.max_steps <= 0 || s_.step - step0 < rc_.max_steps)) {
    const double umax = diag::max_speed(g_, s_.vel);
    const double dt = choose_dt(umax, dt_prev);
    if (!(dt >= rc_.dt_min) && s_.t + dt < rc_.t_end - tiny) {
      std::ostringstream m;
      m << "time step collapsed to " << dt << " s (floor time.dt_min = " << rc_.dt_min
        << " s) at t = " << s_.t << " s, step " << s_.step << ", max |u| = " << umax
        << " m/s; the flow is blowing up: try a smaller time.cfl or time.dt_max";
      write_diag();
      throw RunError(m.str());
    }
    last = stepper_.step(s_, dt);
    if (last.fp_capped) ++fp_capped_steps;
    mu_floor_max = std::max(mu_floor_max, last.mu_i_floor_cells);
    mu_cap_max = std::max(mu_cap_max, last.mu_i_cap_cells);
    max_fp_iters = std::max(max_fp_iters, last.fp_iters);
    dt_prev = dt;
    // Failure detection: a non-finite velocity or pressure anywhere stops the run.
    PetscReal nv, np;
    GF_PETSC(VecNorm(s_.vel, NORM_INFINITY, &nv));
    GF_PETSC(VecNorm(s_.p, NORM_INFINITY, &np));
    if (!std::isfinite(nv) || !std::isfinite(np)) {
      std::ostringstream m;
      m << "non-finite velocity or pressure at t = " << s_.t << " s, step " << s_.step
        << " (dt = " << dt << " s); try a smaller time.cfl or time.dt";
      throw RunError(m.str());
    }
    const bool at_end = s_.t >= rc_.t_end - tiny;
    if (s_.t >= next_out - tiny || at_end) {
      write_diag();
      while (next_out <= s_.t + tiny) next_out += rc_.output_interval;
    }
    if (rc_.vtk_interval > 0 && (s_.t >= next_vtk - tiny || at_end)) {
      write_vtk();
      while (next_vtk <= s_.t + tiny) next_vtk += rc_.vtk_interval;
    }
    const double now = wall_now();
    if (root && rc_.progress_interval > 0 && now - last_progress >= rc_.progress_interval) {
      const double rate = (s_.step - step0) / (now - t0);
      const double eta_s = (rc_.t_end - s_.t) / dt / std::max(rate, 1e-30);
      std::fprintf(stderr, "t = %.4f s  dt = %.3e s  step %lld  %.1f steps/s  ETA %.0f s\n",
                   s_.t, dt, s_.step, rate, eta_s);
      last_progress = now;
    }
  }
  sum.steps = s_.step - step0;
  sum.t_end = s_.t;
  sum.wall_s = wall_now() - t0;
  sum.max_divergence = max_div_run;

  io::JsonObject js;
  js.set("title", rc_.title)
      .set("version", std::string(GRANFLOW_GIT_HASH))
      .set("ranks", static_cast<long long>(g_.size()))
      .set("nx", static_cast<long long>(g_.nx()))
      .set("ny", static_cast<long long>(g_.ny()))
      .set("cells", static_cast<long long>(g_.nx() * g_.ny()))
      .set("steps", sum.steps)
      .set("t_end", sum.t_end)
      .set("wall_s", sum.wall_s)
      .set("s_per_step", sum.steps > 0 ? sum.wall_s / sum.steps : 0.0)
      .set("max_divergence", sum.max_divergence)
      .set("volume_change_pct", sum.volume_change_pct)
      .set("max_speed", diag::max_speed(g_, s_.vel))
      .set("kinetic_energy", diag::kinetic_energy(g_, s_.vel, s_.rho))
      .set("max_fp_iters", static_cast<long long>(max_fp_iters))
      .set("warnings_fp_capped_steps", fp_capped_steps)
      .set("mu_i_floor_cells_max", mu_floor_max)
      .set("mu_i_cap_cells_max", mu_cap_max);
  collapse.summarize(js);
  if (prescribed && cfg.levelset) {
    // Sharp-interface measures against the initial shape (levelset/LevelSet.hpp).
    const double a0 = levelset::granular_area(g_, phi0, 0.0);
    const double a1 = levelset::granular_area(g_, s_.phi, 0.0);
    js.set("area_change_pct", a0 > 0 ? 100.0 * (a1 - a0) / a0 : 0.0)
        .set("interface_l1_error_m2", levelset::interface_l1_error(g_, s_.phi, phi0));
  }
  if (root) js.write(rc_.out_dir + "/summary.json");
  return sum;
}

}  // namespace gf
