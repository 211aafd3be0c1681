// DofInsertionInput.h — how the input side of the solver follows insertDofs()/mergeDofs()
// without a pass that rebuilds it from the whole new matrix (paper §4.2: only the dirty part
// of the factor is touched; here the same holds for the maps that feed it).
//
// The solver keeps, besides the factor, a copy of the matrix (pattern and values), the strict
// upper pattern of C = P A P^T (for dirty-path marking) and, per supernode, an assembly map
// from the value array into the supernode's block. After a cut or merge:
//   - diffInput() compares the new matrix with the current one column by column; a column whose
//     entries and values are the same (the vast majority) costs a sequential compare, and gives
//     a position map old value position -> new one. Differing columns are matched entry by entry:
//     the dofs they touch are "changed", the entries the old matrix did not have are "fresh".
//   - remapAssemblyMaps(): a clean supernode's entries all survive with the same row positions,
//     so only their source positions are mapped; a dirty supernode's map is rebuilt from its old
//     map (surviving entries, new row positions) plus the fresh entries of its columns.
//   - remapUpperPattern(): an unchanged dof keeps its neighbours (renumbered); a changed one
//     keeps its unchanged neighbours and gets its changed neighbours from the new matrix.
// All of it is O(nnz) in simple sequential passes (no sorting, no scattered rebuild), and the
// scratch arrays live in the solver between calls.

#ifndef EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_INPUT_H
#define EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_INPUT_H

#include <algorithm>
#include <cstring>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal An entry of the new C = P A P^T that the previous matrix did not have: its source
  * position in the new value array (~position when it is read conjugated) and its place in the
  * lower triangle of C (row >= col, new permuted numbering). */
template <typename StorageIndex>
struct FreshEntry {
  Index source;
  StorageIndex row, col;
};

/** \internal The result of diffInput() and the scratch space of the insertions, kept by the
  * solver between calls so that they allocate (and fault in) nothing proportional to nnz: the
  * spare pattern, values and upper pattern are the previous matrix's, swapped back and forth. */
template <typename Scalar, typename StorageIndex>
struct InputDiff {
  std::vector<char> changed;    ///< by current dof: its row/column differs in the new matrix (or it goes)
  std::vector<StorageIndex> posMap;  ///< current value position -> new position, -1 for an entry that is gone
  std::vector<Index> fresh;     ///< new positions of kept-triangle entries the current matrix lacks
  std::vector<StorageIndex> freshOuter;  ///< the outer index (new numbering) of each fresh entry
  std::vector<Index> stamp;     ///< scratch by current dof, all -1 between uses
  std::vector<StorageIndex> position;    ///< scratch by new permuted row, all -1 between uses
  InputPattern<StorageIndex> sparePattern;      ///< buffers for the next matrix's pattern,
  std::vector<Scalar> spareValues;              ///< values
  CompressedPattern<StorageIndex> spareUpper;   ///< and strict upper pattern of C

  /** Bytes held by the scratch arrays and spare buffers. */
  Index bytes() const {
    return Index(changed.capacity() + (stamp.capacity() + fresh.capacity()) * sizeof(Index) +
                 (posMap.capacity() + freshOuter.capacity() + position.capacity()) * sizeof(StorageIndex) +
                 (sparePattern.outer.capacity() + sparePattern.inner.capacity() + spareUpper.idx.capacity()) *
                     sizeof(StorageIndex) +
                 spareUpper.ptr.capacity() * sizeof(Index) + spareValues.capacity() * sizeof(Scalar));
  }
};

/** \internal Compares the new compressed matrix (\a outer, \a inner, \a values, \a total outer
  * vectors) with the current one (\a old, \a oldValues), where \a oldOfNew maps a new dof to its
  * current one (-1 for a copy). Only the UpLo triangle counts. Fills \a d (changed, posMap, fresh);
  * \a allowed(x, y) is asked about each fresh off-diagonal entry (new numbering) and a false
  * answer stops the comparison with false. */
template <int UpLo, bool RowMajor, typename Scalar, typename StorageIndex, typename Allowed>
bool diffInput(const InputPattern<StorageIndex>& old, const Scalar* oldValues, const StorageIndex* outer,
               const StorageIndex* inner, const Scalar* values, Index total,
               const std::vector<StorageIndex>& oldOfNew, const std::vector<StorageIndex>& newOfOld,
               InputDiff<Scalar, StorageIndex>& d, Allowed&& allowed) {
  const Index n = old.cols;
  auto kept = [](Index o, Index i) {  // outer index o, inner index i
    const Index row = RowMajor ? o : i, col = RowMajor ? i : o;
    return UpLo == Lower ? row >= col : row <= col;
  };
  d.changed.assign(n, 0);
  d.stamp.resize(n, -1);
  d.posMap.resize(old.inner.size());
  d.fresh.clear();
  d.freshOuter.clear();
  const StorageIndex* oldOuter = old.outer.data();
  const StorageIndex* oldInner = old.inner.data();
  // new dofs below this one are the current dofs of the same index (all old ones for an insertion)
  Index identityBelow = 0;
  while (identityBelow < total && oldOfNew[identityBelow] == identityBelow) ++identityBelow;
  for (Index x = 0; x < total; ++x) {
    const Index ox = oldOfNew[x];
    const Index nb = outer[x], ne = outer[x + 1];
    if (ox >= 0) {
      const Index ob = oldOuter[ox], oe = oldOuter[ox + 1], len = ne - nb;
      bool same = oe - ob == len;
      if (same && len > 0) {  // bitwise the same indices and values (a sequential compare) ...
        same = std::memcmp(inner + nb, oldInner + ob, len * sizeof(StorageIndex)) == 0 &&
               std::memcmp(values + nb, oldValues + ob, len * sizeof(Scalar)) == 0;
        for (Index k = 0; same && k < len && identityBelow < n; ++k) same = inner[nb + k] < identityBelow;
        if (!same && oe - ob == len) {  // ... or the same dofs and values under the renumbering
          same = true;
          for (Index k = 0; same && k < len; ++k)
            same = oldOfNew[inner[nb + k]] == oldInner[ob + k] && values[nb + k] == oldValues[ob + k];
        }
      }
      if (same) {  // the common case: the column moved as a whole
        for (Index k = 0; k < len; ++k) d.posMap[ob + k] = StorageIndex(nb + k);
        continue;
      }
      for (Index p = ob; p < oe; ++p) {
        d.posMap[p] = -1;
        if (kept(ox, oldInner[p])) d.stamp[oldInner[p]] = p;
      }
    }
    for (Index p = nb; p < ne; ++p) {
      const Index y = inner[p];
      if (!kept(x, y)) continue;
      const Index oy = oldOfNew[y];
      if (ox >= 0 && oy >= 0 && d.stamp[oy] >= 0) {  // an entry the current matrix has
        if (!(values[p] == oldValues[d.stamp[oy]])) d.changed[ox] = d.changed[oy] = 1;
        d.posMap[d.stamp[oy]] = StorageIndex(p);
        d.stamp[oy] = -2;
        continue;
      }
      if (x != y && !allowed(x, y)) {
        if (ox >= 0)
          for (Index q = oldOuter[ox]; q < oldOuter[ox + 1]; ++q) d.stamp[oldInner[q]] = -1;
        return false;
      }
      if (ox >= 0) d.changed[ox] = 1;
      if (oy >= 0) d.changed[oy] = 1;
      d.fresh.push_back(p);
      d.freshOuter.push_back(StorageIndex(x));
    }
    if (ox >= 0)
      for (Index p = oldOuter[ox]; p < oldOuter[ox + 1]; ++p) {
        const Index y = oldInner[p];
        if (d.stamp[y] >= 0) d.changed[ox] = d.changed[y] = 1;  // an entry that is gone
        d.stamp[y] = -1;
      }
  }
  for (Index o = 0; o < n; ++o) {  // merged dofs: every entry of theirs is gone
    if (newOfOld[o] >= 0) continue;
    d.changed[o] = 1;
    for (Index p = oldOuter[o]; p < oldOuter[o + 1]; ++p) {
      d.changed[oldInner[p]] = 1;
      d.posMap[p] = -1;
    }
  }
  return true;
}

/** \internal Renews every supernode's assembly map after relabelFactor(): clean supernodes map
  * their sources through \a posMap; dirty ones (\a dirty) are rebuilt from their old maps (kept in
  * the nodes; old rows, first columns and column counts in \a backup) and the \a fresh entries,
  * column by column like every map. */
template <typename Scalar, typename StorageIndex>
void remapAssemblyMaps(SupernodalFactor<Scalar, StorageIndex>& f, const FactorStructureBackup<Scalar, StorageIndex>& backup,
                       const DofRelabeling<StorageIndex>& relabel, const std::vector<char>& mark,
                       const std::vector<Index>& dirty, const std::vector<StorageIndex>& posMap,
                       std::vector<FreshEntry<StorageIndex> >& fresh, std::vector<StorageIndex>& position) {
  const Index ns = f.count();
  for (Index s = 0; s < ns; ++s) {
    if (mark[s]) continue;
    for (Index& src : f.nodes[s].assemblySource) {
      src = posMap[src];
      eigen_assert(src >= 0 && "remapAssemblyMaps: an entry of a clean supernode is gone");
    }
  }
  std::sort(fresh.begin(), fresh.end(), [&](const FreshEntry<StorageIndex>& a, const FreshEntry<StorageIndex>& b) {
    return f.colToSuper[a.col] < f.colToSuper[b.col];
  });
  position.resize(f.n, StorageIndex(-1));
  std::vector<Index> source, target, order;
  auto next = fresh.begin();
  for (Index s : dirty) {
    auto& node = f.nodes[s];
    const Index nr = node.nrows();
    for (Index k = 0; k < nr; ++k) position[node.rows[k]] = StorageIndex(k);
    const auto& oldRows = backup.rows[s];
    const Index oldNr = Index(oldRows.size()), oldFirst = backup.firstCol[s];
    source.clear();
    target.clear();
    for (Index k = 0; k < Index(node.assemblySource.size()); ++k) {
      const Index src = posMap[node.assemblySource[k]];
      if (src < 0) continue;  // an entry that is gone
      const Index t = node.assemblyTarget[k], u = t >= 0 ? t : ~t;
      const Index c = u / oldNr, r = u - c * oldNr;
      const Index col = relabel.newPosition[oldFirst + c] - node.firstCol, row = position[relabel.newPosition[oldRows[r]]];
      eigen_assert(col >= 0 && row >= 0 && "remapAssemblyMaps: a surviving entry left the structure");
      const Index offset = col * nr + row;
      source.push_back(src);
      target.push_back(t >= 0 ? offset : ~offset);
    }
    while (next != fresh.end() && f.colToSuper[next->col] < s) ++next;  // (cannot happen: fresh entries are dirty)
    for (; next != fresh.end() && f.colToSuper[next->col] == s; ++next) {
      const Index offset = (Index(next->col) - node.firstCol) * nr + position[next->row];
      eigen_assert(position[next->row] >= 0 && "remapAssemblyMaps: a fresh entry outside the structure");
      source.push_back(next->source >= 0 ? next->source : ~next->source);
      target.push_back(next->source >= 0 ? offset : ~offset);
    }
    // the map lists the entries column by column, as buildAssemblyMaps() does (the Dirichlet
    // coupling finds a column's range by bisection)
    order.resize(source.size());
    for (Index k = 0; k < Index(order.size()); ++k) order[k] = k;
    auto columnOf = [nr](Index t) { return (t >= 0 ? t : ~t) / nr; };
    std::stable_sort(order.begin(), order.end(),
                     [&](Index a, Index b) { return columnOf(target[a]) < columnOf(target[b]); });
    node.assemblySource.resize(order.size());
    node.assemblyTarget.resize(order.size());
    for (Index k = 0; k < Index(order.size()); ++k) {
      node.assemblySource[k] = source[order[k]];
      node.assemblyTarget[k] = target[order[k]];
    }
    for (Index k = 0; k < nr; ++k) position[node.rows[k]] = StorageIndex(-1);
  }
}

/** \internal The strict upper pattern of the new C (column i lists its neighbours j < i) from the
  * current one: a column of an unchanged dof is renumbered as it is; a changed dof keeps its
  * unchanged neighbours and takes its changed ones from \a pairs (i > j, new permuted). */
template <typename StorageIndex>
void remapUpperPattern(const CompressedPattern<StorageIndex>& old, const StorageIndex* oldPinv,
                       const std::vector<char>& changed, const DofRelabeling<StorageIndex>& relabel,
                       const std::vector<std::pair<StorageIndex, StorageIndex> >& pairs,
                       CompressedPattern<StorageIndex>& out) {
  const Index n = old.size(), total = relabel.newSize;
  out.ptr.assign(total + 1, 0);
  auto survives = [&](Index k, Index p) { return !changed[oldPinv[k]] || !changed[oldPinv[old.idx[p]]]; };
  for (Index k = 0; k < n; ++k) {
    const Index i = relabel.newPosition[k];
    if (i < 0) continue;
    Index count = 0;
    if (!changed[oldPinv[k]])
      count = old.ptr[k + 1] - old.ptr[k];
    else
      for (Index p = old.ptr[k]; p < old.ptr[k + 1]; ++p) count += survives(k, p);
    out.ptr[i + 1] = count;
  }
  for (const auto& e : pairs) ++out.ptr[e.first + 1];
  for (Index i = 0; i < total; ++i) out.ptr[i + 1] += out.ptr[i];
  out.idx.resize(out.ptr[total]);
  std::vector<Index> fill(out.ptr.begin(), out.ptr.end() - 1);
  for (Index k = 0; k < n; ++k) {
    const Index i = relabel.newPosition[k];
    if (i < 0) continue;
    Index q = fill[i];
    const bool all = !changed[oldPinv[k]];
    for (Index p = old.ptr[k]; p < old.ptr[k + 1]; ++p)
      if (all || survives(k, p)) out.idx[q++] = relabel.newPosition[old.idx[p]];
    fill[i] = q;
  }
  for (const auto& e : pairs) out.idx[fill[e.first]++] = e.second;
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_INPUT_H
