#pragma once
// Anderson acceleration (Walker & Ni 2011, "Anderson acceleration for fixed-point iterations",
// SIAM J. Numer. Anal. 49) of a fixed-point map x -> G(x), for an unknown split in several PETSc
// Vecs (here S on the cells and s_t on the wall faces). With the residual f_k = G(x_k) - x_k and
// the last m differences dF_i = f_{i+1} - f_i, dG_i = G(x_{i+1}) - G(x_i):
//   gamma = argmin || f_k - dF gamma ||_2,   x_{k+1} = G(x_k) - dG gamma.
// It has the same fixed points as the plain iteration x_{k+1} = G(x_k) (m = 0); for the
// contraction of eq. 31, whose slow modes shrink by (1 - theta) per iteration, it reaches a
// tolerance in far fewer viscous solves. The caller re-projects the result (|S| <= 1).
//
// Only the entries that can be non-zero take part (set_active): S vanishes in the air and s_t
// off the walls, in both x and G(x), so their f, dF and dG are zero and they add nothing to the
// least-squares problem; x_{k+1} = G(x_k) there. The history is kept packed over the active
// entries: case A has 75-80 % of its cells in the air and s_t lives on 2 (nx + ny) of the
// 2 nx ny velocity faces, so an update costs a fifth of the full-Vec version for the same
// iterates (the sums run over the same non-zero terms in the same order).
#include <petscvec.h>

#include <vector>

namespace gf::linsolve {

class Anderson {
 public:
  // m: history depth (0 = plain iteration); comm: the communicator of the Vecs.
  Anderson(int m, MPI_Comm comm);

  // The entries of each block (indices into the Vec's local array) that may be non-zero in x or
  // G(x) during the coming iterations; all others must be zero in both. Resets the history.
  void set_active(std::vector<std::vector<PetscInt>> idx);
  void reset() { count_ = 0; head_ = 0; have_prev_ = false; }
  // x: the current iterate x_k (overwritten with x_{k+1}); g: G(x_k). Blocks in the order of
  // set_active.
  void update(const std::vector<Vec>& x, const std::vector<Vec>& g);

 private:
  int m_;
  MPI_Comm comm_;
  int count_ = 0;  // history entries stored (<= m)
  int head_ = 0;   // ring-buffer position of the next entry
  bool have_prev_ = false;
  std::vector<std::vector<PetscInt>> idx_;  // active local indices per block
  size_t n_ = 0;                            // total active entries on this rank
  // Packed over the active entries: f_k, f_{k-1}, G(x_{k-1}), G(x_k), and the ring buffers of
  // dF and dG (m slots of n_ each).
  std::vector<double> f_cur_, f_prev_, g_prev_, g_cur_, dF_, dG_;
  // The Gram matrix dF_i . dF_j of the stored differences (m x m, slots of the ring buffer),
  // kept up to date: a new difference costs its m dot products, not all m^2 again, and all dot
  // products of an update go through one MPI reduction.
  std::vector<double> gram_;
};

}  // namespace gf::linsolve
