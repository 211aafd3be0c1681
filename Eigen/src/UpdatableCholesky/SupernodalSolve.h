// SupernodalSolve.h — supernodal forward and backward substitution with a block of right-hand
// sides (paper §3.1: the solve that follows every factorization or update). Forward: for each
// supernode in postorder, X_S := L11^{-1} X_S, then the rows below receive -L21 X_S (gathered
// product, scattered subtraction). Backward: in reverse order, X_S -= L21^H X_below, then
// X_S := L11^{-H} X_S. X is in the permuted numbering, column-major with leading dimension ldx.

#ifndef EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H
#define EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H

#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Supernodes up to this many columns are solved with inline column loops. */
enum { SmallSolveColumns = 24 };

/** \internal x := L^{-1} x for one right-hand side (matrix-vector kernels). */
template <typename Scalar, typename StorageIndex>
void forwardSolveVector(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* x, Scalar* work) {
  for (const auto& node : f.nodes) {
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    const Scalar* L = node.values.data();
    Scalar* xs = x + node.firstCol;
    if (nc <= SmallSolveColumns) {  // one pass down each column: x_S and the product below
      std::fill(work, work + m, Scalar(0));
      for (Index j = 0; j < nc; ++j) {
        const Scalar* lj = L + j * nr;
        const Scalar xj = (xs[j] /= lj[j]);
        for (Index i = j + 1; i < nc; ++i) xs[i] -= lj[i] * xj;
        const Scalar* lb = lj + nc;
        for (Index i = 0; i < m; ++i) work[i] += lb[i] * xj;
      }
    } else {
      trsvLower(false, nc, L, nr, xs);
      if (m == 0) continue;
      gemvProduct(false, m, nc, L + nc, nr, xs, work);
    }
    const StorageIndex* rows = node.rows.data() + nc;
    for (Index i = 0; i < m; ++i) x[rows[i]] -= work[i];
  }
}

/** \internal x := L^{-H} x for one right-hand side (matrix-vector kernels). */
template <typename Scalar, typename StorageIndex>
void backwardSolveVector(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* x, Scalar* work) {
  for (Index s = f.count() - 1; s >= 0; --s) {
    const auto& node = f.nodes[s];
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    const Scalar* L = node.values.data();
    Scalar* xs = x + node.firstCol;
    const StorageIndex* rows = node.rows.data() + nc;
    for (Index i = 0; i < m; ++i) work[i] = x[rows[i]];
    if (nc <= SmallSolveColumns) {  // one pass up each column: dot products with x
      for (Index j = nc - 1; j >= 0; --j) {
        const Scalar* lj = L + j * nr;
        Scalar sum = xs[j];
        for (Index i = j + 1; i < nc; ++i) sum -= numext::conj(lj[i]) * xs[i];
        const Scalar* lb = lj + nc;
        Scalar below(0);
        for (Index i = 0; i < m; ++i) below += numext::conj(lb[i]) * work[i];
        xs[j] = (sum - below) / numext::conj(lj[j]);
      }
      continue;
    }
    if (m > 0) gemvProduct(true, m, nc, L + nc, nr, work, xs);
    trsvLower(true, nc, L, nr, xs);
  }
}

/** \internal X := L^{-1} X for the k columns of X. \a work must hold maxBelow()*k scalars. */
template <typename Scalar, typename StorageIndex>
void forwardSolve(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Index k, Scalar* work) {
  if (k == 1) return forwardSolveVector(f, X, work);
  for (const auto& node : f.nodes) {
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    const Scalar* L = node.values.data();
    Scalar* xs = X + node.firstCol;
    trsmLeftLower(false, nc, k, L, nr, xs, ldx);
    if (m == 0) continue;
    gemmProduct(false, false, m, k, nc, L + nc, nr, xs, ldx, work, m);
    const StorageIndex* rows = node.rows.data() + nc;
    for (Index c = 0; c < k; ++c) {
      Scalar* xc = X + c * ldx;
      const Scalar* wc = work + c * m;
      for (Index i = 0; i < m; ++i) xc[rows[i]] -= wc[i];
    }
  }
}

/** \internal X := L^{-H} X for the k columns of X. \a work must hold maxBelow()*k scalars. */
template <typename Scalar, typename StorageIndex>
void backwardSolve(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Index k, Scalar* work) {
  if (k == 1) return backwardSolveVector(f, X, work);
  for (Index s = f.count() - 1; s >= 0; --s) {
    const auto& node = f.nodes[s];
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    const Scalar* L = node.values.data();
    Scalar* xs = X + node.firstCol;
    if (m > 0) {
      const StorageIndex* rows = node.rows.data() + nc;
      for (Index c = 0; c < k; ++c) {
        const Scalar* xc = X + c * ldx;
        Scalar* wc = work + c * m;
        for (Index i = 0; i < m; ++i) wc[i] = xc[rows[i]];
      }
      gemmProduct(true, true, nc, k, m, L + nc, nr, work, m, xs, ldx);
    }
    trsmLeftLower(true, nc, k, L, nr, xs, ldx);
  }
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H
