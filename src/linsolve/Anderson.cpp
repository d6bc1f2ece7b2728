#include "linsolve/Anderson.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/Error.hpp"

namespace gf::linsolve {

Anderson::Anderson(int m, MPI_Comm comm) : m_(m), comm_(comm) {
  if (m_ > 0) gram_.assign(static_cast<size_t>(m_) * m_, 0.0);
}

void Anderson::set_active(std::vector<std::vector<PetscInt>> idx) {
  idx_ = std::move(idx);
  n_ = 0;
  for (const auto& v : idx_) n_ += v.size();
  if (m_ > 0) {
    for (auto* v : {&f_cur_, &f_prev_, &g_prev_, &g_cur_}) v->resize(n_);
    dF_.resize(n_ * m_);
    dG_.resize(n_ * m_);
  }
  reset();
}

void Anderson::update(const std::vector<Vec>& x, const std::vector<Vec>& g) {
  if (x.size() != idx_.size() || g.size() != idx_.size())
    throw std::logic_error("Anderson::update: the blocks differ from those of set_active");
  if (m_ <= 0) {
    for (size_t b = 0; b < x.size(); ++b) GF_PETSC(VecCopy(g[b], x[b]));
    return;
  }
  // G(x_k) and f_k = G(x_k) - x_k on the active entries.
  size_t o = 0;
  for (size_t b = 0; b < x.size(); ++b) {
    const PetscScalar *xa, *ga;
    GF_PETSC(VecGetArrayRead(x[b], &xa));
    GF_PETSC(VecGetArrayRead(g[b], &ga));
    for (const PetscInt q : idx_[b]) {
      g_cur_[o] = ga[q];
      f_cur_[o] = ga[q] - xa[q];
      ++o;
    }
    GF_PETSC(VecRestoreArrayRead(g[b], &ga));
    GF_PETSC(VecRestoreArrayRead(x[b], &xa));
  }
  int slot = -1;     // the ring-buffer slot written by this update (-1: none)
  if (have_prev_) {  // push dF = f_k - f_{k-1}, dG = g_k - g_{k-1}
    slot = head_;
    double* dFs = dF_.data() + slot * n_;
    double* dGs = dG_.data() + slot * n_;
    for (size_t q = 0; q < n_; ++q) {
      dFs[q] = f_cur_[q] - f_prev_[q];
      dGs[q] = g_cur_[q] - g_prev_[q];
    }
    head_ = (head_ + 1) % m_;
    if (count_ < m_) ++count_;
  }
  std::copy(f_cur_.begin(), f_cur_.end(), f_prev_.begin());
  std::copy(g_cur_.begin(), g_cur_.end(), g_prev_.begin());
  have_prev_ = true;
  // x_{k+1} = g - dG gamma, gamma from the normal equations (dF^T dF + eps I) gamma = dF^T f:
  // m is small (<= 10); the regularisation guards against nearly dependent differences.
  for (size_t b = 0; b < x.size(); ++b) GF_PETSC(VecCopy(g[b], x[b]));
  const int n = count_;  // the stored slots are 0 .. n-1
  if (n == 0) return;
  // Local parts of dF_j . f (n values) and, for the new slot, dF_slot . dF_j (n values), then
  // one reduction for all of them.
  std::vector<double> loc(2 * n, 0.0), glob(2 * n, 0.0);
  const double* fs = slot >= 0 ? dF_.data() + slot * n_ : nullptr;
  for (int j = 0; j < n; ++j) {
    const double* dj = dF_.data() + j * n_;
    double sf = 0, ss = 0;
    for (size_t q = 0; q < n_; ++q) sf += dj[q] * f_cur_[q];
    if (fs)
      for (size_t q = 0; q < n_; ++q) ss += dj[q] * fs[q];
    loc[j] = sf;
    loc[n + j] = ss;
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
  // dG gamma on the active entries (f_cur_ is free now and holds it), subtracted from x.
  std::fill(f_cur_.begin(), f_cur_.end(), 0.0);
  for (int i = 0; i < n; ++i) {
    const double* di = dG_.data() + i * n_;
    for (size_t q = 0; q < n_; ++q) f_cur_[q] += gam[i] * di[q];
  }
  o = 0;
  for (size_t b = 0; b < x.size(); ++b) {
    PetscScalar* xa;
    GF_PETSC(VecGetArray(x[b], &xa));
    for (const PetscInt q : idx_[b]) xa[q] -= f_cur_[o++];
    GF_PETSC(VecRestoreArray(x[b], &xa));
  }
}

}  // namespace gf::linsolve
