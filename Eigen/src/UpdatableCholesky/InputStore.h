// InputStore.h — the solver's copy of the matrix it factors: the kept (UpLo) triangle only, by
// outer vector in the user's orientation and numbering, in a pool where an outer vector may be
// replaced by appending its new entries (paper §4.2: a cut touches a few columns, so the copy
// should cost what they cost, not what the whole matrix costs).
//
// The supernodes' assembly maps hold positions in this pool. An insertion (insertDofs) or the
// merge of trailing dofs rewrites only the outer vectors whose kept entries differ; every other
// entry keeps its position, so the maps of the supernodes that do not own a rewritten entry stay
// valid as they are. The positions a rewrite leaves behind are garbage; the pool is compacted
// (and every map renewed) when garbage outgrows the live entries.
//
// TransposedPattern is the store's pattern the other way round (for each dof, the outer vectors
// that hold it), kept in the same way; together they give every neighbour of a dof, for the
// dirty-path marking of updateColumns()/removeDofs(), the Dirichlet coupling and the pattern
// checks of insertDofs()/mergeDofs().

#ifndef EIGEN_UPDATABLE_CHOLESKY_INPUT_STORE_H
#define EIGEN_UPDATABLE_CHOLESKY_INPUT_STORE_H

#include <algorithm>
#include <utility>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal True when entry (outer \a o, inner \a i) of a matrix of the given orientation lies in
  * the triangle \a UpLo (Lower: row >= col) that the solver reads. */
template <int UpLo, bool RowMajor>
inline bool inKeptTriangle(Index o, Index i) {
  const Index row = RowMajor ? o : i, col = RowMajor ? i : o;
  return UpLo == Lower ? row >= col : row <= col;
}

/** \internal The kept triangle of the current matrix: outer vector o holds the pool entries
  * [begin[o], end[o]) in the order of the user's matrix. */
template <typename Scalar, typename StorageIndex>
struct InputStore {
  Index rows = 0, cols = 0;
  std::vector<Index> begin, end;    ///< per outer vector, its range in the pool
  std::vector<StorageIndex> inner;  ///< pool: inner indices
  std::vector<Scalar> values;       ///< pool: values
  Index live = 0;                   ///< entries in use (the rest of the pool is garbage)

  Index outerSize() const { return Index(begin.size()); }
  /** True when the pool holds more garbage than live entries (compact at the next rewrite). */
  bool wasteful() const { return Index(inner.size()) > 2 * live + 16; }

  /** A compact copy of the kept triangle of the compressed matrix \a a. */
  template <int UpLo, typename CompressedMatrix>
  void assign(const CompressedMatrix& a) {
    constexpr bool rowMajor = bool(CompressedMatrix::IsRowMajor);
    rows = a.rows();
    cols = a.cols();
    const Index no = a.outerSize();
    const auto* outer = a.outerIndexPtr();
    const auto* in = a.innerIndexPtr();
    const auto* val = a.valuePtr();
    begin.resize(no);
    end.resize(no);
    inner.clear();
    values.clear();
    // (with headroom for the outer vectors that later updates rewrite at the end of the pool:
    // the first cuts after compute() then do not move it)
    const Index expected = a.nonZeros() / 2 + no;
    inner.reserve(expected + expected / 8);
    values.reserve(expected + expected / 8);
    for (Index o = 0; o < no; ++o) {
      begin[o] = Index(inner.size());
      for (Index p = outer[o]; p < outer[o + 1]; ++p)
        if (inKeptTriangle<UpLo, rowMajor>(o, in[p])) {
          inner.push_back(StorageIndex(in[p]));
          values.push_back(val[p]);
        }
      end[o] = Index(inner.size());
    }
    live = Index(inner.size());
  }

  /** True when the kept triangle of \a a (compressed) has exactly the stored pattern. */
  template <int UpLo, typename CompressedMatrix>
  bool matchesPattern(const CompressedMatrix& a) const {
    constexpr bool rowMajor = bool(CompressedMatrix::IsRowMajor);
    if (a.rows() != rows || a.cols() != cols || a.outerSize() != outerSize()) return false;
    const auto* outer = a.outerIndexPtr();
    const auto* in = a.innerIndexPtr();
    for (Index o = 0; o < outerSize(); ++o) {
      Index q = begin[o];
      for (Index p = outer[o]; p < outer[o + 1]; ++p) {
        if (!inKeptTriangle<UpLo, rowMajor>(o, in[p])) continue;
        if (q == end[o] || inner[q] != in[p]) return false;
        ++q;
      }
      if (q != end[o]) return false;
    }
    return true;
  }

  /** Copies the kept values of \a a, whose kept pattern matches (matchesPattern()). */
  template <int UpLo, typename CompressedMatrix>
  void copyValues(const CompressedMatrix& a) {
    constexpr bool rowMajor = bool(CompressedMatrix::IsRowMajor);
    const auto* outer = a.outerIndexPtr();
    const auto* in = a.innerIndexPtr();
    const auto* val = a.valuePtr();
    for (Index o = 0; o < outerSize(); ++o) {
      Index q = begin[o];
      for (Index p = outer[o]; p < outer[o + 1]; ++p)
        if (inKeptTriangle<UpLo, rowMajor>(o, in[p])) values[q++] = val[p];
    }
  }

  /** Bytes held. */
  Index bytes() const {
    return Index((begin.capacity() + end.capacity()) * sizeof(Index) + inner.capacity() * sizeof(StorageIndex) +
                 values.capacity() * sizeof(Scalar));
  }
};

/** \internal The other half of the store's pattern: for each dof y, the dofs x != y whose outer
  * vector in the store holds an entry at inner index y. With the store's own outer vector of y,
  * it lists every neighbour of y, in the user's numbering, which an insertion does not change: a
  * cut rewrites only the lists of the changed dofs and adds those of the copies (appended to the
  * pool, the old range becoming garbage, as in the store), instead of renumbering a pattern of
  * the whole matrix. */
template <typename StorageIndex>
struct TransposedPattern {
  std::vector<Index> begin, end;   ///< per dof, its range in the pool
  std::vector<StorageIndex> pool;  ///< the listed dofs
  Index live = 0;                  ///< entries in use (the rest of the pool is garbage)

  /** A list replaced (or dropped) since beginRewrites(), and its previous range. */
  struct Rewrite {
    Index dof, begin, end;
  };
  std::vector<Rewrite> rewrites;
  Index oldPool = 0, oldSize = 0, oldLive = 0;  ///< the extent before beginRewrites()
  std::vector<StorageIndex> targets, list, sources;  ///< scratch of followInPlaceRewrite()
  std::vector<Index> slot;  ///< scratch of followInPlaceRewrite(), by dof (read only at its targets)

  Index size() const { return Index(begin.size()); }
  /** True when the pool holds more garbage than live entries. */
  bool wasteful() const { return Index(pool.size()) > 2 * live + 16; }
  /** True when \a x is listed for \a y. */
  bool lists(Index y, Index x) const {
    for (Index q = begin[y]; q < end[y]; ++q)
      if (Index(pool[q]) == x) return true;
    return false;
  }
  /** True when the store holds an entry at (u, v), u != v, in either orientation. */
  bool holds(Index u, Index v) const { return lists(u, v) || lists(v, u); }

  /** Builds the lists of \a store from scratch, compactly. */
  template <typename Scalar>
  void assign(const InputStore<Scalar, StorageIndex>& store) {
    const Index n = store.outerSize();
    begin.assign(n, 0);
    end.resize(n);
    for (Index x = 0; x < n; ++x)
      for (Index p = store.begin[x]; p < store.end[x]; ++p)
        if (Index(store.inner[p]) != x) ++begin[store.inner[p]];
    Index sum = 0;
    for (Index y = 0; y < n; ++y) {
      const Index count = begin[y];
      begin[y] = end[y] = sum;
      sum += count;
    }
    pool.reserve(sum + sum / 8 + n);  // (headroom for rewrites, as the store's)
    pool.resize(sum);
    for (Index x = 0; x < n; ++x)
      for (Index p = store.begin[x]; p < store.end[x]; ++p) {
        const Index y = store.inner[p];
        if (y != x) pool[end[y]++] = StorageIndex(x);
      }
    live = sum;
    rewrites.clear();
  }

  /** Starts replacing lists in place (rewrite()): the dofs become \a n (the lists of new ones are
    * empty, those of dofs beyond \a n are dropped); revert() undoes everything since. */
  void beginRewrites(Index n) {
    oldPool = Index(pool.size());
    oldSize = size();
    oldLive = live;
    rewrites.clear();
    for (Index y = n; y < oldSize; ++y) {
      rewrites.push_back(Rewrite{y, begin[y], end[y]});
      live -= end[y] - begin[y];
    }
    begin.resize(n, 0);
    end.resize(n, 0);
  }
  /** Replaces the list of \a y by the \a count dofs at \a list (not in the pool). */
  void rewrite(Index y, const StorageIndex* list, Index count) {
    rewrites.push_back(Rewrite{y, begin[y], end[y]});
    live += count - (end[y] - begin[y]);
    begin[y] = Index(pool.size());
    pool.insert(pool.end(), list, list + count);
    end[y] = Index(pool.size());
  }
  /** Follows a rewrite of \a store in place, where the dofs below min(\a previous, new size)
    * kept their numbers (an insertion appends dofs, a merge of trailing dofs drops them): the
    * dofs in \a changedList (flagged in \a changed, by previous dof) that stay, and the new ones,
    * get their lists anew. Each keeps its neighbours that did not change and gets the changed
    * ones from the new store; every other list stays as it is. revert() undoes it. */
  template <typename Scalar>
  void followInPlaceRewrite(const InputStore<Scalar, StorageIndex>& store, const std::vector<StorageIndex>& changedList,
                            const std::vector<char>& changed, Index previous) {
    const Index total = store.outerSize();
    auto isChanged = [&](Index x) { return x >= previous || changed[x]; };
    targets.clear();
    if (Index(changedList.size()) * 16 < total) {  // few: sorted
      for (StorageIndex o : changedList)
        if (o < total) targets.push_back(o);
      std::sort(targets.begin(), targets.end());
    } else {  // many (a long seam): read off the flags in order, cheaper than a sort
      for (Index x = 0; x < (std::min)(previous, total); ++x)
        if (changed[x]) targets.push_back(StorageIndex(x));
    }
    for (Index x = previous; x < total; ++x) targets.push_back(StorageIndex(x));
    // the pairs (y, x) where the outer vector of x holds y, both changed or new (so y is a target
    // too), bucketed by y with x increasing: counted, then placed (a counting sort)
    slot.resize(total);
    for (StorageIndex y : targets) slot[y] = 0;
    auto forEachPair = [&](auto&& visit) {
      for (StorageIndex x : targets)
        for (Index p = store.begin[x]; p < store.end[x]; ++p) {
          const StorageIndex y = store.inner[p];
          if (y != x && isChanged(y)) visit(y, x);
        }
    };
    forEachPair([&](StorageIndex y, StorageIndex) { ++slot[y]; });
    Index placed = 0;
    for (StorageIndex y : targets) {
      const Index count = slot[y];
      slot[y] = placed;
      placed += count;
    }
    sources.resize(placed);
    forEachPair([&](StorageIndex y, StorageIndex x) { sources[slot[y]++] = x; });  // (slot[y]: the end of y's bucket)
    beginRewrites(total);
    Index from = 0;
    for (StorageIndex y : targets) {
      list.clear();
      if (y < previous)  // its unchanged neighbours stay
        for (Index q = begin[y]; q < end[y]; ++q)
          if (!changed[pool[q]]) list.push_back(pool[q]);
      list.insert(list.end(), sources.begin() + from, sources.begin() + slot[y]);
      from = slot[y];
      rewrite(y, list.data(), Index(list.size()));
    }
  }

  /** Puts back the lists as they were at beginRewrites(). */
  void revert() {
    begin.resize(oldSize, 0);
    end.resize(oldSize, 0);
    for (auto r = rewrites.rbegin(); r != rewrites.rend(); ++r) {
      begin[r->dof] = r->begin;
      end[r->dof] = r->end;
    }
    pool.resize(oldPool);
    live = oldLive;
    rewrites.clear();
  }

  /** Bytes held. */
  Index bytes() const {
    return Index((begin.capacity() + end.capacity()) * sizeof(Index) +
                 (pool.capacity() + targets.capacity() + list.capacity() + sources.capacity()) * sizeof(StorageIndex) +
                 slot.capacity() * sizeof(Index) +
                 rewrites.capacity() * sizeof(Rewrite));
  }
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_INPUT_STORE_H
