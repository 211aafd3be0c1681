// IncrementalForwardSolve.h — the forward substitution y = L^{-1} c kept from one solve to the
// next, so that a solve after an update substitutes again only what the update changed. This is
// the paper's partial refactorization (Alg. 3, §4.1) carried over to the solve: y on a supernode
// depends only on the blocks and right-hand side of its subtree, so when the blocks of some
// supernodes change (the dirty paths of an update) and the right-hand side changes on some rows
// (a Dirichlet solve's coupling term), y changes only on those supernodes and their ancestors.
//
// To recompute a supernode without its clean descendants, the forward pass is done in
// multifrontal form: supernode s assembles its right-hand side from c and the update vectors of
// its children (scattered through the parentPosition maps, as the extend-add of the numeric
// factorization), substitutes, and leaves its own update vector -L21 y_S (plus what its children
// passed through) for its parent. The cache keeps c, y and every update vector: about
// (2n + Σ rows below each supernode)·k scalars for k right-hand sides. A substituted supernode
// gives bitwise the values of a full pass over the same factor and right-hand side. The backward
// pass changes every entry of x whenever anything changed, so it is always done in full.
//
// insertDofs() and mergeDofs() keep the supernodes and renumber the columns (paper §4.2): the
// kept values follow the renumbering (relabel()); the clean supernodes keep their blocks, their
// rows below and so their update vectors, and only the dirty ones are substituted again.

#ifndef EIGEN_UPDATABLE_CHOLESKY_INCREMENTAL_FORWARD_SOLVE_H
#define EIGEN_UPDATABLE_CHOLESKY_INCREMENTAL_FORWARD_SOLVE_H

#include <cstring>
#include <limits>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Forward substitution of one supernode in multifrontal form for K ≤ 4 right-hand
  * sides (K = 0: any number k, BLAS kernels). v (nr×k, leading dimension nr) holds on entry the
  * supernode's right-hand side in its first nc rows and the update vectors of its children
  * assembled in all rows; on return y_S in the first nc rows and its own update vector below. */
template <int K, typename Scalar, typename StorageIndex>
void forwardFront(const Supernode<Scalar, StorageIndex>& node, Index k, Scalar* v, Scalar* work) {
  const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
  const Scalar* L = node.values.data();
  if (K > 0 && nc <= SmallSolveColumns) return forwardColumnBlocks<(K > 0 ? K : 1)>(nr, nc, L, v);
  if (k == 1) {
    trsvLower(false, nc, L, nr, v);
    if (m == 0) return;
    gemvProduct(false, m, nc, L + nc, nr, v, work);
    for (Index i = 0; i < m; ++i) v[nc + i] -= work[i];
  } else {
    trsmLeftLower(false, nc, k, L, nr, v, nr);
    if (m > 0) gemmProduct(false, true, m, k, nc, L + nc, nr, v, nr, v + nc, nr);
  }
}

/** \internal The forward substitution of the last solve, for reuse by the next one.
  *
  * Usage: forward() replaces X by L^{-1} X. Between two calls, the owner reports every change of
  * the factor: markChanged() with the supernodes whose blocks were rewritten, or invalidate()
  * when all of them were or the structure changed. The right-hand side's changes need no report:
  * forward() compares it with the kept one, supernode by supernode. */
template <typename Scalar, typename StorageIndex>
class ForwardSolveCache {
 public:
  typedef SupernodalFactor<Scalar, StorageIndex> Factor;

  /** Forgets the kept substitution: the next forward() does a full pass (and keeps it). */
  void invalidate() { m_valid = false; }

  /** Reports that the blocks of \a supernodes changed since the last forward(). */
  void markChanged(const std::vector<Index>& supernodes) {
    if (!m_valid) return;
    for (Index s : supernodes) m_redo[s] = 1;
  }

  /** Follows a change of the numbering that keeps the supernodes (insertDofs(), mergeDofs():
    * each old permuted column k moves to \a newPosition[k], or leaves when it is -1; \a f has
    * the new structure). The kept values of the columns that stay move with them; every new
    * column gets a right-hand side that matches nothing (so it is substituted). A supernode keeps
    * its update vector when its number of rows below is the same, and is substituted again
    * otherwise; the caller still reports the supernodes whose blocks changed (markChanged()). */
  template <typename Positions>
  void relabel(const Positions& newPosition, const Factor& f) {
    if (!m_valid) return;
    const Index ns = f.count(), oldN = m_n, newN = f.n, k = m_k;
    if (Index(newPosition.size()) != oldN || Index(m_redo.size()) != ns) return invalidate();
    typedef typename NumTraits<Scalar>::Real Real;
    m_spareRhs.assign(newN * k, Scalar(std::numeric_limits<Real>::quiet_NaN()));  // (NaN equals nothing)
    m_spareY.assign(newN * k, Scalar(0));
    for (Index c = 0; c < k; ++c)
      for (Index q = 0; q < oldN; ++q) {
        const Index to = Index(newPosition[q]);
        if (to < 0) continue;
        m_spareRhs[to + c * newN] = m_rhs[q + c * oldN];
        m_spareY[to + c * newN] = m_y[q + c * oldN];
      }
    m_rhs.swap(m_spareRhs);
    m_y.swap(m_spareY);
    updateOffsets(f, k, m_spareOffset);
    m_spareUpdate.resize(m_spareOffset[ns]);
    for (Index s = 0; s < ns; ++s) {
      const Index length = m_spareOffset[s + 1] - m_spareOffset[s];
      if (length != m_offset[s + 1] - m_offset[s]) {
        m_redo[s] = 1;
        continue;
      }
      std::copy(m_update.begin() + m_offset[s], m_update.begin() + m_offset[s + 1], m_spareUpdate.begin() + m_spareOffset[s]);
    }
    m_update.swap(m_spareUpdate);
    m_offset.swap(m_spareOffset);
    m_n = newN;
  }

  /** Frees the memory held (the next forward() does a full pass). */
  void release() {
    m_valid = false;
    std::vector<Scalar>().swap(m_rhs);
    std::vector<Scalar>().swap(m_y);
    std::vector<Scalar>().swap(m_update);
    std::vector<Index>().swap(m_offset);
    std::vector<Scalar>().swap(m_spareRhs);
    std::vector<Scalar>().swap(m_spareY);
    std::vector<Scalar>().swap(m_spareUpdate);
    std::vector<Index>().swap(m_spareOffset);
    std::vector<char>().swap(m_redo);
  }

  /** \returns the bytes held. */
  Index bytes() const {
    return Index((m_rhs.capacity() + m_y.capacity() + m_update.capacity() + m_spareRhs.capacity() +
                  m_spareY.capacity() + m_spareUpdate.capacity()) * sizeof(Scalar) +
                 (m_offset.capacity() + m_spareOffset.capacity()) * sizeof(Index) + m_redo.capacity());
  }

  /** \returns the columns substituted by the last forward() (all n after a full pass). */
  Index substitutedColumns() const { return m_substitutedColumns; }

  /** X := L^{-1} X for the k columns of X (leading dimension ldx, permuted numbering), reusing
    * the kept substitution where neither the blocks nor the right-hand side changed below.
    * \a work holds 2*maxRows()*k scalars. */
  void forward(const Factor& f, Scalar* X, Index ldx, Index k, Scalar* work) {
    switch (k) {
      case 1: return forwardPass<1>(f, X, ldx, k, work);
      case 2: return forwardPass<2>(f, X, ldx, k, work);
      case 3: return forwardPass<3>(f, X, ldx, k, work);
      case 4: return forwardPass<4>(f, X, ldx, k, work);
      default: return forwardPass<0>(f, X, ldx, k, work);
    }
  }

 private:
  /** Where each supernode's update vector starts (below()·k scalars each), and the total at [ns]. */
  static void updateOffsets(const Factor& f, Index k, std::vector<Index>& offset) {
    const Index ns = f.count();
    offset.resize(ns + 1);
    offset[0] = 0;
    for (Index s = 0; s < ns; ++s) offset[s + 1] = offset[s] + f.nodes[s].below() * k;
  }

  /** Sizes the kept arrays for the factor and k right-hand sides; every supernode to be redone. */
  void reset(const Factor& f, Index k) {
    const Index ns = f.count();
    m_n = f.n;
    m_k = k;
    updateOffsets(f, k, m_offset);
    m_rhs.resize(m_n * k);
    m_y.resize(m_n * k);
    m_update.resize(m_offset[ns]);
    m_redo.assign(ns, 1);
  }

  /** \internal Whether a[0..n) == b[0..n) (by value: a NaN differs from everything, and the
    * padding bytes of long double are not compared). */
  static bool sameValues(const Scalar* a, const Scalar* b, Index n) {
    bool same = true;
    for (Index i = 0; i < n; ++i) same &= bool(a[i] == b[i]);
    return same;
  }

  template <int K>
  void forwardPass(const Factor& f, Scalar* X, Index ldx, Index k, Scalar* work) {
    const Index ns = f.count();
    if (!m_valid || m_k != k || m_n != f.n || Index(m_redo.size()) != ns) reset(f, k);
    m_valid = false;  // (until the pass is complete)
    // 1. What to substitute: changed blocks, changed right-hand sides, and everything above them.
    for (Index s = 0; s < ns; ++s) {
      const auto& node = f.nodes[s];
      for (Index c = 0; c < k && !m_redo[s]; ++c)
        m_redo[s] = !sameValues(X + node.firstCol + c * ldx, m_rhs.data() + node.firstCol + c * m_n, node.ncols);
      if (m_redo[s] && f.parent[s] != -1) m_redo[f.parent[s]] = 1;
    }
    // 2. The pass: kept values where nothing changed, a multifrontal substitution elsewhere.
    m_substitutedColumns = 0;
    Scalar* v = work;
    Scalar* scratch = work + f.maxRows() * k;  // (the gemv of a large supernode, k = 1)
    for (Index s = 0; s < ns; ++s) {
      const auto& node = f.nodes[s];
      const Index nr = node.nrows(), nc = node.ncols;
      if (!m_redo[s]) {
        for (Index c = 0; c < k; ++c)
          std::memcpy(X + node.firstCol + c * ldx, m_y.data() + node.firstCol + c * m_n, std::size_t(nc) * sizeof(Scalar));
        continue;
      }
      m_redo[s] = 0;
      m_substitutedColumns += nc;
      prefetchSupernode(node);
      for (Index c = 0; c < k; ++c) {
        const Scalar* xs = X + node.firstCol + c * ldx;
        std::memcpy(m_rhs.data() + node.firstCol + c * m_n, xs, std::size_t(nc) * sizeof(Scalar));
        Scalar* vc = v + c * nr;
        std::memcpy(vc, xs, std::size_t(nc) * sizeof(Scalar));
        std::fill(vc + nc, vc + nr, Scalar(0));
      }
      for (Index ch = f.firstChild[s]; ch != -1; ch = f.nextSibling[ch]) {  // extend-add of the children
        const auto& child = f.nodes[ch];
        const Index m = child.below();
        const StorageIndex* position = child.parentPosition.data();
        for (Index c = 0; c < k; ++c) {
          const Scalar* u = m_update.data() + m_offset[ch] + c * m;
          Scalar* vc = v + c * nr;
          for (Index i = 0; i < m; ++i) vc[position[i]] += u[i];
        }
      }
      forwardFront<K>(node, k, v, scratch);
      for (Index c = 0; c < k; ++c) {
        const Scalar* vc = v + c * nr;
        std::memcpy(X + node.firstCol + c * ldx, vc, std::size_t(nc) * sizeof(Scalar));
        std::memcpy(m_y.data() + node.firstCol + c * m_n, vc, std::size_t(nc) * sizeof(Scalar));
        std::memcpy(m_update.data() + m_offset[s] + c * (nr - nc), vc + nc, std::size_t(nr - nc) * sizeof(Scalar));
      }
    }
    m_valid = true;
  }

  bool m_valid = false;
  Index m_n = 0, m_k = 0, m_substitutedColumns = 0;
  std::vector<Scalar> m_rhs;     ///< the right-hand side of the kept substitution, n×k
  std::vector<Scalar> m_y;       ///< its result L^{-1} c, n×k
  std::vector<Scalar> m_update;  ///< each supernode's update vector, below()×k at m_offset[s]
  std::vector<Index> m_offset;
  std::vector<char> m_redo;      ///< supernodes to substitute again (all zero after a pass)
  std::vector<Scalar> m_spareRhs, m_spareY, m_spareUpdate;  ///< relabel()'s targets, swapped in
  std::vector<Index> m_spareOffset;
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_INCREMENTAL_FORWARD_SOLVE_H
