// SupernodalSolve.h — supernodal forward and backward substitution with a block of right-hand
// sides (paper §3.1: the solve that follows every factorization or update). Forward: for each
// supernode in postorder, X_S := L11^{-1} X_S, then the rows below receive -L21 X_S (gathered
// product, scattered subtraction). Backward: in reverse order, X_S -= L21^H X_below, then
// X_S := L11^{-H} X_S. X is in the permuted numbering, column-major with leading dimension ldx.
//
// The solve reads the whole factor twice and does two flops per entry read, so it is bound by
// memory traffic and by the fixed cost of each supernode. Small supernodes (the vast majority on
// meshes) and up to four right-hand sides therefore go through inline kernels that read every
// entry of L once per pass for all right-hand sides together, four columns at a time, with no
// library call, while the next supernode's block is prefetched. Large supernodes and blocks of
// more right-hand sides use the BLAS-2/3 kernels of DenseKernels.h.

#ifndef EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H
#define EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H

#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Supernodes up to this many columns are solved with the inline kernels. */
enum { SmallSolveColumns = 24 };
/** \internal Up to this many right-hand sides are solved by the inline kernels in one pass. */
enum { InlineSolveRhs = 4 };
/** \internal Bytes of the next supernode's block prefetched while the current one is solved. */
enum { SolvePrefetchBytes = 4096 };

/** \internal Asks the memory system for the first bytes of a supernode's block and rows. */
template <typename Scalar, typename StorageIndex>
EIGEN_STRONG_INLINE void prefetchSupernode(const Supernode<Scalar, StorageIndex>& node) {
  const char* v = reinterpret_cast<const char*>(node.values.data());
  const Index bytes = (std::min)(Index(node.values.size() * sizeof(Scalar)), Index(SolvePrefetchBytes));
  for (Index b = 0; b < bytes; b += 64) internal::prefetch(v + b);
  const char* r = reinterpret_cast<const char*>(node.rows.data());
  const Index rowBytes = (std::min)(Index(node.rows.size() * sizeof(StorageIndex)), Index(512));
  for (Index b = 0; b < rowBytes; b += 64) internal::prefetch(r + b);
}

/** \internal W (m×K, leading dimension m) op= L(:, 0..B) X(0..B, :) for B ≤ 4 columns of L
  * (leading dimension ldl) and the K right-hand sides x (leading dimension ldx); op is = when
  * \a first, += otherwise. */
template <int B, int K, typename Scalar>
EIGEN_STRONG_INLINE void blockProduct(bool first, Index m, const Scalar* l, Index ldl, const Scalar* x, Index ldx,
                                      Scalar* w) {
  const Scalar* lc[4];
  Scalar xc[4][K];
  for (int b = 0; b < B; ++b) {
    lc[b] = l + b * ldl;
    for (int c = 0; c < K; ++c) xc[b][c] = x[b + c * ldx];
  }
  for (int c = 0; c < K; ++c) {
    Scalar* wc = w + c * m;
    if (first)
      for (Index i = 0; i < m; ++i) {
        Scalar s = lc[0][i] * xc[0][c];
        for (int b = 1; b < B; ++b) s += lc[b][i] * xc[b][c];
        wc[i] = s;
      }
    else
      for (Index i = 0; i < m; ++i) {
        Scalar s = wc[i];
        for (int b = 0; b < B; ++b) s += lc[b][i] * xc[b][c];
        wc[i] = s;
      }
  }
}

/** \internal X(0..B, :) -= L(:, 0..B)^H W for B ≤ 4 columns of L and K right-hand sides
  * (W is m×K with leading dimension m; X has leading dimension ldx). */
template <int B, int K, typename Scalar>
EIGEN_STRONG_INLINE void blockAdjointProduct(Index m, const Scalar* l, Index ldl, const Scalar* w, Scalar* x,
                                             Index ldx) {
  const Scalar* lc[4];
  for (int b = 0; b < B; ++b) lc[b] = l + b * ldl;
  for (int c = 0; c < K; ++c) {
    const Scalar* wc = w + c * m;
    Scalar s[4] = {Scalar(0), Scalar(0), Scalar(0), Scalar(0)};
    Scalar t[4] = {Scalar(0), Scalar(0), Scalar(0), Scalar(0)};
    Index i = 0;
    for (; i + 1 < m; i += 2) {  // two chains per column: a shorter dependency on the adds
      const Scalar w0 = wc[i], w1 = wc[i + 1];
      for (int b = 0; b < B; ++b) {
        s[b] += numext::conj(lc[b][i]) * w0;
        t[b] += numext::conj(lc[b][i + 1]) * w1;
      }
    }
    if (i < m)
      for (int b = 0; b < B; ++b) s[b] += numext::conj(lc[b][i]) * wc[i];
    for (int b = 0; b < B; ++b) x[b + c * ldx] -= s[b] + t[b];
  }
}

/** \internal W (m×K) := L21 X_S for a small supernode, four columns of L at a time. */
template <int K, typename Scalar>
void smallBelowProduct(Index m, Index nc, const Scalar* l21, Index ldl, const Scalar* xs, Index ldx, Scalar* w) {
  Index j = 0;
  for (; j + 4 <= nc; j += 4) blockProduct<4, K>(j == 0, m, l21 + j * ldl, ldl, xs + j, ldx, w);
  switch (nc - j) {
    case 3: blockProduct<3, K>(j == 0, m, l21 + j * ldl, ldl, xs + j, ldx, w); break;
    case 2: blockProduct<2, K>(j == 0, m, l21 + j * ldl, ldl, xs + j, ldx, w); break;
    case 1: blockProduct<1, K>(j == 0, m, l21 + j * ldl, ldl, xs + j, ldx, w); break;
    default: break;
  }
}

/** \internal X_S -= L21^H W for a small supernode, four columns of L at a time. */
template <int K, typename Scalar>
void smallBelowAdjointProduct(Index m, Index nc, const Scalar* l21, Index ldl, const Scalar* w, Scalar* xs,
                              Index ldx) {
  Index j = 0;
  for (; j + 4 <= nc; j += 4) blockAdjointProduct<4, K>(m, l21 + j * ldl, ldl, w, xs + j, ldx);
  switch (nc - j) {
    case 3: blockAdjointProduct<3, K>(m, l21 + j * ldl, ldl, w, xs + j, ldx); break;
    case 2: blockAdjointProduct<2, K>(m, l21 + j * ldl, ldl, w, xs + j, ldx); break;
    case 1: blockAdjointProduct<1, K>(m, l21 + j * ldl, ldl, w, xs + j, ldx); break;
    default: break;
  }
}

/** \internal X_S := L11^{-1} X_S for a small diagonal block and K right-hand sides. */
template <int K, typename Scalar>
EIGEN_STRONG_INLINE void smallForwardTriangle(Index nc, const Scalar* l, Index ldl, Scalar* xs, Index ldx) {
  for (Index j = 0; j < nc; ++j) {
    const Scalar* lj = l + j * ldl;
    for (int c = 0; c < K; ++c) {
      Scalar* xc = xs + c * ldx;
      const Scalar xj = (xc[j] /= lj[j]);
      for (Index i = j + 1; i < nc; ++i) xc[i] -= lj[i] * xj;
    }
  }
}

/** \internal X_S := L11^{-H} X_S for a small diagonal block and K right-hand sides. */
template <int K, typename Scalar>
EIGEN_STRONG_INLINE void smallBackwardTriangle(Index nc, const Scalar* l, Index ldl, Scalar* xs, Index ldx) {
  for (Index j = nc - 1; j >= 0; --j) {
    const Scalar* lj = l + j * ldl;
    for (int c = 0; c < K; ++c) {
      Scalar* xc = xs + c * ldx;
      Scalar sum = xc[j];
      for (Index i = j + 1; i < nc; ++i) sum -= numext::conj(lj[i]) * xc[i];
      xc[j] = sum / numext::conj(lj[j]);
    }
  }
}

/** \internal X := L^{-1} X for K ≤ InlineSolveRhs right-hand sides, one pass over L. */
template <int K, typename Scalar, typename StorageIndex>
void forwardSolveFew(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Scalar* work) {
  const Index ns = f.count();
  for (Index s = 0; s < ns; ++s) {
    const auto& node = f.nodes[s];
    if (s + 1 < ns) prefetchSupernode(f.nodes[s + 1]);
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    const Scalar* L = node.values.data();
    Scalar* xs = X + node.firstCol;
    if (nc <= SmallSolveColumns) {
      smallForwardTriangle<K>(nc, L, nr, xs, ldx);
      if (m == 0) continue;
      smallBelowProduct<K>(m, nc, L + nc, nr, xs, ldx, work);
    } else if (K == 1) {
      trsvLower(false, nc, L, nr, xs);
      if (m == 0) continue;
      gemvProduct(false, m, nc, L + nc, nr, xs, work);
    } else {
      trsmLeftLower(false, nc, K, L, nr, xs, ldx);
      if (m == 0) continue;
      gemmProduct(false, false, m, K, nc, L + nc, nr, xs, ldx, work, m);
    }
    const StorageIndex* rows = node.rows.data() + nc;
    for (int c = 0; c < K; ++c) {
      Scalar* xc = X + c * ldx;
      const Scalar* wc = work + c * m;
      for (Index i = 0; i < m; ++i) xc[rows[i]] -= wc[i];
    }
  }
}

/** \internal X := L^{-H} X for K ≤ InlineSolveRhs right-hand sides, one pass over L. */
template <int K, typename Scalar, typename StorageIndex>
void backwardSolveFew(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Scalar* work) {
  for (Index s = f.count() - 1; s >= 0; --s) {
    const auto& node = f.nodes[s];
    if (s > 0) prefetchSupernode(f.nodes[s - 1]);
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    const Scalar* L = node.values.data();
    Scalar* xs = X + node.firstCol;
    const StorageIndex* rows = node.rows.data() + nc;
    for (int c = 0; c < K; ++c) {
      const Scalar* xc = X + c * ldx;
      Scalar* wc = work + c * m;
      for (Index i = 0; i < m; ++i) wc[i] = xc[rows[i]];
    }
    if (nc <= SmallSolveColumns) {
      if (m > 0) smallBelowAdjointProduct<K>(m, nc, L + nc, nr, work, xs, ldx);
      smallBackwardTriangle<K>(nc, L, nr, xs, ldx);
    } else if (K == 1) {
      if (m > 0) gemvProduct(true, m, nc, L + nc, nr, work, xs);
      trsvLower(true, nc, L, nr, xs);
    } else {
      if (m > 0) gemmProduct(true, true, nc, K, m, L + nc, nr, work, m, xs, ldx);
      trsmLeftLower(true, nc, K, L, nr, xs, ldx);
    }
  }
}

/** \internal X := L^{-1} X for the k columns of X. \a work must hold maxBelow()*k scalars. */
template <typename Scalar, typename StorageIndex>
void forwardSolve(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Index k, Scalar* work) {
  switch (k) {
    case 1: return forwardSolveFew<1>(f, X, ldx, work);
    case 2: return forwardSolveFew<2>(f, X, ldx, work);
    case 3: return forwardSolveFew<3>(f, X, ldx, work);
    case 4: return forwardSolveFew<4>(f, X, ldx, work);
    default: break;
  }
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
  switch (k) {
    case 1: return backwardSolveFew<1>(f, X, ldx, work);
    case 2: return backwardSolveFew<2>(f, X, ldx, work);
    case 3: return backwardSolveFew<3>(f, X, ldx, work);
    case 4: return backwardSolveFew<4>(f, X, ldx, work);
    default: break;
  }
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
