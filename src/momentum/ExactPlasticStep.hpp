#pragma once
// One step's plastic problem solved exactly (issue 19): eq. 31 with theta = 0 and kappa frozen,
//
//   A u - C Pi (kappa S) = b,    S = P(S + c E u)   in every cell with kappa > 0,
//
// A the assembled prediction operator (Predictor::assemble), b the rest of its right-hand side,
// C and B the plastic matrices (PlasticMatrices.hpp), E u = L (B u + d0) the deviatoric strain
// rate (Dxx - Dyy)/2, Dxy that the projection of eq. 29 acts on, Pi (sxx, sxy) = (sxx, sxy,
// -sxx) the traceless tensor and P the projection on the unit ball of the paper's norm
// |S|^2 = Sxx^2 + Sxy^2. Its solution does not depend on c > 0: in a rigid cell E u = 0 and
// |S| <= 1, in a yielded one S = E u / |E u|; the rigid zones are rigid, not elastic as with
// theta > 0 (the unit test RelaxedProjectionFixedPointDependsOnROverTheta).
//
// Method of multipliers (augmented Lagrangian): for a multiplier lambda, the inner problem
//   F(u) = A u - C Pi kappa P(lambda + c E u) - b = 0
// is the gradient of a convex C^1 function with a semismooth gradient (the Moreau envelope of
// the yield dissipation, on the walls where C = -B^T W), solved by Newton's method (PETSc SNES,
// line search, the generalised Jacobian A - C Pi kappa c P'(q) L B, P'(q) = I inside the ball
// and (I - n n^T) / |q| outside; options prefix -exact_, default a direct solve), then
// lambda <- P(lambda + c E u). It stops when the multiplier changes by less than tol in every
// cell (|lambda_new - lambda| = |P(q) - lambda|: in a rigid cell c |E u|, in a yielded one the
// misalignment of lambda with E u), after a converged inner solve.
//
// Measured (test_exact_plastic_step_mpi.cpp, steady Bingham channel, direct solves): the plug
// below its threshold stays at rest (|u| 1.5e-10 and 1.8e-11 m/s at c factor 1 and 3, 33 and 18
// multiplier updates of one Newton iteration each); the Bingham Poiseuille profile with error
// 1.1e-2 and 2.7e-3 at 16 and 32 cells across (second order), independent of c to 3e-11; but
// the outer loop is slow where the flow yields (52 and 130 updates at c factor 10; at 64 cells
// not converged in 200 updates and 4084 Newton iterations, error 6.8e-4), and at c factor 100
// the Newton line search on |F| fails on the held plug. Not robust enough for the stepper:
// solve_newton below (u and S updated together) converges in 2-6 iterations on the same
// problems.
//
// Without NewtonPressure the pressure is not in this problem (the projection of eq. 32 follows
// it), so a zone held rigid here can still be deformed by the pressure correction
// (docs/RHEOLOGY.md, the Coulomb block's first step); with it (solve_newton's last argument)
// the pressure is solved in the same Newton system. The stepper uses solve_newton
// (momentum/NewtonPlastic.hpp); solve() is verified by
// tests/unit/momentum/test_exact_plastic_step_mpi.cpp and kept for comparison.
#include <petscsnes.h>

#include <functional>
#include <string>
#include <vector>

#include "grid/Grid.hpp"
#include "momentum/PlasticMatrices.hpp"

namespace gf::momentum {

struct ExactStepOptions {
  double tol = 1e-10;   // largest change of the multiplier in a cell, dimensionless
  int max_outer = 200;  // multiplier updates (solve) or Newton iterations (solve_newton)
  // solve_newton: the rigid cells and the sticking wall faces (the last linearisation's
  // classes) must also be below rigid_tol_factor * tol (PETSc option -exactpd_rigid_tol_factor).
  // A dead zone's pressure keeps what the steps leave in its rigid cells (p^{n+1} = p^n + psi,
  // and an error of p^n there is carried by the zone's plastic stress, not corrected): case B at
  // n = 64, whose peak granular pressure is in its dead zone, moves by 4.8e-4 between tol 1e-6
  // and 2.5e-8 over its first 0.16 s, by 7.5e-5 with the rigid cells at 0.1 (1.5 times the
  // iterations) and 1.4e-5 at 0.01 (3.2 times, 4 capped steps at the cap of 160); but at 0.1 case
  // A at n = 64 takes twice the iterations and caps 7 steps in 0.2 s. So 1: the stopping test of
  // before (docs/RHEOLOGY.md, twelfth session). With the cap of 1000 (thirteenth session), 0.01
  // moves case B's peak by at most 7.7e-5 under a factor 4 in r_factor or newton_tol over 0.2 s
  // with 1 capped step in 5 runs, but case A then takes 5.9 times the iterations. Since the
  // fourteenth session the whole tolerance is 1e-7 by default (rheology.newton_tol), which
  // holds the rigid cells as 0.1 did at 1e-6, for 1.9 to 2.8 times the iterations of 1e-6;
  // since the sixteenth 5e-8 (Schema.cpp).
  double rigid_tol_factor = 1;
  double inner_rtol = 1e-12;  // Newton: relative reduction of |F|
  // solve_newton: the floor of |q| - 1 in a yielded cell's tangential stiffness
  // gamma = c / max(|q| - 1, gap_floor) (dimensionless; any gamma >= 0 has the exact fixed
  // point, the floor only bounds the stiffness of a cell at the yield limit). A cell just past
  // the limit (|q| - 1 below the floor) then converges linearly, by about (|q| - 1) / gap_floor
  // per iteration; NewtonPlastic uses 1e-9 without the pressure (see there).
  double gap_floor = 1e-3;
  // solve_newton: the step length of the rigid cells' augmented update, in units of c
  // (dimensionless; the fixed point does not depend on it). Large: the update is close to
  // Newton's E u = 0 and converges in fewer iterations; the direct solve's round-off grows with
  // it. Measured in the unit test's channel (16-64 cells, c factors 1-100): at 1e3, 3-11
  // iterations, c factor 3 against 30 differ by 2.4e-10 of max |u|; at 1e4, 2-6 and 1.0e-8;
  // at 1e6, 2-4 and 6.6e-7; at 1e7 the round-off shows in the profile; at 1, the cells' step
  // is the multipliers' and the iteration cycles. (Measured without rigid_boost_max; with it,
  // at 1e4, c factor 3 against 30 differ by 6.9e-8.)
  double rigid_factor = 1e4;
  // solve_newton: linearise each cell at P(S_k), S_k retracted onto the unit ball, instead of
  // at S_k (see solve_newton; false: the linearisation of before 2026-12-07). The fixed points
  // are the same (the exact solution); the iteration counts are not. Measured (eleventh session,
  // docs/RHEOLOGY.md): case A at n = 32 to 0.1 s 2,904 iterations against 4,003, case B at
  // n = 32 to 0.5 s 3,808 against 4,868, case A at n = 64 to 0.1 s 3,347 against 4,587.
  // PETSc option -exactpd_retract false: off.
  // Not with NewtonPressure, where it took more iterations (the unit test's channel with
  // gravity: 74 instead of 21).
  bool retract = true;
  // solve_newton with NewtonWalls::refresh: the largest change of kappa_b between the last two
  // iterates, relative to its largest value, at which the iteration stops.
  double kappa_b_tol = 1e-5;
  // The same for the sticking Coulomb wall faces (a diagonal term: no conditioning cost). On a
  // block held by its wall friction the distribution of the wall traction is not unique, the
  // multipliers drift along it, and the residual left is that drift over this factor: at 1e4
  // the iteration stalled at 3e-7, at 1e6 the residual moves to the rigid cells (1e-8).
  double wall_rigid_factor = 1e6;
  // solve_newton: the largest factor on rigid_factor once the active sets have stopped
  // changing (see solve_newton; 1: off). Measured on case A at n = 16 to 1.06 s (the walls'
  // load from the step's start): 9 of 1060 steps capped without it, 0 with 1e4 (47 s instead
  // of 68 s); at n = 32 to 0.1 s, 34 of 100 and 10 (these with the sticking wall faces boosted
  // too, and with the looser stopping test of before 2026-12-06).
  double rigid_boost_max = 1e4;
  // The same for the sticking wall faces alone (1: their step stays wall_rigid_factor c_b).
  // Boosted like the cells, a sticking face's step reached 1e10 c_b, and the direct solve's
  // round-off in u_t then moved s_t by up to 1 between two iterations (case A at n = 32, a
  // left-wall face at q = -1.019 after an iteration at residual 3e-6, no class changed).
  // Measured with the stopping test at the step's own c (2026-12-06, seventh session):
  // case A at n = 32 to 1.06 s, 3 of 1060 steps capped and 10,321 iterations with the faces
  // boosted to 1e4, 0 and 10,613 at 1; at n = 64, first 100 steps, 7 capped (5,170
  // iterations) at 1e4, 1 (5,198) at 100 with wall_rigid_factor 1e4, 2 (4,796) at 1.
  double wall_boost_max = 1;
  // solve_newton: after this many iterations in a row whose line search took a step of 1/64
  // or less, the next takes its Newton point whole (0: never). Where a cell at its yield limit
  // changes class at every Newton point, the line search's short steps gain nothing: case B at
  // n = 64 capped 3 of 1360 steps so, the residual creeping at 1.6e-6 to 8.0e-6 with about 7
  // halvings per iteration over the last 60 (docs/RHEOLOGY.md). Measured at 3: case B at
  // n = 64 to 1.36 s 0 capped and 18,767 iterations (3 and 19,244 without); case A at n = 64
  // 2 of 1061 capped (residual left up to 2.9e-5; 2 up to 9.2e-6 without) and 12,676
  // iterations (13,536); case A at n = 32 0 of 1060 and 10,564 (0 and 10,613).
  int creep_steps = 3;
  // NewtonPlastic: refresh the Coulomb walls' kappa_b from the iterate's S and D (the paper's
  // kappa_b^{n+1}, rheology.newton_wall_load = "iterate"); false: kappa_b from the step's start
  // (p^n, S^n, u^n), fixed like kappa, which makes the step a convex problem with a unique
  // velocity. kappa_b includes kappa S_nn (eq. 22), and a rigid zone's S is not unique: refreshed
  // from it, kappa_b drifts with the iterates. Measured on case A at n = 16 to 0.3 s: 211 of
  // 300 steps capped refreshed, 25 frozen (docs/RHEOLOGY.md).
  bool refresh_kappa_b = false;
  // solve_newton without the pressure, with local rows (NewtonPlastic: the granular cells
  // widened by solver.viscous_local_margin): from the second Newton iteration of a step on,
  // the Newton system is solved on those rows only, the others frozen at the last full solve's
  // values (their rows hold no plastic term, and A is dominated by its mass term, so the
  // correction decays away from the grains). A step converges only when also the momentum
  // residual over all rows, |A u - b - C Pi kappa S + walls| <= momentum_rtol |b| (2-norms);
  // otherwise its next iteration is a full solve.
  double momentum_rtol = 1e-10;
  // NewtonPlastic: the margin of the local rows in cells (solver.viscous_local_margin; 0 = every
  // Newton system solved on every row).
  int local_margin = 0;
};

// The Coulomb walls in solve_newton (boundary/Coulomb.hpp, eqs. 22 and 30 with theta = 0), in
// the wall storage of dm_vel Vecs: on a wall face with kappa_b > 0 the traction -kappa_b s_t / h
// acts on the face's velocity u_t (Predictor::add_plastic; h the spacing normal to the wall)
// and s_t = P_b(s_t + c_b u_t). Linearised like the cells: sticking (|q| <= 1), s_t = s_t,k +
// rigid_factor c_b u_t; sliding, s_t = sign(q_k) (P_b' = 0 there). Faces with kappa_b = 0 get
// s_t = 0. The moving gate is not covered (its slip is relative to the plate).
struct NewtonWalls {
  Vec kappa_b = nullptr;  // Pa; refreshed by refresh() at every linearisation
  Vec c_num = nullptr;    // Pa s/m: c_b kappa_b (c_b = c_num / kappa_b, s/m)
  Vec s_wall = nullptr;   // in: the start; out: the solution
  // kappa_b from the strain rate D = B u + d0 and S (both dm_ten); empty: fixed. Called at
  // the start and each time the iteration has converged with kappa_b fixed, until kappa_b
  // changes by less than tol of its largest value.
  std::function<void(Vec D, Vec S, Vec kappa_b)> refresh;
};

// The side walls' friction in solve_newton (boundary/SideWalls.hpp, the projection of eq. 30 on
// the unit disc, with theta = 0): in a cell with k > 0 the body force -I^T (k s) acts on the
// faces, U = I u the cell-centred velocity, and s = P_disc(s + c_s U). Linearised like the
// cells' S: sticking (|q| <= 1, q = P(s_k) + c_s U_k), s = P(s_k) + rigid_factor c_s U (the
// augmented form of U = 0); sliding, s = n + gamma (I - n n^T) U with n = q / |q| and
// gamma = c_s / (|q| - 1). The Newton matrix gains I^T k G I, symmetric positive
// semi-definite, so that J stays symmetric positive definite where it was. Its residual
// (k / k_max) |s - P(s + c_s U)|, in units of the largest friction bound as the fixed point's
// change (SideWalls::update), joins the cells' (max, 2-norm, and the sticking cells' in the
// rigid part).
// k is fixed for the step (from p^n, or p_hyd; SideWalls::yield).
struct NewtonSide {
  Vec k = nullptr;  // dm_cell, N/m^3: the friction bound k = (2/W) tan(alpha_w) K p^+ c
  Vec c = nullptr;  // dm_cell, s/m: the augmentation c_s (the answer does not depend on it)
  Vec s = nullptr;  // dm_vel read as cell-centred vectors: in the start, out the solution
};

// The pressure in solve_newton (rheology.newton_pressure = "coupled"): the prediction of eq. 31
// and the projection of eq. 32 solved as one system, so that the (u, S) it returns is
// divergence-free and the plastic stress is in equilibrium with the step's pressure:
//   A u - C Pi kappa S + G psi = b,   D u = 0,   S = P(S + c E u),
// psi = p^{n+1} - p^n (b holds -grad p^n). Without it the projection that follows the plastic
// step changes u where the plastic problem held it at rest (docs/RHEOLOGY.md). The blocks are
// fixed by the grid (saddle_blocks below); each Newton iteration solves the saddle point
// [[J, G], [D, Z]] by one direct solve (MUMPS LU, KSP prefix -exactpd_sp_).
struct NewtonPressure {
  Mat G = nullptr;    // dm_vel x dm_cell: (psi_i - psi_{i-1}) / h on the interior faces, Pa/m
  Mat Dv = nullptr;   // dm_cell x dm_vel: div u (1/s), the pinned cell's row empty
  Mat Z = nullptr;    // dm_cell x dm_cell: 1 on the pinned cell's diagonal (psi = 0 there)
  Vec psi = nullptr;  // dm_cell, Pa: in the start; out p^{n+1} - p^n, 0 in the pinned cell
};

// The fixed blocks of NewtonPressure for the grid g: the interior faces' gradient and the cells'
// divergence of projection/Projection.hpp (walls carry no flux; periodic x wraps), with the
// divergence row of cell (0, 0) replaced by psi = 0 there. The divergence rows sum to zero on
// a closed domain, so one of them is redundant and pinning psi takes its place: the solution
// is the projection's up to the constant (the level is set afterwards). Collective; the caller
// destroys G, Dv and Z. Not with the gate (its faces' open part is not in them).
void saddle_blocks(const Grid& g, NewtonPressure& p);

struct ExactStepStats {
  int outer = 0;          // multiplier updates
  int newton = 0;         // Newton iterations, all inner solves
  int backtracks = 0;     // solve_newton: halvings of the step in the line search
  int refreshes = 0;      // solve_newton: kappa_b refreshed after a converged iteration
  double change = 0;      // the last multiplier change (max over cells)
  double rigid = 0;       // solve_newton: the last residual's max over the rigid cells and
                          // sticking wall faces
  bool converged = false;
  int local = 0;          // solve_newton: iterations solved on the local rows
  int full = 0;           // solve_newton: iterations solved on every row
  bool cholesky = false;  // solve_newton: ended with a Cholesky PC and its matrix flagged SPD
};

class ExactPlasticStep {
 public:
  explicit ExactPlasticStep(const Grid& g);
  ~ExactPlasticStep();
  ExactPlasticStep(const ExactPlasticStep&) = delete;
  ExactPlasticStep& operator=(const ExactPlasticStep&) = delete;

  // Solves the problem above. A: the prediction operator (dm_vel layout); b: dm_vel; kappa:
  // dm_cell yield stress (Pa); c: dm_cell augmentation (s; the answer does not depend on it,
  // the iteration count does); u: dm_vel, in: the start, out: the solution; S: dm_ten, in: the
  // start multiplier, out: the plastic tensor (0 where kappa <= 0). Collective.
  ExactStepStats solve(Mat A, Vec b, const PlasticMatrices& m, Vec kappa, Vec c, Vec u, Vec S,
                       const ExactStepOptions& opt = {});

  // The same problem by a primal-dual semismooth Newton method: u and S are updated together,
  // one linear solve per iteration (stats: outer = newton = the iterations). With q_k =
  // P(S_k) + c E u_k in a cell (below), the linearisation of S = P(S + c E u) at (u_k, P(S_k))
  // gives
  //   yielded (|q_k| > 1):  S_{k+1} = n_k + gamma_k (I - n_k n_k^T) E u_{k+1},
  //                         n_k = q_k / |q_k|, gamma_k = c / (|q_k| - 1)  (Newton at P(S_k)),
  //   rigid   (|q_k| <= 1): E u_{k+1} = 0, taken as S_{k+1} = P(S_k) + c_R E u_{k+1} with
  //                         c_R = rigid_factor c (or the cell's c_rigid): the saddle point
  //                         of Newton's step with a (2,2) block -I/c_R, which is not
  //                         singular where a rigid zone's
  //                         multiplier is not unique, and is Newton's step as c_R -> infinity,
  // where q_k = P(S_k) + c E u_k: the linearisation point is S_k retracted onto the unit ball
  // (ExactStepOptions::retract; without it S_k and q_k = S_k + c E u_k). After a yielded cell's
  // step S lies on the tangent line at n_k, outside the ball; from there |q_k| - 1 is that
  // overshoot rather than c n.E u, and in a cell at its yield limit (c |E u| of 2e-6 to 7e-6)
  // gamma_k came out 4 to 100 times too small, the cell's stress turning by 1e-3 to 4e-2 rad per
  // iteration for 30 iterations (case A at n = 32, a bottom-row cell, -exactpd_monitor). The
  // retraction leaves the fixed points alone: at one, S = n + t tau with t = gamma tau.E u (tau
  // a unit tangent) and tau.q_k = 0 give (gamma / |S| + c) tau.E u = 0, so t = 0, |S| = 1 and
  // S = n parallel to E u; a rigid one, S = P(S) + c_R E u with |P(S) + c E u| <= 1, has E u = 0
  // (else |S| > 1, E u parallel to S and |q| > 1).
  // So u_{k+1} solves (A - C Pi kappa G_k L B) u = b + C Pi kappa (S0_k + G_k L d0) with
  // G_k, S0_k the cell's (gamma_k (I - n n^T), n_k) or (c_R I, P(S_k)). Every fixed point of this
  // iteration is the exact solution, whatever gamma >= 0 and c_R > 0: E u = 0 in the rigid
  // cells, and in the yielded ones S = n, which makes S parallel to E u. From the second
  // iteration on, when the Newton point has changed the active sets (a cell rigid <-> yielded,
  // a wall face sticking <-> sliding), the step is halved until the 2-norm of
  // |S - P(S + c E u)| over the cells decreases (all the points between two iterates satisfy
  // the momentum equation, linear in (u, S)); with the same active sets the full step is taken
  // (on case A at n = 16 the halvings then slowed the bottom row's cells at the yield limit to
  // a linear tail: 17 capped steps of 300 with them, 10 without). If ten halvings find no decrease,
  // the Newton point is taken after all (a face or cell at its threshold can make the residual
  // rise along the whole segment), and so is it after creep_steps short steps in a row
  // (ExactStepOptions::creep_steps). A step that reaches max_outer ends at its best iterate (the
  // smallest max residual after a solve), not its last. Once the active sets have
  // stayed the same for two iterations, c_R grows tenfold per iteration up to rigid_boost_max
  // times its value (ExactStepOptions::rigid_boost_max; the sticking wall faces' up to
  // wall_boost_max). Stops when max |S - P(S + c E u)| <=
  // tol over the cells (the criterion of solve()). Linear solves: KSP prefix -exactpd_,
  // default a direct solve (MUMPS: Cholesky where the Newton matrix is symmetric, else LU;
  // ordering QAMD: -exactpd_mat_mumps_icntl_7 6 unless the user sets it); -exactpd_monitor
  // prints the residual of every iteration.
  //
  // With `pressure` (NewtonPressure), each iteration solves the saddle point with the pressure
  // instead (solve_saddle), and a rigid cell's incompressibility is taken in the same augmented
  // form as its E u = 0: psi = psi_k - kappa c_R div u, c |div u| in its residual. Measured
  // (the unit test's channel with gravity, ny = 32): the velocity of the step without the
  // pressure to 3e-11, the rows' mean vertical stress hydrostatic to 1e-10, in 21 iterations
  // on 1 rank and 31 on 2 (4 without the pressure: the rigid cells' pressure moves by its
  // proximal step); the plug at rest (1.6e-15 m/s) in 29.
  //
  // Measured (test_exact_plastic_step_mpi.cpp, the steady channel, c factors 1 to 100, 16 to
  // 64 cells across, rigid_factor 1e4): 2-3 Newton iterations for the plug (|u| 1.2e-12 m/s),
  // 4-6 for the Bingham Poiseuille profile at every grid (second order: 1.09e-2, 2.71e-3,
  // 6.78e-4, and 1.70e-4 at 128 cells), no backtracking; where the method of multipliers takes
  // 33 to 130 updates, and does not converge in 200 at 64 cells. With c_R = c the rigid
  // cells' step is the multipliers' (an Uzawa step) and the iteration cycles at c factor 10
  // (residual 2: a yielded cell's direction flips); the line search then makes it converge,
  // but linearly (ratio 0.9).
  ExactStepStats solve_newton(Mat A, Vec b, const PlasticMatrices& m, Vec kappa, Vec c, Vec u,
                              Vec S, const ExactStepOptions& opt = {},
                              const NewtonWalls* walls = nullptr, Vec c_rigid = nullptr,
                              const NewtonPressure* pressure = nullptr,
                              const std::vector<PetscInt>* local_rows = nullptr,
                              const NewtonSide* side = nullptr);

 private:
  const Grid& g_;
  SNES snes_ = nullptr;
  // Per solve: what the SNES callbacks read.
  Mat A_ = nullptr, J_ = nullptr, CMB_ = nullptr, M_ = nullptr;
  // J = A - C M B in the union of A's and C M B's patterns (C M B has no entry in the rows of
  // the faces that are not unknowns, where A has 1), made once per step with m_ and M_ set,
  // and AJ_ = A in that pattern: each iteration then copies it instead of adding A by
  // MatAXPY's row-by-row insertion for a pattern that is a subset (case A at n = 32: the two
  // MatAXPY per iteration were 11 % of the run's time).
  Mat AJ_ = nullptr;
  // J_ factorised by Cholesky this step (the default without the pressure, unless
  // -exactpd_pc_type lu); a failed Cholesky factorisation, or a J that is not symmetric, makes
  // it LU for the rest of this object's life.
  bool spd_ = false, cholesky_failed_ = false;
  // Whether J is symmetric for every G: A symmetric (checked once: a_checked_, a_symmetric_)
  // and C = -B^T W on the columns of the cells with a yield stress (every step: the grains may
  // have reached a no-slip wall). Collective.
  bool a_checked_ = false, a_symmetric_ = false;
  bool newton_matrix_symmetric(Mat A);
  void use_lu();  // LU for both KSPs from now on (this object)
  // The PC of k (after its KSPSetFromOptions): Cholesky (spd_) or LU, with
  // -exactpd_pc_factor_mat_solver_type or MUMPS; nothing if the user chose another PC.
  bool pc_auto_ = true;
  std::string solver_ = "mumps";  // -exactpd_pc_factor_mat_solver_type, read each step
  void set_factorisation(KSP k);
  void jacobian_pattern(Mat A);
  // M_ anew, with a zero 3 x 3 block in every cell, or only in those with kappa_ > 0 (new
  // entries elsewhere are then an error). Collective.
  void make_M(bool granular_only);
  void fill_jacobian();  // J_ = AJ_ - CMB_, CMB_ current. Collective.
  // Per entry of CMB_'s local diagonal block, then of its off-diagonal block, the index of the
  // same entry in J_'s block's value array (made by the first fill_jacobian of a pattern;
  // jacobian_pattern clears it).
  std::vector<PetscInt> map_;
  size_t map_diag_ = 0;
  bool map_built_ = false;
  const PlasticMatrices* m_ = nullptr;
  Vec b_ = nullptr, kappa_ = nullptr, c_ = nullptr, lambda_ = nullptr, D_ = nullptr,
      T_ = nullptr, CT_ = nullptr;  // CT_: C T of the residual (dm_vel)
  void plastic_stress(Vec u, Vec T, bool jacobian);
  // solve_newton: the linear solver, each cell's (S0x, S0y, G00, G01, G11) of the last
  // linearisation, the right-hand side, the last iterate and the Newton point.
  KSP ksp_ = nullptr;
  std::vector<double> lin_;
  Vec rhs_ = nullptr, u_prev_ = nullptr, u_newton_ = nullptr, S_prev_ = nullptr,
      S_newton_ = nullptr;
  // The pressure (null: none): the saddle point's solver, its assembled matrix and vectors,
  // and the line search's copies of psi.
  const NewtonPressure* pres_ = nullptr;
  KSP ksp_sp_ = nullptr;
  Mat K_ = nullptr;
  Vec X_ = nullptr, R_ = nullptr, psi_prev_ = nullptr, psi_newton_ = nullptr;
  // Per owned cell, kappa c_R of a rigid cell in the last linearisation (0: yielded or no
  // yield stress); the (2,2) block with 1 / (kappa c_R) there, and the psi rows' rhs.
  std::vector<double> prox_;
  Mat Zk_ = nullptr;
  Vec zdiag_ = nullptr;
  // One Newton system with the pressure: (J_, G; Dv, Zk_) (u, psi) = (rhs_, Zk_ psi_k), psi_k
  // the current psi (0 in the pinned cell). Collective.
  void solve_saddle(Vec u, int it);
  // Local Newton solves (solve_newton's local_rows): the rows' index set, the sub-matrix of J,
  // its direct solver, work vectors; solve_local solves J_RR d = (rhs - J u)_R, u_R += d.
  IS is_loc_ = nullptr;
  Mat Jloc_ = nullptr;
  KSP ksp_loc_ = nullptr;
  Vec work_vel_ = nullptr;
  Vec u_best_ = nullptr, S_best_ = nullptr, sw_best_ = nullptr;  // the best iterate of a step
  void solve_local(Vec u, int it);
  // Where the largest residual of the last linearisation is (-exactpd_monitor): a cell (kind 0,
  // q = |q|), a Coulomb wall face (kind 1: u on the bottom or top, 2: v on the left or right;
  // q = s_t + c_b u_t) or a cell's side-wall friction (kind 3, q = |s + c_s U|).
  struct Worst {
    double r = -1;
    int i = -1, j = -1, kind = 0;
    double q = 0;
  } worst_;
  void print_worst() const;  // collective
  // |A u - b|_2 over the rows outside the local rows, over |b|_2.
  double momentum_residual(Vec u);
  // The walls (null: none): per face (s0, g) of the last linearisation (two per dm_vel local
  // entry), the diagonal kappa_b g / h and the right-hand side -kappa_b s0 / h they add, and
  // the line search's copies of s_t.
  const NewtonWalls* walls_ = nullptr;
  Vec c_rigid_ = nullptr;  // dm_cell, s: the rigid cells' step (null: rigid_factor c)
  std::vector<double> linw_;
  Vec wdiag_ = nullptr, wrhs_ = nullptr, sw_prev_ = nullptr, sw_newton_ = nullptr,
      kb_old_ = nullptr;
  // The side walls (null: none): I_ the cell-centred velocity (dm_vel cell vectors <- dm_vel
  // faces, the wall faces left out: they are not unknowns), Ms_ the cells' k G blocks (2 x 2,
  // the cells with k > 0), SIDE_ = I_^T Ms_ I_, per cell (s0x, s0y, G00, G01, G11) of the last
  // linearisation in lins_, the right-hand side's -I^T (k s0) in srhs_, U = I u in Us_, and
  // the line search's copies of s.
  const NewtonSide* side_ = nullptr;
  Mat I_ = nullptr, Ms_ = nullptr, SIDE_ = nullptr;
  std::vector<double> lins_;
  PetscReal side_kmax_ = 1;  // the step's largest k (N/m^3): the side residual's weight k / k_max
  Vec srhs_ = nullptr, ks0_ = nullptr, Us_ = nullptr, ss_prev_ = nullptr, ss_newton_ = nullptr,
      ss_best_ = nullptr;
  void side_matrices();  // I_ (once), Ms_'s pattern and SIDE_ for this step. Collective.
  double linearise_side(Vec u, const ExactStepOptions& opt, double& l2, double& changes,
                        double& rigid);
  void newton_update_side(Vec u);
  // kappa_b from (u, lambda_); returns max |change| / max kappa_b.
  double refresh_kappa_b(Vec u);
  // Calls f(i, j, q, h) for the local wall faces of the Coulomb storage: q = 0 (u, bottom and
  // top rows) or 1 (v, left and right columns), h the spacing normal to the wall.
  template <class F> void for_wall_faces(F&& f) const;
  double linearise_walls(Vec u, const ExactStepOptions& opt, double& l2, double& changes,
                         double& rigid);
  void newton_update_walls(Vec u);
  struct Residual {
    double max, l2;  // of |lambda - P(lambda + c E u)| over the cells
    double rigid;    // max over the rigid cells and sticking wall faces
  };
  // Linearises at (u, lambda_): M_ = Pi kappa G L, T_ = Pi kappa (S0 + G L d0), lin_; returns
  // the residual there. Collective.
  Residual linearise(Vec u, const ExactStepOptions& opt);
  // Per local cell and wall face, the class of the last linearisation (0 none, 1 rigid or
  // sticking, 2 yielded or sliding), and how many changed class in it (all ranks).
  std::vector<signed char> active_;
  double active_changes_ = 0;
  // The factor on the rigid cells' steps (ExactStepOptions::rigid_boost_max), and, up to
  // wall_boost_max, on the sticking faces'.
  double boost_ = 1;
  // lambda_ = S0 + G L (B u + d0) from lin_.
  void newton_update(Vec u);
  static PetscErrorCode residual(SNES, Vec u, Vec F, void* ctx);
  static PetscErrorCode jacobian(SNES, Vec u, Mat J, Mat P, void* ctx);
};

}  // namespace gf::momentum
