#include "sim/Simulation.hpp"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>

#include "core/Error.hpp"
#include "core/Log.hpp"
#include "core/Profile.hpp"
#include "core/Signal.hpp"
#include "core/Version.hpp"
#include "diagnostics/Diagnostics.hpp"
#include "io/IoError.hpp"
#include "io/Json.hpp"
#include "levelset/LevelSet.hpp"
#include "sim/Counters.hpp"
#include "vof/Vof.hpp"

namespace gf {

namespace {

double wall_now() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string hex(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%a", v);
  return b;
}

// The first time of the schedule k interval (k = 1, 2, ...) after t + tiny. Computed, not
// stepped to: a loop adding the interval until it passes t never ends when the interval is
// below t's resolution (1e-300, or t = 1e308), and would take 1e300 turns if it did.
double next_on_schedule(double t, double interval, double tiny) {
  if (!(interval > 0)) return std::numeric_limits<double>::infinity();
  const double k = std::floor((t + tiny) / interval) + 1;
  const double next = k * interval;
  return next > t + tiny ? next : (k + 1) * interval;  // the division's round-off
}

// k times `interval` as the decimal number the user wrote it is a multiple of: the interval's
// shortest decimal form (0.1 -> 1e-1) times k, correctly rounded (3 x 0.1 gives 0.3, not the
// product 0.30000000000000004). The product where the decimal form is long (1/3).
double decimal_multiple(long long k, double interval) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, interval, std::chars_format::scientific);
  const std::string s(buf, r.ptr);  // "d.ddde[+-]x"
  const auto e = s.find('e');
  std::string digits;
  for (std::size_t i = 0; i < e; ++i)
    if (s[i] != '.') digits += s[i];
  if (r.ec != std::errc() || e == std::string::npos || digits.size() > 15 || k < 0)
    return static_cast<double>(k) * interval;
  const int exp10 = std::atoi(s.c_str() + e + 1) - static_cast<int>(digits.size()) + 1;
  unsigned __int128 m = static_cast<unsigned __int128>(std::stoull(digits)) *
                        static_cast<unsigned __int128>(k);
  std::string text;
  do {
    text.insert(text.begin(), static_cast<char>('0' + static_cast<int>(m % 10)));
    m /= 10;
  } while (m > 0);
  text += "e" + std::to_string(exp10);
  return std::strtod(text.c_str(), nullptr);
}

// The prognostic fields, in checkpoint order (their names are checked on loading).
std::vector<io::CheckpointField> checkpoint_fields(State& s, Vec phi0, Vec frac0,
                                                   const ModelTraits& tr) {
  // rho and eta are derived from phi (and, with mu(I), from u and p) but are kept as the last
  // step left them, so that a restart needs no recomputation that could differ.
  std::vector<io::CheckpointField> f = {
      {"phi", s.phi}, {"velocity", s.vel}, {"velocity_old", s.vel_old}, {"p", s.p},
      {"S", s.S},     {"s_wall", s.s_wall}, {"rho", s.rho},             {"eta", s.eta}};
  if (tr.returns_to_start) f.push_back({"phi0", phi0});
  if (tr.node_copy) f.push_back({"S_node", s.S_node});  // rheology.plastic_grid = "cell_node"
  if (tr.side_walls) f.push_back({"s_side", s.s_side});  // boundary.side_walls
  if (tr.newton) f.push_back({"velocity_prediction", s.vel_pred});  // rheology.solver = newton
  if (tr.conservative) {  // interface.method = "clsvof": the volume fraction carries the mass
    f.push_back({"volume_fraction", s.frac});
    if (tr.returns_to_start) f.push_back({"volume_fraction0", frac0});
  }
  return f;
}

const std::vector<std::string> kDiagnosticsColumns = {
    "t", "dt", "step", "granular_volume", "volume_change_pct", "max_speed", "granular_u",
    "granular_v", "kinetic_energy", "max_divergence", "visc_its", "pres_its", "fp_iters",
    "fp_change", "left_stick_m", "left_slide_m", "bottom_stick_m", "bottom_slide_m",
    "left_normal_N", "left_friction_N", "bottom_normal_N", "bottom_friction_N", "front_x",
    "backwall_h", "max_p_granular", "max_speed_granular", "volume_step_change",
    "potential_energy", "dissipated_viscous", "dissipated_plastic", "dissipated_friction",
    "energy_residual", "side_stick_m2", "side_slide_m2", "side_normal_N", "side_friction_x_N",
    "side_friction_y_N", "gate_bottom_m", "gate_normal_N", "gate_friction_N", "fp_change_max",
    "fp_capped_steps"};

}  // namespace

// The files of a run and the scratch fields of its outputs, open for the duration of run().
struct Simulation::Output {
  io::CsvWriter csv;
  io::ProbeWriter probes;
  io::CollapseMonitor collapse;  // profiles.csv, structure.csv, deposit.csv
  std::unique_ptr<io::VtkSeries> vtk;
  Field dnorm, snorm, yielded;  // plastic fields (cells)
  Field ucell, speed;  // cell-centred velocity (2 interleaved components, dm_vel layout) and |u|
  Output(const Grid& g, const RunConfig& rc, bool two_phase, bool restarted, long long diag_bytes,
         const std::vector<long long>& probe_bytes, const io::CheckpointHeader* restart)
      : csv(restarted ? io::CsvWriter(rc.out_dir + "/diagnostics.csv", kDiagnosticsColumns,
                                      diag_bytes, g.comm())
                      : io::CsvWriter(rc.out_dir + "/diagnostics.csv", kDiagnosticsColumns,
                                      g.comm())),
        probes(g, rc.out_dir, rc.probes, io::default_extra_cell_fields(),
               restarted ? probe_bytes : std::vector<long long>{}),
        collapse(g, rc.collapse, rc.out_dir, two_phase, restart),
        dnorm(g.dm_cell(), "D_norm"),
        snorm(g.dm_cell(), "S_norm"),
        yielded(g.dm_cell(), "yielded"),
        ucell(g.dm_vel(), "u_cell"),
        speed(g.dm_cell(), "speed") {}
};

Simulation::Simulation(const Grid& g, State& s, TimeStepper& stepper, const RunConfig& rc)
    : g_(g),
      s_(s),
      stepper_(stepper),
      rc_(rc),
      phi0_(g.dm_cell(), "phi0"),
      frac0_(g.dm_cell(), "volume_fraction0") {}

Simulation::~Simulation() = default;

void Loop::add(const StepStats& st, double dt) {
  last = st;
  if (st.fp_capped) {
    ++fp_capped_steps;
    fp_capped_change = std::max(fp_capped_change, st.fp_change);
    ++row_fp_capped;
  }
  row_fp_change_max = std::max(row_fp_change_max, st.fp_change);
  if (st.pres_fallback) ++pres_fallbacks;
  mu_floor_max = std::max(mu_floor_max, st.mu_i_floor_cells);
  mu_cap_max = std::max(mu_cap_max, st.mu_i_cap_cells);
  max_fp_iters = std::max(max_fp_iters, st.fp_iters);
  fp_iters_total += st.fp_iters;
  visc_its_total += st.visc_its;
  visc_polish_its_total += st.visc_polish_its;
  if (st.visc_polish_its > 0) ++visc_polish_steps;
  if (st.redistanced) ++redistancings;
  diss_viscous += st.diss_viscous;
  diss_plastic += st.diss_plastic;
  diss_friction += st.diss_friction;
  dt_prev = dt;
}

double Simulation::choose_dt(double umax, double dt_prev) const {
  double dt;
  if (rc_.dt_fixed) {
    dt = rc_.dt;
  } else {
    const double h = std::min(g_.hx(), g_.hy());
    dt = rc_.dt_max;
    if (umax > 0) dt = std::min(dt, rc_.cfl * h / umax);
    const auto& gr = stepper_.traits().gravity;
    const double gmag = std::hypot(gr[0], gr[1]);
    // A fluid starting from rest accelerates by |g|: it must not cross more than a cell
    // fraction in one step (sqrt(h/|g|) is the time to fall one cell from rest, times sqrt 2).
    if (gmag > 0 && stepper_.traits().solves_momentum)
      dt = std::min(dt, rc_.cfl * std::sqrt(h / gmag));
    if (dt_prev > 0) dt = std::min(dt, 1.2 * dt_prev);
    else if (rc_.dt > 0) dt = std::min(dt, rc_.dt);
  }
  const double remaining = rc_.t_end - s_.t;
  if (dt > remaining) dt = remaining;
  return dt;
}

// ------------------------------------------------------------------------------ checkpoints

void Simulation::save_checkpoint(const std::string& reason) {
  io::CheckpointHeader h;
  const Box& b = g_.box();
  h.set_text("version", gf::git_version());
  h.set_text("reason", reason);
  h.set("ranks", static_cast<long long>(g_.size()));
  h.set("grid.nx", static_cast<long long>(b.nx));
  h.set("grid.ny", static_cast<long long>(b.ny));
  h.set("grid.periodic_x", static_cast<long long>(b.periodic_x));
  h.set("domain.Lx", b.Lx);
  h.set("domain.Ly", b.Ly);
  h.set("t", s_.t);
  h.set("dt", s_.dt);
  h.set("dt_old", s_.dt_old);
  h.set("step", s_.step);
  Loop l = lp_;
  l.wall_s += wall_now() - seg_t0_;  // the wall clock of every run so far
  counters::save(counters::loop_counters(), l, h);
  counters::save(counters::step_counters(), lp_.last, h);
  if (out_) out_->collapse.save(h);
  // Where the output files stood (rank 0 knows; rank 0 writes the header).
  h.set("files.diagnostics", out_ ? out_->csv.bytes() : 0);
  const auto pb = out_ ? out_->probes.file_bytes() : decltype(out_->probes.file_bytes()){};
  h.set("files.probes", static_cast<long long>(pb.size()));
  for (std::size_t k = 0; k < pb.size(); ++k)
    h.set_text("files.probe." + std::to_string(k), std::to_string(pb[k].second) + " " + pb[k].first);
  const auto& ve = out_ && out_->vtk ? out_->vtk->entries() : vtk_entries_;
  h.set("vtk.count", static_cast<long long>(ve.size()));
  for (std::size_t k = 0; k < ve.size(); ++k)
    h.set_text("vtk." + std::to_string(k), hex(ve[k].first) + " " + ve[k].second);
  prof::Scope pscope(prof::Checkpoint);
  io::write_checkpoint(g_.comm(), rc_.out_dir, std::move(h),
                       checkpoint_fields(s_, phi0_, frac0_, stepper_.traits()), ckpt_files_);
  last_ckpt_step_ = s_.step;
  last_ckpt_t_ = s_.t;
  if (g_.rank() == 0)
    log::to_file("granflow: checkpoint (" + reason + ") at t = " + num(s_.t) + " s, step " +
                 std::to_string(s_.step) + " in " + rc_.out_dir + "/checkpoint");
}

void Simulation::restart(const std::string& ckpt_dir, const io::CheckpointHeader& h) {
  const Box& b = g_.box();
  const std::string src = h.source();
  // The grid first: a checkpoint of another grid cannot be loaded at all.
  const long long nx = h.get_int("grid.nx"), ny = h.get_int("grid.ny");
  const bool periodic = h.get_int("grid.periodic_x") != 0;
  const double Lx = h.get_double("domain.Lx"), Ly = h.get_double("domain.Ly");
  if (nx != b.nx || ny != b.ny)
    throw InputError(src + ": the checkpoint is for a " + std::to_string(nx) + " x " +
                     std::to_string(ny) + " grid, the case has " + std::to_string(b.nx) +
                     " x " + std::to_string(b.ny) +
                     " (grid.n / grid.nx differ): a restart continues on the same grid");
  if (Lx != b.Lx || Ly != b.Ly || periodic != b.periodic_x)
    throw InputError(src + ": the checkpoint is for a " + num(Lx) + " m x " + num(Ly) +
                     " m domain" + (periodic ? " (periodic in x)" : "") + ", the case has " +
                     num(b.Lx) + " m x " + num(b.Ly) + " m" + (b.periodic_x ? " (periodic in x)" : ""));
  const double t = h.get_double("t");
  if (rc_.t_end < t)
    throw InputError("time.t_end = " + num(rc_.t_end) + " s is before the checkpoint time t = " +
                     num(t) + " s (" + src + "): a restart continues forward; set time.t_end >= " +
                     num(t) + " s");
  s_.t = t;
  s_.dt = h.get_double("dt");
  s_.dt_old = h.get_double("dt_old");
  s_.step = h.get_int("step");
  // The header checksum catches an edit; these catch a header written from a broken state.
  if (!(std::isfinite(t) && t >= 0) || !(std::isfinite(s_.dt) && s_.dt >= 0) ||
      !(std::isfinite(s_.dt_old) && s_.dt_old >= 0) || s_.step < 0)
    throw io::IoError(src + ": t = " + num(t) + " s, dt = " + num(s_.dt) + " s, dt_old = " +
                      num(s_.dt_old) + " s, step " + std::to_string(s_.step) +
                      ": not a state to continue from (each must be finite and >= 0): corrupt "
                      "checkpoint");
  counters::restore(counters::loop_counters(), h, lp_);
  counters::restore(counters::step_counters(), h, lp_.last);
  ++lp_.restarts;
  diag_bytes_ = h.get_int("files.diagnostics");
  restart_header_ = h;  // the collapse monitor reads its history from it in run()
  // Probe files by name: the case comparison (setup/) has made sure the probes are the same.
  const long long np = h.get_int("files.probes");
  probe_bytes_.clear();
  for (const auto& spec : rc_.probes) {
    long long bytes = -1;
    for (long long k = 0; k < np; ++k) {
      const std::string v = h.get_text("files.probe." + std::to_string(k));
      const auto sp = v.find(' ');
      if (sp != std::string::npos && v.substr(sp + 1) == spec.name)
        bytes = std::stoll(v.substr(0, sp));
    }
    if (bytes < 0)
      throw InputError(src + ": the checkpoint has no record of probe '" + spec.name +
                       "': the probes of the case changed since the checkpoint");
    probe_bytes_.push_back(bytes);
  }
  vtk_entries_.clear();
  const long long nv = h.get_int("vtk.count");
  for (long long k = 0; k < nv; ++k) {
    const std::string v = h.get_text("vtk." + std::to_string(k));
    const auto sp = v.find(' ');
    char* end = nullptr;
    const double te = std::strtod(v.c_str(), &end);
    if (sp == std::string::npos || end != v.c_str() + sp)
      throw io::IoError(src + ": malformed entry vtk." + std::to_string(k) + " '" + v + "'");
    vtk_entries_.emplace_back(te, v.substr(sp + 1));
  }
  io::read_checkpoint_fields(g_.comm(), ckpt_dir, h,
                             checkpoint_fields(s_, phi0_, frac0_, stepper_.traits()));
  restarted_ = true;
  last_ckpt_step_ = s_.step;
  last_ckpt_t_ = s_.t;
}

// ------------------------------------------------------------------------------ outputs

double Simulation::granular_volume() const {
  const ModelTraits& tr = stepper_.traits();
  if (!tr.two_phase) return g_.box().Lx * g_.box().Ly;
  // With the volume fraction the granular volume is the conserved sum c hx hy (vof/Vof.hpp).
  return tr.conservative ? vof::volume(g_, s_.frac) : diag::granular_volume(g_, s_.phi, tr.eps);
}

double Simulation::potential_energy() const {
  const ModelTraits& tr = stepper_.traits();
  // A sharp volume fraction: its mass at the centroids of the PLIC polygons (vof/Vof.hpp).
  if (tr.conservative)
    return vof::potential_energy(g_, s_.frac, s_.phi, vof::Normals::LevelSet, tr.rho_air,
                                 tr.rho_gran, tr.gravity);
  return diag::potential_energy(g_, s_.rho, tr.gravity);
}

void Simulation::write_diagnostics() {
  prof::Scope pscope(prof::Output);
  const ModelTraits& tr = stepper_.traits();
  const double eps = tr.two_phase ? tr.eps : 0.0;
  const double vol = granular_volume();
  const double vchange = lp_.vol0 > 0 ? 100.0 * (vol - lp_.vol0) / lp_.vol0 : 0.0;
  const double div = diag::max_divergence(g_, s_.vel);
  lp_.max_div = std::max(lp_.max_div, div);
  const auto gu = tr.conservative ? diag::granular_mean_velocity(g_, s_.vel, s_.frac)
                                  : diag::granular_mean_velocity(g_, s_.vel, s_.phi, eps);
  // The energy budget: what the kinetic and potential energy lost since t = 0 beyond the
  // dissipation of the model's stresses is the numerical dissipation (< 0: energy created).
  const double ke = diag::kinetic_energy(g_, s_.vel, s_.rho);
  const double pe = potential_energy();
  const double residual =
      lp_.energy0 - ke - pe - lp_.diss_viscous - lp_.diss_plastic - lp_.diss_friction;
  // Where the granular material sticks to / slides on the back wall and the bottom (eqs. 22-23).
  const auto wc = stepper_.wall_contact(s_);
  const auto &stick = wc.stick_m, &slide = wc.slide_m;
  const StepStats& last = lp_.last;
  // The time written: the scheduled one when the step landed on it within round-off.
  const double t_out = output_time(rc_.output_interval);
  const auto col = out_->collapse.sample(s_.t, s_.phi, s_.vel, s_.p, t_out);
  const double speed = diag::max_speed(g_, s_.vel);
  // Rank 0 writes; a failure there must stop every rank, after the collective calls below.
  std::string err;
  try {
    out_->csv.row({t_out, s_.dt, static_cast<double>(s_.step), vol, vchange, speed, gu[0], gu[1],
                   ke, div, static_cast<double>(last.visc_its),
                   static_cast<double>(last.pres_its), static_cast<double>(last.fp_iters),
                   last.fp_change, stick[0], slide[0], stick[2], slide[2], wc.normal_N[0],
                   wc.friction_N[0], wc.normal_N[2], wc.friction_N[2], col.front_x,
                   col.backwall_h, col.max_p_granular, col.max_speed_granular, lp_.vol_step_max,
                   pe, lp_.diss_viscous, lp_.diss_plastic, lp_.diss_friction, residual,
                   wc.side.stick_m2, wc.side.slide_m2, wc.side.normal_N, wc.side.friction_N[0],
                   wc.side.friction_N[1], wc.gate_bottom_m, wc.gate_normal_N,
                   wc.gate_friction_N, lp_.row_fp_change_max,
                   static_cast<double>(lp_.row_fp_capped)});
  } catch (const io::IoError& e) {
    err = e.what();
  }
  lp_.vol_step_max = 0;
  lp_.row_fp_change_max = 0;
  lp_.row_fp_capped = 0;
  // The plastic fields only when a probe samples them (one extra strain-rate evaluation).
  io::NamedCellFields extra;
  if (out_->probes.samples("D_norm") || out_->probes.samples("S_norm")) {
    stepper_.derived_fields(s_, out_->dnorm, out_->snorm, out_->yielded);
    extra = {{"D_norm", out_->dnorm}, {"S_norm", out_->snorm}};
  }
  if (out_->probes.samples("kappa")) extra.emplace_back("kappa", stepper_.kappa());
  out_->probes.write(t_out, s_.phi, s_.rho, s_.vel, s_.p, s_.eta, extra);
  io::raise_on_all_ranks(g_.comm(), err);
  lp_.volume_change_pct = vchange;
  // Mass conservation is not exact with a level set: a drift beyond the threshold is a
  // warning (counted in summary.json), said once.
  if (tr.two_phase && std::abs(vchange) > rc_.volume_warn_pct) {
    if (lp_.volume_warn_rows == 0 && g_.rank() == 0)
      log::message("granflow: warning: the granular volume has changed by " + num(vchange) +
                   " % at t = " + num(s_.t) + " s (beyond output.volume_warn_pct = " +
                   num(rc_.volume_warn_pct) +
                   " %): the interface is under-resolved; try a larger grid.n or a smaller "
                   "time.cfl (counted in summary.json)");
    ++lp_.volume_warn_rows;
  }
}

void Simulation::write_vtk() {
  if (!out_->vtk) return;
  prof::Scope pscope(prof::Output);
  Output& o = *out_;
  io::cell_velocity(g_, s_.vel, o.ucell, nullptr, o.speed);
  stepper_.derived_fields(s_, o.dnorm, o.snorm, o.yielded);
  std::vector<io::CellField> f = {{"phi", s_.phi, 1},       {"rho", s_.rho, 1},
                                 {"u", o.ucell, 2},         {"speed", o.speed, 1},
                                 {"p", s_.p, 1},            {"eta", s_.eta, 1},
                                 {"D_norm", o.dnorm, 1},    {"S_norm", o.snorm, 1},
                                 {"yielded", o.yielded, 1}, {"kappa", stepper_.kappa(), 1}};
  if (stepper_.traits().conservative) f.push_back({"volume_fraction", s_.frac, 1});
  // The scheduled time in fields.pvd and TimeValue (0.1, not 0.10000000000000007).
  o.vtk->write(output_time(rc_.vtk_interval), f);
}

void Simulation::write_summary(const std::string& status, const std::string& message) {
  RunSummary& sum = summary_;
  sum.steps = s_.step;
  sum.t_end = s_.t;
  sum.wall_s = lp_.wall_s + (wall_now() - seg_t0_);
  sum.max_divergence = lp_.max_div;
  sum.volume_change_pct = lp_.volume_change_pct;
  io::JsonObject js;
  js.set("title", rc_.title)
      .set("status", status)
      .set("version", std::string(gf::git_version()))
      .set("ranks", static_cast<long long>(g_.size()))
      .set("nx", static_cast<long long>(g_.nx()))
      .set("ny", static_cast<long long>(g_.ny()))
      .set("cells", static_cast<long long>(g_.nx() * g_.ny()))
      .set("steps", sum.steps)
      .set("t_end", sum.t_end)
      .set("wall_s", sum.wall_s)
      .set("s_per_step", sum.steps > 0 ? sum.wall_s / sum.steps : 0.0);
  counters::summarize(lp_, counters::Summary::First, js);
  js.set("max_speed", diag::max_speed(g_, s_.vel))
      .set("kinetic_energy", diag::kinetic_energy(g_, s_.vel, s_.rho));
  counters::summarize(lp_, counters::Summary::Second, js);
  if (lp_.stress_steps >= 0) counters::summarize(lp_, counters::Summary::InitialStress, js);
  out_->collapse.summarize(js);
  {
    // Time by phase (core/Profile.hpp), the largest over the ranks, s: for this process, i.e.
    // since the start or the last restart. Peak resident memory, MiB: largest rank, all ranks.
    std::array<double, prof::kCount + 1> loc{}, mx{};
    for (int k = 0; k < prof::kCount; ++k) loc[k] = prof::seconds()[k];
    loc[prof::kCount] = prof::peak_rss_mib();
    MPI_Allreduce(loc.data(), mx.data(), prof::kCount + 1, MPI_DOUBLE, MPI_MAX, g_.comm());
    double rss_sum = 0;
    MPI_Allreduce(&loc[prof::kCount], &rss_sum, 1, MPI_DOUBLE, MPI_SUM, g_.comm());
    for (int k = 0; k < prof::kCount; ++k)
      js.set(std::string("time_") + prof::name(static_cast<prof::Phase>(k)) + "_s", mx[k]);
    js.set("peak_rss_mib_max_rank", mx[prof::kCount]).set("peak_rss_mib_all_ranks", rss_sum);
  }
  if (last_ckpt_step_ >= 0)
    js.set("checkpoint_t", last_ckpt_t_).set("checkpoint_step", last_ckpt_step_);
  if (!message.empty()) js.set("message", message);
  const ModelTraits& tr = stepper_.traits();
  if (tr.returns_to_start && tr.two_phase) {
    // Sharp-interface measures against the initial shape (levelset/LevelSet.hpp).
    const double a0 = levelset::granular_area(g_, phi0_, 0.0);
    const double a1 = levelset::granular_area(g_, s_.phi, 0.0);
    js.set("area_change_pct", a0 > 0 ? 100.0 * (a1 - a0) / a0 : 0.0)
        .set("interface_l1_error_m2", levelset::interface_l1_error(g_, s_.phi, phi0_));
    // The volume fraction's own L1 error, sum |c - c0| hx hy (interface.method = "clsvof").
    if (tr.conservative) js.set("fraction_l1_error_m2", vof::l1_error(g_, s_.frac, frac0_));
  }
  js.write_root(rc_.out_dir + "/summary.json", g_.comm());
}

std::string Simulation::when() const {
  return "t = " + num(s_.t) + " s, step " + std::to_string(s_.step);
}

void Simulation::fail(const std::string& what) {
  std::string msg = what;
  if (last_ckpt_step_ >= 0)
    msg += ". The last good checkpoint (t = " + num(last_ckpt_t_) + " s, step " +
           std::to_string(last_ckpt_step_) + ") is kept in " + rc_.out_dir +
           "/checkpoint" +
           (unsane_since_t_ >= 0 ? " (none was written from t = " + num(unsane_since_t_) +
                                       " s on: the state was not sane)"
                                 : "") +
           ": continue from it with `granflow run --restart " + rc_.out_dir +
           "` and a smaller step (--set time.cfl=... or time.dt=...)";
  else
    msg += ". No checkpoint was written before the failure (output.checkpoint_interval_steps, "
           "output.checkpoint_wall_s)";
  write_diagnostics();
  write_summary("failed", msg);
  throw RunError(msg);
}

// ------------------------------------------------------------------------------ the loop

void Simulation::open_outputs() {
  out_ = std::make_unique<Output>(g_, rc_, stepper_.traits().two_phase, restarted_, diag_bytes_,
                                  probe_bytes_, restarted_ ? &restart_header_ : nullptr);
  if (rc_.vtk_interval <= 0) return;
  out_->vtk = std::make_unique<io::VtkSeries>(g_, rc_.out_dir, "fields");
  if (!restarted_) return;
  const int missing = out_->vtk->resume(vtk_entries_);
  if (missing && g_.rank() == 0)
    log::message("granflow: warning: " + std::to_string(missing) +
                 " VTK file(s) listed at the checkpoint are missing; fields.pvd no "
                 "longer lists them");
}

void Simulation::equilibrate() {
  const double dt0 = choose_dt(0.0, 0.0);
  try {
    const double eps = stepper_.traits().eps;
    const auto [n, speed] = stepper_.equilibrate(
        s_, dt0, rc_.stress_max_steps, rc_.stress_tol, [&, k = 0](const State& st) mutable {
          // A stop signal ends the pseudo-steps (up to initial.stress_max_steps): their state
          // is no state to continue from, so no checkpoint; summary.json says so.
          int sig = signal::stop_signal();
          MPI_Allreduce(MPI_IN_PLACE, &sig, 1, MPI_INT, MPI_MAX, g_.comm());
          if (sig) {
            const std::string msg =
                std::string("stopped by ") + signal::name(sig) +
                " during the initial stress equilibrium (initial.stress = \"equilibrium\", "
                "pseudo-step " + std::to_string(k) + "): no checkpoint (the equilibrium was not "
                "reached, there is no state to continue from); run the case again with --overwrite";
            write_summary("interrupted", msg);
            throw Interrupted(msg);
          }
          const double v = diag::max_granular_speed(g_, st.vel, st.phi, eps);
          if (++k % 50 == 0 && g_.rank() == 0)
            log::message("granflow: initial stress: pseudo-step " + std::to_string(k) +
                         ", granular speed " + num(v) + " m/s");
          return v;
        });
    lp_.stress_steps = n;
    lp_.stress_speed = speed;
  } catch (const RunError& e) {
    fail(std::string(e.what()) + " (in the initial stress, initial.stress = \"equilibrium\")");
  }
  if (g_.rank() == 0)
    log::message("granflow: initial stress: " + std::to_string(lp_.stress_steps) +
                 " pseudo-steps of " + num(dt0) + " s, the last one made " +
                 num(lp_.stress_speed) + " m/s" +
                 (lp_.stress_speed < rc_.stress_tol
                      ? ""
                      : " (WARNING: above initial.stress_tol: no equilibrium reached)"));
}

void Simulation::start() {
  // A flow that returns the interface to its start (one turn, a reversed vortex) has the
  // initial shape as exact answer: keep it for the interface error at the end (before the
  // model's start, which with the volume fraction rebuilds phi from c).
  if (stepper_.traits().returns_to_start) {
    GF_PETSC(VecCopy(s_.phi, phi0_));
    GF_PETSC(VecCopy(s_.frac, frac0_));
  }
  try {
    stepper_.initialize(s_);
  } catch (const RunError& e) {
    fail(std::string(e.what()) + " (in the initial pressure of the fluid at rest, t = 0)");
  }
  if (rc_.stress_equilibrium && stepper_.traits().solves_momentum) equilibrate();
  lp_.vol0 = lp_.vol_prev = granular_volume();
  lp_.energy0 = diag::kinetic_energy(g_, s_.vel, s_.rho) + potential_energy();
  write_diagnostics();
  write_vtk();
  lp_.next_out = s_.t + rc_.output_interval;
  lp_.next_vtk = s_.t + rc_.vtk_interval;
}

double Simulation::advance(double dt) {
  const double t_before = s_.t;
  StepStats st;
  try {
    st = stepper_.step(s_, dt);
  } catch (const RunError& e) {
    fail(std::string(e.what()) + " (in the step from t = " + num(t_before) + " s, step " +
         std::to_string(s_.step + 1) + ", dt = " + num(dt) + " s)");
  }
  if (st.pres_fallback && lp_.pres_fallbacks == 0 && g_.rank() == 0)
    log::message("granflow: warning: the pressure solve's CG broke down (indefinite "
                 "preconditioner) in the step to t = " + num(s_.t) +
                 " s; solved again with GMRES (further cases counted in summary.json)");
  lp_.add(st, dt);
  // The granular volume's change in this step (diagnostics.csv volume_step_change: the largest
  // since the last row, relative to the volume at t = 0).
  if (stepper_.traits().two_phase) {
    const double v = granular_volume();
    if (lp_.vol0 > 0) lp_.vol_step_max = std::max(lp_.vol_step_max, std::abs(v - lp_.vol_prev) / lp_.vol0);
    lp_.vol_prev = v;
  }

  // Failure detection: a non-finite value in any prognostic field, or a speed no flow of this
  // solver reaches (an explicit-convection blow-up grows without NaN for a while).
  const Box& box = g_.box();
  auto where = [&](const diag::CellIndex& c) {
    return "cell (i, j) = (" + std::to_string(c.i) + ", " + std::to_string(c.j) +
           ") at (x, y) = (" + num(box.xc(c.i)) + ", " + num(box.yc(c.j)) + ") m";
  };
  const std::pair<const char*, Vec> fields[] = {
      {"velocity", s_.vel}, {"pressure", s_.p}, {"level set phi", s_.phi}, {"plastic tensor S", s_.S}};
  for (const auto& [what, v] : fields) {
    const diag::CellIndex c = diag::first_nonfinite(g_, v);
    if (c.found())
      fail(std::string("non-finite ") + what + " (NaN or Inf), first in " + where(c) + ", at " +
           when() + " (dt = " + num(dt) +
           " s): the run blew up; try a smaller time step (time.cfl, time.dt_max, or time.dt "
           "with time.dt_mode = fixed)");
  }
  if (st.fp_capped && st.fp_change > rc_.fp_fail_change) {
    const std::string at = ", at " + when() + " (dt = " + num(dt) + " s): ";
    if (rc_.newton)
      fail("the exact plastic step (rheology.solver = \"newton\") did not converge: after "
           "rheology.newton_max_iter = " + std::to_string(st.fp_iters) + " iterations its "
           "residual is " + num(st.fp_change) + " (above rheology.fp_fail_change = " +
           num(rc_.fp_fail_change) + ")" + at + "try a smaller time step, or rheology.solver = "
           "\"fixed_point\"; --set \"solver.petsc_options=-exactpd_monitor\" logs every "
           "iteration");
    fail("the fixed point of eq. 31 did not converge: after rheology.fp_max_iter = " +
         std::to_string(st.fp_iters) + " iterations its change is " + num(st.fp_change) +
         " (above rheology.fp_fail_change = " + num(rc_.fp_fail_change) + "; a sign flip of S "
         "or s_t is a change of 2)" + at + "try a smaller rheology.r_factor (the augmentation), "
         "a smaller time step, or a wider interface (levelset.eps_cells); --set "
         "rheology.fp_monitor=true logs every iteration");
  }
  const diag::SpeedAt sp = diag::max_speed_at(g_, s_.vel);
  const double h = std::min(g_.hx(), g_.hy());
  if (sp.speed > rc_.max_speed)
    fail("speed " + num(sp.speed) + " m/s above time.max_speed = " + num(rc_.max_speed) +
         " m/s in " + where(sp.at) + ", at " + when() + " (dt = " + num(dt) +
         " s, CFL number of the step max|u| dt / h = " + num(sp.speed * dt / h) +
         "): the run is blowing up; try a smaller time step (time.cfl, time.dt_max, or "
         "time.dt with time.dt_mode = fixed), or raise time.max_speed if such speeds are real");
  return sp.speed;
}

double Simulation::tiny() const { return 1e-12 * std::max(1.0, rc_.t_end); }

double Simulation::output_time(double interval) const {
  // Only the printed value: the step times (and so the physics) are the loop's own.
  const double t = s_.t, eps = tiny();
  if (std::abs(t - rc_.t_end) <= eps) return rc_.t_end;
  if (!(interval > 0)) return t;
  const double k = std::round(t / interval);
  if (!(k >= 0 && k < 9e18)) return t;
  const double on = decimal_multiple(static_cast<long long>(k), interval);
  return std::abs(t - on) <= eps ? on : t;
}

void Simulation::scheduled_output(bool at_end) {
  const double eps = tiny();
  if (s_.t >= lp_.next_out - eps || at_end) {
    write_diagnostics();
    if (lp_.next_out <= s_.t + eps)
      lp_.next_out = next_on_schedule(s_.t, rc_.output_interval, eps);
  }
  if (rc_.vtk_interval > 0 && (s_.t >= lp_.next_vtk - eps || at_end)) {
    write_vtk();
    if (lp_.next_vtk <= s_.t + eps) lp_.next_vtk = next_on_schedule(s_.t, rc_.vtk_interval, eps);
  }
}

void Simulation::stop_if_signalled(bool diag_written) {
  int sig = signal::stop_signal();  // per rank: all ranks act on the same decision
  MPI_Allreduce(MPI_IN_PLACE, &sig, 1, MPI_INT, MPI_MAX, g_.comm());
  if (!sig) return;
  const std::string name = signal::name(sig);
  save_checkpoint(name);
  // The checkpoint recorded the files' sizes before this extra row: a restart drops it.
  if (!diag_written) write_diagnostics();
  const std::string msg = "stopped by " + name + " at " + when() + "; checkpoint written to " +
                          rc_.out_dir + "/checkpoint. Continue with: granflow run --restart " +
                          rc_.out_dir;
  write_summary("interrupted", msg);
  throw Interrupted(msg);
}

void Simulation::checkpoint_if_due(double now, double& last_ckpt_wall, bool diag_written) {
  stop_if_signalled(diag_written);
  // The wall clock is per rank: rank 0 decides for all.
  const bool root = g_.rank() == 0;
  int by_wall = root && rc_.checkpoint_wall_s > 0 && now - last_ckpt_wall >= rc_.checkpoint_wall_s;
  MPI_Bcast(&by_wall, 1, MPI_INT, 0, g_.comm());
  const bool by_steps =
      rc_.checkpoint_interval_steps > 0 && s_.step % rc_.checkpoint_interval_steps == 0;
  if (!by_steps && !by_wall) return;
  // Not a state to continue from (see the header): the last checkpoint stays the last good one.
  if (!unsane_.empty()) {
    if (unsane_since_t_ < 0) {
      unsane_since_t_ = s_.t;
      if (root)
        log::message("granflow: warning: no checkpoint at " + when() + ": the state is not "
                     "sane, " + unsane_ + " (a blow-up may have begun); the last checkpoint" +
                     (last_ckpt_step_ >= 0 ? " (t = " + num(last_ckpt_t_) + " s, step " +
                                                 std::to_string(last_ckpt_step_) + ")"
                                           : "") +
                     " is kept, and the next ones are skipped while the state is not sane");
    }
    return;
  }
  save_checkpoint(by_steps ? "every " + std::to_string(rc_.checkpoint_interval_steps) + " steps"
                           : "wall clock");
  last_ckpt_wall = wall_now();
  unsane_since_t_ = -1;  // sane again: the next skip is said again
}

RunSummary Simulation::run() {
  namespace fs = std::filesystem;
  if (g_.rank() == 0) fs::create_directories(rc_.out_dir);
  MPI_Barrier(g_.comm());
  seg_t0_ = wall_now();
  open_outputs();
  struct Close {  // the files are closed however run() ends
    std::unique_ptr<Output>& o;
    ~Close() { o.reset(); }
  } close{out_};

  try {
    run_loop();
  } catch (const io::IoError& e) {
    // Results were lost: summary.json must not keep saying "running" or "completed". It may
    // not be writable either (the folder removed): the error is what matters.
    try {
      write_summary("failed", std::string("file error: ") + e.what());
    } catch (const io::IoError&) {
    }
    throw;
  }
  return summary_;
}

void Simulation::run_loop() {
  const bool root = g_.rank() == 0;
  if (!restarted_)
    start();
  else
    stepper_.resume(s_);
  // A signal during the start-up (the handler is installed before PetscInitialize).
  stop_if_signalled(true);
  const double t0 = seg_t0_;
  double last_progress = t0, last_ckpt_wall = t0;
  const long long step0 = s_.step;
  const double tiny = this->tiny();
  const double h = std::min(g_.hx(), g_.hy());
  double umax = diag::max_speed(g_, s_.vel);
  while (s_.t < rc_.t_end - tiny && (rc_.max_steps <= 0 || s_.step - step0 < rc_.max_steps)) {
    const double dt = choose_dt(umax, lp_.dt_prev);
    if (!(dt >= rc_.dt_min) && s_.t + dt < rc_.t_end - tiny)
      fail("time step collapsed to " + num(dt) + " s (floor time.dt_min = " + num(rc_.dt_min) +
           " s) at " + when() + ", max |u| = " + num(umax) +
           " m/s: the flow is blowing up; try a smaller time.cfl or time.dt_max");
    // 1. The step and its failure checks.
    const double u_before = umax;
    umax = advance(dt);
    // The state's sanity (see the header).
    unsane_.clear();
    constexpr double kSaneSpeedFactor = 10;
    if (rc_.speed_scale > 0) {
      if (!(umax <= kSaneSpeedFactor * rc_.speed_scale))
        unsane_ = "its max|u| = " + num(umax) + " m/s is more than " + num(kSaneSpeedFactor) +
                  " times the case's velocity scale U = " + num(rc_.speed_scale) + " m/s";
    } else {
      const double cfl = std::max(u_before * dt, umax * choose_dt(umax, dt)) / h;
      if (!(cfl <= 1 + 1e-9))  // 1, and the round-off of (cfl h / u) u / h at cfl = 1
        unsane_ = "the CFL number max|u| dt / h of its steps is " + num(cfl) + " > 1";
    }
    // The solvers have now read every PETSc option they use: name those nobody read.
    if (s_.step == step0 + 1 && root)
      for (const auto& o : unused_petsc_options())
        log::message("granflow: warning: PETSc option " + o +
                     " was not used by the first step: misspelled, or for a solver or "
                     "preconditioner this run does not use (the solvers' prefixes are -pres_ "
                     "and -visc_)");
    // 2. Scheduled output.
    const bool at_end = s_.t >= rc_.t_end - tiny;
    const bool diag_now = s_.t >= lp_.next_out - tiny || at_end;
    scheduled_output(at_end);
    // 3. Checkpoints (and a polite stop on SIGINT/SIGTERM).
    const double now = wall_now();
    checkpoint_if_due(now, last_ckpt_wall, diag_now);
    // 4. Progress.
    if (root && rc_.progress_interval > 0 && now - last_progress >= rc_.progress_interval) {
      const double rate = (s_.step - step0) / (now - t0);
      const double eta_s = (rc_.t_end - s_.t) / dt / std::max(rate, 1e-30);
      char line[160];
      std::snprintf(line, sizeof line, "t = %.4f s  dt = %.3e s  step %lld  %.1f steps/s  ETA %.0f s",
                    s_.t, dt, s_.step, rate, eta_s);
      log::message(line);
      last_progress = now;
    }
  }
  // The end (t_end or time.max_steps): a checkpoint, from which a longer run can continue.
  if (s_.step != last_ckpt_step_) save_checkpoint("end of run");
  write_summary(s_.t >= rc_.t_end - tiny ? "completed" : "stopped at time.max_steps", "");
}

}  // namespace gf
