// The column-collapse monitor of a run (io/Collapse.hpp): the measures of
// diagnostics/Collapse.hpp at every output, their files, their history in the checkpoint and
// their summary.
#include "io/Collapse.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "core/Error.hpp"
#include "diagnostics/Diagnostics.hpp"
#include "io/IoError.hpp"

namespace gf::io {

using namespace diag;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

namespace {
std::string hex_list(const std::vector<double>& v) {
  std::string s;
  char buf[40];
  for (const double x : v) {
    std::snprintf(buf, sizeof buf, "%a ", x);
    s += buf;
  }
  return s.empty() ? "-" : s;
}
std::vector<double> parse_list(const CheckpointHeader& h, const std::string& key) {
  const std::string s = h.get_text(key);
  std::vector<double> v;
  if (s == "-") return v;
  const char* p = s.c_str();
  char* end = nullptr;
  for (;;) {
    while (*p == ' ') ++p;
    if (!*p) break;
    v.push_back(std::strtod(p, &end));
    if (end == p) throw IoError(h.source() + ": malformed number list for key " + key);
    p = end;
  }
  return v;
}
}  // namespace

CollapseMonitor::CollapseMonitor(const Grid& g, CollapseConfig cfg, const std::string& out_dir,
                                 bool write_files, const CheckpointHeader* restart)
    : g_(g), cfg_(std::move(cfg)) {
  x_.resize(g.nx());
  for (PetscInt i = 0; i < g.nx(); ++i) x_[i] = g.box().xc(i);
  long long bytes[3] = {-1, -1, -1};
  if (restart) {
    const auto& h = *restart;
    gate_ = h.get_double("collapse.gate");
    Hc_ = h.get_double("collapse.Hc");
    max_p_ = h.get_double("collapse.max_p");
    u_ref_ = h.get_double("collapse.u_ref");
    first_ = h.get_int("collapse.first") != 0;
    t_ = parse_list(h, "collapse.t");
    // The times written (older checkpoints: the step times).
    tw_ = h.has("collapse.t_written") ? parse_list(h, "collapse.t_written") : t_;
    front_ = parse_list(h, "collapse.front");
    umax_ = parse_list(h, "collapse.umax");
    h_last_ = parse_list(h, "collapse.h_last");
    if (front_.size() != t_.size() || umax_.size() != t_.size() || tw_.size() != t_.size() ||
        (!h_last_.empty() && h_last_.size() != x_.size()))
      throw IoError(h.source() + ": inconsistent collapse history (collapse.*)");
    bytes[0] = h.get_int("collapse.bytes_profiles");
    bytes[1] = h.get_int("collapse.bytes_structure");
    bytes[2] = h.get_int("collapse.bytes_deposit");
  }
  if (write_files) {
    auto open = [&](const std::string& name, std::vector<std::string> cols, long long b) {
      const std::string path = out_dir + "/" + name;
      return b >= 0 ? std::make_unique<CsvWriter>(path, std::move(cols), b, g.comm())
                    : std::make_unique<CsvWriter>(path, std::move(cols), g.comm());
    };
    profiles_ = open("profiles.csv", {"t", "x", "h"}, bytes[0]);
    structure_ = open("structure.csv", {"t", "cutoff", "x", "h", "h_deposit", "h_l"}, bytes[1]);
    deposit_ = open("deposit.csv",
                    {"t", "cutoff", "max_speed_granular", "u_ref", "front_x", "x_deposit", "L",
                     "L_d", "L_h", "A", "A_d", "Ad_over_A"},
                    bytes[2]);
  }
}

void CollapseMonitor::save(CheckpointHeader& h) const {
  h.set("collapse.gate", gate_);
  h.set("collapse.Hc", Hc_);
  h.set("collapse.max_p", max_p_);
  h.set("collapse.u_ref", u_ref_);
  h.set("collapse.first", static_cast<long long>(first_));
  h.set_text("collapse.t", hex_list(t_));
  h.set_text("collapse.t_written", hex_list(tw_));
  h.set_text("collapse.front", hex_list(front_));
  h.set_text("collapse.umax", hex_list(umax_));
  h.set_text("collapse.h_last", hex_list(h_last_));
  h.set("collapse.bytes_profiles", profiles_ ? profiles_->bytes() : -1LL);
  h.set("collapse.bytes_structure", structure_ ? structure_->bytes() : -1LL);
  h.set("collapse.bytes_deposit", deposit_ ? deposit_->bytes() : -1LL);
}

CollapseMonitor::~CollapseMonitor() = default;

CollapseMonitor::Sample CollapseMonitor::sample(double t, Vec phi, Vec vel, Vec p,
                                                 double t_written) {
  Sample s;
  const std::vector<double> h = surface_heights(g_, phi);
  s.front_x = front_position(g_, phi);
  s.backwall_h = backwall_height(h);
  s.max_p_granular = max_in_granular(g_, p, phi);
  s.max_speed_granular = max_granular_speed(g_, vel, phi, cfg_.eps);
  if (first_) {
    // The gate and the column height of the initial state (see the header).
    gate_ = s.front_x;
    Hc_ = 0.0;
    for (const double v : h) Hc_ = std::max(Hc_, v);
    first_ = false;
  }
  // The reference speed of the cut-offs: the largest granular speed so far (see the header).
  if (std::isnan(s.max_speed_granular) || std::isnan(u_ref_)) u_ref_ = kNaN;
  else u_ref_ = std::max(u_ref_, s.max_speed_granular);
  const auto deps = basal_deposits(g_, vel, h, s.front_x, gate_, u_ref_, cfg_.cutoffs);
  max_p_ = std::isnan(max_p_) || std::isnan(s.max_p_granular) ? kNaN
                                                                : std::max(max_p_, s.max_p_granular);
  const double tw = std::isnan(t_written) ? t : t_written;
  t_.push_back(t);
  tw_.push_back(tw);
  front_.push_back(s.front_x);
  umax_.push_back(s.max_speed_granular);
  h_last_ = h;
  // The history keeps the step time (the stage fits use it); the files the time written.
  std::string err;  // rank 0 writes; its failure is raised on every rank
  if (profiles_ && g_.rank() == 0) {
    try {
      const double a_min = 1e-6 * g_.hx() * g_.hy();
      for (std::size_t i = 0; i < h.size(); ++i) profiles_->row({tw, x_[i], h[i]});
      for (const auto& d : deps) {
        for (std::size_t i = 0; i < h.size(); ++i)
          structure_->row({tw, d.cutoff, x_[i], h[i], d.h_deposit[i], h[i] - d.h_deposit[i]});
        deposit_->row({tw, d.cutoff, s.max_speed_granular, u_ref_, s.front_x, d.x_deposit, d.L,
                       d.L_d, d.L_h, d.A, d.A_d, d.A >= a_min ? d.A_d / d.A : kNaN});
      }
    } catch (const IoError& e) {
      err = e.what();
    }
  }
  if (profiles_) raise_on_all_ranks(g_.comm(), err);
  return s;
}

void CollapseMonitor::summarize(JsonObject& js) const {
  if (t_.empty()) return;
  const Stages st = detect_stages(t_, front_, umax_, cfg_.stages);
  // A stage time is one of the output times: reported as it was written (the schedule's).
  const auto written = [&](double t) {
    for (std::size_t k = 0; k < t_.size(); ++k)
      if (t_[k] == t) return tw_[k];
    return t;
  };
  const double front = front_.back();
  const double p_scale = cfg_.rho_s * cfg_.gravity * Hc_;
  const auto& bk = cfg_.slope_back_range;
  const auto& fr = cfg_.slope_front_range;
  double max_front = front_[0];
  for (const double f : front_)
    max_front = std::isnan(f) || std::isnan(max_front) ? kNaN : std::max(max_front, f);
  js.set("runout_m", front)
      .set("max_front_x_m", max_front)
      .set("backwall_height_m", backwall_height(h_last_))
      .set("front_speed_mps", st.front_speed)
      .set("max_front_speed_mps", st.max_front_speed)
      .set("t1_s", written(st.t1))
      .set("t2_s", written(st.t2))
      .set("t3_s", written(st.t3))
      .set("tf_s", written(st.tf))
      .set("max_p_granular_pa", max_p_)
      .set("pressure_scale_pa", p_scale)
      .set("max_p_granular_ratio", p_scale > 0 ? max_p_ / p_scale : kNaN)
      .set("slope_back_deg", fit_slope_deg(x_, h_last_, bk[0], bk[1], front))
      .set("slope_front_deg", fit_slope_deg(x_, h_last_, fr[0], fr[1], front))
      .set("front_angle_deg",
           fit_slope_deg(x_, h_last_, front - cfg_.front_fit_length, front, front))
      .set("gate_x_m", gate_)
      .set("column_height_m", Hc_)
      .set("max_speed_granular_end", umax_.back());
}

}  // namespace gf::io
