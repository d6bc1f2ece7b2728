#pragma once
// Anderson acceleration (Walker & Ni 2011, "Anderson acceleration for fixed-point iterations",
// SIAM J. Numer. Anal. 49) of a fixed-point map x -> G(x), for an unknown split in several PETSc
// Vecs (here S on the cells and s_t on the wall faces). With the residual f_k = G(x_k) - x_k and
// the last m differences dF_i = f_{i+1} - f_i, dG_i = G(x_{i+1}) - G(x_i):
//   gamma = argmin || f_k - dF gamma ||_2,   x_{k+1} = G(x_k) - dG gamma.
// It has the same fixed points as the plain iteration x_{k+1} = G(x_k) (m = 0); for the
// contraction of eq. 31, whose slow modes shrink by (1 - theta) per iteration, it reaches a
// tolerance in far fewer viscous solves. The caller re-projects the result (|S| <= 1).
#include <petscvec.h>

#include <vector>

namespace gf {

class Anderson {
 public:
  // templates: one Vec per block, to size the history; m: history depth (0 = plain iteration).
  Anderson(const std::vector<Vec>& templates, int m);
  ~Anderson();
  Anderson(const Anderson&) = delete;
  Anderson& operator=(const Anderson&) = delete;

  void reset() { count_ = 0; head_ = 0; have_prev_ = false; }
  // x: the current iterate x_k (overwritten with x_{k+1}); g: G(x_k). Blocks in template order.
  void update(const std::vector<Vec>& x, const std::vector<Vec>& g);
  int depth() const { return m_; }

 private:
  int m_;
  int count_ = 0;  // history entries stored (<= m)
  int head_ = 0;   // ring-buffer position of the next entry
  size_t nb_;
  // Per block: previous f and g, and the ring buffers of dF and dG.
  std::vector<Vec> f_prev_, g_prev_, f_cur_;
  std::vector<Vec*> dF_, dG_;  // per block: m Vecs each (VecDuplicateVecs)
  bool have_prev_ = false;
  // The Gram matrix dF_i . dF_j of the stored differences (m x m, slots of the ring buffer),
  // kept up to date: a new difference costs its m dot products, not all m^2 again, and all dot
  // products of an update go through one MPI reduction.
  std::vector<double> gram_;
  MPI_Comm comm_ = MPI_COMM_NULL;
};

}  // namespace gf
