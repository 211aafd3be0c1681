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
                           const std::vector<StorageIndex>& removedNow) {
  std::vector<Index> rankOut(f.count(), 0), local(f.count(), 0);
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
  return flops;
}

/** \internal Removes the permuted columns \a removedNow (whose flags are already set in
  * \a removed, with those of earlier removals) from the factor by a low-rank update of the dirty
  * supernodes \a dirty (increasing, as from dirtySupernodes()), keeping the cached update
  * matrices \a cache consistent. \returns the flops spent. */
template <typename Scalar, typename StorageIndex>
double lowRankRemoval(SupernodalFactor<Scalar, StorageIndex>& f, std::vector<std::vector<Scalar> >& cache,
                      const std::vector<Index>& dirty, const char* removed) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  std::vector<Dense> carried(f.count());  // W passed from a supernode to its parent
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
    // 3. fold W into the kept columns with Givens rotations: [L(:,j) W(:,q)] G, G unitary
    for (Index j = 0; j < nc; ++j) {
      if (removed[node.rows[j]]) continue;
      Scalar* lj = L + j * nr;
      for (Index t = 0; t < rank; ++t) {
        Scalar* w = W.data() + t * nr;
        const Scalar wj = w[j];
        if (wj == Scalar(0)) continue;
        const RealScalar ljj = numext::real(lj[j]);
        const RealScalar r = numext::hypot(ljj, numext::abs(wj));
        const RealScalar cosine = r / ljj;
        const Scalar sine = wj / ljj;
        const Scalar conjSine = numext::conj(sine);
        lj[j] = Scalar(r);
        w[j] = Scalar(0);
        const RealScalar invCos = RealScalar(1) / cosine;
        for (Index i = j + 1; i < nr; ++i) {
          const Scalar l = (lj[i] + conjSine * w[i]) * invCos;
          lj[i] = l;
          w[i] = cosine * w[i] - sine * l;
        }
        flops += 4.0 * double(nr - j);
      }
    }
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
