#pragma once
// The column-collapse monitor of a run (section 4 of the paper): at every output it takes the
// measures of diagnostics/Collapse.hpp (front, profile, back-wall height, pressure bound, basal
// deposit), writes them (profiles.csv, structure.csv, deposit.csv), keeps their history for the
// stage times and the final deposit of summary.json, and saves and restores that history in a
// checkpoint so that a restarted run's files and stages are those of an uninterrupted one.
#include <petscvec.h>

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "diagnostics/Collapse.hpp"
#include "grid/Grid.hpp"
#include "io/Checkpoint.hpp"
#include "io/Csv.hpp"
#include "io/Json.hpp"

namespace gf::io {

// ---- The monitor of a run: samples at every output, writes the files, fills summary.json.

struct CollapseConfig {
  std::vector<double> cutoffs{0.075, 0.0075};
  std::array<double, 2> slope_back_range{0.05, 0.15};  // m
  std::array<double, 2> slope_front_range{0.2, 0.8};  // m
  double front_fit_length = 0.02;                     // m
  diag::StageRule stages;
  double rho_s = 1550;     // kg/m^3, for the pressure scale rho_s g H_c
  double gravity = 9.81;   // m/s^2, |g|
  double eps = 0;          // m, half-width of H_eps: the band left out of max_speed_granular
};

class CollapseMonitor {
 public:
  // write_files: profiles.csv, structure.csv, deposit.csv in out_dir (collective: rank 0
  // creates them). Without the files (a one-phase run) the measures are still taken.
  // With `restart`: the history saved by save() in that checkpoint header is restored and the
  // files continue from their size at the checkpoint (rows written after it are cut off), so
  // that the stage times and the files of a restarted run are those of an uninterrupted one.
  CollapseMonitor(const Grid& g, CollapseConfig cfg, const std::string& out_dir,
                  bool write_files, const CheckpointHeader* restart = nullptr);
  ~CollapseMonitor();
  struct Sample {
    double front_x, backwall_h, max_p_granular, max_speed_granular;
  };
  // Collective. Measures the state at time t, appends to the history and the files, whose
  // rows carry the time t_written (the output schedule's time; NaN: t). A failed write throws
  // IoError on every rank.
  Sample sample(double t, Vec phi, Vec vel, Vec p,
                double t_written = std::numeric_limits<double>::quiet_NaN());
  // Adds the collapse keys (runout_m ... front_angle_deg, see the README) to `js`.
  void summarize(JsonObject& js) const;
  // The history (times, fronts, speeds, the last profile, the gate, H_c, the running maxima) and
  // the files' sizes, exactly (hex floats), into a checkpoint header (keys "collapse.*").
  void save(CheckpointHeader& h) const;

 private:
  const Grid& g_;
  CollapseConfig cfg_;
  std::vector<double> x_;  // column centres, m
  std::vector<double> t_, front_, umax_;
  std::vector<double> tw_;  // the times written for t_ (the output schedule's)
  std::vector<double> h_last_;
  double gate_ = 0, Hc_ = 0, max_p_ = 0;
  double u_ref_ = 0;  // m/s, the largest max_speed_granular so far: the cut-offs' reference
  bool first_ = true;
  std::unique_ptr<CsvWriter> profiles_, structure_, deposit_;
};

}  // namespace gf::io
