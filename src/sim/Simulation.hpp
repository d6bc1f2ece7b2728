#pragma once
// A simulation is a model (grid, state, stepper) plus the time loop: the time-step choice,
// scheduled diagnostics, VTK output and probes, the progress line, failure detection and the
// final summary. It reads the state only; the physics is in stepper/.
#include <array>
#include <string>
#include <vector>

#include "diagnostics/Collapse.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "io/Probes.hpp"
#include "stepper/Stepper.hpp"

namespace gf {

struct RunConfig {
  double t_end = 1;            // s
  bool dt_fixed = false;
  double dt = 0;               // s: the fixed step, or the first adaptive step (0 = automatic)
  double cfl = 0.5;            // convective CFL number (and gravity-wave limit, see choose_dt)
  double dt_max = 1e-3;        // s
  double dt_min = 1e-9;        // s: below this the run stops as failed
  long long max_steps = 0;     // 0 = unlimited
  double output_interval = 0.01;    // s
  double vtk_interval = 0.05;       // s, 0 = none
  double progress_interval = 2.0;   // s of wall clock
  std::vector<io::ProbeSpec> probes;
  diag::CollapseConfig collapse;  // front, profile, deposit measures (diagnostics/Collapse.hpp)
  std::string out_dir;
  std::string title;
};

struct RunSummary {
  long long steps = 0;
  double t_end = 0, wall_s = 0, max_divergence = 0, volume_change_pct = 0;
};

class Simulation {
 public:
  Simulation(const Grid& g, State& s, Stepper& stepper, const RunConfig& rc);
  // Runs to t_end; writes diagnostics.csv, VTK, probes and summary.json into out_dir.
  // Throws RunError on NaN / dt collapse / solver failure, after writing what it has.
  RunSummary run();
  // The next time step: fixed, or min(dt_max, cfl h / max|u|, cfl sqrt(h/|g|)), growing by at
  // most 20 % per step (keeps the variable-step BDF2 stable) and clipped to land on t_end.
  double choose_dt(double max_speed, double dt_prev) const;

 private:
  const Grid& g_;
  State& s_;
  Stepper& stepper_;
  RunConfig rc_;
};

}  // namespace gf
