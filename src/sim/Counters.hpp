#pragma once
// Internal to sim/: the one table of the time loop's counters (Loop, and the last step's
// statistics StepStats). Each row names a member once, with its checkpoint key, its summary.json
// key and whether older checkpoints may lack it; save_checkpoint, restart and the summary all go
// through these rows, so a new counter is one new row.
#include <type_traits>
#include <variant>
#include <vector>

#include "io/Checkpoint.hpp"
#include "io/Json.hpp"
#include "sim/Simulation.hpp"

namespace gf::counters {

// Where a counter appears in summary.json: not at all, before the state's max_speed and
// kinetic_energy, after them, or with the initial-stress keys (only when asked for).
enum class Summary { None, First, Second, InitialStress };

template <class S>
struct Counter {
  const char* key;  // checkpoint header key
  std::variant<double S::*, long long S::*, int S::*, bool S::*> field;
  const char* summary_key = nullptr;
  Summary group = Summary::None;
  bool optional = false;  // absent from older checkpoints: keep the default value
};

inline const std::vector<Counter<Loop>>& loop_counters() {
  using S = Summary;
  static const std::vector<Counter<Loop>> rows = {
      {"loop.dt_prev", &Loop::dt_prev},
      {"loop.next_out", &Loop::next_out},
      {"loop.next_vtk", &Loop::next_vtk},
      {"loop.vol0", &Loop::vol0},
      {"loop.wall_s", &Loop::wall_s},
      {"loop.restarts", &Loop::restarts, "restarts", S::First},
      {"loop.max_div", &Loop::max_div, "max_divergence", S::First},
      {"loop.volume_change_pct", &Loop::volume_change_pct, "volume_change_pct", S::First},
      {"loop.max_fp_iters", &Loop::max_fp_iters, "max_fp_iters", S::Second},
      {"loop.fp_iters_total", &Loop::fp_iters_total, "fp_iters_total", S::Second, true},
      {"loop.visc_its_total", &Loop::visc_its_total, "visc_its_total", S::Second, true},
      {"loop.visc_polish_its_total", &Loop::visc_polish_its_total, "visc_polish_its_total",
       S::Second, true},
      {"loop.visc_polish_steps", &Loop::visc_polish_steps, "visc_polish_steps", S::Second, true},
      {"loop.redistancings", &Loop::redistancings, "redistancings", S::Second, true},
      {"loop.fp_capped_steps", &Loop::fp_capped_steps, "warnings_fp_capped_steps", S::Second},
      {"loop.fp_capped_change", &Loop::fp_capped_change, "fp_capped_max_change", S::Second},
      {"loop.volume_warn_rows", &Loop::volume_warn_rows, "warnings_volume_drift_rows", S::Second},
      {"loop.pres_fallbacks", &Loop::pres_fallbacks, "warnings_pressure_gmres_fallbacks",
       S::Second, true},
      {"loop.mu_floor_max", &Loop::mu_floor_max, "mu_i_floor_cells_max", S::Second},
      {"loop.mu_cap_max", &Loop::mu_cap_max, "mu_i_cap_cells_max", S::Second},
      {"loop.energy0", &Loop::energy0, nullptr, S::None, true},
      {"loop.diss_viscous", &Loop::diss_viscous, nullptr, S::None, true},
      {"loop.diss_plastic", &Loop::diss_plastic, nullptr, S::None, true},
      {"loop.diss_friction", &Loop::diss_friction, nullptr, S::None, true},
      {"loop.vol_prev", &Loop::vol_prev, nullptr, S::None, true},
      {"loop.vol_step_max", &Loop::vol_step_max, nullptr, S::None, true},
      {"loop.row_fp_change_max", &Loop::row_fp_change_max, nullptr, S::None, true},
      {"loop.row_fp_capped", &Loop::row_fp_capped, nullptr, S::None, true},
      {"loop.stress_steps", &Loop::stress_steps, "initial_stress_steps", S::InitialStress, true},
      {"loop.stress_speed", &Loop::stress_speed, "initial_stress_speed_mps", S::InitialStress,
       true},
  };
  return rows;
}

// The last step's statistics: the diagnostics columns of a row written right after a restart.
inline const std::vector<Counter<StepStats>>& step_counters() {
  static const std::vector<Counter<StepStats>> rows = {
      {"last.visc_its", &StepStats::visc_its},
      {"last.pres_its", &StepStats::pres_its},
      {"last.fp_iters", &StepStats::fp_iters},
      {"last.fp_change", &StepStats::fp_change},
      {"last.fp_capped", &StepStats::fp_capped},
      {"last.mu_i_floor_cells", &StepStats::mu_i_floor_cells},
      {"last.mu_i_cap_cells", &StepStats::mu_i_cap_cells},
      {"last.redistanced", &StepStats::redistanced},
  };
  return rows;
}

template <class S>
void save(const std::vector<Counter<S>>& rows, const S& s, io::CheckpointHeader& h) {
  for (const auto& r : rows)
    std::visit(
        [&](auto m) {
          using T = std::remove_cvref_t<decltype(s.*m)>;
          if constexpr (std::is_same_v<T, double>)
            h.set(r.key, s.*m);
          else
            h.set(r.key, static_cast<long long>(s.*m));
        },
        r.field);
}

template <class S>
void restore(const std::vector<Counter<S>>& rows, const io::CheckpointHeader& h, S& s) {
  for (const auto& r : rows) {
    if (r.optional && !h.has(r.key)) continue;
    std::visit(
        [&](auto m) {
          using T = std::remove_cvref_t<decltype(s.*m)>;
          if constexpr (std::is_same_v<T, double>)
            s.*m = h.get_double(r.key);
          else if constexpr (std::is_same_v<T, bool>)
            s.*m = h.get_int(r.key) != 0;
          else
            s.*m = static_cast<T>(h.get_int(r.key));
        },
        r.field);
  }
}

inline void summarize(const Loop& l, Summary group, io::JsonObject& js) {
  for (const auto& r : loop_counters())
    if (r.group == group)
      std::visit(
          [&](auto m) {
            using T = std::remove_cvref_t<decltype(l.*m)>;
            if constexpr (std::is_same_v<T, double>)
              js.set(r.summary_key, l.*m);
            else
              js.set(r.summary_key, static_cast<long long>(l.*m));
          },
          r.field);
}

}  // namespace gf::counters
