// BlockedDowndate.h — the downdate L L^H − N N^H of a supernode's columns by blocked hyperbolic
// Householder reflections, so that most of its work runs in matrix products (the negative half
// of the folds of insertDofs/mergeDofs, LowRankTopUpdate.h; paper §4.2 with Davis & Hager's
// downdates, DESIGN §3).
//
// Column j of the supernode and the r columns of N form the rows [L(i,j), N(i,:)]. A hyperbolic
// reflection Θ (Θ J Θ^H = J with J = diag(1, −I_r), so L L^H − N N^H is kept) maps row j to
// [β, 0] with β² = L(j,j)² − |N(j,:)|²; the rows below it are multiplied by Θ too. Θ is
// I − τ J u u^H with u^H = [L(j,j) − β, N(j,:)], τ = 1 / (β (β − L(j,j))), and β is taken
// negative so that L(j,j) − β does not cancel (the column's sign is flipped back afterwards).
// Each reflection touches only column j of L and N, so a panel of b columns is reduced with the
// panel's own rows first, one reflection at a time, and its b reflections are then applied to
// all the rows below the panel at once in compact form, Θ_1 ⋯ Θ_b = I − J U T U^H (T upper
// triangular, as LAPACK's ?larft): two matrix products of rows × r × b and one of rows × b × b,
// instead of b · r rotations that each pass over the rows (rotationSweep()).
//
// A pivot that is lost (β² ≤ 0, or not finite) is reported: the new matrix is then not
// positive definite in floating point, and the caller refactors instead.

#ifndef EIGEN_UPDATABLE_CHOLESKY_BLOCKED_DOWNDATE_H
#define EIGEN_UPDATABLE_CHOLESKY_BLOCKED_DOWNDATE_H

#include <algorithm>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Columns of L per panel of downdateByBlockedReflections(). */
enum { DowndatePanelColumns = 32 };

/** \internal Downdates the supernode's columns from \a start on by the W columns [first,
  * first+count) (zero above row \a start and on the rows of removed columns), by blocked
  * hyperbolic Householder reflections: on return L L^H − W W^H is unchanged on every row pair,
  * with W zero on the supernode's own rows (what is left lives on the rows below). Removed
  * columns (unit columns, \a removed by permuted row, may be null) are skipped. \returns false
  * on a lost pivot (the block is then partly changed); \a flops gets the work. */
template <typename Scalar, typename StorageIndex, typename Dense>
bool downdateByBlockedReflections(Supernode<Scalar, StorageIndex>& node, Dense& W, Index first, Index count,
                                  Index start, const char* removed, double& flops) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  typedef Matrix<Scalar, Dynamic, Dynamic> Block;
  typedef Map<Block, 0, OuterStride<> > BlockMap;
  const Index nr = node.nrows(), nc = node.ncols;
  if (count == 0 || start >= nc) return true;
  Scalar* L = node.values.data();
  Scalar* N = W.data() + first * nr;
  const Index b = Index(DowndatePanelColumns);
  Block V(count, b), Vh(b, count), T(b, b), M(nr, b), MT(nr, b);
  // the panel's rows of W, one column per row (rank × panel), so that the reductions and updates
  // of step 1 run along the rank in contiguous memory rather than with stride nr
  Block P(count, b);
  std::vector<RealScalar> d(b), tau(b);
  std::vector<char> active(b);
  for (Index j0 = start; j0 < nc; j0 += b) {
    const Index j1 = (std::min)(nc, j0 + b), pb = j1 - j0;
    T.topLeftCorner(pb, pb).setZero();
    for (Index t = 0; t < count; ++t)
      for (Index ii = 0; ii < pb; ++ii) P(t, ii) = N[j0 + ii + t * nr];
    // 1. the panel's reflections, each applied to the panel's rows below its own
    for (Index kk = 0; kk < pb; ++kk) {
      const Index k = j0 + kk;
      Scalar* lk = L + k * nr;
      const RealScalar xx = P.col(kk).squaredNorm();
      active[kk] = xx > RealScalar(0) && !(removed && removed[node.rows[k]]);
      if (!active[kk]) {
        d[kk] = tau[kk] = RealScalar(0);
        V.col(kk).setZero();
        continue;
      }
      const RealScalar alpha = numext::real(lk[k]), x = numext::sqrt(xx);
      const RealScalar beta2 = (alpha - x) * (alpha + x);
      if (!(beta2 > RealScalar(0)) || !(beta2 < NumTraits<RealScalar>::highest())) return false;
      const RealScalar beta = numext::sqrt(beta2);  // (|β|; β itself is −|β|)
      d[kk] = alpha + beta;
      tau[kk] = RealScalar(1) / (beta * (beta + alpha));
      V.col(kk) = P.col(kk).conjugate();
      for (Index i = k + 1; i < j1; ++i) {  // y := y − τ (y J u) u^H on the panel's rows
        auto row = P.col(i - j0);
        Scalar s = lk[i] * d[kk] - row.cwiseProduct(V.col(kk)).sum();
        s *= tau[kk];
        lk[i] -= s * d[kk];
        row -= s * V.col(kk).conjugate();
      }
      lk[k] = Scalar(-beta);
      P.col(kk).setZero();
      // T(0:kk, kk) = τ T(0:kk, 0:kk) V(:, 0:kk)^H V(:, kk), T(kk, kk) = τ
      if (kk > 0) {
        const Matrix<Scalar, Dynamic, 1> g = V.leftCols(kk).adjoint() * V.col(kk);
        T.col(kk).head(kk).noalias() = T.topLeftCorner(kk, kk).template triangularView<Upper>() * g;
        T.col(kk).head(kk) *= tau[kk];
      }
      T(kk, kk) = Scalar(tau[kk]);
      flops += 4.0 * double(count + 1) * double(j1 - k) + 2.0 * double(count) * double(kk);
    }
    for (Index t = 0; t < count; ++t)
      for (Index ii = 0; ii < pb; ++ii) N[j0 + ii + t * nr] = P(t, ii);
    // 2. ... applied to the rows below the panel at once: Y := Y − (Y J U) T U^H for
    //    Y = [L(rows, panel) N(rows, :)], U = [diag(d); V] (nothing to do when W was zero on
    //    the panel's rows)
    const Index rows = nr - j1;
    if (rows > 0 && std::find(active.begin(), active.begin() + pb, char(1)) != active.begin() + pb) {
      BlockMap Lp(L + j0 * nr + j1, rows, pb, OuterStride<>(nr));
      BlockMap Nb(N + j1, rows, count, OuterStride<>(nr));
      auto YJU = M.topRows(rows).leftCols(pb);
      gemmProduct(false, false, rows, pb, count, N + j1, nr, V.data(), V.rows(), YJU.data(), M.rows());  // N V
      for (Index kk = 0; kk < pb; ++kk) YJU.col(kk) = Lp.col(kk) * d[kk] - YJU.col(kk);
      auto Mt = MT.topRows(rows).leftCols(pb);
      // (T's lower triangle is zero: a plain product, which BLAS runs faster than a triangular one)
      gemmProduct(false, false, rows, pb, pb, YJU.data(), M.rows(), T.data(), T.rows(), Mt.data(), MT.rows());
      for (Index kk = 0; kk < pb; ++kk) Lp.col(kk) -= Mt.col(kk) * d[kk];
      Vh.topLeftCorner(pb, count) = V.leftCols(pb).adjoint();
      gemmProduct(false, true, rows, count, pb, Mt.data(), MT.rows(), Vh.data(), Vh.rows(), N + j1, nr);
      flops += 4.0 * double(rows) * double(pb) * double(count) + double(rows) * double(pb) * double(pb);
    }
    // 3. β was taken negative: flip the columns of the panel's reflections
    for (Index kk = 0; kk < pb; ++kk)
      if (active[kk]) {
        Scalar* lk = L + (j0 + kk) * nr;
        for (Index i = j0 + kk; i < nr; ++i) lk[i] = -lk[i];
      }
  }
  return true;
}

/** \internal Downdates the supernode's kept columns by the W columns of \a sources (in W in the
  * order of the list, sorted by start), by groups (forEachSourceGroup()): blocked reflections
  * (downdateByBlockedReflections()) when a group has at least BlockedFoldMinRank columns and
  * spans as many of the supernode's columns, else hyperbolic rotations (rotationSweep()).
  * \returns false on a lost pivot (the block is then partly changed); \a flops gets the work. */
template <typename Scalar, typename StorageIndex, typename Dense>
bool downdateSources(Supernode<Scalar, StorageIndex>& node, Dense& W, const std::vector<FoldSource>& sources,
                     const char* removed, double& flops) {
  return forEachSourceGroup(sources, node.ncols, [&](Index first, Index count, Index start) {
    if (count >= Index(BlockedFoldMinRank) && node.ncols - start >= Index(BlockedFoldMinRank))
      return downdateByBlockedReflections(node, W, first, count, start, removed, flops);
    return rotationSweep</*Hyperbolic=*/true>(node, W, first, count, start, removed, flops);
  });
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_BLOCKED_DOWNDATE_H
