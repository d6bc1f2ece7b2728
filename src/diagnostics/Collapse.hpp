#pragma once
// Measures of a granular column collapse (section 4 of the paper): the front, the surface
// profile, the back-wall height, the pressure bound, the basal deposit and flowing layer of
// section 4.2.5, the four stages of the front (section 4.1.3, Fig. 8) and the final deposit.
// They read the state only. The per-output measures are collective on the grid's
// communicator and return the same values on every rank; the rest are pure functions of
// their arguments (the output history), so that they can be tested on synthetic data.
//
// Exact definitions (cell (i, j) has its centre at (x_i, y_j) = ((i + 1/2) hx, (j + 1/2) hy);
// phi < 0 is granular; phi is sampled at the cell centres and read as linear between them):
//
//   surface height h_i (profiles.csv), at x_i, m: the top of the granular phase in column i.
//     Take the highest cell j with phi_{i,j} < 0. If j = ny - 1, h_i = Ly; otherwise h_i is the
//     zero of phi between the centres j and j + 1, y_j + hy phi_{i,j} / (phi_{i,j} - phi_{i,j+1}).
//     A layer thinner than hy/2 has no granular cell centre: if phi_{i,0} >= 0 but phi
//     extrapolated linearly from the centres 0 and 1 to the bottom, (3 phi_{i,0} - phi_{i,1})/2,
//     is < 0, h_i is the zero of that line between y = 0 and y_0. Otherwise h_i = 0. The
//     interpolation is exact where phi is linear across the surface (second order for a smooth
//     phi). Granular material above an air gap counts: h is the top, not the thickness.
//   front_x, m: the furthest x where the granular phase touches the bottom. phi is extrapolated
//     to the bottom, phi^b_i = (3 phi_{i,0} - phi_{i,1}) / 2 (second order, as for h), and
//     front_x is the zero of phi^b between x_k and x_{k+1}, k the largest column with
//     phi^b_k < 0; Lx if k = nx - 1; 0 if no column has phi^b < 0.
//   backwall_h, m: h extrapolated linearly to the back wall x = 0 from the first two columns,
//     (3 h_0 - h_1) / 2 (h_0 if h_1 = 0): exact for a planar surface.
//   max_p_granular, Pa: max_in_granular(p) of Diagnostics.hpp (cells with phi < 0); the paper
//     bounds it by rho_s g H_c (section 4.1.2).
//   max_speed_granular, m/s: the largest cell-centre speed (Diagnostics.hpp) over the cells
//     with phi < -eps, the granular phase outside the smeared band of H_eps (eq. 25), where
//     rho = rho_s exactly; U below. The band is left out because its cells are dragged by the
//     air: on case A at n = 32 the cells with -eps < phi < 0 keep 0.04-0.15 m/s long after the
//     pile has stopped, which would hide both the stop (tf) and the deposit (c U).
//   L_c and H_c, m: the gate and the column height, measured on the initial level set as
//     front_x and max_i h_i at the first output (initial.x1 and initial.y1 for the rectangle).
//
// Basal deposit and flowing layer (section 4.2.5, Figs. 22-27), for each cut-off c (a fraction):
//   the deposit is the granular material whose speed is at most c U (the paper uses c = 7.5 %
//   and 0.75 %: the speed, unlike |D u|, is smooth enough to separate the two layers). In a run
//   (CollapseMonitor) U is the largest max_speed_granular of the outputs so far, not the current
//   one: "the maximum velocity norm" of the paper is not more precise, and with the current
//   maximum the threshold vanishes with the motion, so that at rest the split follows noise
//   (case A at n = 32 after 0.7 s: A_d/A jumping between 0 and 0.8), whereas in the paper
//   A_d/A rises to 1 as the motion stops (Fig. 27).
//   y*_i, m: the lowest height in column i where the cell-centre speed s exceeds c U, linear
//     between the centres j* - 1 and j*, j* the lowest cell with s > c U: 0 if j* = 0 (the
//     bottom cell moves: no deposit under it), Ly if there is none.
//   deposit height h^d_i = min(h_i, y*_i); flowing-layer height h^l_i = h_i - h^d_i >= 0.
//   x_d, m: the front of the basal deposit, the zero of s - c U along the bottom row of cells
//     from the back wall (between the last slow and the first fast cell, linear), capped at
//     front_x (Lx, hence front_x, if the whole bottom row is slow; 0 if its first cell moves).
//   L = front_x - L_c, L_d = x_d - L_c, L_h = L - L_d (the sliding head), m.
//   A and A_d, m^2/m: the areas of the mass and of the deposit beyond the gate,
//     sum_i w_i h_i hx and sum_i w_i h^d_i hx, w_i = clamp((x_i + hx/2 - L_c) / hx, 0, 1) the
//     part of column i beyond x = L_c. A_d / A is NaN while A < 1e-6 hx hy (nothing beyond the
//     gate yet: the ratio of round-off).
//   At rest (U = 0) everything is deposit: h^d = h, x_d = front_x.
//
// The four stages of the front (section 4.1.3, Fig. 8), from the outputs (t_k, front_x_k):
//   V_k, m/s: the front speed, the least-squares slope of front_x(t) over the outputs with
//     |t_m - t_k| <= speed_window / 2.
//   [t1, t2]: the constant-speed phase, the longest run of consecutive outputs containing the
//     fastest one (V_max) along which V_k >= plateau_fraction V_max; t1 ends the acceleration,
//     t2 starts the deceleration. front_speed: the least-squares slope of front_x over [t1, t2].
//   t3: the front stops, the first output after which the front advances less than
//     stop_distance: front_x_m - front_x_k < stop_distance for every later output m ("the front
//     has reached the runout distance and does not advance anymore", section 4.1.3). A front
//     that recedes afterwards (the thin tip lost with granular volume) does not move t3. NaN
//     if only the last output qualifies (the front still advanced at the end of the run).
//   tf: motion stops, the first output from which max_speed_granular stays below rest_speed to
//     the end of the run; NaN if the last output is not below it. The speed decays
//     exponentially rather than vanishing (docs/RHEOLOGY.md), so tf depends on rest_speed
//     (default 1 mm/s, a bead diameter of case A per second).
//   max_front_x: the furthest front position over the run, m (> runout if the front recedes).
//
// Final deposit, from the last output: runout = front_x, the back-wall height, and slopes as
//   angles atan(-dh/dx) in degrees (> 0 for a surface that descends towards the front), each
//   the least-squares slope of h_i over the columns with h_i > 0 and x_i < front_x:
//   slope_back over slope_back_range, slope_front over slope_front_range (the paper's case B
//   deposit: 29 deg for x <= 0.35 m, 7 deg for x >= 0.5 m, section 4.2.2), and the front angle
//   over the last front_fit_length before the front (2.5 deg in the experiment of case B).
//   NaN when fewer than two columns are in the range.
#include <petscvec.h>

#include <array>
#include <string>
#include <vector>

#include "grid/Grid.hpp"

namespace gf::diag {

// ---- Per-output measures (collective; identical on every rank).

// h_i of every column i = 0 .. nx-1, m.
std::vector<double> surface_heights(const Grid& g, Vec phi);
// front_x, m (NaN if phi holds a NaN in the bottom rows).
double front_position(const Grid& g, Vec phi);
// max_speed_granular over the cells with phi < -eps, m/s (NaN-propagating; 0 if there is no
// such cell).
double max_granular_speed(const Grid& g, Vec vel, Vec phi, double eps);

struct BasalDeposit {
  double cutoff = 0;               // -, fraction of U
  std::vector<double> h_deposit;   // m, h^d_i per column
  double x_deposit = 0;            // m, x_d
  double L = 0, L_d = 0, L_h = 0;  // m
  double A = 0, A_d = 0;           // m^2/m
};
// One deposit per cut-off. h: surface_heights(); U: max_granular_speed().
std::vector<BasalDeposit> basal_deposits(const Grid& g, Vec vel, const std::vector<double>& h,
                                         double front_x, double gate_x, double U,
                                         const std::vector<double>& cutoffs);

// ---- Pure functions of profiles and histories.

// backwall_h from h_0, h_1, m.
double backwall_height(const std::vector<double>& h);
// atan(-slope) in degrees of the least-squares line through (x_i, h_i) over the i with
// lo <= x_i <= hi, x_i < front and h_i > 0; NaN with fewer than two such points.
double fit_slope_deg(const std::vector<double>& x, const std::vector<double>& h, double lo,
                     double hi, double front);
// Least-squares slope of y(t) over the points with lo <= t_k <= hi; NaN with fewer than two
// distinct t.
double ls_slope(const std::vector<double>& t, const std::vector<double>& y, double lo, double hi);

struct StageRule {
  double speed_window = 0.05;     // s
  double plateau_fraction = 0.9;  // -
  double stop_distance = 1e-3;    // m
  double rest_speed = 1e-3;       // m/s
};
struct Stages {
  double t1, t2, t3, tf;  // s (NaN: not found)
  double front_speed;     // m/s over [t1, t2]
  double max_front_speed; // m/s, V_max
};
// t, front_x, max_speed_granular: one entry per output, in time order.
Stages detect_stages(const std::vector<double>& t, const std::vector<double>& front,
                     const std::vector<double>& max_speed_granular, const StageRule& rule);

}  // namespace gf::diag
