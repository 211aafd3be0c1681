// DofUpdates.h — the bookkeeping of in-place updates (paper §3.3, Algorithm 3, and §4.1):
// checking the indices a user passes, finding the dirty supernodes (the union of the
// supernodal-etree paths from the changed columns to the roots), the flop count of a partial
// refactorization, the statistics of an update, and the right-hand side of a Dirichlet solve.
//
// Removing dofs B (paper eq. 14) turns their rows and columns into those of the identity; the
// factor of that matrix, A^B, has unit columns at B (Appendix A). A column whose value changes
// makes dirty its own supernode and, through symmetry, the supernodes of the columns where its
// entries are assembled (its neighbours earlier in the elimination order); every ancestor of a
// dirty supernode is dirty. A removed dof's row may also sit, in the factor's structure, in
// supernodes outside those paths (amalgamation, a cut's duplicated pattern): supernodesHoldingRow()
// finds them, so that the removal can make that row exactly zero there too.

#ifndef EIGEN_UPDATABLE_CHOLESKY_DOF_UPDATES_H
#define EIGEN_UPDATABLE_CHOLESKY_DOF_UPDATES_H

#include <algorithm>
#include <vector>

namespace Eigen {

/** \ingroup UpdatableCholesky_Module
  * \brief The algorithm an update uses (see UpdatableSupernodalLLT::setUpdateRoute()). */
enum class UpdateRoute {
  Automatic,               ///< the cheapest route by the cost model (default)
  PartialRefactorization,  ///< recompute the dirty supernodes only (Algorithm 3); exact
  LowRank,                 ///< removeDofs: fold L(I,B) into L(I,I) along the paths of B; updateColumns/insertDofs/
                           ///< mergeDofs/restoreDofs: as Mixed
  Refactorization,         ///< recompute every supernode
  Mixed                    ///< removeDofs: low-rank below, partial refactorization of the top; updateColumns/
                           ///< insertDofs/mergeDofs: each dirty supernode refactored or updated by signed low-rank
                           ///< folds (LowRankTopUpdate.h); restoreDofs: likewise, each restored row and column going
                           ///< from the identity's to the matrix's
};

/** \ingroup UpdatableCholesky_Module
  * \brief What the last update did (UpdatableSupernodalLLT::lastUpdate()). */
struct UpdateStatistics {
  UpdateRoute route = UpdateRoute::Automatic;  ///< the route taken
  Index changedColumns = 0;    ///< columns whose values changed
  Index dirtySupernodes = 0;   ///< supernodes recomputed
  Index dirtyColumns = 0;      ///< columns of L recomputed
  double flops = 0;            ///< dense flops spent
  double flopFraction = 0;     ///< flops / flops of a full factorization
  double seconds = 0;          ///< wall time of the update call, its checks of the input included
  /** \name Where insertDofs(), mergeDofs() and updateColumns() spent #seconds (zero after
    * removeDofs() and restoreDofs(); the rest of #seconds is the commit, or the revert of a
    * failed update, after the numeric work)
    * @{ */
  double compareSeconds = 0;    ///< checking the input, comparing the new matrix with the current one and its pattern
  double structureSeconds = 0;  ///< the new layout, marking the dirty supernodes, relabeling the factor, its input maps and the permutation (Algorithm 4's symbolic part)
  double planSeconds = 0;       ///< choosing which dirty supernodes are refactored and which are folded
  double numericSeconds = 0;    ///< refactorizations and folds
  /** @} */
  /** insertDofs()/mergeDofs(): columns of L whose position in the factor's numbering moved. When
    * the origins' supernodes have free positions for the copies (and always for a merge), only
    * the columns after the origins (merged dofs) inside those supernodes; else the layout is
    * made anew, with room for later cuts, and most columns move. */
  Index movedPositions = 0;
  /** insertDofs()/mergeDofs(): supernodes not recomputed whose row indices were renumbered. */
  Index renumberedSupernodes = 0;
};

namespace internal {
namespace updatable_cholesky {

/** \internal Per-supernode scratch space of the updates, allocated once per analysis and left
  * clean (all zero / empty) after every use, so that an update costs nothing proportional to the
  * size of the matrix. */
template <typename Scalar>
struct UpdateWorkspace {
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  std::vector<char> mark;                                   ///< dirty marks
  std::vector<Index> rank, local, first;                    ///< per-supernode ranks, first columns (cost model)
  std::vector<double> cost;                                 ///< per-supernode low-rank flops (cost model)
  std::vector<Index> foldBound;  ///< 1 + position of a refactored child of a folded supernode in the plan's boundary list (folding plans), else 0
  std::vector<char> eligible;    ///< folding plans (insertions, restores): a dirty supernode may be folded (zero for the others between calls)
  std::vector<Index> rankColumns, likelyRankColumns, rowRank;  ///< folding plans: per dirty supernode (zero between calls)
  std::vector<Matrix<Scalar, Dynamic, Dynamic> > carried;   ///< W passed to the parent
  std::vector<Matrix<Scalar, Dynamic, Dynamic> > carriedNegative;  ///< downdate part passed up (folding routes)
  /** folding plans: per dirty supernode, the rank its own input change adds (two per changed
    * or new column) and the first of those columns (its position in the supernode); zero between calls */
  std::vector<Index> ownRank, ownStart;
  /** folding routes: per folded supernode, its own input change split as P P^H − N N^H (rows: the
    * supernode's rows), and where each column of P (and of N) starts to be non-zero */
  std::vector<Matrix<Scalar, Dynamic, Dynamic> > ownPositive, ownNegative;
  std::vector<std::vector<Index> > ownPositiveStart, ownNegativeStart;
  /** folding routes: the W columns of a fold by one signed rotation sweep (foldIntoSupernode()),
    * kept between folds so that a small supernode's fold allocates nothing for them */
  std::vector<Scalar> sweep;
  void resize(Index supernodes) {
    mark.assign(supernodes, 0);
    rank.assign(supernodes, 0);
    local.assign(supernodes, 0);
    first.assign(supernodes, 0);
    cost.assign(supernodes, 0.0);
    foldBound.assign(supernodes, 0);
    eligible.assign(supernodes, 0);
    rankColumns.assign(supernodes, 0);
    likelyRankColumns.assign(supernodes, 0);
    rowRank.assign(supernodes, 0);
    ownRank.assign(supernodes, 0);
    ownStart.assign(supernodes, 0);
    ownPositive.clear();
    ownPositive.resize(supernodes);
    ownNegative.clear();
    ownNegative.resize(supernodes);
    ownPositiveStart.clear();
    ownPositiveStart.resize(supernodes);
    ownNegativeStart.clear();
    ownNegativeStart.resize(supernodes);
    carried.clear();
    carried.resize(supernodes);
    carriedNegative.clear();
    carriedNegative.resize(supernodes);
  }
};

/** \internal Checks a list of dof indices: every index in [0,n), none repeated (found by
  * sorting a copy when the list is short, so that the cost is that of the list, not of n; by
  * flags when it holds more than n/16 indices, where a sort costs more than a pass over n).
  * On success fills \a out; otherwise returns false and leaves a reason in \a why. */
template <typename Indices, typename StorageIndex>
bool checkIndices(const Indices& indices, Index n, std::vector<StorageIndex>& out, const char*& why) {
  const Index count = Index(indices.size());
  out.resize(count);
  for (Index k = 0; k < count; ++k) {
    const Index i = Index(indices[k]);
    if (i < 0 || i >= n) {
      why = "index out of range";
      return false;
    }
    out[k] = StorageIndex(i);
  }
  bool repeated = false;
  if (count * 16 < n) {  // few: sorted
    std::vector<StorageIndex> sorted(out);
    std::sort(sorted.begin(), sorted.end());
    repeated = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
  } else {  // many (a long seam): flagged, cheaper than a sort
    std::vector<char> seen(n, 0);
    for (Index k = 0; k < count && !repeated; ++k) {
      repeated = seen[out[k]] != 0;
      seen[out[k]] = 1;
    }
  }
  if (repeated) {
    why = "index repeated";
    return false;
  }
  return true;
}

/** \internal Marks supernode \a s and its ancestors up to the first marked one, appending them to \a dirty. */
template <typename Scalar, typename StorageIndex>
void markPathToRoot(const SupernodalFactor<Scalar, StorageIndex>& f, Index s, std::vector<char>& mark,
                    std::vector<Index>& dirty) {
  for (; s != -1 && !mark[s]; s = f.parent[s]) {
    mark[s] = 1;
    dirty.push_back(s);
  }
}

/** \internal Calls visit(y, a) for every entry A(y, d) = a, y != d, of column \a d of the current
  * matrix (user numbering), read from the store: its own outer vector d, and the outer vectors
  * that \a transposed lists for d. The cost is that of column d and of those outer vectors. */
template <bool RowMajor, typename Scalar, typename StorageIndex, typename Visit>
void forEachColumnEntry(const InputStore<Scalar, StorageIndex>& store, const TransposedPattern<StorageIndex>& transposed,
                        Index d, Visit&& visit) {
  for (Index p = store.begin[d]; p < store.end[d]; ++p) {  // outer d, inner y: A(y, d), or A(d, y) row-major
    const Index y = store.inner[p];
    if (y != d) visit(y, RowMajor ? Scalar(numext::conj(store.values[p])) : store.values[p]);
  }
  for (Index q = transposed.begin[d]; q < transposed.end[d]; ++q) {  // outer x, inner d: A(d, x), or A(x, d) row-major
    const Index x = transposed.pool[q];
    for (Index p = store.begin[x]; p < store.end[x]; ++p)
      if (Index(store.inner[p]) == d) {
        visit(x, RowMajor ? store.values[p] : Scalar(numext::conj(store.values[p])));
        break;
      }
  }
}

/** \internal The dirty supernodes, increasing, for the changed permuted columns \a columns:
  * their supernodes, those of their neighbours (read from the store and its transposed pattern;
  * \a perm and \a pinv: the permutation and its inverse), and all ancestors. */
template <typename Scalar, typename StorageIndex>
std::vector<Index> dirtySupernodes(const SupernodalFactor<Scalar, StorageIndex>& f,
                                   const InputStore<Scalar, StorageIndex>& store,
                                   const TransposedPattern<StorageIndex>& transposed, const StorageIndex* perm,
                                   const StorageIndex* pinv, const std::vector<StorageIndex>& columns,
                                   UpdateWorkspace<Scalar>& ws) {
  std::vector<char>& mark = ws.mark;
  std::vector<Index> dirty;
  auto markPath = [&](Index s) { markPathToRoot(f, s, mark, dirty); };
  for (StorageIndex k : columns) {
    markPath(f.colToSuper[k]);
    const Index d = pinv[k];
    for (Index p = store.begin[d]; p < store.end[d]; ++p) markPath(f.colToSuper[perm[store.inner[p]]]);
    for (Index q = transposed.begin[d]; q < transposed.end[d]; ++q) markPath(f.colToSuper[perm[transposed.pool[q]]]);
  }
  std::sort(dirty.begin(), dirty.end());
  for (Index s : dirty) mark[s] = 0;
  return dirty;
}

/** \internal Appends to \a out the supernodes that hold permuted row \a b below their columns
  * (the row subtree of b in the factor's structure, which may hold more than the row subtree of
  * the current matrix's pattern: supernodes are amalgamated, and a cut keeps the duplicated
  * pattern). A supernode's rows below its columns lie in its parent's columns or rows, so they
  * form a tree hanging from b's supernode, searched through the children. \a stack: scratch. */
template <typename Scalar, typename StorageIndex>
void supernodesHoldingRow(const SupernodalFactor<Scalar, StorageIndex>& f, Index b, std::vector<Index>& out,
                          std::vector<Index>& stack) {
  stack.assign(1, f.colToSuper[b]);
  while (!stack.empty()) {
    const Index s = stack.back();
    stack.pop_back();
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) {
      const auto& rows = f.nodes[c].rows;
      if (f.lastRow[c] < StorageIndex(b) ||
          !std::binary_search(rows.begin() + f.nodes[c].ncols, rows.end(), StorageIndex(b)))
        continue;
      out.push_back(c);
      stack.push_back(c);
    }
  }
}

/** \internal Dense flops of recomputing the given supernodes (reduced fronts counted on their
  * kept rows and columns when \a removed, flags by permuted column, is given). */
template <typename Scalar, typename StorageIndex>
double supernodeFlops(const SupernodalFactor<Scalar, StorageIndex>& f, const std::vector<Index>& nodes,
                      const char* removed = nullptr) {
  double flops = 0;
  for (Index s : nodes) flops += frontFlops(f.nodes[s], removed);
  return flops;
}

/** \internal Dense flops of a full refactorization: \a total (all fronts whole) while few dofs are
  * removed, else counted with the reduced fronts (\a removed flags by permuted column, \a count
  * of them set). */
template <typename Scalar, typename StorageIndex>
double refactorizationFlops(const SupernodalFactor<Scalar, StorageIndex>& f, double total, const char* removed,
                            Index count) {
  if (!removed || 8 * count < f.n) return total;
  double flops = 0;
  for (const auto& node : f.nodes) flops += frontFlops(node, removed);
  return flops;
}

/** \internal The Dirichlet coupling in the permuted numbering: X(i,:) -= C(i,k) X(k,:) for every
  * removed permuted column k in \a removedColumns and every kept row i (\a removed flags the
  * removed permuted indices), with C = P A P^T read from the store (\a perm, \a pinv: P and its
  * inverse). X (leading dimension ldx, \a rhs columns) holds the known values in the removed
  * rows. Only the columns of the removed dofs are read: the cost is that of their entries, not
  * of the matrix. */
template <bool RowMajor, typename Scalar, typename StorageIndex>
void subtractDirichletCoupling(const InputStore<Scalar, StorageIndex>& store,
                               const TransposedPattern<StorageIndex>& transposed, const StorageIndex* perm,
                               const StorageIndex* pinv, const char* removed,
                               const std::vector<StorageIndex>& removedColumns, Scalar* X, Index ldx, Index rhs) {
  for (StorageIndex k : removedColumns)
    forEachColumnEntry<RowMajor>(store, transposed, pinv[k], [&](Index y, const Scalar& c) {  // C(perm[y], k) = c
      const Index i = perm[y];
      if (removed[i]) return;
      for (Index r = 0; r < rhs; ++r) X[i + r * ldx] -= c * X[k + r * ldx];
    });
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_DOF_UPDATES_H
