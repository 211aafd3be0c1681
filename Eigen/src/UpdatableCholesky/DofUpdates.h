// DofUpdates.h — the bookkeeping of in-place updates (paper §3.3, Algorithm 3, and §4.1):
// checking the indices a user passes, finding the dirty supernodes (the union of the
// supernodal-etree paths from the changed columns to the roots), the flop count of a partial
// refactorization, the statistics of an update, and the right-hand side of a Dirichlet solve.
//
// Removing dofs B (paper eq. 14) turns their rows and columns into those of the identity; the
// factor of that matrix, A^B, has unit columns at B (Appendix A). A column whose value changes
// makes dirty its own supernode and, through symmetry, the supernodes of the columns where its
// entries are assembled (its neighbours earlier in the elimination order); every ancestor of a
// dirty supernode is dirty.

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
  LowRank,                 ///< removeDofs: fold L(I,B) into L(I,I) along the paths of B; insertDofs/mergeDofs: as Mixed
  Refactorization,         ///< recompute every supernode
  Mixed                    ///< removeDofs: low-rank below, partial refactorization of the top; insertDofs/mergeDofs:
                           ///< partial refactorization below, signed low-rank folds on top (LowRankTopUpdate.h)
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
  double seconds = 0;          ///< wall time of the update
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
  std::vector<Matrix<Scalar, Dynamic, Dynamic> > carried;   ///< W passed to the parent
  std::vector<Matrix<Scalar, Dynamic, Dynamic> > carriedNegative;  ///< downdate part passed up (insertions)
  void resize(Index supernodes) {
    mark.assign(supernodes, 0);
    rank.assign(supernodes, 0);
    local.assign(supernodes, 0);
    first.assign(supernodes, 0);
    cost.assign(supernodes, 0.0);
    carried.clear();
    carried.resize(supernodes);
    carriedNegative.clear();
    carriedNegative.resize(supernodes);
  }
};

/** \internal Checks a list of dof indices: every index in [0,n), none repeated (found by
  * sorting a copy, so the cost is that of the list, not of n). On success fills \a out;
  * otherwise returns false and leaves a reason in \a why. */
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
  std::vector<StorageIndex> sorted(out);
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
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

/** \internal The dirty supernodes, increasing, for the changed permuted columns \a columns:
  * their supernodes, those of their neighbours earlier in the order (\a upper holds, for every
  * permuted column k, the rows i < k of C), and all ancestors. */
template <typename Scalar, typename StorageIndex>
std::vector<Index> dirtySupernodes(const SupernodalFactor<Scalar, StorageIndex>& f,
                                   const CompressedPattern<StorageIndex>& upper,
                                   const std::vector<StorageIndex>& columns, UpdateWorkspace<Scalar>& ws) {
  std::vector<char>& mark = ws.mark;
  std::vector<Index> dirty;
  auto markPath = [&](Index s) { markPathToRoot(f, s, mark, dirty); };
  for (StorageIndex k : columns) {
    markPath(f.colToSuper[k]);
    for (Index p = upper.ptr[k]; p < upper.ptr[k + 1]; ++p) markPath(f.colToSuper[upper.idx[p]]);
  }
  std::sort(dirty.begin(), dirty.end());
  for (Index s : dirty) mark[s] = 0;
  return dirty;
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

/** \internal Calls visit(i, c) for every entry C(i,k) = c, i != k, of column \a k of the
  * permuted matrix C = P A P^T, reading the values \a values of the input through the assembly
  * maps of the factor: the rows i > k from the map of k's own column, the rows i < k (listed by
  * \a upper) from the maps of their columns, conjugated. The cost is that of column k and of
  * a binary search per entry, independent of n. */
template <typename Scalar, typename StorageIndex, typename Visit>
void forEachPermutedColumnEntry(const SupernodalFactor<Scalar, StorageIndex>& f,
                                const CompressedPattern<StorageIndex>& upper, const Scalar* values, Index k,
                                Visit&& visit) {
  // The entries of a supernode's map come column by column: the range of local column c.
  auto columnRange = [](const Supernode<Scalar, StorageIndex>& node, Index c, Index& begin, Index& end) {
    const Index nr = node.nrows();
    const auto& t = node.assemblyTarget;
    auto columnOf = [nr](Index target) { return (target >= 0 ? target : ~target) / nr; };
    begin = std::partition_point(t.begin(), t.end(), [&](Index x) { return columnOf(x) < c; }) - t.begin();
    end = std::partition_point(t.begin() + begin, t.end(), [&](Index x) { return columnOf(x) <= c; }) - t.begin();
  };
  auto valueAt = [&](const Supernode<Scalar, StorageIndex>& node, Index q) {
    const Scalar v = values[node.assemblySource[q]];
    return node.assemblyTarget[q] >= 0 ? v : Scalar(numext::conj(v));
  };
  const auto& own = f.nodes[f.colToSuper[k]];
  Index begin, end;
  columnRange(own, k - own.firstCol, begin, end);
  for (Index q = begin; q < end; ++q) {  // C(i,k), i >= k, stored in column k
    const Index target = own.assemblyTarget[q] >= 0 ? own.assemblyTarget[q] : ~own.assemblyTarget[q];
    const Index i = own.rows[target % own.nrows()];
    if (i != k) visit(i, valueAt(own, q));
  }
  for (Index p = upper.ptr[k]; p < upper.ptr[k + 1]; ++p) {  // C(i,k) = conj(C(k,i)), i < k
    const Index i = upper.idx[p];
    const auto& node = f.nodes[f.colToSuper[i]];
    const Index nr = node.nrows(), c = i - node.firstCol;
    const Index position = std::lower_bound(node.rows.begin(), node.rows.end(), StorageIndex(k)) - node.rows.begin();
    const Index wanted = c * nr + position;
    columnRange(node, c, begin, end);
    for (Index q = begin; q < end; ++q) {
      const Index target = node.assemblyTarget[q] >= 0 ? node.assemblyTarget[q] : ~node.assemblyTarget[q];
      if (target == wanted) visit(i, Scalar(numext::conj(valueAt(node, q))));
    }
  }
}

/** \internal The Dirichlet coupling in the permuted numbering: X(i,:) -= C(i,k) X(k,:) for every
  * removed permuted column k in \a removedColumns and every kept row i (\a removed flags the
  * removed permuted indices). X (leading dimension ldx, \a rhs columns) holds the known values in
  * the removed rows. Only the columns of the removed dofs are read: the cost is that of their
  * entries, not of the matrix. */
template <typename Scalar, typename StorageIndex>
void subtractDirichletCoupling(const SupernodalFactor<Scalar, StorageIndex>& f,
                               const CompressedPattern<StorageIndex>& upper, const Scalar* values, const char* removed,
                               const std::vector<StorageIndex>& removedColumns, Scalar* X, Index ldx, Index rhs) {
  for (StorageIndex k : removedColumns)
    forEachPermutedColumnEntry(f, upper, values, Index(k), [&](Index i, const Scalar& c) {
      if (removed[i]) return;
      for (Index r = 0; r < rhs; ++r) X[i + r * ldx] -= c * X[k + r * ldx];
    });
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_DOF_UPDATES_H
