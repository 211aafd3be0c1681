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

#include <vector>

namespace Eigen {

/** \ingroup UpdatableCholesky_Module
  * \brief The algorithm an update uses (see UpdatableSupernodalLLT::setUpdateRoute()). */
enum class UpdateRoute {
  Automatic,               ///< the cheapest route by the cost model (default)
  PartialRefactorization,  ///< recompute the dirty supernodes only (Algorithm 3); exact
  LowRank,                 ///< removeDofs only: fold L(I,B) into L(I,I) along the paths of B
  Refactorization,         ///< recompute every supernode
  Mixed                    ///< removeDofs only: low-rank below, partial refactorization of the top
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
  void resize(Index supernodes) {
    mark.assign(supernodes, 0);
    rank.assign(supernodes, 0);
    local.assign(supernodes, 0);
    first.assign(supernodes, 0);
    cost.assign(supernodes, 0.0);
    carried.clear();
    carried.resize(supernodes);
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

/** \internal y -= A(:,B) g(B) on the rows outside B, i.e. subtracts the Dirichlet coupling A_IB g_B,
  * for the stored UpLo triangle of A (pattern \a pattern, values \a values, row- or column-major)
  * and the removed flags \a removed in A's own numbering. y and g are n×k, column-major. */
template <int UpLo, bool RowMajor, typename Scalar, typename StorageIndex>
void subtractDirichletCoupling(const InputPattern<StorageIndex>& pattern, const Scalar* values, const char* removed,
                          const Scalar* g, Index ldg, Scalar* y, Index ldy, Index k) {
  const Index outerSize = Index(pattern.outer.size()) - 1;
  for (Index o = 0; o < outerSize; ++o)
    for (Index p = pattern.outer[o]; p < pattern.outer[o + 1]; ++p) {
      const Index row = RowMajor ? o : Index(pattern.inner[p]);
      const Index col = RowMajor ? Index(pattern.inner[p]) : o;
      if ((UpLo == Lower && row < col) || (UpLo == Upper && row > col) || row == col) continue;
      const bool rowRemoved = removed[row] != 0, colRemoved = removed[col] != 0;
      if (rowRemoved == colRemoved) continue;
      // A(row,col) = v and A(col,row) = conj(v): the kept index receives the removed one's value.
      for (Index c = 0; c < k; ++c) {
        if (colRemoved)
          y[row + c * ldy] -= values[p] * g[col + c * ldg];
        else
          y[col + c * ldy] -= numext::conj(values[p]) * g[row + c * ldg];
      }
    }
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_DOF_UPDATES_H
