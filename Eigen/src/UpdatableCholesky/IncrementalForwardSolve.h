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
    * otherwise; the caller still reports the supernodes whose blocks changed (markChanged()).
    * \a firstMoved: the old columns below it keep their position (0 if unknown); \a reshaped:
    * the only supernodes whose number of rows may have changed (null: any). */
  template <typename Positions>
  void relabel(const Positions& newPosition, const Factor& f, Index firstMoved = 0,
               const std::vector<Index>* reshaped = nullptr) {
    if (!m_valid) return;
    const Index ns = f.count(), oldN = m_n, newN = f.n;
    if (Index(newPosition.size()) != oldN || Index(m_redo.size()) != ns) return invalidate();
    typedef typename NumTraits<Scalar>::Real Real;
    if (!planMove(newPosition, newN, (std::min)(firstMoved, oldN))) return invalidate();
    moveInPlace(newN, m_rhs, Scalar(std::numeric_limits<Real>::quiet_NaN()));  // (NaN equals nothing)
    moveInPlace(newN, m_y, Scalar(0));
    m_n = newN;
    // the update vectors: a supernode whose rows below changed is substituted again, in its
    // region if it fits, else in a new one at the end; the regions are laid out anew once the
    // abandoned ones hold as much as the live ones
    if (reshaped)
      for (Index s : *reshaped) resizeUpdate(f, s);
    else
      for (Index s = 0; s < ns; ++s) resizeUpdate(f, s);
    if (m_abandoned > m_live) compactUpdates();
  }

  /** Frees the memory held (the next forward() does a full pass). */
  void release() {
    m_valid = false;
    std::vector<Scalar>().swap(m_rhs);
    std::vector<Scalar>().swap(m_y);
    std::vector<Scalar>().swap(m_update);
    std::vector<Index>().swap(m_offset);
    std::vector<Index>().swap(m_length);
    std::vector<Index>().swap(m_capacity);
    std::vector<Index>().swap(m_runs);
    std::vector<char>().swap(m_redo);
  }

  /** \returns the bytes held. */
  Index bytes() const {
    return Index((m_rhs.capacity() + m_y.capacity() + m_update.capacity()) * sizeof(Scalar) +
                 (m_offset.capacity() + m_length.capacity() + m_capacity.capacity() + m_runs.capacity()) * sizeof(Index) +
                 m_redo.capacity());
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
  /** Sizes the kept arrays for the factor and k right-hand sides, the update vectors one after
    * the other (below()·k scalars each); every supernode to be redone. */
  void reset(const Factor& f, Index k) {
    const Index ns = f.count();
    m_n = f.n;
    m_k = k;
    m_offset.resize(ns);
    m_length.resize(ns);
    Index total = 0;
    for (Index s = 0; s < ns; ++s) {
      m_offset[s] = total;
      m_length[s] = f.nodes[s].below() * k;
      total += m_length[s];
    }
    m_capacity = m_length;
    m_abandoned = 0;
    m_live = total;
    m_rhs.resize(m_n * k);
    m_y.resize(m_n * k);
    m_update.resize(total);
    m_redo.assign(ns, 1);
  }

  /** Gives supernode \a s an update vector of its current size (a new region at the end when
    * its own is too small), to be substituted again if the size changed. */
  void resizeUpdate(const Factor& f, Index s) {
    const Index length = f.nodes[s].below() * m_k;
    if (length == m_length[s]) return;
    m_redo[s] = 1;
    m_live += length - m_length[s];
    m_length[s] = length;
    if (length <= m_capacity[s]) return;
    m_abandoned += m_capacity[s];
    m_offset[s] = Index(m_update.size());
    m_capacity[s] = length;
    if (m_update.capacity() < m_update.size() + std::size_t(length))  // (grown by an eighth, not doubled)
      m_update.reserve(m_update.size() + std::size_t(length) + m_update.size() / 8);
    m_update.resize(m_update.size() + std::size_t(length));
  }

  /** Lays the update vectors out again one after the other (the kept ones keep their values). */
  void compactUpdates() {
    const Index ns = Index(m_offset.size());
    Index total = 0;
    for (Index s = 0; s < ns; ++s) total += m_length[s];
    std::vector<Scalar> compact(total);
    for (Index s = 0, at = 0; s < ns; ++s) {
      if (!m_redo[s])
        std::copy(m_update.begin() + m_offset[s], m_update.begin() + m_offset[s] + m_length[s], compact.begin() + at);
      m_offset[s] = at;
      m_capacity[s] = m_length[s];
      at += m_length[s];
    }
    m_update.swap(compact);
    m_abandoned = 0;
  }

  /** Plans the renumbering of the n×k arrays (column-major, leading dimension m_n) to leading
    * dimension \a newN: entry q of each column goes to newPosition[q], or leaves when it is -1.
    * The kept entries keep their order, so they move in runs of the same shift (m_runs). \returns
    * false when the positions are not such a renumbering in one direction (all kept entries
    * moving up, or all moving down), which moveInPlace() could not do in place. The entries
    * below \a firstMoved keep their position (one run, not read). */
  template <typename Positions>
  bool planMove(const Positions& newPosition, Index newN, Index firstMoved) {
    const Index oldN = m_n;
    std::vector<Index>& runs = m_runs;  // (begin, end, shift) of each run of kept entries
    runs.clear();
    bool up = false, down = false;
    eigen_assert(firstMoved <= newN && "ForwardSolveCache::planMove: the unmoved entries do not fit");
    if (firstMoved > 0) runs.insert(runs.end(), {Index(0), firstMoved, Index(0)});  // (entries that stay)
    for (Index q = firstMoved; q < oldN; ++q) {
      const Index to = Index(newPosition[q]);
      if (to < 0) continue;
      if (to >= newN) return false;
      const Index shift = to - q;
      up = up || shift > 0;
      down = down || shift < 0;
      if (!runs.empty() && runs[runs.size() - 2] == q && runs.back() == shift)
        ++runs[runs.size() - 2];
      else
        runs.insert(runs.end(), {q, q + 1, shift});
    }
    m_moveUp = up || newN > oldN;  // (each entry then moves up: in every column when n does not shrink)
    return !(up && down) && !(m_moveUp && newN < oldN && m_k > 1);
  }

  /** Renumbers the n×k array \a a in place as planMove() planned; the new entries that nothing
    * moves to get \a fill. Runs that do not move (before the first moved entry, in the first
    * column) are not touched. */
  void moveInPlace(Index newN, std::vector<Scalar>& a, const Scalar& fill) const {
    const Index oldN = m_n, k = m_k;
    const std::vector<Index>& runs = m_runs;
    const Index count = Index(runs.size()) / 3;
    auto fillHoles = [&](Index c) {  // the new entries of column c that no run reached
      Scalar* column = a.data() + c * newN;
      Index next = 0;
      for (Index r = 0; r < count; ++r) {
        const Index begin = runs[3 * r] + runs[3 * r + 2];
        std::fill(column + next, column + begin, fill);
        next = runs[3 * r + 1] + runs[3 * r + 2];
      }
      std::fill(column + next, column + newN, fill);
    };
    auto moveRun = [&](Index c, Index r) {
      const Index begin = runs[3 * r], end = runs[3 * r + 1], shift = runs[3 * r + 2];
      const Scalar* from = a.data() + c * oldN + begin;
      Scalar* to = a.data() + c * newN + begin + shift;
      if (from != to) std::memmove(to, from, std::size_t(end - begin) * sizeof(Scalar));
    };
    if (m_moveUp) {  // from the last entry down, after growing
      if (newN > oldN) a.resize(std::size_t(newN * k));
      for (Index c = k - 1; c >= 0; --c) {
        for (Index r = count - 1; r >= 0; --r) moveRun(c, r);
        fillHoles(c);
      }
    } else {  // from the first entry up
      for (Index c = 0; c < k; ++c) {
        for (Index r = 0; r < count; ++r) moveRun(c, r);
        fillHoles(c);
      }
    }
    a.resize(std::size_t(newN * k));  // (shrinking, when entries left)
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
        if (nr > nc)  // (a root keeps no update vector: m_update may even be empty)
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
  std::vector<Index> m_offset;   ///< where each supernode's region of m_update starts
  std::vector<Index> m_length;   ///< the scalars of each supernode's update vector (below()·k)
  std::vector<Index> m_capacity; ///< the scalars its region holds (relabel() reuses it when they fit)
  Index m_abandoned = 0;         ///< scalars of m_update in regions no supernode uses any more
  Index m_live = 0;              ///< scalars of m_update in use (the sum of m_length)
  std::vector<char> m_redo;      ///< supernodes to substitute again (all zero after a pass)
  std::vector<Index> m_runs;     ///< planMove()'s runs of kept entries: (begin, end, shift) each
  bool m_moveUp = false;         ///< planMove(): the entries move up (moveInPlace() goes from the end)
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_INCREMENTAL_FORWARD_SOLVE_H
