#pragma once
// A simulation is a model (grid, state, time stepper) plus the time loop: the time-step choice,
// scheduled diagnostics, VTK output and probes, checkpoints, the progress line, failure
// detection and the final summary. It reads the state only; the physics is in stepper/.
//
// Each step of the loop, after the stepper:
//   1. failure checks: non-finite velocity, pressure, phi or S; a speed above max_speed
//      (RunError, after writing the diagnostics and summary.json; no checkpoint of the bad
//      state, so the last checkpoint stays the last good one);
//   2. scheduled output: diagnostics.csv and probes every output_interval, VTK every
//      vtk_interval (the next time computed as a multiple of the interval, never stepped to;
//      a time within round-off of the schedule is written as the scheduled time);
//   3. checkpoint if due (every checkpoint_interval_steps steps, every checkpoint_wall_s of
//      wall clock) and the state is sane (below), or on SIGINT/SIGTERM (then Interrupted is
//      thrown);
//   4. the progress line (stderr and granflow.log).
// A sane state: its max|u| at most kSaneSpeedFactor (10) times the case's velocity scale U
// (the report's, e.g. sqrt(|g| H)); without a scale (U = 0), the step into it and the step
// out of it within the convective stability limit, max|u| dt / h <= 1. No flow of the bundled
// cases comes near (the water dam break, the fastest, reaches 3.7 U where it splashes on the
// wall); a blow-up passes it within a step or two (case A at n = 64 with a fixed dt = 0.01 s:
// 2.6 U, then 23 U, then 2700 U). A periodic checkpoint of a state that is not sane is not
// written (said once in the log), so that the checkpoint kept when the run then fails is from
// before the blow-up began: a restart from it with a smaller step continues.
// A SIGINT/SIGTERM during the start-up (the initial pressure, the initial stress) stops the
// run there: after the initial state, with a checkpoint of it; during the initial stress
// equilibrium, without (its pseudo-steps are not a state to continue from).
// A failed write of any output (diagnostics, probes, collapse files, VTK, checkpoint, summary;
// also a file deleted while the run writes it) throws IoError on every rank, after trying to
// write summary.json with the status "failed".
// A restart (restart() before run()) restores the state and every loop variable from the
// checkpoint and cuts the output files back to their size at the checkpoint, so a restarted
// run writes exactly the rows and files the uninterrupted run writes after that point.
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "io/Checkpoint.hpp"
#include "io/Collapse.hpp"
#include "io/Csv.hpp"
#include "io/Probes.hpp"
#include "io/Vtk.hpp"
#include "stepper/TimeStepper.hpp"

namespace gf {

struct RunConfig {
  double t_end = 1;            // s
  bool dt_fixed = false;
  double dt = 0;               // s: the fixed step, or the first adaptive step (0 = automatic)
  double cfl = 0.5;            // convective CFL number (and gravity-wave limit, see choose_dt)
  double dt_max = 1e-3;        // s
  double dt_min = 1e-9;        // s: below this the run stops as failed
  double max_speed = 100;      // m/s: above this anywhere the run stops as blown up
  double speed_scale = 0;      // m/s, the case's velocity scale U (setup/Report.hpp), 0 = none
  long long max_steps = 0;     // 0 = unlimited (steps of this run, not counting a restart's past)
  double output_interval = 0.01;    // s
  double vtk_interval = 0.05;       // s, 0 = none
  double progress_interval = 2.0;   // s of wall clock
  long long checkpoint_interval_steps = 0;  // steps, 0 = none (besides the end and signals)
  double checkpoint_wall_s = 0;             // s of wall clock, 0 = none
  double volume_warn_pct = 1.0;  // %: |granular volume change| above this counts as a warning
  double fp_fail_change = 1.0;   // -: a fixed point at its cap with a larger last change fails
  bool newton = false;           // rheology.solver = "newton" (for the messages)
  bool stress_equilibrium = false;  // initial.stress = "equilibrium" (Stepper::equilibrate)
  int stress_max_steps = 1000;
  double stress_tol = 1e-7;  // m/s
  std::vector<io::ProbeSpec> probes;
  io::CollapseConfig collapse;  // front, profile, deposit measures (io/Collapse.hpp)
  std::string out_dir;
  std::string title;
};

struct RunSummary {
  long long steps = 0;  // all steps since t = 0 (a restarted run includes the earlier ones)
  double t_end = 0, wall_s = 0, max_divergence = 0, volume_change_pct = 0;
};

// Everything of the loop that the next steps and the final summary depend on: checkpointed
// (sim/Counters.hpp lists each member once, with its checkpoint and summary.json keys).
struct Loop {
  double dt_prev = 0;                 // s, the last step (0 before the first)
  double next_out = 0, next_vtk = 0;  // s, next diagnostics / VTK time
  double vol0 = 0;                    // m^2/m, granular volume at t = 0
  double max_div = 0;                 // 1/s, largest divergence in a diagnostics row
  double volume_change_pct = 0;       // %, of the last diagnostics row
  double wall_s = 0;                  // s of wall clock of the runs before this one
  long long fp_capped_steps = 0;      // steps whose fixed point stopped at its cap (a warning)
  double fp_capped_change = 0;        // the largest last change of those steps
  long long volume_warn_rows = 0;     // diagnostics rows with |volume change| > volume_warn_pct
  long long pres_fallbacks = 0;       // pressure solves made again with GMRES (a warning)
  long long mu_floor_max = 0, mu_cap_max = 0;  // mu(I): most granular cells at the bounds
  long long restarts = 0;
  int max_fp_iters = 0;
  long long fp_iters_total = 0, visc_its_total = 0;  // sums over the steps (cost measures)
  // solver.viscous_local_margin: iterations of the closing full solves (included in
  // visc_its_total), and the steps where it took any: what the local solves missed.
  long long visc_polish_its_total = 0, visc_polish_steps = 0;
  long long redistancings = 0;  // steps that redistanced phi
  // The energy budget (diagnostics.csv): the kinetic plus potential energy at t = 0 and the
  // energy dissipated since, J/m, by the viscous stresses, the plastic stress and the Coulomb
  // wall friction (sums of StepStats::diss_*).
  double energy0 = 0, diss_viscous = 0, diss_plastic = 0, diss_friction = 0;
  // The granular volume after the last step (m^2/m) and the largest change of one step since
  // the last diagnostics row, relative to vol0.
  double vol_prev = 0, vol_step_max = 0;
  // Since the last diagnostics row: the largest last change (fixed point) or residual (Newton)
  // of a step's solve of eq. 31, and the steps that ended at its cap (issue 19: every step's
  // convergence in diagnostics.csv, not only the last one's).
  double row_fp_change_max = 0;
  long long row_fp_capped = 0;
  StepStats last;               // the last step's statistics (diagnostics columns)
  // initial.stress = "equilibrium": pseudo-steps taken, the velocity the last one made (m/s);
  // -1: not asked for.
  long long stress_steps = -1;
  double stress_speed = -1;
  // Adds a step's statistics to the counters and keeps them as `last`.
  void add(const StepStats& st, double dt);
};

class Simulation {
 public:
  Simulation(const Grid& g, State& s, TimeStepper& stepper, const RunConfig& rc);
  ~Simulation();
  // Text files stored in every checkpoint folder (name, content), e.g. the resolved case,
  // which a restart compares with the case it is given.
  void set_checkpoint_files(std::vector<std::pair<std::string, std::string>> files) {
    ckpt_files_ = std::move(files);
  }
  // Collective. Before run(): continue from the checkpoint in `ckpt_dir` (read with
  // io::read_checkpoint_header into `h`) instead of starting at t = 0. Checks the checkpoint
  // against this run's grid (InputError naming the mismatch) and t_end, loads the fields
  // (IoError if they cannot be read). Touches no file: run() continues the output files.
  void restart(const std::string& ckpt_dir, const io::CheckpointHeader& h);
  // Runs to t_end; writes diagnostics.csv, VTK, probes, checkpoints and summary.json into
  // out_dir. Throws RunError on NaN / blow-up / dt collapse / solver failure, after writing
  // the diagnostics and summary.json; Interrupted after a SIGINT/SIGTERM, after writing a
  // checkpoint, the diagnostics and summary.json.
  RunSummary run();
  // The next time step: fixed, or min(dt_max, cfl h / max|u|, cfl sqrt(h/|g|)), growing by at
  // most 20 % per step (keeps the variable-step BDF2 stable) and clipped to land on t_end.
  double choose_dt(double max_speed, double dt_prev) const;

 private:
  struct Output;  // the files and scratch fields of run() (Simulation.cpp)

  const Grid& g_;
  State& s_;
  TimeStepper& stepper_;
  RunConfig rc_;
  Loop lp_;
  std::vector<std::pair<std::string, std::string>> ckpt_files_;
  // A restart: where the output files stood at the checkpoint.
  bool restarted_ = false;
  long long diag_bytes_ = 0;
  std::vector<long long> probe_bytes_;
  std::vector<std::pair<double, std::string>> vtk_entries_;
  Field phi0_;   // the initial level set (a flow returning to its start: the exact answer)
  Field frac0_;  // ... and the initial volume fraction (interface.method = "clsvof")
  std::unique_ptr<Output> out_;  // during run()
  io::CheckpointHeader restart_header_;  // of the checkpoint restart() loaded
  long long last_ckpt_step_ = -1;  // step and time of the last checkpoint written or loaded
  double last_ckpt_t_ = 0;
  double seg_t0_ = 0;  // wall clock at the start of run(), s

  // Sanity of the state (see the header): why the state after the last step is not sane
  // ("" if it is); the first time a periodic checkpoint was skipped (-1: none).
  std::string unsane_;
  double unsane_since_t_ = -1;

  // The stages of run().
  double tiny() const;          // s: the time loop's tolerance, 1e-12 max(1, t_end)
  // s: the time written for the current state: the scheduled one (a multiple of interval, or
  // t_end) when the step landed on it within round-off, else the step time.
  double output_time(double interval) const;
  void stop_if_signalled(bool diag_written);  // collective: a checkpoint, then Interrupted
  void run_loop();                   // run() without its files' opening and closing
  void open_outputs();
  void start();                         // t = 0: the model's start, its first outputs
  void equilibrate();                   // initial.stress = "equilibrium"
  double advance(double dt);            // one step, its counters and failure checks; max |u|
  void scheduled_output(bool at_end);  // diagnostics, probes, VTK when due
  void checkpoint_if_due(double now, double& last_ckpt_wall, bool diag_written);
  // Outputs.
  double granular_volume() const;
  double potential_energy() const;  // J/m, for the energy budget
  void write_diagnostics();
  void write_vtk();
  void write_summary(const std::string& status, const std::string& message);
  void save_checkpoint(const std::string& reason);
  // A failed run: its diagnostics row (the bad values included) and summary.json, then the
  // error. No checkpoint: the last one written stays the last good state.
  [[noreturn]] void fail(const std::string& what);
  std::string when() const;  // "t = ... s, step N"
  RunSummary summary_;
};

}  // namespace gf
