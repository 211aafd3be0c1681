// SupernodalFactor.h — storage of a supernodal Cholesky factor, one object per supernode
// (paper §4.2, "Implementation"): each supernode keeps its own row indices and its own dense
// block, so that later updates can insert or remove rows and columns of one supernode without
// moving the others. The factor also keeps the supernodal elimination tree, each supernode's
// relative row positions inside its parent (for the extend-add of update matrices), the map
// that scatters the input matrix's values into the blocks, and the flop counts; and the cached
// update matrices, which an insertion moves to new rows without a copy, with the runs of
// positions (PositionRun) that blocks and update matrices are moved by when they are copied.

#ifndef EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_FACTOR_H
#define EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_FACTOR_H

#include <algorithm>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal An allocator whose value-initializing construct() (what std::vector::resize()
  * calls for the new elements) leaves arithmetic scalars uninitialized instead of zeroing them.
  * The cached update matrices are written before they are read (the front's rank-k product
  * overwrites a lower triangle, or the caller zeroes it), so zeroing a new or grown one only
  * cost a pass over its memory per refactored supernode. */
template <typename T>
struct UninitializedAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    typedef UninitializedAllocator<U> other;
  };
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
    ::new (static_cast<void*>(p)) U;  // default-, not value-initialization
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <typename T, typename U>
bool operator==(const UninitializedAllocator<T>&, const UninitializedAllocator<U>&) noexcept {
  return true;
}
template <typename T, typename U>
bool operator!=(const UninitializedAllocator<T>&, const UninitializedAllocator<U>&) noexcept {
  return false;
}

/** \internal Storage of one cached update matrix (column-major, lower triangle meaningful); its
  * new entries are not zeroed by resize(). */
template <typename Scalar>
using UpdateBuffer = std::vector<Scalar, UninitializedAllocator<Scalar> >;

/** \internal A monotone map of positions as runs of consecutive ones: [from, from + length) goes
  * to [to, to + length). A cut adds a few copy rows to hundreds, a merge drops a few: a column is
  * then moved by a few block copies instead of an index per entry. */
struct PositionRun {
  Index from, to, length;
};

/** \internal The runs of the map from(k) -> to(k), k < \a count, both increasing. */
template <typename From, typename To>
void monotoneRuns(Index count, From&& from, To&& to, std::vector<PositionRun>& runs) {
  runs.clear();
  for (Index k = 0; k < count; ++k) {
    const Index source = from(k), target = to(k);
    if (!runs.empty() && runs.back().from + runs.back().length == source && runs.back().to + runs.back().length == target)
      ++runs.back().length;
    else
      runs.push_back(PositionRun{source, target, 1});
  }
}

/** \internal The runs of the spread k -> \a target[k] (k < \a count, target increasing). */
inline void positionRuns(const Index* target, Index count, std::vector<PositionRun>& runs) {
  monotoneRuns(count, [](Index k) { return k; }, [&](Index k) { return target[k]; }, runs);
}

/** \internal The runs of the gather \a source[i] -> i (i < \a count, source increasing). */
inline void gatherRuns(const Index* source, Index count, std::vector<PositionRun>& runs) {
  monotoneRuns(count, [&](Index i) { return source[i]; }, [](Index i) { return i; }, runs);
}

/** \internal Writes column[begin, end) from \a previous (indexed by source position) through
  * \a runs (targets within [0, end)), zero where no run lands (the copies' rows, which the
  * previous matrix extended with identity has zero there). \a first: a run at or before the
  * first that reaches \a begin; it is advanced to that run, so that a walk over columns with
  * increasing begin passes each run once. */
template <typename Scalar>
void copyByRuns(const Scalar* previous, const std::vector<PositionRun>& runs, std::size_t& first, Scalar* column,
                Index begin, Index end) {
  while (first < runs.size() && runs[first].to + runs[first].length <= begin) ++first;
  Index i = begin;
  for (std::size_t r = first; r < runs.size(); ++r) {
    const PositionRun& run = runs[r];
    const Index skip = (std::max)(Index(0), begin - run.to), to = run.to + skip;
    std::fill(column + i, column + to, Scalar(0));
    std::copy(previous + run.from + skip, previous + run.from + run.length, column + to);
    i = run.to + run.length;
  }
  std::fill(column + i, column + end, Scalar(0));
}

/** \internal The previous update matrix \a oldU (lower triangle, at.size() square) written into
  * \a U (m × m) at the new positions \a at of its rows: the rows and columns of the copies a
  * supernode gained below are zero, as for the previous matrix extended with identity. \a runs:
  * scratch. */
template <typename Scalar, typename Buffer>
void extendUpdateMatrix(const Scalar* oldU, const std::vector<Index>& at, Index m, Buffer& U,
                        std::vector<PositionRun>& runs) {
  const Index oldM = Index(at.size());
  positionRuns(at.data(), oldM, runs);
  U.resize(m * m);  // (only the lower triangle is written: the upper one is never read)
  std::size_t first = 0;
  for (Index j = 0, b = 0; j < m; ++j) {
    if (b < oldM && at[b] == j) {  // a previous column (from its diagonal on); else a copy's, zero
      copyByRuns(oldU + b * oldM, runs, first, U.data() + j * m, j, m);
      ++b;
    } else {
      std::fill(U.data() + j * m + j, U.data() + (j + 1) * m, Scalar(0));
    }
  }
}

/** \internal A cached update matrix (m × m, column-major, lower triangle meaningful), stored in
  * its own layout or in an earlier one: a supernode folded by an insertion gains copy rows below,
  * which are zero in its previous update matrix, so the matrix keeps its storage and a row map
  * (stored row i is row layout[i]) instead of being copied into the new rows (measurement log,
  * stop 49: up to 0.7 ms of a 3 ms insertion). Whoever reads the values calls layOut() first;
  * a merge that drops only rows the storage does not hold relabels them (keepRows()). The map
  * goes with the storage through swap(); resize() starts a matrix in its own layout. */
template <typename Scalar>
class CachedUpdate {
 public:
  /** The stored values (in the matrix's own layout only when inOwnLayout()). */
  Scalar* data() { return m_values.data(); }
  /** The stored values (in the matrix's own layout only when inOwnLayout()). */
  const Scalar* data() const { return m_values.data(); }
  /** The number of stored values. */
  std::size_t size() const { return m_values.size(); }
  /** The number of values the storage holds without reallocating. */
  std::size_t capacity() const { return m_values.capacity(); }
  /** Whether nothing is stored. */
  bool empty() const { return m_values.empty(); }
  /** The stored values, first. */
  typename UpdateBuffer<Scalar>::iterator begin() { return m_values.begin(); }
  /** The stored values, past the last. */
  typename UpdateBuffer<Scalar>::iterator end() { return m_values.end(); }
  /** Gives it \a count values in its own layout; the previous values are not kept. */
  void resize(std::size_t count) {
    m_values.resize(count);
    m_layout.clear();
  }
  /** Exchanges storage and layout with \a other. */
  void swap(CachedUpdate& other) {
    m_values.swap(other.m_values);
    m_layout.swap(other.m_layout);
    std::swap(m_rows, other.m_rows);
  }
  /** Whether the stored values are in the matrix's own layout. */
  bool inOwnLayout() const { return m_layout.empty(); }
  /** The rows of the matrix (\a rows of them) move: row i becomes row \a at[i] (increasing) of
    * \a m, and the others are zero. Nothing is copied. */
  void relabelRows(Index rows, const std::vector<Index>& at, Index m) {
    eigen_assert(Index(at.size()) == rows && (m_layout.empty() || m_rows == rows) && "relabelRows: wrong row count");
    EIGEN_UNUSED_VARIABLE(rows);
    if (m_layout.empty()) {
      m_layout.assign(at.begin(), at.end());
    } else {
      for (Index& r : m_layout) r = at[r];
    }
    m_rows = m;
    dropIdentity();
  }
  /** The matrix (\a rows rows) keeps only its rows \a kept[0..m) (increasing), which become rows
    * 0..m: relabeled without a copy when every stored row is kept. \returns false (nothing
    * changed) when a stored row is dropped. */
  bool keepRows(Index rows, const Index* kept, Index m) {
    eigen_assert((m_layout.empty() || m_rows == rows) && "keepRows: wrong row count");
    const Index stored = m_layout.empty() ? rows : Index(m_layout.size());
    // walks the stored rows with their new numbers (sink(p, i): stored row p becomes row i);
    // false at the first stored row that is not kept
    auto walk = [&](auto&& sink) {
      for (Index p = 0, i = 0; p < stored; ++p) {
        const Index r = m_layout.empty() ? p : m_layout[p];
        while (i < m && kept[i] < r) ++i;
        if (i == m || kept[i] != r) return false;
        sink(p, i);
      }
      return true;
    };
    if (!walk([](Index, Index) {})) return false;  // (checked first: nothing changes on false)
    if (m_layout.empty()) {
      m_layout.resize(std::size_t(stored));
      for (Index p = 0; p < stored; ++p) m_layout[p] = p;
    }
    walk([&](Index p, Index i) { m_layout[p] = i; });  // (row p is read before it is rewritten)
    m_rows = m;
    dropIdentity();
    return true;
  }
  /** Writes the values into the matrix's own layout (a no-op when they are), by runs of
    * consecutive rows (extendUpdateMatrix()). */
  void layOut() {
    if (m_layout.empty()) return;
    std::vector<PositionRun> runs;  // (a few per matrix, beside the new m × m storage)
    UpdateBuffer<Scalar> out;
    extendUpdateMatrix(m_values.data(), m_layout, m_rows, out, runs);
    m_values.swap(out);
    m_layout.clear();
  }
  /** Forgets the layout: the storage (and capacity) stays, its values no longer describe any
    * matrix (a spare, to be given new values by resize()). */
  void discardLayout() { m_layout.clear(); }
  /** Bytes held. */
  Index bytes() const {
    return Index(m_values.capacity() * sizeof(Scalar) + m_layout.capacity() * sizeof(Index));
  }

 private:
  void dropIdentity() {
    bool identity = Index(m_layout.size()) == m_rows;
    for (Index p = 0; p < Index(m_layout.size()) && identity; ++p) identity = m_layout[p] == p;
    if (identity) m_layout.clear();
  }
  UpdateBuffer<Scalar> m_values;
  std::vector<Index> m_layout;  ///< stored row -> row of the matrix (increasing); empty: the identity
  Index m_rows = 0;             ///< the matrix's rows when the layout is not its own
};

/** \internal The dense block of a supernode: rows() × cols() values, column-major, in storage
  * that keeps its capacity when the block shrinks or changes shape. An update that reshapes a
  * supernode sets its previous block aside and reuses the blocks of earlier calls
  * (FactorStructureBackup::takeSpare()): with Eigen's Matrix only a block of exactly the same
  * size could be reused, and a seam one vertex longer gave the root separator a new allocation,
  * whose first touch cost about a page fault per 4 KiB (igea's 738-column root: ~1,000 faults,
  * 18 ms, three times its refactorization). Entries are not initialized by resize(). */
template <typename Scalar>
class SupernodeBlock {
 public:
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;

  /** The number of rows of the block (the supernode's rows). */
  Index rows() const { return m_rows; }
  /** The number of columns of the block (the supernode's columns). */
  Index cols() const { return m_cols; }
  /** rows() × cols(). */
  Index size() const { return m_rows * m_cols; }
  /** The number of values the storage holds without reallocating. */
  Index capacity() const { return Index(m_data.capacity()); }
  /** The values, column-major with leading dimension rows(). */
  Scalar* data() { return m_data.data(); }
  /** The values, column-major with leading dimension rows(). */
  const Scalar* data() const { return m_data.data(); }
  /** The entry in row \a i and column \a j. */
  Scalar& operator()(Index i, Index j) { return m_data[std::size_t(i + j * m_rows)]; }
  /** The entry in row \a i and column \a j. */
  const Scalar& operator()(Index i, Index j) const { return m_data[std::size_t(i + j * m_rows)]; }
  /** The block as an Eigen matrix expression (no copy). */
  Map<Dense> matrix() { return Map<Dense>(data(), m_rows, m_cols); }
  /** The block as an Eigen matrix expression (no copy). */
  Map<const Dense> matrix() const { return Map<const Dense>(data(), m_rows, m_cols); }
  /** Column \a j as an Eigen expression (no copy). */
  typename Map<Dense>::ColXpr col(Index j) { return matrix().col(j); }
  /** Column \a j as an Eigen expression (no copy). */
  typename Map<const Dense>::ConstColXpr col(Index j) const { return matrix().col(j); }

  /** Gives the block \a rows × \a cols values; the previous values are not kept (nor copied when
    * the storage grows). */
  void resize(Index rows, Index cols) {
    const std::size_t count = std::size_t(rows * cols);
    if (count > m_data.capacity()) UpdateBuffer<Scalar>().swap(m_data);
    m_data.resize(count);
    m_rows = rows;
    m_cols = cols;
  }
  /** Makes room for \a count values (the block and its values unchanged). */
  void reserve(Index count) { m_data.reserve(std::size_t(count)); }
  /** Copies an Eigen matrix in. */
  template <typename Derived>
  SupernodeBlock& operator=(const MatrixBase<Derived>& other) {
    const Dense copy = other;  // (it may read this block)
    resize(copy.rows(), copy.cols());
    matrix() = copy;
    return *this;
  }
  /** Exchanges the storage and shape with \a other (no copy). */
  void swap(SupernodeBlock& other) {
    m_data.swap(other.m_data);
    std::swap(m_rows, other.m_rows);
    std::swap(m_cols, other.m_cols);
  }

 private:
  UpdateBuffer<Scalar> m_data;
  Index m_rows = 0, m_cols = 0;
};

/** \internal One supernode: columns firstCol .. firstCol+ncols-1 of L, stored as a dense
  * column-major block of rows.size() × ncols values (lower trapezoid meaningful). */
template <typename Scalar, typename StorageIndex>
struct Supernode {
  Index firstCol = 0;                        ///< first column (in the permuted numbering)
  Index ncols = 0;                           ///< number of columns
  std::vector<StorageIndex> rows;            ///< its columns first, then the rows below, increasing
  std::vector<StorageIndex> parentPosition;  ///< for each row below, its position in the parent's rows
  SupernodeBlock<Scalar> values;             ///< the dense block L(rows, columns)
  /** Entries of the input matrix scattered into \c values: value source[k] goes to offset
    * target[k] of the block; a negative target ~t means "conjugate, then store at t". Listed
    * column by column (increasing local column), which the Dirichlet coupling relies on. */
  std::vector<Index> assemblySource, assemblyTarget;

  Index nrows() const { return Index(rows.size()); }
  Index below() const { return Index(rows.size()) - ncols; }
  /** Flops of this supernode's dense work: potrf, trsm and the update-matrix herk. */
  double flops() const { return flopsOf(ncols, below()); }
  /** Flops of the dense work of a supernode of \a columns columns and \a below rows below them. */
  static double flopsOf(Index columns, Index below) {
    const double c = double(columns), m = double(below);
    return c * c * c / 3.0 + m * c * c + m * m * c;
  }
};

/** \internal The whole factor: the supernodes in postorder, and their tree. */
template <typename Scalar, typename StorageIndex>
struct SupernodalFactor {
  typedef Supernode<Scalar, StorageIndex> Node;
  /** The number of positions: the columns of every supernode and the free positions after them
    * (SupernodalFactor::ownedEnd()); n >= the number of dofs. At a free position colToSuper
    * holds its owner; no row list names one. */
  Index n = 0;
  std::vector<Node> nodes;
  std::vector<StorageIndex> parent;         ///< supernodal elimination tree, -1 for roots
  std::vector<StorageIndex> firstChild, nextSibling;  ///< children lists in increasing order
  std::vector<StorageIndex> firstDescendant;          ///< subtree of s = [firstDescendant[s], s]
  std::vector<StorageIndex> colToSuper;
  /** The last row of each supernode (kept by the renumberings of insertDofs()/mergeDofs(), which
    * skip the supernodes that lie wholly below the first column that moves without reading them). */
  std::vector<StorageIndex> lastRow;

  Index count() const { return Index(nodes.size()); }
  /** The end of the positions supernode \a s owns: its columns, then its free positions (room
    * for the copies of later insertions, which no row names), up to the next supernode's first
    * column (n for the last). */
  Index ownedEnd(Index s) const { return s + 1 < count() ? nodes[s + 1].firstCol : n; }
  /** The free positions of supernode \a s. */
  Index freePositions(Index s) const { return ownedEnd(s) - nodes[s].firstCol - nodes[s].ncols; }

  /** Sets lastRow[s] from supernode s's rows (after they changed). */
  void noteLastRow(Index s) { lastRow[s] = nodes[s].rows.empty() ? StorageIndex(-1) : nodes[s].rows.back(); }

  /** Builds the supernodes from a partition (values left empty). */
  void build(const SupernodalPartition<StorageIndex>& part) {
    const Index ns = part.count();
    n = Index(part.colToSuper.size());
    nodes.assign(ns, Node());
    parent = part.parent;
    colToSuper = part.colToSuper;
    firstChild.assign(ns, StorageIndex(-1));
    nextSibling.assign(ns, StorageIndex(-1));
    firstDescendant.resize(ns);
    for (Index s = 0; s < ns; ++s) firstDescendant[s] = StorageIndex(s);
    for (Index s = ns - 1; s >= 0; --s) {
      if (parent[s] == -1) continue;
      nextSibling[s] = firstChild[parent[s]];
      firstChild[parent[s]] = StorageIndex(s);
    }
    for (Index s = 0; s < ns; ++s)
      if (parent[s] != -1 && firstDescendant[s] < firstDescendant[parent[s]])
        firstDescendant[parent[s]] = firstDescendant[s];
    for (Index s = 0; s < ns; ++s) {
      Node& node = nodes[s];
      node.firstCol = part.start[s];
      node.ncols = part.start[s + 1] - part.start[s];
      node.rows.assign(part.rowIdx.begin() + part.rowPtr[s], part.rowIdx.begin() + part.rowPtr[s + 1]);
    }
    lastRow.resize(ns);
    for (Index s = 0; s < ns; ++s) noteLastRow(s);
    std::vector<StorageIndex> position(n, StorageIndex(-1));
    for (Index p = 0; p < ns; ++p) {
      const Node& pn = nodes[p];
      for (Index k = 0; k < pn.nrows(); ++k) position[pn.rows[k]] = StorageIndex(k);
      for (Index c = firstChild[p]; c != -1; c = nextSibling[c]) {
        Node& cn = nodes[c];
        cn.parentPosition.resize(cn.below());
        for (Index k = 0; k < cn.below(); ++k) cn.parentPosition[k] = position[cn.rows[cn.ncols + k]];
      }
    }
  }

  /** Number of stored entries of L (lower trapezoids, explicit zeros of relaxation included). */
  Index nonZeros() const {
    Index nnz = 0;
    for (const Node& node : nodes) nnz += node.ncols * (node.ncols + 1) / 2 + node.ncols * node.below();
    return nnz;
  }

  /** Flops of a full numeric factorization. */
  double flops() const {
    double f = 0;
    for (const Node& node : nodes) f += node.flops();
    return f;
  }

  /** The largest number of rows of any supernode (workspace of the solve). */
  Index maxRows() const {
    Index m = 0;
    for (const Node& node : nodes) m = (std::max)(m, node.nrows());
    return m;
  }
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_FACTOR_H
