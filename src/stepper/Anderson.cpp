#include "stepper/Anderson.hpp"

#include <cmath>

#include "core/Error.hpp"

namespace gf {

Anderson::Anderson(const std::vector<Vec>& templates, int m) : m_(m), nb_(templates.size()) {
  if (m_ <= 0) return;
  f_prev_.resize(nb_);
  g_prev_.resize(nb_);
  f_cur_.resize(nb_);
  dF_.assign(nb_, nullptr);
  dG_.assign(nb_, nullptr);
  for (size_t b = 0; b < nb_; ++b) {
    GF_PETSC(VecDuplicate(templates[b], &f_prev_[b]));
    GF_PETSC(VecDuplicate(templates[b], &g_prev_[b]));
    GF_PETSC(VecDuplicate(templates[b], &f_cur_[b]));
    GF_PETSC(VecDuplicateVecs(templates[b], m_, &dF_[b]));
    GF_PETSC(VecDuplicateVecs(templates[b], m_, &dG_[b]));
  }
  gram_.assign(static_cast<size_t>(m_) * m_, 0.0);
  GF_PETSC(PetscObjectGetComm(reinterpret_cast<PetscObject>(templates[0]), &comm_));
}

Anderson::~Anderson() {
  if (m_ <= 0) return;
  for (size_t b = 0; b < nb_; ++b) {
    VecDestroy(&f_prev_[b]);
    VecDestroy(&g_prev_[b]);
    VecDestroy(&f_cur_[b]);
    VecDestroyVecs(m_, &dF_[b]);
    VecDestroyVecs(m_, &dG_[b]);
  }
}

void Anderson::update(const std::vector<Vec>& x, const std::vector<Vec>& g) {
  if (m_ <= 0) {
    for (size_t b = 0; b < nb_; ++b) GF_PETSC(VecCopy(g[b], x[b]));
    return;
  }
  // f_k = g - x
  for (size_t b = 0; b < nb_; ++b) GF_PETSC(VecWAXPY(f_cur_[b], -1.0, x[b], g[b]));
  int slot = -1;     // the ring-buffer slot written by this update (-1: none)
  if (have_prev_) {  // push dF = f_k - f_{k-1}, dG = g_k - g_{k-1}
    slot = head_;
    for (size_t b = 0; b < nb_; ++b) {
      GF_PETSC(VecWAXPY(dF_[b][slot], -1.0, f_prev_[b], f_cur_[b]));
      GF_PETSC(VecWAXPY(dG_[b][slot], -1.0, g_prev_[b], g[b]));
    }
    head_ = (head_ + 1) % m_;
    if (count_ < m_) ++count_;
  }
  for (size_t b = 0; b < nb_; ++b) {
    GF_PETSC(VecCopy(f_cur_[b], f_prev_[b]));
    GF_PETSC(VecCopy(g[b], g_prev_[b]));
  }
  have_prev_ = true;
  // x_{k+1} = g - dG gamma, gamma from the normal equations (dF^T dF + eps I) gamma = dF^T f:
  // m is small (<= 10); the regularisation guards against nearly dependent differences.
  const int n = count_;  // the stored slots are 0 .. n-1
  for (size_t b = 0; b < nb_; ++b) GF_PETSC(VecCopy(g[b], x[b]));
  if (n == 0) return;
  // Local parts of dF_i . f (n values) and, for the new slot, dF_slot . dF_j (n values), then
  // one reduction for all of them.
  std::vector<double> loc(2 * n, 0.0), glob(2 * n, 0.0);
  for (size_t b = 0; b < nb_; ++b) {
    PetscInt len;
    GF_PETSC(VecGetLocalSize(f_cur_[b], &len));
    const PetscScalar* f;
    GF_PETSC(VecGetArrayRead(f_cur_[b], &f));
    const PetscScalar* fs = nullptr;
    if (slot >= 0) GF_PETSC(VecGetArrayRead(dF_[b][slot], &fs));
    for (int j = 0; j < n; ++j) {
      const PetscScalar* dj;
      GF_PETSC(VecGetArrayRead(dF_[b][j], &dj));
      double sf = 0, ss = 0;
      for (PetscInt q = 0; q < len; ++q) sf += dj[q] * f[q];
      if (fs)
        for (PetscInt q = 0; q < len; ++q) ss += dj[q] * fs[q];
      loc[j] += sf;
      loc[n + j] += ss;
      GF_PETSC(VecRestoreArrayRead(dF_[b][j], &dj));
    }
    if (fs) GF_PETSC(VecRestoreArrayRead(dF_[b][slot], &fs));
    GF_PETSC(VecRestoreArrayRead(f_cur_[b], &f));
  }
  MPI_Allreduce(loc.data(), glob.data(), 2 * n, MPI_DOUBLE, MPI_SUM, comm_);
  std::vector<double> rhs(glob.begin(), glob.begin() + n);
  if (slot >= 0)
    for (int j = 0; j < n; ++j) gram_[slot * m_ + j] = gram_[j * m_ + slot] = glob[n + j];
  std::vector<double> A(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A[i * n + j] = gram_[i * m_ + j];
  double trace = 0;
  for (int i = 0; i < n; ++i) trace += A[i * n + i];
  if (!(trace > 0)) return;
  for (int i = 0; i < n; ++i) A[i * n + i] += 1e-12 * trace / n;
  // Cholesky-free Gaussian elimination with partial pivoting on the small SPD system.
  std::vector<double> gam(rhs);
  std::vector<int> piv(n);
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(A[r * n + c]) > std::abs(A[p * n + c])) p = r;
    if (A[p * n + c] == 0.0) return;  // singular: fall back to the plain step
    if (p != c) {
      for (int k = 0; k < n; ++k) std::swap(A[c * n + k], A[p * n + k]);
      std::swap(gam[c], gam[p]);
    }
    for (int r = c + 1; r < n; ++r) {
      const double f = A[r * n + c] / A[c * n + c];
      for (int k = c; k < n; ++k) A[r * n + k] -= f * A[c * n + k];
      gam[r] -= f * gam[c];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    for (int k = c + 1; k < n; ++k) gam[c] -= A[c * n + k] * gam[k];
    gam[c] /= A[c * n + c];
  }
  std::vector<PetscScalar> neg(n);
  for (int i = 0; i < n; ++i) neg[i] = -gam[i];
  for (size_t b = 0; b < nb_; ++b) GF_PETSC(VecMAXPY(x[b], n, neg.data(), dG_[b]));
}

}  // namespace gf
