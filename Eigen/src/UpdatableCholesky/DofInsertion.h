// DofInsertion.h — symbolic edits of the supernodal factor when dofs are added or merged
// (paper §4.2, Algorithm 4, and the example of eq. 17/18).
//
// insertDofs: a mesh cut duplicates vertices; each new dof copies an old one (its origin) and is
// eliminated right after it. A copy and its origin behave like one vertex of the old graph
// (indistinguishable nodes), so the old symbolic structure, with every origin row followed by the
// rows of its copies, holds the factor of the new matrix. Only the supernodes on the paths from
// the changed columns to the roots (the dirty ones) get the copies' rows; they are refactored
// anyway. The clean ones keep their values: their columns have no entry at a copy, and neither
// do their descendants', so their rows are only renumbered. Each copy becomes a column of its
// origin's supernode.
//
// mergeDofs: the reverse. Merged dofs leave the numbering; their rows and columns leave the
// supernodes (always dirty ones); their entries in the new matrix must be covered by the
// remaining structure, which holds when the merged dofs are copies made by insertDofs.
//
// Everything here works in the permuted numbering of the factor. A relabeling maps each old
// permuted column to its new position (or -1 when merged away) and says how many copies follow
// it; the factor's previous row lists, values, and relative positions are kept
// aside (moved, not copied) so that a failed update can put them back.

#ifndef EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_H
#define EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_H

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal How the permuted columns move: old permuted column k goes to newPosition[k]
  * (-1: merged away) and, in dirty supernodes, is followed by copies[k] new rows/columns. */
template <typename StorageIndex>
struct DofRelabeling {
  std::vector<StorageIndex> newPosition;  ///< old permuted -> new permuted, or -1
  std::vector<StorageIndex> copies;       ///< copies placed right after each old permuted column
  std::vector<StorageIndex> oldPosition;  ///< new permuted -> old permuted, or -1 for a copy
  Index newSize = 0;
  Index firstMoved = 0;  ///< old permuted columns below this one keep their position
  /** newPosition and oldPosition hold k at every k below this (kept by buildForCopies() and
    * buildForDrops() between their calls, which then write only the rest) */
  Index identityPrefix = 0;
  /** When the relabeling has at most MaxSteps steps (old columns that get copies, or that are
    * dropped): kept old column k moves to k + the stepShift of every step with stepAt < k;
    * steps < 0 when there are more. */
  enum { MaxSteps = 8 };
  enum { LookUp = -2 };  ///< steps of a relabeling built by buildWithRoom(): newPositionsOf() reads newPosition
  StorageIndex stepAt[MaxSteps], stepShift[MaxSteps];
  Index steps = -1;
  /** With more steps: the shift of the old columns of each block of 2^BlockBits (the same for
    * all of them when no step lies in the block), or MixedBlock when a step does. */
  enum { BlockBits = 8 };
  std::vector<StorageIndex> blockShift;
  static constexpr StorageIndex MixedBlock = NumTraits<StorageIndex>::highest();
  /** Built by buildForCopies(): the old columns move by runs (forEachCopyRun()). */
  bool byRuns = false;

  /** out[i] = the new position of the kept old column oldColumn(i), for i < count, in one pass
    * in order rather than a load from newPosition at a random place per column (the columns
    * come in the user's order: that load misses the cache once newPosition outgrows it). With
    * few steps, by compares (they vectorize); with more, from the shift of the column's block
    * (a table that stays in cache), newPosition only for the blocks that hold a step. */
  template <typename OldColumn>
  void newPositionsOf(Index count, OldColumn&& oldColumn, StorageIndex* EIGEN_RESTRICT out) const {
    if (steps == LookUp) {  // (a layout laid out anew: read off newPosition)
      const StorageIndex* to = newPosition.data();
      for (Index i = 0; i < count; ++i) out[i] = to[oldColumn(i)];
      return;
    }
    if (steps < 0) {
      const StorageIndex* block = blockShift.data();
      const StorageIndex* to = newPosition.data();
      for (Index i = 0; i < count; ++i) {
        const StorageIndex k = StorageIndex(oldColumn(i)), shift = block[k >> BlockBits];
        out[i] = shift != MixedBlock ? StorageIndex(k + shift) : to[k];
      }
      return;
    }
    StorageIndex at[MaxSteps], shift[MaxSteps];  // (unused steps: never passed, add nothing)
    for (Index q = 0; q < Index(MaxSteps); ++q) {
      at[q] = q < steps ? stepAt[q] : NumTraits<StorageIndex>::highest();
      shift[q] = q < steps ? stepShift[q] : StorageIndex(0);
    }
    for (Index i = 0; i < count; ++i) {
      const StorageIndex k = StorageIndex(oldColumn(i));
      StorageIndex moved = 0;
      for (Index q = 0; q < Index(MaxSteps); ++q) moved += k > at[q] ? shift[q] : StorageIndex(0);
      out[i] = k + moved;
    }
  }

  /** build() for an insertion: nothing dropped, and copies is non-zero only at (some of) the old
    * permuted columns \a at (increasing, distinct). The columns up to the first of them keep
    * their positions; the rest move by the copies before them, which is written run by run (one
    * run between two origins), in order, without reading copies per column. */
  void buildForCopies(const std::vector<StorageIndex>& at) {
    byRuns = true;
    const Index n = Index(copies.size());
    Index shift = 0;
    for (StorageIndex p : at) shift += copies[p];
    newSize = n + shift;
    firstMoved = at.empty() ? n : Index(at.front()) + 1;  // (no copies: nothing moves)
    newPosition.resize(n);
    oldPosition.resize(newSize);
    StorageIndex* EIGEN_RESTRICT to = newPosition.data();
    StorageIndex* EIGEN_RESTRICT from = oldPosition.data();
    for (Index k = (std::min)(identityPrefix, firstMoved); k < firstMoved; ++k) to[k] = from[k] = StorageIndex(k);
    recordSteps(at, [&](Index q) { return copies[at[q]]; });
    forEachCopyRun(at, [&](Index origin, Index count, Index begin, Index end, Index shift) {
      for (Index t = 1; t <= count; ++t) from[origin + shift - count + t] = StorageIndex(-1);  // its copies
      for (Index k = begin; k < end; ++k) {
        to[k] = StorageIndex(k + shift);
        from[k + shift] = StorageIndex(k);
      }
    });
    identityPrefix = firstMoved;
  }

  /** The runs of an insertion's relabeling (copies at the old permuted columns \a at, increasing,
    * as given to buildForCopies()), in order: run(origin, count, begin, end, shift) for each
    * origin with its count copies, placed right after it, and the old columns [begin, end) after
    * it up to the next origin (included), which move by shift (the copies up to this origin's). */
  /** build() for an insertion that lays the positions of factor \a f out anew (when some origin's
    * supernode has fewer free positions than the copies it gets, see SupernodalFactor): each
    * supernode keeps its columns in order, each origin (old positions \a at, increasing,
    * distinct, copies[] of each) followed by its copies, then its free positions: as many as
    * it had less the copies it took, and at least roomFor(its new column count). Free old
    * positions beyond that map to -1; new ones have no old position (-1). */
  template <typename Factor, typename Room>
  void buildWithRoom(const std::vector<StorageIndex>& at, const Factor& f, Room&& roomFor) {
    byRuns = false;
    steps = LookUp;
    const Index n = Index(copies.size()), ns = f.count();
    newPosition.resize(n);
    StorageIndex* EIGEN_RESTRICT to = newPosition.data();
    Index shift = 0;
    std::size_t q = 0;
    for (Index s = 0; s < ns; ++s) {
      const Index first = f.nodes[s].firstCol, used = f.nodes[s].ncols, end = f.ownedEnd(s);
      Index inside = 0;  // the copies placed so far in s
      for (Index k = first; k < first + used; ++k) {
        to[k] = StorageIndex(k + shift + inside);
        if (q < at.size() && Index(at[q]) == k) inside += copies[at[q++]];
      }
      const Index free = end - first - used, room = (std::max)(free - inside, Index(roomFor(used + inside)));
      for (Index i = 0; i < free; ++i) to[first + used + i] = i < room ? StorageIndex(first + used + shift + inside + i) : StorageIndex(-1);
      shift += inside + room - free;
    }
    newSize = n + shift;
    oldPosition.assign(newSize, StorageIndex(-1));
    firstMoved = n;
    for (Index k = n - 1; k >= 0; --k) {
      if (to[k] < 0) {
        firstMoved = k;
        continue;
      }
      oldPosition[to[k]] = StorageIndex(k);
      if (to[k] != k) firstMoved = k;
    }
    identityPrefix = firstMoved;
  }

  template <typename Run>
  void forEachCopyRun(const std::vector<StorageIndex>& at, Run&& run) const {
    const Index n = Index(copies.size());
    Index shift = 0;
    for (std::size_t q = 0; q < at.size(); ++q) {
      const Index origin = Index(at[q]), count = Index(copies[origin]);
      shift += count;
      run(origin, count, origin + 1, q + 1 < at.size() ? Index(at[q + 1]) + 1 : n, shift);
    }
  }

  /** build() for a merge: the old permuted columns \a at (increasing, distinct) are dropped and
    * no column gets copies. The columns up to the first of them keep their positions; the rest
    * move down by the dropped ones before them, written run by run (one run between two dropped
    * columns), in order. */
  void buildForDrops(const std::vector<StorageIndex>& at) {
    byRuns = false;
    const Index n = Index(copies.size());
    newSize = n - Index(at.size());
    firstMoved = at.empty() ? n : Index(at.front());
    newPosition.resize(n);
    oldPosition.resize(newSize);
    StorageIndex* EIGEN_RESTRICT to = newPosition.data();
    StorageIndex* EIGEN_RESTRICT from = oldPosition.data();
    for (Index k = (std::min)(identityPrefix, firstMoved); k < firstMoved; ++k) to[k] = from[k] = StorageIndex(k);
    recordSteps(at, [](Index) { return -1; });
    for (std::size_t q = 0; q < at.size(); ++q) {
      const Index dropped = Index(at[q]), shift = Index(q) + 1;
      to[dropped] = StorageIndex(-1);
      const Index end = q + 1 < at.size() ? Index(at[q + 1]) : n;
      for (Index k = dropped + 1; k < end; ++k) {
        to[k] = StorageIndex(k - shift);
        from[k - shift] = StorageIndex(k);
      }
    }
    identityPrefix = firstMoved;
  }

 private:
  template <typename Shift>
  void recordSteps(const std::vector<StorageIndex>& at, Shift&& shiftOf) {
    steps = Index(at.size()) <= Index(MaxSteps) ? Index(at.size()) : Index(-1);
    for (Index q = 0; q < steps; ++q) {
      stepAt[q] = at[q];
      stepShift[q] = StorageIndex(shiftOf(q));
    }
    if (steps >= 0) return;
    // the block table: a column moves by the shifts of the steps below it, the same for a whole
    // block when no step lies in it
    const Index n = Index(copies.size()), blocks = (n >> BlockBits) + 1, count = Index(at.size());
    blockShift.resize(blocks);
    StorageIndex shift = 0;
    for (Index b = 0, q = 0; b < blocks; ++b) {
      const Index begin = b << BlockBits, end = begin + (Index(1) << BlockBits);
      for (; q < count && Index(at[q]) < begin; ++q) shift += StorageIndex(shiftOf(q));
      blockShift[b] = q < count && Index(at[q]) < end ? MixedBlock : shift;
    }
  }
};

/** \internal Storage (blocks or buffers) set aside by one call for the next, found by its size:
  * filled with add(), then seal()ed (sorted by size once), then take()n from; a taken entry is
  * skipped by the following searches through a next-free link with path compression, so that a
  * call with many supernodes of one size does not rescan the ones already taken. */
template <typename Storage>
struct SparePool {
  std::vector<std::pair<Index, Storage> > entries;  ///< (size, storage), sorted by size once sealed
  std::vector<Index> nextFree;                      ///< an entry at or after this one that may be free

  /** Frees every entry (the arrays keep their capacity). */
  void clear() {
    entries.clear();
    nextFree.clear();
  }
  /** Moves \a storage (left empty) into the pool under \a size. */
  void add(Index size, Storage& storage) {
    entries.emplace_back(size, Storage());
    entries.back().second.swap(storage);
  }
  /** Sorts the entries by size; every entry is free. */
  void seal() {
    std::sort(entries.begin(), entries.end(),
              [](const std::pair<Index, Storage>& a, const std::pair<Index, Storage>& b) { return a.first < b.first; });
    nextFree.resize(entries.size() + 1);
    for (std::size_t k = 0; k < nextFree.size(); ++k) nextFree[k] = Index(k);
  }
  /** Swaps into \a out (empty) the free entry of the smallest size in [least, most], if there is
    * one; \returns whether there was. */
  bool take(Index least, Index most, Storage& out) {
    const Index count = Index(entries.size());
    if (count == 0) return false;
    Index k = Index(std::lower_bound(entries.begin(), entries.end(), least,
                                     [](const std::pair<Index, Storage>& e, Index v) { return e.first < v; }) -
                    entries.begin());
    k = firstFree(k);
    if (k >= count || entries[k].first > most) return false;
    out.swap(entries[k].second);
    nextFree[k] = k + 1;  // (taken: searches go on past it)
    return true;
  }
  /** Bytes of the bookkeeping (not of the storage). */
  Index bytes() const {
    return Index(entries.capacity() * sizeof(std::pair<Index, Storage>) + nextFree.capacity() * sizeof(Index));
  }

 private:
  Index firstFree(Index k) {
    Index root = k;
    while (nextFree[root] != root) root = nextFree[root];
    while (nextFree[k] != root) {  // path compression
      const Index up = nextFree[k];
      nextFree[k] = root;
      k = up;
    }
    return root;
  }
};

/** \internal The parts of the factor an insertion or merge changes, kept for a revert (kept by
  * the solver between calls, so that its per-supernode arrays are reused). */
template <typename Scalar, typename StorageIndex>
struct FactorStructureBackup {
  Index n = 0;
  std::vector<StorageIndex> colToSuper;
  std::vector<Index> firstCol, ncols;
  std::vector<std::vector<StorageIndex> > rows, parentPosition;  ///< dirty supernodes only
  std::vector<Matrix<Scalar, Dynamic, Dynamic> > values;          ///< dirty supernodes only
  std::vector<UpdateBuffer<Scalar> > cache;                        ///< dirty supernodes only
  /** The deferred corrections of the dirty supernodes' cached update matrices, set aside with
    * them rather than applied: a refactored supernode never needs them, a folded one carries them
    * on (extended to its new rows), and only a refactored child of a folded one, whose previous
    * update matrix the fold compares with the new one, applies them (applyPendingTo()). */
  std::vector<std::vector<typename SupernodalNumeric<Scalar, StorageIndex>::Correction> > pending;
  /** The previous call's cached update matrices, kept as buffers for this call's dirty supernodes
    * (by size): a buffer that is already allocated, touched and large enough needs neither the
    * page faults nor the zeroing of a new one (the update matrices of an insertion and of the
    * merge that undoes it are the same sizes, swapped). */
  SparePool<UpdateBuffer<Scalar> > spareCache;
  /** The previous call's blocks of its dirty supernodes, kept likewise for blocks of the same
    * number of entries (a block's storage is reused only at the same size). */
  SparePool<Matrix<Scalar, Dynamic, Dynamic> > spareValues;

  /** Empties what the call kept of the \a dirty supernodes (and of their children), so that
    * every per-supernode entry is empty between calls: the row lists keep their storage (the
    * next call's dirty supernodes swap it in for their new rows, with no allocation); the
    * update matrices and blocks become the spare buffers of the next call (those the call did
    * not use are freed). */
  template <typename Factor>
  void release(const Factor& f, const std::vector<Index>& dirty) {
    spareCache.clear();
    spareValues.clear();
    for (Index s : dirty) {
      rows[s].clear();
      if (s < Index(pending.size())) pending[s].clear();
      if (values[s].size() > 0) spareValues.add(values[s].size(), values[s]);  // (leaves it empty)
      if (!cache[s].empty()) spareCache.add(Index(cache[s].capacity()), cache[s]);  // (by capacity: what it can hold)
      UpdateBuffer<Scalar>().swap(cache[s]);
      for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) parentPosition[c].clear();
    }
    spareCache.seal();
    spareValues.seal();
  }

  /** Sets aside the deferred corrections of the cached update matrices of the \a dirty
    * supernodes (with their matrices: see pending). */
  void takePending(SupernodalNumeric<Scalar, StorageIndex>& numeric, Index count, const std::vector<Index>& dirty) {
    pending.resize(count);
    for (Index s : dirty) pending[s].swap(numeric.pendingCorrections(s));
  }

  /** Applies the set-aside corrections of supernode \a s to its previous update matrix (cache[s],
    * \a m × \a m), which is then exact on its own. */
  void applyPendingTo(Index s, Index m) {
    if (!pending[s].empty()) SupernodalNumeric<Scalar, StorageIndex>::applyCorrectionsTo(pending[s], m, cache[s].data());
  }

  /** Gives \a block (empty) the storage of a spare block of exactly rows × cols entries, if there
    * is one, resized to rows × cols (its values are stale: the caller overwrites them). */
  void takeSpare(Index rows, Index cols, Matrix<Scalar, Dynamic, Dynamic>& block) {
    const Index size = rows * cols;
    if (size == 0 || !spareValues.take(size, size, block)) return;
    block.resize(rows, cols);  // (the same number of entries: no reallocation)
#ifndef NDEBUG
    block.setConstant(Scalar(std::numeric_limits<typename NumTraits<Scalar>::Real>::quiet_NaN()));
#endif
  }

  /** Moves into \a buffer the smallest spare buffer of at least \a size scalars, if there is one
    * that holds at most twice as many (so that buffers do not grow from call to call; its values
    * are stale: the caller writes what it reads). */
  void takeSpare(Index size, UpdateBuffer<Scalar>& buffer) {
    if (size == 0 || !spareCache.take(size, 2 * size, buffer)) return;
#ifndef NDEBUG  // stale values: poisoned, so that a test reading them fails
    std::fill(buffer.begin(), buffer.end(), Scalar(std::numeric_limits<typename NumTraits<Scalar>::Real>::quiet_NaN()));
#endif
  }

  /** Bytes held between calls (the spare buffers and the storage of the emptied row lists). */
  Index bytes() const {
    Index b = 0;
    for (const auto& entry : spareCache.entries) b += Index(entry.second.capacity() * sizeof(Scalar));
    for (const auto& entry : spareValues.entries) b += Index(entry.second.size() * sizeof(Scalar));
    b += spareCache.bytes() + spareValues.bytes();
    for (const auto& list : rows) b += Index(list.capacity() * sizeof(StorageIndex));
    for (const auto& list : parentPosition) b += Index(list.capacity() * sizeof(StorageIndex));
    return b;
  }
};

/** \internal Applies \a relabel to the factor: dirty supernodes (mark != 0) get new row lists
  * (merged rows dropped, copies inserted after their origins) and lose their values and cached
  * update matrix (moved into \a backup, to be recomputed); clean ones are renumbered in place.
  * Recomputes first columns, column counts, colToSuper and the relative positions of the
  * children of dirty supernodes. The assembly maps stay as they are (see remapAssemblyMaps()).
  * \a position: scratch by new permuted row, all -1 between uses. */
template <typename Scalar, typename StorageIndex>
void relabelFactor(SupernodalFactor<Scalar, StorageIndex>& f, std::vector<UpdateBuffer<Scalar> >& cache,
                   const DofRelabeling<StorageIndex>& relabel, const std::vector<char>& mark,
                   FactorStructureBackup<Scalar, StorageIndex>& backup, std::vector<StorageIndex>& position) {
  const Index ns = f.count();
  backup.n = f.n;
  backup.colToSuper.swap(f.colToSuper);
  backup.firstCol.resize(ns);
  backup.ncols.resize(ns);
  backup.rows.resize(ns);  // (all empty, some with storage: the previous call released them)
  backup.parentPosition.resize(ns);
  backup.values.resize(ns);
  backup.cache.resize(ns);
  backup.pending.resize(ns);
  for (Index s = 0; s < ns; ++s) {
    // a clean supernode wholly below the first moved column stays as it is, unread (backup.firstCol
    // and backup.ncols are written for the dirty supernodes only)
    if (!mark[s] && Index(f.lastRow[s]) < relabel.firstMoved) continue;
    auto& node = f.nodes[s];
    if (!mark[s]) {  // (rows are increasing: those before the first moved column stay)
      const Index nr = node.nrows();
      StorageIndex* EIGEN_RESTRICT rows = node.rows.data();
      const StorageIndex* EIGEN_RESTRICT to = relabel.newPosition.data();
      const Index from = Index(rows[0]) >= relabel.firstMoved
                             ? Index(0)
                             : Index(std::lower_bound(rows, rows + nr, StorageIndex(relabel.firstMoved)) - rows);
      for (Index k = from; k < nr; ++k) rows[k] = to[rows[k]];
    } else {
      backup.firstCol[s] = node.firstCol;
      backup.ncols[s] = node.ncols;
      backup.rows[s].swap(node.rows);
      backup.values[s].swap(node.values);
      if (Index(cache.size()) == ns) backup.cache[s].swap(cache[s]);
      const auto& old = backup.rows[s];
      Index columns = 0;
      node.rows.reserve(old.size() + (old.size() >> 2));  // (copies make it longer)
      for (Index k = 0; k < Index(old.size()); ++k) {
        const StorageIndex r = old[k], p = relabel.newPosition[r];
        if (p < 0) continue;
        const Index added = 1 + relabel.copies[r];
        for (Index t = 0; t < added; ++t) node.rows.push_back(StorageIndex(p + t));
        if (k < node.ncols) columns += added;
      }
      node.ncols = columns;
      backup.takeSpare(node.nrows(), node.ncols, node.values);
      if (Index(cache.size()) == ns) backup.takeSpare(node.below() * node.below(), cache[s]);
    }
    node.firstCol = node.ncols > 0 ? Index(node.rows[0]) : 0;
    f.noteLastRow(s);
  }
  f.n = relabel.newSize;
  f.colToSuper.resize(f.n);  // one pass in order: a copy belongs to the supernode of its origin
  const Index unmoved = (std::min)(relabel.firstMoved, f.n);  // (the columns below keep their supernode)
  std::copy(backup.colToSuper.begin(), backup.colToSuper.begin() + unmoved, f.colToSuper.begin());
  StorageIndex owner = unmoved > 0 ? f.colToSuper[unmoved - 1] : StorageIndex(-1);
  for (Index j = unmoved; j < f.n; ++j) {
    const StorageIndex k = relabel.oldPosition[j];
    if (k >= 0) owner = backup.colToSuper[k];
    f.colToSuper[j] = owner;
  }
  // relative positions of the children of dirty supernodes (the parents' rows changed)
  position.resize(f.n, StorageIndex(-1));
  for (Index p = 0; p < ns; ++p) {
    if (!mark[p]) continue;
    const auto& pn = f.nodes[p];
    for (Index k = 0; k < pn.nrows(); ++k) position[pn.rows[k]] = StorageIndex(k);
    for (Index c = f.firstChild[p]; c != -1; c = f.nextSibling[c]) {
      auto& cn = f.nodes[c];
      backup.parentPosition[c].swap(cn.parentPosition);
      cn.parentPosition.resize(cn.below());
      for (Index k = 0; k < cn.below(); ++k) cn.parentPosition[k] = position[cn.rows[cn.ncols + k]];
    }
    for (Index k = 0; k < pn.nrows(); ++k) position[pn.rows[k]] = StorageIndex(-1);
  }
}

/** \internal Undoes relabelFactor(): puts back the structure and the dirty supernodes' values
  * and cached update matrices (not the assembly maps: the caller rebuilds them). */
template <typename Scalar, typename StorageIndex>
void restoreFactor(SupernodalFactor<Scalar, StorageIndex>& f, std::vector<UpdateBuffer<Scalar> >& cache,
                   const DofRelabeling<StorageIndex>& relabel, const std::vector<char>& mark,
                   FactorStructureBackup<Scalar, StorageIndex>& backup) {
  const Index ns = f.count();
  for (Index s = 0; s < ns; ++s) {
    if (!mark[s] && Index(f.lastRow[s]) < relabel.firstMoved) continue;  // (relabelFactor() left it as it was)
    auto& node = f.nodes[s];
    if (!mark[s]) {
      for (auto& r : node.rows) r = relabel.oldPosition[r];
      node.firstCol = node.ncols > 0 ? Index(node.rows[0]) : 0;
    } else {
      node.firstCol = backup.firstCol[s];
      node.ncols = backup.ncols[s];
      node.rows.swap(backup.rows[s]);
      node.values.swap(backup.values[s]);
      if (Index(cache.size()) == ns) cache[s].swap(backup.cache[s]);
    }
    f.noteLastRow(s);
  }
  for (Index p = 0; p < ns; ++p) {
    if (!mark[p]) continue;
    for (Index c = f.firstChild[p]; c != -1; c = f.nextSibling[c]) f.nodes[c].parentPosition.swap(backup.parentPosition[c]);
  }
  f.n = backup.n;
  f.colToSuper.swap(backup.colToSuper);
}

/** \internal True when permuted row \a row lies in the rows of the supernode of permuted column
  * \a col (row > col): the structure then holds entry (row, col). */
template <typename Scalar, typename StorageIndex>
bool structureHolds(const SupernodalFactor<Scalar, StorageIndex>& f, Index row, Index col) {
  const auto& rows = f.nodes[f.colToSuper[col]].rows;
  return std::binary_search(rows.begin(), rows.end(), StorageIndex(row));
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_DOF_INSERTION_H
