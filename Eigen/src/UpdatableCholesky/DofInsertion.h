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

/** \internal The free positions kept after a supernode of \a columns columns when a cut lays the
  * positions out anew (DofRelabeling::buildWithRoom()), for the copies of later cuts: a cut gives
  * each seam vertex one copy, so that a fresh seam then fits in the supernodes it crosses. */
inline Index copyRoomFor(Index columns) { return (std::max)(Index(2), columns); }

/** \internal How the positions move (SupernodalFactor::n counts them: each supernode's columns,
  * then its free positions). Old position k goes to newPosition[k] (-1: merged away, or a free
  * position that was used up) and, in dirty supernodes, is followed by copies[k] new rows and
  * columns. An insertion is local when every origin's supernode has free positions for its
  * copies (buildLocalCopies()), and a merge always is (buildLocalDrops()): only the columns of
  * those supernodes after the first origin or merged column move, inside their supernode, and
  * the number of positions stays. Otherwise an insertion lays every position out anew
  * (buildWithRoom()), with room for later ones. */
template <typename StorageIndex>
struct DofRelabeling {
  std::vector<StorageIndex> newPosition;  ///< old position -> new position, or -1
  std::vector<StorageIndex> copies;       ///< copies placed right after each old position (zero elsewhere)
  std::vector<StorageIndex> oldPosition;  ///< new position -> old position, or -1 (a copy, a new free position)
  Index newSize = 0;     ///< the number of new positions
  Index firstMoved = 0;  ///< old positions below this one keep their place
  Index moved = 0;       ///< used old positions (columns) that move
  /** A local relabeling: the positions move only inside the windows, and newSize is the old size. */
  bool local = false;
  /** The windows of a local relabeling: [begin, end) is a range of positions, inside one
    * supernode's, out of which newPosition and oldPosition are the identity. */
  std::vector<std::pair<StorageIndex, StorageIndex> > windows;

  /** A local insertion: copies (non-zero only at the old positions \a at, increasing, distinct)
    * go right after their origins; in each supernode that gets some (\a f's, which must have as
    * many free positions), its columns after its first origin move up by the copies before them,
    * into its free positions. Writes only the windows (and undoes the previous call's). */
  template <typename Factor>
  void buildLocalCopies(const std::vector<StorageIndex>& at, const Factor& f) {
    walkWindows(
        at, f,
        [this](Index k, bool origin, Index shift) {
          newPosition[k] = StorageIndex(k + shift);
          oldPosition[k + shift] = StorageIndex(k);
          moved += shift > 0;
          if (!origin) return shift;
          for (Index t = 1; t <= Index(copies[k]); ++t) oldPosition[k + shift + t] = StorageIndex(-1);
          return shift + Index(copies[k]);
        },
        [this, &f](Index owner, Index usedEnd, Index shift) {
          eigen_assert(shift <= f.freePositions(owner) && "buildLocalCopies: a supernode without room for its copies");
          EIGEN_UNUSED_VARIABLE(owner);
          for (Index k = usedEnd; k < usedEnd + shift; ++k) newPosition[k] = StorageIndex(-1);  // (free, used up)
          return usedEnd + shift;
        });
  }

  /** A local merge: the old positions \a at (increasing, distinct, used columns) are dropped; in
    * each supernode that loses some, its columns after them move down by the dropped ones
    * before them, and as many free positions appear after its columns. */
  template <typename Factor>
  void buildLocalDrops(const std::vector<StorageIndex>& at, const Factor& f) {
    walkWindows(
        at, f,
        [this](Index k, bool dropped, Index shift) {
          if (dropped) {
            newPosition[k] = StorageIndex(-1);
            return shift + 1;
          }
          newPosition[k] = StorageIndex(k - shift);
          oldPosition[k - shift] = StorageIndex(k);
          moved += shift > 0;
          return shift;
        },
        [this](Index, Index usedEnd, Index shift) {
          for (Index k = usedEnd - shift; k < usedEnd; ++k) oldPosition[k] = StorageIndex(-1);  // (free now)
          return usedEnd;
        });
  }

  /** An insertion that lays the positions of factor \a f out anew (when some origin's supernode
    * has fewer free positions than the copies it gets): each supernode keeps its columns in
    * order, each origin (old positions \a at, increasing, distinct) followed by its copies, then
    * its free positions: as many as it had less the copies it took, and at least
    * roomFor(its new column count). Free old positions beyond that map to -1; new ones have no
    * old position (-1). */
  template <typename Factor, typename Room>
  void buildWithRoom(const std::vector<StorageIndex>& at, const Factor& f, Room&& roomFor) {
    local = false;
    windows.clear();
    const Index n = Index(copies.size()), ns = f.count();
    newPosition.resize(n);
    StorageIndex* EIGEN_RESTRICT to = newPosition.data();
    Index shift = 0;
    std::size_t q = 0;
    moved = 0;
    for (Index s = 0; s < ns; ++s) {
      const Index first = f.nodes[s].firstCol, used = f.nodes[s].ncols, end = f.ownedEnd(s);
      Index inside = 0;  // the copies placed so far in s
      for (Index k = first; k < first + used; ++k) {
        to[k] = StorageIndex(k + shift + inside);
        moved += shift + inside > 0;
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
      if (to[k] >= 0) oldPosition[to[k]] = StorageIndex(k);
      if (to[k] != k) firstMoved = k;
    }
  }

 private:
  /** Makes newPosition and oldPosition the identity on \a n positions (after a local call, only
    * its windows are written back). */
  void startLocal(Index n) {
    if (local && Index(newPosition.size()) == n && Index(oldPosition.size()) == n) {
      for (const auto& w : windows)
        for (Index k = w.first; k < w.second; ++k) newPosition[k] = oldPosition[k] = StorageIndex(k);
    } else {
      newPosition.resize(n);
      oldPosition.resize(n);
      for (Index k = 0; k < n; ++k) newPosition[k] = oldPosition[k] = StorageIndex(k);
    }
    windows.clear();
    local = true;
    moved = 0;
  }
  void finishLocal(Index n) {
    newSize = n;
    firstMoved = windows.empty() ? n : Index(windows.front().first);
  }
  /** The walk of a local relabeling: for each supernode of \a f holding old positions of \a at
    * (increasing), its used columns k from the first of them on get column(k, k listed in at,
    * the shift so far), which returns the shift after k; finish(supernode, its used end, the
    * final shift) returns the end of the supernode's window, which starts at its first listed
    * position. */
  template <typename Factor, typename Column, typename Finish>
  void walkWindows(const std::vector<StorageIndex>& at, const Factor& f, Column&& column, Finish&& finish) {
    const Index n = Index(copies.size());
    startLocal(n);
    for (std::size_t q = 0; q < at.size();) {
      const Index owner = f.colToSuper[at[q]], first = Index(at[q]);
      const Index usedEnd = f.nodes[owner].firstCol + f.nodes[owner].ncols;
      Index shift = 0;
      for (Index k = first; k < usedEnd; ++k) {
        const bool listed = q < at.size() && Index(at[q]) == k;
        shift = column(k, listed, shift);
        q += listed;
      }
      windows.emplace_back(StorageIndex(first), StorageIndex(finish(owner, usedEnd, shift)));
    }
    finishLocal(n);
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
  /** The relabeling was local: colToSuper (left empty) is the factor's, which it kept. */
  bool local = false;
  std::vector<StorageIndex> colToSuper;
  /** A local relabeling's clean supernodes, renumbered (cleanHoldersOfWindows()). */
  std::vector<Index> renumbered;
  Index renumberedCount = 0;  ///< clean supernodes renumbered, by either relabeling
  std::vector<char> flag;  ///< scratch by supernode, zero between calls
  /** The supernode of each previous position. */
  const std::vector<StorageIndex>& previousColToSuper(const SupernodalFactor<Scalar, StorageIndex>& f) const {
    return local ? f.colToSuper : colToSuper;
  }
  std::vector<Index> firstCol, ncols;
  std::vector<std::vector<StorageIndex> > rows, parentPosition;  ///< dirty supernodes only
  std::vector<SupernodeBlock<Scalar> > values;                    ///< dirty supernodes only
  std::vector<CachedUpdate<Scalar> > cache;                        ///< dirty supernodes only
  /** The deferred corrections of the dirty supernodes' cached update matrices, set aside with
    * them rather than applied: a refactored supernode never needs them, a folded one carries them
    * on (extended to its new rows), and only a refactored child of a folded one, whose previous
    * update matrix the fold compares with the new one, applies them (applyPendingTo()). */
  std::vector<std::vector<typename SupernodalNumeric<Scalar, StorageIndex>::Correction> > pending;
  /** The previous call's cached update matrices, kept as buffers for this call's dirty supernodes
    * (by size): a buffer that is already allocated, touched and large enough needs neither the
    * page faults nor the zeroing of a new one (the update matrices of an insertion and of the
    * merge that undoes it are the same sizes, swapped). */
  SparePool<CachedUpdate<Scalar> > spareCache;
  /** The previous call's blocks of its dirty supernodes, kept likewise (by capacity). */
  SparePool<SupernodeBlock<Scalar> > spareValues;

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
      if (values[s].capacity() > 0) spareValues.add(values[s].capacity(), values[s]);  // (leaves it empty)
      if (!cache[s].empty()) {  // (by capacity: what it can hold; any values, in no layout of a matrix)
        cache[s].discardLayout();
        spareCache.add(Index(cache[s].capacity()), cache[s]);
      }
      CachedUpdate<Scalar>().swap(cache[s]);
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
    cache[s].layOut();
    if (!pending[s].empty()) SupernodalNumeric<Scalar, StorageIndex>::applyCorrectionsTo(pending[s], m, cache[s].data());
  }

  /** Gives \a block (empty) rows × cols entries: the storage of the smallest spare block that
    * holds them and at most twice as many, or else new storage with an eighth more room, so that a
    * later cut that gives the supernode a few more rows or columns fits in it (its values are
    * stale: the caller overwrites them). */
  void takeSpare(Index rows, Index cols, SupernodeBlock<Scalar>& block) {
    const Index size = rows * cols;
    if (size == 0) return;
    if (!spareValues.take(size, 2 * size, block)) block.reserve(size + size / 8);
    block.resize(rows, cols);  // (within the capacity: no reallocation)
#ifndef NDEBUG
    std::fill(block.data(), block.data() + size, Scalar(std::numeric_limits<typename NumTraits<Scalar>::Real>::quiet_NaN()));
#endif
  }

  /** Moves into \a buffer the smallest spare buffer of at least \a size scalars, if there is one
    * that holds at most twice as many (so that buffers do not grow from call to call; its values
    * are stale: the caller writes what it reads). */
  void takeSpare(Index size, CachedUpdate<Scalar>& buffer) {
    if (size == 0 || !spareCache.take(size, 2 * size, buffer)) return;
#ifndef NDEBUG  // stale values: poisoned, so that a test reading them fails
    std::fill(buffer.begin(), buffer.end(), Scalar(std::numeric_limits<typename NumTraits<Scalar>::Real>::quiet_NaN()));
#endif
  }

  /** Bytes held between calls (the spare buffers and the storage of the emptied row lists). */
  Index bytes() const {
    Index b = 0;
    for (const auto& entry : spareCache.entries) b += Index(entry.second.capacity() * sizeof(Scalar));
    for (const auto& entry : spareValues.entries) b += Index(entry.second.capacity() * sizeof(Scalar));
    b += spareCache.bytes() + spareValues.bytes();
    for (const auto& list : rows) b += Index(list.capacity() * sizeof(StorageIndex));
    for (const auto& list : parentPosition) b += Index(list.capacity() * sizeof(StorageIndex));
    return b;
  }
};

/** \internal The clean supernodes (mark == 0) that hold a position of a window of the local
  * relabeling \a relabel as a row, appended to \a out once each (\a flag: scratch by supernode,
  * zero between uses). A window lies in its owner's columns; a supernode holding one of them as a
  * row lies below the owner, and so do all between them (a row passes from child to parent): they
  * are found from the owner's children down, a child that holds none ending the search. */
template <typename Scalar, typename StorageIndex>
void cleanHoldersOfWindows(const SupernodalFactor<Scalar, StorageIndex>& f, const DofRelabeling<StorageIndex>& relabel,
                           const std::vector<char>& mark, std::vector<char>& flag, std::vector<Index>& out) {
  std::vector<Index> below;
  flag.resize(f.count(), 0);
  for (const auto& w : relabel.windows) {
    const Index owner = f.colToSuper[w.first];
    for (Index c = f.firstChild[owner]; c != -1; c = f.nextSibling[c]) below.push_back(c);
    while (!below.empty()) {
      const Index c = below.back();
      below.pop_back();
      const auto& node = f.nodes[c];
      const auto it = std::lower_bound(node.rows.begin() + node.ncols, node.rows.end(), w.first);
      if (it == node.rows.end() || *it >= w.second) continue;
      if (!mark[c] && !flag[c]) {
        flag[c] = 1;
        out.push_back(c);
      }
      for (Index g = f.firstChild[c]; g != -1; g = f.nextSibling[g]) below.push_back(g);
    }
  }
  for (Index c : out) flag[c] = 0;
}

/** \internal Calls \a step(s) on every supernode whose rows a relabeling changes: after a local
  * relabeling the dirty ones (the clean ones it renumbers are handled apart), otherwise every dirty
  * supernode and every clean one with a row at or past the first moved position (the others keep
  * their rows: positions below \a firstMoved do not move, and moved ones only go up). */
template <typename Scalar, typename StorageIndex, typename Step>
void forEachRelabeledSupernode(const SupernodalFactor<Scalar, StorageIndex>& f, bool local, Index firstMoved,
                               const std::vector<char>& mark, const std::vector<Index>& dirty, Step&& step) {
  if (local) {
    for (Index s : dirty) step(s);
  } else {
    for (Index s = 0; s < f.count(); ++s)
      if (mark[s] || Index(f.lastRow[s]) >= firstMoved) step(s);
  }
}

/** \internal Applies \a relabel to the factor: dirty supernodes (mark != 0) get new row lists
  * (merged rows dropped, copies inserted after their origins) and lose their values and cached
  * update matrix (moved into \a backup, to be recomputed); clean ones are renumbered in place
  * (after a local relabeling, only those that hold a moved position, backup.renumbered).
  * Recomputes first columns, column counts, colToSuper (unchanged by a local relabeling: the
  * positions keep their owners) and the relative positions of the children of dirty
  * supernodes. The assembly maps stay as they are (see remapAssemblyMaps()).
  * \a position: scratch by new position, all -1 between uses. */
template <typename Scalar, typename StorageIndex>
void relabelFactor(SupernodalFactor<Scalar, StorageIndex>& f, std::vector<CachedUpdate<Scalar> >& cache,
                   const DofRelabeling<StorageIndex>& relabel, const std::vector<char>& mark,
                   const std::vector<Index>& dirty, FactorStructureBackup<Scalar, StorageIndex>& backup,
                   std::vector<StorageIndex>& position) {
  const Index ns = f.count();
  backup.n = f.n;
  backup.local = relabel.local;
  backup.renumbered.clear();
  backup.renumberedCount = 0;
  if (relabel.local) {  // (the clean supernodes renumbered: found before the dirty ones' rows change)
    cleanHoldersOfWindows(f, relabel, mark, backup.flag, backup.renumbered);
    const Index from = relabel.firstMoved;
    for (Index s : backup.renumbered) {
      auto& node = f.nodes[s];
      StorageIndex* EIGEN_RESTRICT rows = node.rows.data();
      const StorageIndex* EIGEN_RESTRICT to = relabel.newPosition.data();
      const Index nr = node.nrows();
      for (Index k = Index(std::lower_bound(rows, rows + nr, StorageIndex(from)) - rows); k < nr; ++k) rows[k] = to[rows[k]];
      f.noteLastRow(s);
    }
    backup.renumberedCount = Index(backup.renumbered.size());
  } else {
    backup.colToSuper.swap(f.colToSuper);
  }
  backup.firstCol.resize(ns);
  backup.ncols.resize(ns);
  backup.rows.resize(ns);  // (all empty, some with storage: the previous call released them)
  backup.parentPosition.resize(ns);
  backup.values.resize(ns);
  backup.cache.resize(ns);
  backup.pending.resize(ns);
  auto relabelSupernode = [&](Index s) {
    auto& node = f.nodes[s];
    backup.renumberedCount += !mark[s];
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
  };
  // a clean supernode wholly below the first moved column stays as it is, unread (backup.firstCol
  // and backup.ncols are written for the dirty supernodes only); after a local relabeling, so
  // does every one but those renumbered above
  forEachRelabeledSupernode(f, relabel.local, relabel.firstMoved, mark, dirty, relabelSupernode);
  f.n = relabel.newSize;
  if (!relabel.local) {
    f.colToSuper.resize(f.n);  // one pass in order: a copy or a free position belongs to the supernode before it
    const Index unmoved = (std::min)(relabel.firstMoved, f.n);  // (the columns below keep their supernode)
    std::copy(backup.colToSuper.begin(), backup.colToSuper.begin() + unmoved, f.colToSuper.begin());
    StorageIndex owner = unmoved > 0 ? f.colToSuper[unmoved - 1] : StorageIndex(-1);
    for (Index j = unmoved; j < f.n; ++j) {
      const StorageIndex k = relabel.oldPosition[j];
      if (k >= 0) owner = backup.colToSuper[k];
      f.colToSuper[j] = owner;
    }
  }
  // relative positions of the children of dirty supernodes (the parents' rows changed)
  position.resize(f.n, StorageIndex(-1));
  for (Index p : dirty) {
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
void restoreFactor(SupernodalFactor<Scalar, StorageIndex>& f, std::vector<CachedUpdate<Scalar> >& cache,
                   const DofRelabeling<StorageIndex>& relabel, const std::vector<char>& mark,
                   const std::vector<Index>& dirty, FactorStructureBackup<Scalar, StorageIndex>& backup) {
  const Index ns = f.count();
  for (Index s : backup.renumbered) {  // (a local relabeling's clean supernodes)
    for (auto& r : f.nodes[s].rows) r = relabel.oldPosition[r];
    f.noteLastRow(s);
  }
  auto restoreSupernode = [&](Index s) {
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
  };
  // (the ones relabelFactor() left as they were are skipped)
  forEachRelabeledSupernode(f, backup.local, relabel.firstMoved, mark, dirty, restoreSupernode);
  for (Index p : dirty)
    for (Index c = f.firstChild[p]; c != -1; c = f.nextSibling[c]) f.nodes[c].parentPosition.swap(backup.parentPosition[c]);
  f.n = backup.n;
  if (!backup.local) f.colToSuper.swap(backup.colToSuper);
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
