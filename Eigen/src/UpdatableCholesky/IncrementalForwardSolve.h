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
// passed through) for its parent. The cache keeps c and y by position, in two vectors as long as
// the factor's positions (read and written in order of the supernodes, so that the checks and
// copies of the clean supernodes stream through memory), and every update vector in a region of
// its own: about (2 × positions + Σ rows below each supernode)·k scalars for k right-hand sides
// (positions: n plus the free positions a cut's layout leaves, design §6). A supernode
// is substituted again when its right-hand side is not bitwise the kept one (stricter than
// equality: -0 against +0 counts as a change, which costs only a substitution), and a substituted
// supernode gives bitwise the values of a full pass over the same factor and right-hand side. The
// backward pass changes every entry of x whenever anything changed, so it is always done in full.
//
// insertDofs() and mergeDofs() keep the supernodes and renumber the columns (paper §4.2). The
// update vectors are stored by supernode, so they stay where they are; c and y move with their
// supernode's columns when a layout anew moves them (followStructure(), once per layout: a local
// relabeling moves no clean supernode's columns). Only the dirty supernodes, whose shapes change,
// get regions of their new sizes and are substituted again.

#ifndef EIGEN_UPDATABLE_CHOLESKY_INCREMENTAL_FORWARD_SOLVE_H
#define EIGEN_UPDATABLE_CHOLESKY_INCREMENTAL_FORWARD_SOLVE_H

#include <cstring>
#include <type_traits>
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

  /** Follows a change of the numbering that keeps the supernodes (insertDofs(), mergeDofs();
    * \a f has the new structure; \a reshaped: the only supernodes whose shape may have changed):
    * a supernode keeps what it kept when its shape (columns, rows below) is the same, and is
    * substituted again in a region of its new size otherwise. \a columnsMoved: the first
    * columns of clean supernodes may have moved (a layout anew, not a local relabeling); their
    * kept c and y then move with them, in one pass over the supernodes (without the flag, only
    * a change of the position count starts that pass, and a column moved unreported is found by
    * the next forward(), which substitutes that supernode again). The caller still reports the
    * supernodes whose blocks changed (markChanged()). */
  void followStructure(const Factor& f, const std::vector<Index>& reshaped, bool columnsMoved) {
    if (!m_valid) return;
    const Index ns = f.count();
    if (Index(m_redo.size()) != ns) return invalidate();
    // a region too small is abandoned for a new one at the end; the regions are laid out anew
    // once the abandoned ones hold as much as the live ones
    for (Index s : reshaped) resizeRegion(f, s);
    if (m_abandoned > m_live) compactRegions();
    if (!columnsMoved && f.n == m_n) return;  // (a local relabeling: no clean supernode moved)
    // into the spare pair, not into new vectors: only a clean supernode's columns are read before a
    // pass writes them, so the rest need no zeroing or allocation (on igea the pair is 2 × 2.2 MB;
    // the first cut after compute() still touches it fresh, 12 ms, later ones 0.005-0.25 ms)
    std::vector<Scalar>& rhs = m_spareRhs;
    std::vector<Scalar>& y = m_spareY;
    rhs.resize(std::size_t(f.n * m_k));
    y.resize(std::size_t(f.n * m_k));
    for (Index s = 0; s < ns; ++s) {
      const Index to = f.nodes[s].firstCol, from = m_firstCol[s];
      m_firstCol[s] = to;
      if (m_redo[s]) continue;
      for (Index c = 0; c < m_k; ++c) {
        std::copy(m_rhs.begin() + (from + c * m_n), m_rhs.begin() + (from + c * m_n + m_columns[s]),
                  rhs.begin() + (to + c * f.n));
        std::copy(m_y.begin() + (from + c * m_n), m_y.begin() + (from + c * m_n + m_columns[s]),
                  y.begin() + (to + c * f.n));
      }
    }
    m_rhs.swap(rhs);
    m_y.swap(y);
    m_n = f.n;
  }

  /** Frees the memory held (the next forward() does a full pass). */
  void release() {
    m_valid = false;
    std::vector<Scalar>().swap(m_kept);
    std::vector<Scalar>().swap(m_rhs);
    std::vector<Scalar>().swap(m_y);
    std::vector<Scalar>().swap(m_spareRhs);
    std::vector<Scalar>().swap(m_spareY);
    std::vector<Index>().swap(m_firstCol);
    std::vector<Index>().swap(m_offset);
    std::vector<Index>().swap(m_columns);
    std::vector<Index>().swap(m_below);
    std::vector<Index>().swap(m_capacity);
    std::vector<char>().swap(m_redo);
  }

  /** \returns the bytes held. */
  Index bytes() const {
    return Index((m_kept.capacity() + m_rhs.capacity() + m_y.capacity() + m_spareRhs.capacity() + m_spareY.capacity()) *
                     sizeof(Scalar) +
                 (m_firstCol.capacity() + m_offset.capacity() + m_columns.capacity() + m_below.capacity() +
                  m_capacity.capacity()) * sizeof(Index) +
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
  /** Sizes the kept regions for the factor and k right-hand sides, one after the other; every
    * supernode to be redone. */
  void reset(const Factor& f, Index k) {
    const Index ns = f.count();
    m_n = f.n;
    m_k = k;
    m_rhs.resize(std::size_t(m_n * k));
    m_y.resize(std::size_t(m_n * k));
    m_firstCol.resize(ns);
    m_offset.resize(ns);
    m_columns.resize(ns);
    m_below.resize(ns);
    m_capacity.resize(ns);
    Index total = 0;
    for (Index s = 0; s < ns; ++s) {
      m_firstCol[s] = f.nodes[s].firstCol;
      m_columns[s] = f.nodes[s].ncols;
      m_below[s] = f.nodes[s].below();
      m_offset[s] = total;
      m_capacity[s] = regionLength(s);
      total += m_capacity[s];
    }
    m_abandoned = 0;
    m_live = total;
    m_kept.reserve(std::size_t(total + total / 8));  // (room for the dirty supernodes that grow: no
    m_kept.resize(total);                            // reallocation of everything at the first cut)
    m_redo.assign(ns, 1);
  }

  /** Scalars of supernode s's region: its update vector (rows below × k), column by column. */
  Index regionLength(Index s) const { return m_below[s] * m_k; }
  Scalar* updateOf(Index s) { return m_kept.data() + m_offset[s]; }

  /** Gives supernode \a s a region of its current shape (a new one at the end when its own is
    * too small), to be substituted again if the shape changed. */
  void resizeRegion(const Factor& f, Index s) {
    const auto& node = f.nodes[s];
    if (node.ncols == m_columns[s] && node.below() == m_below[s]) return;
    m_redo[s] = 1;
    m_live -= regionLength(s);
    m_columns[s] = node.ncols;
    m_below[s] = node.below();
    const Index length = regionLength(s);
    m_live += length;
    if (length <= m_capacity[s]) return;
    m_abandoned += m_capacity[s];
    m_offset[s] = Index(m_kept.size());
    m_capacity[s] = length;
    if (m_kept.capacity() < m_kept.size() + std::size_t(length))  // (grown by an eighth, not doubled)
      m_kept.reserve(m_kept.size() + std::size_t(length) + m_kept.size() / 8);
    m_kept.resize(m_kept.size() + std::size_t(length));
  }

  /** Lays the regions out again one after the other (the kept ones keep their values). */
  void compactRegions() {
    const Index ns = Index(m_offset.size());
    Index total = 0;
    for (Index s = 0; s < ns; ++s) total += regionLength(s);
    std::vector<Scalar> compact(total);
    for (Index s = 0, at = 0; s < ns; ++s) {
      const Index length = regionLength(s);
      if (!m_redo[s]) std::copy(m_kept.begin() + m_offset[s], m_kept.begin() + m_offset[s] + length, compact.begin() + at);
      m_offset[s] = at;
      m_capacity[s] = length;
      at += length;
    }
    m_kept.swap(compact);
    m_abandoned = 0;
  }

  /** \internal Whether the right-hand side a[0..n) is the kept one b[0..n): for float and double
    * scalars (real or complex), whether they hold the same bits, one memcmp (stricter than
    * equality: -0 against +0 counts as a change, which costs only a substitution); for other
    * scalars by value (long double carries padding bytes, which may differ). */
  static bool sameRightHandSide(const Scalar* a, const Scalar* b, Index n) {
    typedef typename NumTraits<Scalar>::Real Real;
    if constexpr (std::is_same<Real, float>::value || std::is_same<Real, double>::value) {
      return std::memcmp(a, b, std::size_t(n) * sizeof(Scalar)) == 0;
    } else {
      bool same = true;
      for (Index i = 0; i < n; ++i) same &= bool(a[i] == b[i]);
      return same;
    }
  }

  template <int K>
  void forwardPass(const Factor& f, Scalar* X, Index ldx, Index k, Scalar* work) {
    const Index ns = f.count();
    if (!m_valid || m_k != k || m_n != f.n || Index(m_redo.size()) != ns) reset(f, k);
    m_valid = false;  // (until the pass is complete)
    // 1. What to substitute: changed blocks, changed right-hand sides, and everything above them.
    for (Index s = 0; s < ns; ++s) {
      const auto& node = f.nodes[s];
      resizeRegion(f, s);  // (a shape that changed unreported: substituted again)
      if (node.firstCol != m_firstCol[s]) {  // (columns moved unreported: likewise)
        m_firstCol[s] = node.firstCol;
        m_redo[s] = 1;
      }
      for (Index c = 0; c < k && !m_redo[s]; ++c)
        m_redo[s] = !sameRightHandSide(X + node.firstCol + c * ldx, m_rhs.data() + node.firstCol + c * m_n, node.ncols);
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
          const Scalar* u = updateOf(ch) + c * m;
          Scalar* vc = v + c * nr;
          for (Index i = 0; i < m; ++i) vc[position[i]] += u[i];
        }
      }
      forwardFront<K>(node, k, v, scratch);
      for (Index c = 0; c < k; ++c) {
        const Scalar* vc = v + c * nr;
        std::memcpy(X + node.firstCol + c * ldx, vc, std::size_t(nc) * sizeof(Scalar));
        std::memcpy(m_y.data() + node.firstCol + c * m_n, vc, std::size_t(nc) * sizeof(Scalar));
        if (nr > nc) std::memcpy(updateOf(s) + c * (nr - nc), vc + nc, std::size_t(nr - nc) * sizeof(Scalar));
      }
    }
    m_valid = true;
  }

  bool m_valid = false;
  Index m_n = 0, m_k = 0, m_substitutedColumns = 0;
  std::vector<Scalar> m_rhs;       ///< the right-hand side c of the kept substitution, by position (n × k)
  std::vector<Scalar> m_y;         ///< y = L^{-1} c, by position (n × k)
  std::vector<Scalar> m_spareRhs, m_spareY;  ///< followStructure()'s targets, swapped with m_rhs and m_y (any values)
  std::vector<Index> m_firstCol;   ///< the first column of each supernode where its c and y are kept
  /** Each supernode's region: its update vector (rows below × k), at m_offset[s] */
  std::vector<Scalar> m_kept;
  std::vector<Index> m_offset;    ///< where each supernode's region starts
  std::vector<Index> m_columns;   ///< the columns of each supernode when its region was laid out
  std::vector<Index> m_below;     ///< its rows below then
  std::vector<Index> m_capacity;  ///< the scalars its region holds (followStructure() reuses it when they fit)
  Index m_abandoned = 0;          ///< scalars of m_kept in regions no supernode uses any more
  Index m_live = 0;               ///< scalars of m_kept in use (the sum of the regions' lengths)
  std::vector<char> m_redo;       ///< supernodes to substitute again (all zero after a pass)
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_INCREMENTAL_FORWARD_SOLVE_H
