// LowRankRemoval.h — removing dofs by a low-rank update of the supernodal factor (the
// "low-rank route" for small changes; Davis & Hager's row deletion done for many dofs in one
// pass, on the supernodal LL^H factor, paper §2 and DESIGN §3).
//
// Split the dofs into kept I and removed B in the current elimination order. Since A = L L^H,
// A_II = L(I,I) L(I,I)^H + W W^H with W = L(I,B): the factor of A^B restricted to I (paper
// Appendix A) is L(I,I) updated by the rank-|B| matrix W, and L^B is the identity on B. Column b
// of W is non-zero only on the supernodal path of b, so the update walks the supernodes of the
// union of those paths in postorder; at supernode S it gathers the W columns of its children and
// of its own removed columns, applies Givens rotations that fold them into S's kept columns
// (cost ~ 4 · rank · rows · columns), and passes the rest of W (compressed to at most as many
// columns as S has rows below) to the parent. The cached update matrix of S changes by exactly
// U_S += W_out W_out^H, so the cache stays usable by later partial refactorizations. Rows of the
// removed dofs are zeroed wherever they appear (the row subtrees of B).
//
// The result solves to the accuracy of a fresh factorization, but is not bitwise equal to it.
// Removal keeps the matrix positive definite, so this route cannot fail.

#ifndef EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_REMOVAL_H
#define EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_REMOVAL_H

#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Flop estimate of the low-rank removal of the permuted columns \a removedNow over the
  * dirty supernodes \a dirty (increasing), from the symbolic structure only. */
template <typename Scalar, typename StorageIndex>
double lowRankRemovalFlops(const SupernodalFactor<Scalar, StorageIndex>& f, const std::vector<Index>& dirty,
                           const std::vector<StorageIndex>& removedNow, UpdateWorkspace<Scalar>& ws) {
  std::vector<Index>& rankOut = ws.rank;
  std::vector<Index>& local = ws.local;
  for (StorageIndex b : removedNow) ++local[f.colToSuper[b]];
  double flops = 0;
  for (Index s : dirty) {
    const auto& node = f.nodes[s];
    Index rank = local[s];
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) rank += rankOut[c];
    const double nr = double(node.nrows()), nc = double(node.ncols), m = double(node.below());
    flops += 4.0 * double(rank) * (nr * nc - nc * nc / 2);
    if (double(rank) > m) flops += double(rank) * m * m;  // compression
    rankOut[s] = (std::min)(rank, node.below());
    flops += m * m * double(rankOut[s]);  // update-matrix correction
  }
  for (Index s : dirty) rankOut[s] = local[s] = 0;
  return flops;
}

/** \internal l := (l + conj(s) w) / c and w := c w - s l (new l), elementwise: one Givens
  * rotation of a column pair. Separate pointers so that the compiler vectorizes it. */
template <typename Scalar, typename RealScalar>
EIGEN_DONT_INLINE void rotateColumns(Index n, Scalar* EIGEN_RESTRICT l, Scalar* EIGEN_RESTRICT w, RealScalar cosine,
                                     RealScalar invCos, Scalar sine, Scalar conjSine) {
  for (Index i = 0; i < n; ++i) {
    const Scalar li = (l[i] + conjSine * w[i]) * invCos;
    l[i] = li;
    w[i] = cosine * w[i] - sine * li;
  }
}

/** \internal Rank-r fold by Givens rotations, column by column: [L(:,j) W(:,t)] G(j,t). */
template <typename Scalar, typename StorageIndex, typename Dense>
double foldByRotations(Supernode<Scalar, StorageIndex>& node, Dense& W, const char* removed) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  const Index nr = node.nrows(), nc = node.ncols, rank = W.cols();
  Scalar* L = node.values.data();
  double flops = 0;
  for (Index j = 0; j < nc; ++j) {
    if (removed[node.rows[j]]) continue;
    Scalar* lj = L + j * nr;
    for (Index t = 0; t < rank; ++t) {
      Scalar* w = W.data() + t * nr;
      const Scalar wj = w[j];
      if (wj == Scalar(0)) continue;
      const RealScalar ljj = numext::real(lj[j]);
      const RealScalar r = numext::hypot(ljj, numext::abs(wj));
      const RealScalar cosine = r / ljj, invCos = ljj / r;
      const Scalar sine = wj / ljj, conjSine = numext::conj(sine);
      lj[j] = Scalar(r);
      w[j] = Scalar(0);
      rotateColumns(nr - j - 1, lj + j + 1, w + j + 1, cosine, invCos, sine, conjSine);
      flops += 4.0 * double(nr - j);
    }
  }
  return flops;
}

/** \internal Below this rank the fold uses rotations; above it LAPACK's blocked
  * triangular-pentagonal LQ (?tplqt/?tpmlqt), where the per-call cost pays off. */
enum { BlockedFoldMinRank = 8 };

/** \internal Folds the columns of W (rows = the supernode's rows; zero on removed rows) into the
  * supernode's kept columns, leaving in W's rows below the part to pass on. Unit columns of
  * removed dofs stay unit columns (their rows are zero in W). \returns the flops spent. */
template <typename Scalar, typename StorageIndex, typename Dense>
double foldIntoColumns(Supernode<Scalar, StorageIndex>& node, Dense& W, const char* removed) {
  const Index nr = node.nrows(), nc = node.ncols, m = nr - nc, rank = W.cols();
  if (rank == 0) return 0;
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    if (rank >= BlockedFoldMinRank && nc >= BlockedFoldMinRank) {
      typedef typename NumTraits<Scalar>::Real RealScalar;
      Scalar* L = node.values.data();
      const int mb = int((std::min<Index>)(32, nc));
      std::vector<Scalar> t(Index(mb) * nc), work(Index(mb) * (std::max)(nc, m));
      // LQ of [L11 W_top] = [L11' 0] Q, then [L21 W_below] Q^H = [L21' W_out]
      int info = blasTplqt(int(nc), int(rank), mb, L, int(nr), W.data(), int(nr), t.data(), mb, work.data());
      if (info == 0 && m > 0)
        info = blasTpmlqtRightAdjoint(int(m), int(rank), int(nc), mb, W.data(), int(nr), t.data(), mb, L + nc,
                                      int(nr), W.data() + nc, int(nr), work.data());
      eigen_assert(info == 0 && "LAPACK tplqt/tpmlqt failed");
      W.topRows(nc).setZero();
      for (Index j = 0; j < nc; ++j)  // Householder LQ may leave negative pivots: flip the column
        if (numext::real(L[j + j * nr]) < RealScalar(0))
          for (Index i = j; i < nr; ++i) L[i + j * nr] = -L[i + j * nr];
      return 2.0 * double(nc) * double(nc) * double(rank) + 4.0 * double(m) * double(nc) * double(rank);
    }
  }
#endif
  return foldByRotations(node, W, removed);
}

/** \internal Removes the permuted columns \a removedNow (whose flags are already set in
  * \a removed, with those of earlier removals) from the factor by a low-rank update of the dirty
  * supernodes \a dirty (increasing, as from dirtySupernodes()), keeping the cached update
  * matrices \a cache consistent. \returns the flops spent. */
template <typename Scalar, typename StorageIndex>
double lowRankRemoval(SupernodalFactor<Scalar, StorageIndex>& f, std::vector<std::vector<Scalar> >& cache,
                      const std::vector<Index>& dirty, const char* removed, UpdateWorkspace<Scalar>& ws) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  std::vector<Dense>& carried = ws.carried;  // W passed from a supernode to its parent
  double flops = 0;
  std::vector<Index> removedPositions, removedColumns;
  for (Index s : dirty) {
    auto& node = f.nodes[s];
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    Scalar* L = node.values.data();
    Scalar* U = m > 0 ? cache[s].data() : nullptr;
    removedPositions.clear();
    removedColumns.clear();
    for (Index p = 0; p < nr; ++p)
      if (removed[node.rows[p]]) removedPositions.push_back(p);
    // 1. W at this supernode: the children's carried columns, then the removed columns that
    //    are still columns of L (not unit yet).
    Index rank = 0;
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) rank += carried[c].cols();
    for (Index p : removedPositions) {
      if (p >= nc) break;
      bool unit = true;
      for (Index i = p + 1; i < nr && unit; ++i) unit = L[i + p * nr] == Scalar(0);
      if (!unit || L[p + p * nr] != Scalar(1)) removedColumns.push_back(p);
    }
    rank += Index(removedColumns.size());
    Dense W = Dense::Zero(nr, rank);
    Index q = 0;
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) {
      const Dense& wc = carried[c];
      const auto& pos = f.nodes[c].parentPosition;
      for (Index j = 0; j < wc.cols(); ++j, ++q)
        for (Index k = 0; k < wc.rows(); ++k) W(pos[k], q) = wc(k, j);
      carried[c] = Dense();
    }
    for (Index p : removedColumns) {
      for (Index i = p + 1; i < nr; ++i) W(i, q) = L[i + p * nr];
      ++q;
    }
    // 2. the removed dofs' rows and columns become those of the identity, in L, U and W
    for (Index p : removedPositions) {
      W.row(p).setZero();
      if (p < nc) {
        for (Index i = 0; i < nr; ++i) L[i + p * nr] = Scalar(0);
        L[p + p * nr] = Scalar(1);
      }
      for (Index j = 0; j < (std::min)(p, nc); ++j) L[p + j * nr] = Scalar(0);
      if (p >= nc) {
        const Index u = p - nc;
        for (Index i = 0; i < m; ++i) {
          U[u + i * m] = Scalar(0);
          U[i + u * m] = Scalar(0);
        }
      }
    }
    if (rank == 0) continue;
    // 3. fold W into the kept columns: [L(:,J) W] G = [L'(:,J) W'] with G unitary and W' zero
    //    on the supernode's own rows
    flops += foldIntoColumns(node, W, removed);
    if (m == 0) continue;
    // 4. what is left of W lives on the rows below: compress, correct U, carry to the parent
    Dense out = W.bottomRows(m);
    if (out.cols() > m) {
      HouseholderQR<Dense> qr(out.adjoint());
      out = qr.matrixQR().topRows(m).template triangularView<Upper>().adjoint();
      flops += double(rank) * double(m) * double(m);
    }
    herkLower(m, out.cols(), RealScalar(1), out.data(), m, U, m);
    flops += double(m) * double(m) * double(out.cols());
    if (f.parent[s] != -1) carried[s].swap(out);
  }
  return flops;
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_REMOVAL_H
