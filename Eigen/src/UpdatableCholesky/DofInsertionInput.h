// DofInsertionInput.h — how the input side of the solver follows insertDofs()/mergeDofs()
// without a pass that rebuilds it from the whole new matrix (paper §4.2: only the dirty part
// of the factor is touched; here the same holds, as far as it can, for what feeds it).
//
// The solver keeps, besides the factor, the kept triangle of the matrix and its transposed
// pattern (InputStore.h) and, per supernode, an assembly map from store positions into the
// supernode's block. After a cut or merge:
//   - diffInput() compares the new matrix with the store outer vector by outer vector; one whose
//     kept entries and values are the same (the vast majority) costs a sequential compare and,
//     for an insertion or the merge of trailing dofs, nothing else: it stays where it is in the
//     store. A differing one is matched entry by entry (the dofs it touches are "changed", the
//     entries the old matrix did not have are "fresh") and rewritten at the end of the store;
//     a position map says where each old entry of it went. Otherwise (dofs renumbered, or a
//     store with too much garbage) the store is rebuilt compactly and every position maps.
//     Told which outer vectors may differ (insertDofs() with a list of changed dofs), it reads
//     only those.
//   - gluingMismatches(): where the cut matrix, its copies added back onto their origins,
//     differs from the uncut one; it bounds the rank of what the mixed route folds
//     (LowRankTopUpdate.h).
//   - remapAssemblyMaps(): a clean supernode keeps its map, or maps its sources through the
//     position map when it owns an entry that moved; a dirty supernode's map is rebuilt from its
//     old map (surviving entries, new row positions) plus the fresh entries of its columns.
//   - the transposed pattern (in the user's numbering, which an insertion keeps): an unchanged
//     dof keeps its list; a changed one keeps its unchanged neighbours and gets its changed ones
//     from the new matrix (TransposedPattern::followInPlaceRewrite()).
// The scratch arrays live in the solver between calls.

#ifndef EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_INPUT_H
#define EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_INPUT_H

#include <algorithm>
#include <cstring>
#include <vector>
#include <utility>

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

/** \internal The scratch of gluingMismatches(), kept by the solver between calls. */
template <typename Scalar>
struct GluingScratch {
  /** One entry of C glued back or of −G, at (row, col) with row >= col, and its magnitude. */
  struct Term {
    Index row, col;
    Scalar value;
    typename NumTraits<Scalar>::Real magnitude;
  };
  std::vector<Term> terms, grouped;  ///< the entries read, and the same grouped by row
  std::vector<Index> bucket;         ///< by G dof: its row's slot, -1 between uses
  std::vector<Index> rows, start;    ///< the rows that occur and where their terms start
  /** Bytes held. */
  Index bytes() const {
    return Index((terms.capacity() + grouped.capacity()) * sizeof(Term) +
                 (bucket.capacity() + rows.capacity() + start.capacity()) * sizeof(Index));
  }
};

/** \internal The result of diffInput() and the scratch space of the insertions, kept by the
  * solver between calls so that they allocate (and fault in) nothing proportional to nnz. */
template <typename Scalar, typename StorageIndex>
struct InputDiff {
  /** A rewritten (or dropped) outer vector of the store and its previous range, for a revert. */
  struct Rewrite {
    Index outer, begin, end;
  };
  std::vector<char> changed;    ///< by current dof: its row/column differs in the new matrix (or it goes)
  std::vector<StorageIndex> changedList;  ///< the dofs flagged in changed, once each
  /** previous store position -> new one (-1: the entry is gone); between calls the identity on
    * every live position, so that an insertion writes only the positions it moves */
  std::vector<StorageIndex> posMap;
  bool posMapIsIdentity = false;  ///< false after the store was assigned anew (analyzePattern())
  bool inPlace = false;         ///< the last diff rewrote outer vectors in place (else rebuilt the store)
  Index nonFinite = -1;  ///< after a refused diff: the new dof whose outer vector holds a NaN or infinity, else -1
  std::vector<Rewrite> rewrites;  ///< in place: the outer vectors rewritten or dropped
  Index oldPool = 0, oldOuter = 0, oldLive = 0;  ///< in place: the store's previous extent
  std::vector<Index> fresh;     ///< new store positions of entries the current matrix lacks
  std::vector<StorageIndex> freshOuter;  ///< the outer index (new numbering) of each fresh entry
  std::vector<Index> stamp;     ///< scratch by current dof, all -1 between uses
  std::vector<StorageIndex> position;    ///< scratch by new permuted row, all -1 between uses
  InputStore<Scalar, StorageIndex> spare;  ///< rebuilt: the previous store (the revert)
  TransposedPattern<StorageIndex> spareTransposed;  ///< rebuilt: the previous transposed pattern (the revert)
  std::vector<FreshEntry<StorageIndex> > freshEntries, freshSorted;  ///< the fresh entries in C, as found / by column
  std::vector<StorageIndex> freshCount;  ///< scratch of sortFreshEntries()
  std::vector<char> mismatch;  ///< scratch by new dof, zero between uses (gluingMismatches())
  std::vector<char> ownerFlag;  ///< scratch by supernode, zero between uses (ownersOfRewrites())
  std::vector<StorageIndex> mismatchList;  ///< the dofs where the cut matrix does not glue back
  GluingScratch<Scalar> gluing;  ///< gluingMismatches()'s scratch

  /** Makes posMap the identity on the positions of \a store. */
  void resetPositions(const InputStore<Scalar, StorageIndex>& store) {
    posMap.reserve(store.inner.capacity());  // (grows with the store, without a copy)
    posMap.resize(store.inner.size());
    for (Index q = 0; q < Index(posMap.size()); ++q) posMap[q] = StorageIndex(q);
    posMapIsIdentity = true;
  }

  /** Puts \a store back as it was before the last diffInput() (its previous entries are still in
    * place, or in the spare) and posMap back to the identity on it. */
  void revert(InputStore<Scalar, StorageIndex>& store) {
    if (!inPlace) {
      std::swap(store, spare);
      resetPositions(store);
      return;
    }
    store.begin.resize(oldOuter);
    store.end.resize(oldOuter);
    store.rows = store.cols = oldOuter;
    for (const Rewrite& r : rewrites) {
      store.begin[r.outer] = r.begin;
      store.end[r.outer] = r.end;
      for (Index q = r.begin; q < r.end; ++q) posMap[q] = StorageIndex(q);
    }
    store.inner.resize(oldPool);
    store.values.resize(oldPool);
    store.live = oldLive;
    posMap.resize(oldPool);
    rewrites.clear();
  }

  /** After a successful update: posMap becomes the identity on the new store. */
  void commit(const InputStore<Scalar, StorageIndex>& store) {
    if (!inPlace) {
      resetPositions(store);
      return;
    }
    const Index before = Index(posMap.size());
    posMap.resize(store.inner.size());
    for (Index q = before; q < Index(posMap.size()); ++q) posMap[q] = StorageIndex(q);
    rewrites.clear();
  }

  /** Bytes held by the scratch arrays and spare buffers. */
  Index bytes() const {
    return Index(changed.capacity() + mismatch.capacity() + ownerFlag.capacity() +
                 (stamp.capacity() + fresh.capacity()) * sizeof(Index) +
                 (posMap.capacity() + freshOuter.capacity() + position.capacity() + changedList.capacity() +
                  mismatchList.capacity()) *
                     sizeof(StorageIndex) +
                 spare.bytes() + spareTransposed.bytes() + rewrites.capacity() * sizeof(Rewrite) + gluing.bytes() +
                 (freshEntries.capacity() + freshSorted.capacity()) * sizeof(FreshEntry<StorageIndex>) +
                 freshCount.capacity() * sizeof(StorageIndex));
  }
};

/** \internal Compares the new compressed matrix (\a outer, \a inner, \a values, \a total outer
  * vectors) with the stored current one \a store, where \a oldOfNew maps a new dof to its current
  * one (-1 for a copy). Only the UpLo triangle counts. Leaves the new matrix in \a store (in place
  * when the numbering of the kept dofs does not change, else rebuilt; d.revert() undoes it) and
  * fills \a d (changed, posMap, fresh). \a allowed(x, y) is asked about each fresh off-diagonal
  * entry (new numbering); a false answer stops the comparison with false and the store unchanged.
  * \a only (sorted, new numbering; null: all): when the store is rewritten in place, the only
  * outer vectors that may differ; the others are taken as equal without being read.
  * \a keptBelow: the dofs below it are known to keep their numbers (none merged away), so
  * neither renumbering nor merged dofs are looked for among them (0: not known). */
template <int UpLo, bool RowMajor, typename Scalar, typename StorageIndex, typename Allowed>
bool diffInput(InputStore<Scalar, StorageIndex>& store, const StorageIndex* outer, const StorageIndex* inner,
               const Scalar* values, Index total, const std::vector<StorageIndex>& oldOfNew,
               const std::vector<StorageIndex>& newOfOld, InputDiff<Scalar, StorageIndex>& d, Allowed&& allowed,
               const std::vector<StorageIndex>* only = nullptr, Index keptBelow = 0) {
  const Index n = store.outerSize();
  d.changed.assign(n, 0);
  d.changedList.clear();
  d.nonFinite = -1;
  auto setChanged = [&d](Index o) {
    if (d.changed[o]) return;
    d.changed[o] = 1;
    d.changedList.push_back(StorageIndex(o));
  };
  d.stamp.resize(n, -1);
  d.fresh.clear();
  d.freshOuter.clear();
  d.rewrites.clear();
  if (!d.posMapIsIdentity || Index(d.posMap.size()) != Index(store.inner.size())) d.resetPositions(store);
  // kept dofs below this one keep their index (all old ones for an insertion)
  Index identityBelow = (std::min)(keptBelow, (std::min)(n, total));
  while (identityBelow < total && oldOfNew[identityBelow] == identityBelow) ++identityBelow;
  d.inPlace = identityBelow >= (std::min)(n, total) && !store.wasteful();
  d.oldPool = Index(store.inner.size());
  d.oldOuter = n;
  d.oldLive = store.live;
  if (!d.inPlace) {  // the new matrix goes to the spare, which then changes places with the store
    d.spare.rows = d.spare.cols = total;
    d.spare.inner.clear();
    d.spare.values.clear();
    d.spare.inner.reserve(store.live + store.live / 8 + total);
    d.spare.values.reserve(store.live + store.live / 8 + total);
  }
  InputStore<Scalar, StorageIndex>& out = d.inPlace ? store : d.spare;
  out.begin.resize((std::max)(n, total));
  out.end.resize((std::max)(n, total));
  auto kept = [](Index o, Index i) { return inKeptTriangle<UpLo, RowMajor>(o, i); };
  const bool subset = only && d.inPlace;
  const Index count = subset ? Index(only->size()) : total;
  for (Index k = 0; k < count; ++k) {
    if (subset && k + AssemblyPrefetchDistance < count) {  // (scattered outer vectors: their loads miss the cache)
      const Index ahead = Index((*only)[k + AssemblyPrefetchDistance]), oa = oldOfNew[ahead];
      internal::prefetch(inner + outer[ahead]);
      internal::prefetch(values + outer[ahead]);
      if (oa >= 0) {
        internal::prefetch(store.inner.data() + store.begin[oa]);
        internal::prefetch(store.values.data() + store.begin[oa]);
      }
    }
    const Index x = subset ? Index((*only)[k]) : k;
    const Index ox = oldOfNew[x];
    const Index nb = outer[x], ne = outer[x + 1];
    const Index ob = ox >= 0 ? store.begin[ox] : 0, oe = ox >= 0 ? store.end[ox] : 0;
    if (ox >= 0) {  // the same kept entries and values, under the renumbering?
      bool same;
      if (d.inPlace) {  // no renumbering: the kept entries, a run of them, compared bitwise
        Index p0 = nb;
        while (p0 < ne && !kept(x, inner[p0])) ++p0;
        const Index len = oe - ob;
        same = (p0 == ne && len == 0) ||
               (p0 + len <= ne && std::memcmp(inner + p0, store.inner.data() + ob, len * sizeof(StorageIndex)) == 0 &&
                std::memcmp(values + p0, store.values.data() + ob, len * sizeof(Scalar)) == 0);
        for (Index p = p0 + len; same && p < ne; ++p) same = !kept(x, inner[p]);
      } else {
        Index q = ob;
        same = true;
        for (Index p = nb; p < ne && same; ++p) {
          const Index y = inner[p];
          if (!kept(x, y)) continue;
          same = q < oe && oldOfNew[y] == store.inner[q] && values[p] == store.values[q];
          ++q;
        }
        same = same && q == oe;
      }
      if (same) {  // the common case: the outer vector stays (in place) or moves as a whole
        if (!d.inPlace) {
          out.begin[x] = Index(out.inner.size());
          for (Index p = nb, r = ob; p < ne; ++p) {
            if (!kept(x, inner[p])) continue;
            d.posMap[r++] = StorageIndex(out.inner.size());
            out.inner.push_back(inner[p]);
            out.values.push_back(values[p]);
          }
          out.end[x] = Index(out.inner.size());
        }
        continue;
      }
      for (Index q2 = ob; q2 < oe; ++q2) {
        d.posMap[q2] = -1;
        d.stamp[store.inner[q2]] = q2;
      }
      if (d.inPlace) d.rewrites.push_back(typename InputDiff<Scalar, StorageIndex>::Rewrite{x, ob, oe});
    }
    const Index start = Index(out.inner.size());
    auto refuse = [&]() {  // (the store and the flags as they were)
      for (Index q = ob; q < oe; ++q) d.stamp[store.inner[q]] = -1;
      if (!d.inPlace) std::swap(store, d.spare);  // (revert() swaps back)
      d.revert(store);
      return false;
    };
    for (Index p = nb; p < ne; ++p) {
      const Index y = inner[p];
      if (!kept(x, y)) continue;
      // a value that is not finite (NaN, infinity) is refused here, where every changed value
      // passes: a fold of the unchanged top would not always meet it as a lost pivot
      if (!(numext::isfinite)(values[p])) {
        d.nonFinite = x;
        return refuse();
      }
      const Index np = Index(out.inner.size());
      out.inner.push_back(StorageIndex(y));
      out.values.push_back(values[p]);
      const Index oy = oldOfNew[y];
      if (ox >= 0 && oy >= 0 && d.stamp[oy] >= 0) {  // an entry the current matrix has
        if (!(values[p] == store.values[d.stamp[oy]])) {
          setChanged(ox);
          setChanged(oy);
        }
        d.posMap[d.stamp[oy]] = StorageIndex(np);
        d.stamp[oy] = -2;
        continue;
      }
      if (x != y && !allowed(x, y)) return refuse();
      if (ox >= 0) setChanged(ox);
      if (oy >= 0) setChanged(oy);
      d.fresh.push_back(np);
      d.freshOuter.push_back(StorageIndex(x));
    }
    out.begin[x] = start;
    out.end[x] = Index(out.inner.size());
    for (Index q = ob; q < oe; ++q) {
      const Index y = store.inner[q];
      if (d.stamp[y] >= 0) {  // an entry that is gone
        setChanged(ox);
        setChanged(y);
      }
      d.stamp[y] = -1;
    }
  }
  for (Index o = (std::min)(keptBelow, n); o < n; ++o) {  // merged dofs: every entry of theirs is gone
    if (newOfOld[o] >= 0) continue;
    setChanged(o);
    for (Index q = store.begin[o]; q < store.end[o]; ++q) {
      setChanged(store.inner[q]);
      d.posMap[q] = -1;
    }
    if (d.inPlace) d.rewrites.push_back(typename InputDiff<Scalar, StorageIndex>::Rewrite{o, store.begin[o], store.end[o]});
  }
  out.begin.resize(total);
  out.end.resize(total);
  out.rows = out.cols = total;
  if (d.inPlace) {
    Index dropped = 0;
    for (const auto& r : d.rewrites) dropped += r.end - r.begin;
    store.live = d.oldLive - dropped + (Index(store.inner.size()) - d.oldPool);
  } else {
    out.live = Index(out.inner.size());
    std::swap(store, d.spare);
  }
  return true;
}

/** \internal A range of one outer vector in a store's pool. */
struct OuterRange {
  Index outer, begin, end;
};

/** \internal Where the cut matrix C, glued back (each dof of C added onto the dof \a glue(x) of G
  * that it copies or is), differs from the matrix G (paper §4.2, eq. 17/18). A cut that only
  * shares out the entries of each origin among it and its copies, as cutting a mesh does to any
  * assembled matrix (Laplacian, mass matrix), glues back to G exactly; then, written in the
  * variables (the last copy, the differences to it), the cut only adds rows and columns, one per
  * copy, and every Schur complement above them changes by one-signed terms of rank at most the
  * copies below (one row addition each). Each dof of G listed here adds at most one to that rank.
  * Only the outer vectors that may differ are read: \a cutRanges of C and \a gluedRanges of G
  * (the others are equal, and glue to equal vectors, by construction). An entry counts as equal
  * when it differs by at most 64 roundings of the magnitudes that make it. Appends the G dofs of
  * the differing entries to \a out, once each, and marks them in \a flag (by G dof, zero on entry
  * for the dofs not in \a out): 2 when some entry of theirs differs by more than sqrt(eps) of its
  * magnitudes, else 1 (a small mismatch, such as a regularization added to every diagonal).
  * \a scratch: kept between calls (its bucket all -1 on entry and on return). */
template <bool RowMajor, typename Scalar, typename StorageIndex, typename Glue>
void gluingMismatches(const InputStore<Scalar, StorageIndex>& cut, const std::vector<OuterRange>& cutRanges, Glue&& glue,
                      const InputStore<Scalar, StorageIndex>& glued, const std::vector<OuterRange>& gluedRanges,
                      std::vector<char>& flag, std::vector<StorageIndex>& out, GluingScratch<Scalar>& scratch) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  typedef typename GluingScratch<Scalar>::Term Term;
  std::vector<Term>& terms = scratch.terms;
  std::vector<Index>& bucket = scratch.bucket;
  Index count = 0;
  for (const OuterRange& range : cutRanges) count += range.end - range.begin;
  for (const OuterRange& range : gluedRanges) count += range.end - range.begin;
  terms.clear();
  terms.reserve(count);
  auto add = [&terms](Index r, Index c, const Scalar& v) {  // entry (r, c) of a Hermitian matrix, as (max, min)
    if (r >= c)
      terms.push_back(Term{r, c, v, numext::abs(v)});
    else
      terms.push_back(Term{c, r, numext::conj(v), numext::abs(v)});
  };
  auto read = [&](const InputStore<Scalar, StorageIndex>& store, const std::vector<OuterRange>& ranges, bool isCut) {
    for (const OuterRange& range : ranges)
      for (Index q = range.begin; q < range.end; ++q) {
        const Index o = range.outer, i = store.inner[q];
        const Index r = RowMajor ? o : i, c = RowMajor ? i : o;
        const Scalar v = store.values[q];
        if (!isCut) {
          add(r, c, -v);
          continue;
        }
        const Index gr = glue(r), gc = glue(c);
        add(gr, gc, gr == gc && r != c ? v + numext::conj(v) : v);  // (r, c) and (c, r) both glue onto the diagonal
      }
  };
  read(cut, cutRanges, true);
  read(glued, gluedRanges, false);
  // group the terms by row (a counting sort over the rows that occur: bucket[row] holds the
  // row's slot, -1 between uses), then by column within each row (a few terms each)
  Index dofs = 0;  // (the G dofs that occur: bucket covers them)
  for (const Term& t : terms) dofs = (std::max)(dofs, t.row + 1);
  if (Index(bucket.size()) < dofs) bucket.resize(dofs, -1);
  std::vector<Index>&rows = scratch.rows, &start = scratch.start;
  rows.clear();
  start.clear();
  for (const Term& t : terms) {
    if (bucket[t.row] < 0) {
      bucket[t.row] = Index(rows.size());
      rows.push_back(t.row);
      start.push_back(0);
    }
    ++start[bucket[t.row]];
  }
  for (Index b = 0, at = 0; b < Index(start.size()); ++b) {
    const Index count = start[b];
    start[b] = at;
    at += count;
  }
  std::vector<Term>& grouped = scratch.grouped;
  grouped.resize(terms.size());  // (kept between calls: no new pages once it has grown)
  for (const Term& t : terms) grouped[start[bucket[t.row]]++] = t;  // (start[b] ends at the row's end)
  for (Index b = 0; b < Index(rows.size()); ++b) {
    bucket[rows[b]] = -1;
    const Index begin = b == 0 ? 0 : start[b - 1];
    std::sort(grouped.begin() + begin, grouped.begin() + start[b], [](const Term& a, const Term& c) { return a.col < c.col; });
  }
  terms.swap(grouped);
  const RealScalar roundings = RealScalar(64) * NumTraits<RealScalar>::epsilon();
  const RealScalar small = numext::sqrt(NumTraits<RealScalar>::epsilon());
  for (std::size_t k = 0; k < terms.size();) {
    std::size_t e = k;
    Scalar sum(0);
    RealScalar magnitude(0);
    for (; e < terms.size() && terms[e].row == terms[k].row && terms[e].col == terms[k].col; ++e) {
      sum += terms[e].value;
      magnitude += terms[e].magnitude;
    }
    if (!(numext::abs(sum) <= roundings * magnitude)) {
      const char level = numext::abs(sum) <= small * magnitude ? 1 : 2;
      for (Index x : {terms[k].row, terms[k].col}) {
        if (!flag[x]) out.push_back(StorageIndex(x));
        flag[x] = (std::max)(flag[x], level);
      }
    }
    k = e;
  }
}

/** \internal The supernodes (old numbering, before relabelFactor()) owning an entry of an outer
  * vector that an in-place diffInput() rewrote, increasing, into \a owners: their assembly maps
  * must follow the entries. */
template <typename Scalar, typename StorageIndex>
void ownersOfRewrites(const SupernodalFactor<Scalar, StorageIndex>& f, const InputStore<Scalar, StorageIndex>& store,
                      InputDiff<Scalar, StorageIndex>& d, const StorageIndex* perm, std::vector<Index>& owners) {
  std::vector<char>& owns = d.ownerFlag;  // (flags: the entries rewritten are many, their owners few)
  owns.resize(f.count(), 0);
  owners.clear();
  for (const auto& r : d.rewrites) {
    const Index pi = perm[r.outer];
    for (Index q = r.begin; q < r.end; ++q) {
      const Index s = f.colToSuper[(std::min)(pi, Index(perm[store.inner[q]]))];
      if (owns[s]) continue;
      owns[s] = 1;
      owners.push_back(s);
    }
  }
  std::sort(owners.begin(), owners.end());
  for (Index s : owners) owns[s] = 0;
}

/** \internal Writes into \a out the fresh \a entries (columns below \a columns) ordered by column,
  * then by source, the order remapAssemblyMaps() reads them in (the source breaks ties so that the
  * maps do not depend on the order the entries were found in). Few entries (a short cut) are
  * sorted, so that the cost is that of the entries, not of \a columns; many (a long cut: tens of
  * thousands) are counted per column, then insertion-sorted within each column (a few entries):
  * linear, where the comparison sort pays a log factor. \a count: scratch. */
template <typename StorageIndex>
void sortFreshEntries(const std::vector<FreshEntry<StorageIndex> >& entries, Index columns,
                      std::vector<StorageIndex>& count, std::vector<FreshEntry<StorageIndex> >& out) {
  if (Index(entries.size()) * 16 < columns) {  // few: sorted
    out.assign(entries.begin(), entries.end());
    std::sort(out.begin(), out.end(), [](const FreshEntry<StorageIndex>& a, const FreshEntry<StorageIndex>& b) {
      return a.col != b.col ? a.col < b.col : a.source < b.source;
    });
    return;
  }
  count.assign(columns + 1, StorageIndex(0));
  for (const auto& e : entries) ++count[Index(e.col) + 1];
  for (Index j = 0; j < columns; ++j) count[j + 1] += count[j];
  out.resize(entries.size());
  for (const auto& e : entries) out[count[Index(e.col)]++] = e;
  for (std::size_t k = 1; k < out.size(); ++k) {
    const FreshEntry<StorageIndex> e = out[k];
    std::size_t i = k;
    for (; i > 0 && out[i - 1].col == e.col && out[i - 1].source > e.source; --i) out[i] = out[i - 1];
    out[i] = e;
  }
}

/** \internal Renews every supernode's assembly map after relabelFactor(): clean supernodes map
  * their sources through \a posMap (only those in \a movedOwners, when given: the others' entries
  * stayed where they were); dirty ones (\a dirty) are rebuilt from their old maps (kept in
  * the nodes; old rows, first columns and column counts in \a backup) and the \a fresh entries
  * (ordered by sortFreshEntries()), column by column like every map. */
template <typename Scalar, typename StorageIndex>
void remapAssemblyMaps(SupernodalFactor<Scalar, StorageIndex>& f, const FactorStructureBackup<Scalar, StorageIndex>& backup,
                       const DofRelabeling<StorageIndex>& relabel, const std::vector<char>& mark,
                       const std::vector<Index>& dirty, const std::vector<StorageIndex>& posMap,
                       const std::vector<FreshEntry<StorageIndex> >& fresh, std::vector<StorageIndex>& position,
                       const std::vector<Index>* movedOwners) {
  auto remapClean = [&](Index s) {
    if (mark[s]) return;
    for (Index& src : f.nodes[s].assemblySource) {
      src = posMap[src];
      eigen_assert(src >= 0 && "remapAssemblyMaps: an entry of a clean supernode is gone");
    }
  };
  if (movedOwners)
    for (Index s : *movedOwners) remapClean(s);
  else
    for (Index s = 0; s < f.count(); ++s) remapClean(s);
  // (a supernode's columns are contiguous: in column order, the fresh entries come supernode by supernode)
  position.resize(f.n, StorageIndex(-1));
  auto next = fresh.begin();
  for (Index s : dirty) {
    auto& node = f.nodes[s];
    const Index nr = node.nrows();
    for (Index k = 0; k < nr; ++k) position[node.rows[k]] = StorageIndex(k);
    const auto& oldRows = backup.rows[s];
    const Index oldNr = Index(oldRows.size()), oldFirst = backup.firstCol[s];
    std::vector<Index>&source = node.assemblySource, &target = node.assemblyTarget;
    // the surviving entries, renumbered in place (the map shrinks: entry k goes to kept <= k)
    Index c = 0, base = 0, kept = 0;  // the old map lists its entries column by column: the column only grows
    const Index na = Index(source.size());
    for (Index k = 0; k < na; ++k) {
      // (posMap is read at scattered store positions: the loads miss the cache, fetched ahead)
      if (k + AssemblyPrefetchDistance < na) internal::prefetch(posMap.data() + source[k + AssemblyPrefetchDistance]);
      const Index t = target[k], u = t >= 0 ? t : ~t;
      while (u >= base + oldNr) {
        ++c;
        base += oldNr;
      }
      const Index src = posMap[source[k]];
      if (src < 0) continue;  // an entry that is gone
      const Index r = u - base;
      const Index col = relabel.newPosition[oldFirst + c] - node.firstCol, row = position[relabel.newPosition[oldRows[r]]];
      eigen_assert(col >= 0 && row >= 0 && "remapAssemblyMaps: a surviving entry left the structure");
      eigen_assert((kept == 0 || col >= (target[kept - 1] >= 0 ? target[kept - 1] : ~target[kept - 1]) / nr) &&
                   "remapAssemblyMaps: kept entries out of column order");
      const Index offset = col * nr + row;
      source[kept] = src;
      target[kept] = t >= 0 ? offset : ~offset;
      ++kept;
    }
    // (in column order: the old map was, and the relabeling keeps the columns' order)
    while (next != fresh.end() && f.colToSuper[next->col] < s) ++next;  // (cannot happen: fresh entries are dirty)
    auto freshEnd = next;
    while (freshEnd != fresh.end() && f.colToSuper[freshEnd->col] == s) ++freshEnd;
    const Index total = kept + Index(freshEnd - next);
    source.resize(total);
    target.resize(total);
    // the map lists the entries column by column, as buildAssemblyMaps() does (the Dirichlet
    // coupling finds a column's range by bisection): the fresh entries, in column order, are
    // merged into the kept ones from the back
    Index out = total, keptLeft = kept;
    for (auto e = freshEnd; e != next;) {
      const auto& fe = *(e - 1);
      const Index col = Index(fe.col) - node.firstCol;
      const Index t = keptLeft > 0 ? target[keptLeft - 1] : 0;
      if (keptLeft > 0 && (t >= 0 ? t : ~t) >= (col + 1) * nr) {  // (the kept entry's column is after col)
        --out;
        --keptLeft;
        source[out] = source[keptLeft];
        target[out] = target[keptLeft];
        continue;
      }
      eigen_assert(position[fe.row] >= 0 && "remapAssemblyMaps: a fresh entry outside the structure");
      const Index offset = col * nr + position[fe.row];
      --out;
      source[out] = fe.source >= 0 ? fe.source : ~fe.source;
      target[out] = fe.source >= 0 ? offset : ~offset;
      --e;
    }
    eigen_assert(out == keptLeft);
    next = freshEnd;
    for (Index k = 0; k < nr; ++k) position[node.rows[k]] = StorageIndex(-1);
  }
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_INPUT_H
