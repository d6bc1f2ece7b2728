// Anderson acceleration (linsolve/Anderson.hpp) against exact answers: on a linear contraction
// G(x) = M x + b with three distinct eigenvalues, Anderson mixing is GMRES in disguise (Walker &
// Ni 2011) and must reach the exact fixed point x* = (I - M)^{-1} b in a handful of iterations
// where the plain iteration needs thousands; the entries outside the active set (zero in x and
// G(x), as S in the air) must stay exactly zero; depth 0 must be the plain iteration. Two blocks
// of different sizes, on 1 and 2 ranks (the least-squares sums are global).
#include <gtest/gtest.h>
#include <petscvec.h>

#include <cmath>
#include <vector>

#include "linsolve/Anderson.hpp"

using namespace gf;
using gf::linsolve::Anderson;

namespace {

struct Problem {
  // Block b has nloc[b] local entries; entry q is active when q % 3 != 1. On active entries
  // G(x)_q = lambda_q x_q + b_q with lambda_q in {0.99, 0.9, 0.5} and b_q = 1 + q % 7.
  std::vector<PetscInt> nloc{30, 20};
  std::vector<Vec> x, g;
  std::vector<std::vector<PetscInt>> active;
  Problem() {
    for (PetscInt n : nloc) {
      Vec v, w;
      VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, &v);
      VecDuplicate(v, &w);
      VecSet(v, 0.0);
      x.push_back(v);
      g.push_back(w);
      std::vector<PetscInt> a;
      for (PetscInt q = 0; q < n; ++q)
        if (q % 3 != 1) a.push_back(q);
      active.push_back(a);
    }
  }
  ~Problem() {
    for (Vec& v : x) VecDestroy(&v);
    for (Vec& v : g) VecDestroy(&v);
  }
  static double lambda(PetscInt q) {
    const double l[3] = {0.99, 0.9, 0.5};
    return l[(q / 3) % 3];
  }
  static double rhs(PetscInt q) { return 1.0 + q % 7; }
  static bool is_active(PetscInt q) { return q % 3 != 1; }
  // g = G(x)
  void apply() {
    for (size_t b = 0; b < x.size(); ++b) {
      const PetscScalar* xa;
      PetscScalar* ga;
      VecGetArrayRead(x[b], &xa);
      VecGetArray(g[b], &ga);
      for (PetscInt q = 0; q < nloc[b]; ++q)
        ga[q] = is_active(q) ? lambda(q) * xa[q] + rhs(q) : 0.0;
      VecRestoreArray(g[b], &ga);
      VecRestoreArrayRead(x[b], &xa);
    }
  }
  // max over both blocks and all ranks of |x - x*| (x* = b / (1 - lambda) on active entries,
  // 0 elsewhere), and whether every inactive entry is exactly zero.
  double error(bool* inactive_zero) const {
    double e = 0;
    int zero = 1;
    for (size_t b = 0; b < x.size(); ++b) {
      const PetscScalar* xa;
      VecGetArrayRead(x[b], &xa);
      for (PetscInt q = 0; q < nloc[b]; ++q) {
        if (is_active(q))
          e = std::max(e, std::abs(xa[q] - rhs(q) / (1.0 - lambda(q))));
        else if (xa[q] != 0.0)
          zero = 0;
      }
      VecRestoreArrayRead(x[b], &xa);
    }
    double ge;
    int gz;
    MPI_Allreduce(&e, &ge, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    MPI_Allreduce(&zero, &gz, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    *inactive_zero = gz != 0;
    return ge;
  }
};

// A problem with its Anderson mixing of depth m over the problem's active entries.
struct Mixing {
  Problem p;
  Anderson a;
  double err = 0;
  bool zero = false;
  explicit Mixing(int m) : a(m, PETSC_COMM_WORLD) { a.set_active(p.active); }
  // Iterations of x <- Anderson(x, G(x)) until |x - x*| < tol (or the cap); returns the count.
  int iterate(double tol, int cap) {
    for (int k = 1; k <= cap; ++k) {
      p.apply();
      a.update(p.x, p.g);
      err = p.error(&zero);
      if (err < tol) return k;
    }
    return cap + 1;
  }
};

}  // namespace

TEST(Anderson, ReachesTheExactFixedPointOfALinearContraction) {
  Mixing r(5);
  const int k = r.iterate(1e-10, 100);
  // Three distinct eigenvalues: GMRES-like convergence in a few iterations (the plain iteration
  // needs log(1e-10 / 100) / log(0.99) ~ 2750).
  EXPECT_LE(k, 12) << "error " << r.err;
  EXPECT_TRUE(r.zero) << "an inactive entry became non-zero";
}

TEST(Anderson, DepthZeroIsThePlainIteration) {
  Mixing r(0);
  r.iterate(0.0, 50);  // exactly 50 plain iterations (the error never reaches 0)
  // x_k = (1 - lambda^k) x*: the slowest entries (lambda 0.99, x* up to 700) are off by
  // 0.99^50 x* = 0.605 x*.
  const double worst = std::pow(0.99, 50) * 7.0 / 0.01;
  EXPECT_NEAR(r.err, worst, 1e-9 * worst);
  EXPECT_TRUE(r.zero);
}

TEST(Anderson, ConvergesAgainAfterSetActive) {
  Mixing r(5);
  r.iterate(1e-10, 100);
  // As at the start of the next time step: set_active again (history dropped) and a start away
  // from the fixed point; it must converge as fast as the first time.
  for (auto& v : r.p.x) VecScale(v, 0.5);
  r.a.set_active(r.p.active);
  const int k = r.iterate(1e-10, 100);
  EXPECT_LE(k, 12) << "error " << r.err;
  EXPECT_TRUE(r.zero);
}

// The history belongs to one fixed-point map. At a new time step the map changes (other S^n,
// kappa, u^n) and the first update must be the plain step x = G(x): a difference f_k - f_{k-1}
// across two maps, or a stored pair of the old map, would send the mixing off. The stepper
// starts each step with set_active, a growing residual calls reset: both must drop everything.
TEST(Anderson, FirstUpdateAfterSetActiveOrResetIsThePlainStep) {
  for (const bool by_reset : {false, true}) {
    Mixing r(5);
    r.iterate(0.0, 8);  // a full history (8 > depth 5)
    // A new map: scale x away from the fixed point, as a new time step starts elsewhere.
    for (auto& v : r.p.x) VecScale(v, 0.3);
    if (by_reset)
      r.a.reset();
    else
      r.a.set_active(r.p.active);
    r.p.apply();
    r.a.update(r.p.x, r.p.g);
    double diff = 0;
    for (size_t b = 0; b < r.p.x.size(); ++b) {
      Vec d;
      VecDuplicate(r.p.x[b], &d);
      VecWAXPY(d, -1.0, r.p.g[b], r.p.x[b]);
      PetscReal nb;
      VecNorm(d, NORM_INFINITY, &nb);
      diff = std::max(diff, static_cast<double>(nb));
      VecDestroy(&d);
    }
    EXPECT_EQ(diff, 0.0) << (by_reset ? "reset" : "set_active")
                         << " left history behind: x != G(x) after the first update";
  }
}
