// LowRankRemoval.h — removing dofs by a low-rank update of the supernodal factor (the
// "low-rank route" for small changes; Davis & Hager's row deletion done for many dofs in one
// pass, on the supernodal LL^H factor, paper §2 and DESIGN §3).
//
// Split the dofs into kept I and removed B in the current elimination order. Since A = L L^H,
// A_II = L(I,I) L(I,I)^H + W W^H with W = L(I,B): the factor of A^B restricted to I (paper
// Appendix A) is L(I,I) updated by the rank-|B| matrix W, and L^B is the identity on B. Column b
// of W is non-zero only on the supernodal path of b, so the update walks the supernodes of the
// union of those paths in postorder; at supernode S it gathers the W columns of its children and
// of its own removed columns, applies Givens rotations that fold them into S's kept columns
// (cost ~ 4 · rank · rows · columns), and passes the rest of W (compressed to at most as many
// columns as S has rows below) to the parent. The cached update matrix of S changes by exactly
// U_S += W_out W_out^H, so the cache stays usable by later partial refactorizations; that
// correction is deferred until the cache is read (SupernodalNumeric::deferCorrection()), since
// most cached matrices on the path are recomputed before they are read again. Rows of the
// removed dofs are zeroed wherever they appear (the row subtrees of B).
//
// The result solves to the accuracy of a fresh factorization, but is not bitwise equal to it.
// Removal keeps the matrix positive definite, so this route cannot fail.

#ifndef EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_REMOVAL_H
#define EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_REMOVAL_H

#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Flops of folding \a rank columns of W whose rows above \a start (in the supernode's
  * own numbering) are zero into a supernode of \a nr rows and \a nc columns: rotations or LQ
  * touch only the columns from \a start on. */
inline double foldFlops(double rank, double nr, double nc, double start) {
  const double width = nc - start;
  return width > 0 ? 4.0 * rank * (nr * width - width * width / 2) : 0.0;
}

/** \internal Flop estimate of the low-rank removal of the permuted columns \a removedNow over the
  * dirty supernodes \a dirty (increasing), from the symbolic structure only. */
template <typename Scalar, typename StorageIndex>
double lowRankRemovalFlops(const SupernodalFactor<Scalar, StorageIndex>& f, const std::vector<Index>& dirty,
                           const std::vector<StorageIndex>& removedNow, UpdateWorkspace<Scalar>& ws) {
  std::vector<Index>& rankOut = ws.rank;
  std::vector<Index>& local = ws.local;
  std::vector<Index>& first = ws.first;  // per supernode, its first column removed now
  for (StorageIndex b : removedNow) {
    const Index s = f.colToSuper[b], k = Index(b) - f.nodes[s].firstCol;
    first[s] = local[s]++ == 0 ? k : (std::min)(first[s], k);
  }
  double total = 0;
  for (Index s : dirty) {
    double flops = 0;
    const auto& node = f.nodes[s];
    const double nr = double(node.nrows()), nc = double(node.ncols), m = double(node.below());
    Index rank = local[s];
    if (local[s] > 0)  // own removed columns start below the first of them
      flops += foldFlops(double(local[s]), nr, nc, double(first[s] + 1));
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) {
      if (rankOut[c] == 0) continue;
      rank += rankOut[c];
      flops += foldFlops(double(rankOut[c]), nr, nc, double(f.nodes[c].parentPosition[0]));
    }
    if (double(rank) > m) flops += double(rank) * m * m;  // compression
    rankOut[s] = (std::min)(rank, node.below());  // (its update-matrix correction is deferred)
    ws.cost[s] = flops;
    total += flops;
  }
  for (Index s : dirty) rankOut[s] = local[s] = 0;
  return total;
}

/** \internal The fixed cost of folding into one supernode (gathering the columns passed up and
  * ordering them, the small dense objects of the fold, clearing its removed rows), in flops of a
  * refactorization: regions of thousands of small supernodes (an ARAP region of interest) are
  * folded at a cost that their flops do not show. restoreDofs' fold plan charges it too (foldPlan()
  * in LowRankTopUpdate.h): a restored region folds as many small supernodes. */
constexpr double RemovalFoldOverheadFlops = 16000.0;

/** \internal The cheapest mix of the two exact-enough routes for a removal: the dirty supernodes
  * split into a lower part updated by low-rank folds and a top part (closed under taking parents)
  * refactored from the cached update matrices, which the folds keep valid. A dynamic program over
  * the dirty tree, from the per-supernode low-rank costs in ws.cost (lowRankRemovalFlops()) and the
  * recomputation costs (reduced fronts counted on their kept rows and columns, \a removed: flags
  * by permuted column or null). Fills \a lowPart and \a topPart (increasing); \returns the flops. */
template <typename Scalar, typename StorageIndex>
double mixedRemovalPlan(const SupernodalFactor<Scalar, StorageIndex>& f, const std::vector<Index>& dirty,
                        UpdateWorkspace<Scalar>& ws, std::vector<Index>& lowPart, std::vector<Index>& topPart,
                        const char* removed) {
  const Index count = Index(dirty.size());
  std::vector<double> lowRank(count, 0.0), best(count, 0.0), lowRankBelow(count, 0.0), bestBelow(count, 0.0);
  std::vector<char> recompute(count, 0);
  std::vector<Index>& position = ws.local;  // supernode -> 1 + its position in dirty
  for (Index k = 0; k < count; ++k) position[dirty[k]] = k + 1;
  double total = 0;
  for (Index k = 0; k < count; ++k) {  // children before parents
    const Index s = dirty[k];
    lowRank[k] = ws.cost[s] + RemovalFoldOverheadFlops + lowRankBelow[k];
    const double again = frontFlops(f.nodes[s], removed) + bestBelow[k];
    recompute[k] = again < lowRank[k];
    best[k] = recompute[k] ? again : lowRank[k];
    const Index p = f.parent[s];
    if (p == -1) {
      total += best[k];
    } else {
      lowRankBelow[position[p] - 1] += lowRank[k];
      bestBelow[position[p] - 1] += best[k];
    }
  }
  std::vector<char> inTop(count, 0);
  for (Index k = count - 1; k >= 0; --k) {  // parents before children
    const Index p = f.parent[dirty[k]];
    inTop[k] = recompute[k] && (p == -1 || inTop[position[p] - 1]);
  }
  lowPart.clear();
  topPart.clear();
  for (Index k = 0; k < count; ++k) (inTop[k] ? topPart : lowPart).push_back(dirty[k]);
  for (Index s : dirty) {
    position[s] = 0;
    ws.cost[s] = 0;
  }
  return total;
}

/** \internal l := (l + conj(s) w) / c and w := c w - s l (new l), elementwise: one Givens
  * rotation of a column pair. Separate pointers so that the compiler vectorizes it. */
template <typename Scalar, typename RealScalar>
EIGEN_DONT_INLINE void rotateColumns(Index n, Scalar* EIGEN_RESTRICT l, Scalar* EIGEN_RESTRICT w, RealScalar cosine,
                                     RealScalar invCos, Scalar sine, Scalar conjSine) {
  for (Index i = 0; i < n; ++i) {
    const Scalar li = (l[i] + conjSine * w[i]) * invCos;
    l[i] = li;
    w[i] = cosine * w[i] - sine * li;
  }
}

/** \internal Columns of L per panel and rows per block of rotationSweep(). */
enum { RotationPanelColumns = 32, RotationRowBlock = 128 };

/** \internal One rotation of rotationSweep(): the column pair (L(:,j), W(:,t)) and its
  * parameters (see rotateColumns()). */
template <typename Scalar>
struct ColumnRotation {
  Index j, t;
  typename NumTraits<Scalar>::Real cosine, invCos;
  Scalar sine, conjSine;
};

/** \internal l := (l − conj(s) w) / c and w := c w − s l (new l), elementwise: one hyperbolic
  * rotation of a column pair (the downdate counterpart of rotateColumns()). */
template <typename Scalar, typename RealScalar>
EIGEN_DONT_INLINE void rotateColumnsHyperbolic(Index n, Scalar* EIGEN_RESTRICT l, Scalar* EIGEN_RESTRICT w,
                                               RealScalar cosine, RealScalar invCos, Scalar sine, Scalar conjSine) {
  for (Index i = 0; i < n; ++i) {
    const Scalar li = (l[i] - conjSine * w[i]) * invCos;
    l[i] = li;
    w[i] = cosine * w[i] - sine * li;
  }
}

/** \internal Sets \a g to the rotation of the column pair whose diagonal entry is \a ljj and
  * whose W entry there is \a wj: a Givens rotation (L L^H + w w^H), or with \a Hyperbolic a
  * hyperbolic one (L L^H − w w^H). \returns the new diagonal entry (not positive and finite: a
  * lost pivot, which the caller checks). */
template <bool Hyperbolic, typename Scalar>
typename NumTraits<Scalar>::Real makeRotation(typename NumTraits<Scalar>::Real ljj, Scalar wj,
                                              ColumnRotation<Scalar>& g) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  const RealScalar aw = numext::abs(wj);
  RealScalar r;
  if (Hyperbolic) {
    const RealScalar r2 = (ljj - aw) * (ljj + aw);
    if (!(r2 > RealScalar(0))) return RealScalar(0);
    r = numext::sqrt(r2);
  } else {
    r = numext::hypot(ljj, aw);
  }
  g.cosine = r / ljj;
  g.invCos = ljj / r;
  g.sine = wj / ljj;
  g.conjSine = numext::conj(g.sine);
  return r;
}

/** \internal Applies to the supernode's kept columns from \a start on, column by column, a
  * rotation with each of the W columns [first, first+count) that is non-zero on the column's
  * diagonal row: Givens rotations (an update, L L^H + w w^H) with the columns below
  * \a hyperbolicFrom, hyperbolic ones (a downdate, L L^H − w w^H) with the others, in that order
  * on each column (see makeRotation()): one sweep folds a signed change, the update first, so
  * that no pivot of the sweep falls below its final value. The rotations and their order on every
  * row are those of the plain loop over columns and W columns, but they are applied in panels
  * of RotationPanelColumns columns: a panel's rotations are made on its own rows, then applied
  * to the rows below one block of RotationRowBlock rows at a time, so that the block's rows of
  * the panel and of W stay in cache while all the panel's rotations pass over them (W and the
  * block are read once per panel, not once per column and sign). \a removed: flags by permuted
  * row, or null (none). \returns false on a lost pivot (the block is then partly changed);
  * \a flops gets the work. */
template <typename Scalar, typename StorageIndex, typename Dense>
bool signedRotationSweep(Supernode<Scalar, StorageIndex>& node, Dense& W, Index first, Index count,
                         Index hyperbolicFrom, Index start, const char* removed, double& flops) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  const Index nr = node.nrows(), nc = node.ncols;
  Scalar* L = node.values.data();
  Scalar* Wd = W.data();
  auto rotate = [hyperbolicFrom](Index n, Scalar* l, Scalar* w, const ColumnRotation<Scalar>& g) {
    if (g.t >= hyperbolicFrom)
      rotateColumnsHyperbolic(n, l, w, g.cosine, g.invCos, g.sine, g.conjSine);
    else
      rotateColumns(n, l, w, g.cosine, g.invCos, g.sine, g.conjSine);
  };
  std::vector<ColumnRotation<Scalar> > panel;
  for (Index j0 = start; j0 < nc; j0 += Index(RotationPanelColumns)) {
    const Index j1 = (std::min)(nc, j0 + Index(RotationPanelColumns));
    panel.clear();
    for (Index j = j0; j < j1; ++j) {  // the panel's rotations, applied to the panel's rows
      if (removed && removed[node.rows[j]]) continue;
      Scalar* lj = L + j * nr;
      for (Index t = first; t < first + count; ++t) {
        Scalar* w = Wd + t * nr;
        if (w[j] == Scalar(0)) continue;
        ColumnRotation<Scalar> rotation;
        rotation.j = j;
        rotation.t = t;
        const RealScalar r = t >= hyperbolicFrom ? makeRotation<true>(numext::real(lj[j]), w[j], rotation)
                                                 : makeRotation<false>(numext::real(lj[j]), w[j], rotation);
        if (!(r > RealScalar(0)) || !(r < NumTraits<RealScalar>::highest())) return false;
        lj[j] = Scalar(r);
        w[j] = Scalar(0);
        rotate(j1 - j - 1, lj + j + 1, w + j + 1, rotation);
        flops += 4.0 * double(nr - j);
        panel.push_back(rotation);
      }
    }
    for (Index i0 = j1; i0 < nr; i0 += Index(RotationRowBlock)) {  // ... then to the rows below, by blocks
      const Index rows = (std::min)(Index(RotationRowBlock), nr - i0);
      for (const ColumnRotation<Scalar>& rotation : panel)
        rotate(rows, L + rotation.j * nr + i0, Wd + rotation.t * nr + i0, rotation);
    }
  }
  return true;
}

/** \internal signedRotationSweep() with one sign: Givens rotations (an update), or with
  * \a Hyperbolic hyperbolic ones (a downdate). */
template <bool Hyperbolic, typename Scalar, typename StorageIndex, typename Dense>
bool rotationSweep(Supernode<Scalar, StorageIndex>& node, Dense& W, Index first, Index count, Index start,
                   const char* removed, double& flops) {
  return signedRotationSweep(node, W, first, count, Hyperbolic ? first : first + count, start, removed, flops);
}

/** \internal Fold by Givens rotations of the W columns [first, first+count), zero above row
  * \a start, column by column: [L(:,j) W(:,t)] G(j,t) for j >= start (rotationSweep()). */
template <typename Scalar, typename StorageIndex, typename Dense>
double foldByRotations(Supernode<Scalar, StorageIndex>& node, Dense& W, Index first, Index count, Index start,
                       const char* removed) {
  double flops = 0;
  rotationSweep<false>(node, W, first, count, start, removed, flops);
  return flops;
}

/** \internal Below this rank the fold uses rotations; above it LAPACK's blocked
  * triangular-pentagonal LQ (?tplqt/?tpmlqt), where the per-call cost pays off. */
enum { BlockedFoldMinRank = 8 };

/** \internal Folds the W columns [first, first+count) (rows = the supernode's rows; zero on
  * removed rows and above row \a start) into the supernode's kept columns, leaving in W's rows
  * below the part to pass on. Unit columns of removed dofs stay unit columns (their rows are
  * zero in W). \returns the flops spent. */
template <typename Scalar, typename StorageIndex, typename Dense>
double foldIntoColumns(Supernode<Scalar, StorageIndex>& node, Dense& W, Index first, Index count, Index start,
                       const char* removed) {
  const Index nr = node.nrows(), nc = node.ncols, m = nr - nc, width = nc - start;
  EIGEN_UNUSED_VARIABLE(m);  // (read by the BLAS path only)
  if (count == 0 || width <= 0) return 0;
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    if (count >= BlockedFoldMinRank && width >= BlockedFoldMinRank) {
      typedef typename NumTraits<Scalar>::Real RealScalar;
      Scalar* L = node.values.data() + start * nr + start;  // the trailing block from (start, start)
      Scalar* Wg = W.data() + first * nr + start;
      const int mb = int((std::min<Index>)(32, width));
      std::vector<Scalar> t(Index(mb) * width), work(Index(mb) * (std::max)(width, m));
      // LQ of [L11 W_top] = [L11' 0] Q, then [L21 W_below] Q^H = [L21' W_out]
      int info = blasTplqt(int(width), int(count), mb, L, int(nr), Wg, int(nr), t.data(), mb, work.data());
      if (info == 0 && m > 0)
        info = blasTpmlqtRightAdjoint(int(m), int(count), int(width), mb, Wg, int(nr), t.data(), mb, L + width,
                                      int(nr), Wg + width, int(nr), work.data());
      eigen_assert(info == 0 && "LAPACK tplqt/tpmlqt failed");
      W.block(start, first, width, count).setZero();
      for (Index j = start; j < nc; ++j)  // Householder LQ may leave negative pivots: flip the column
        if (numext::real(node.values(j, j)) < RealScalar(0)) node.values.col(j).tail(nr - j) *= Scalar(-1);
      return 2.0 * double(width) * double(width) * double(count) + 4.0 * double(m) * double(width) * double(count);
    }
  }
#endif
  return foldByRotations(node, W, first, count, start, removed);
}

/** \internal A block of W columns arriving at a supernode: from a child (child >= 0) or the
  * supernode's own removed columns (child = -1), zero above row \a start. */
struct FoldSource {
  Index start, count, child;
};

/** \internal Calls \a fold(first, count, start) for the W columns of \a sources (in W in the order
  * of the list, sorted by start), one group of sources with close starts at a time, so that each
  * fold touches only the supernode's columns (\a nc of them) from its group's start on.
  * \returns false as soon as a fold does (true otherwise). */
template <typename Fold>
bool forEachSourceGroup(const std::vector<FoldSource>& sources, Index nc, Fold&& fold) {
  for (std::size_t g = 0, first = 0; g < sources.size();) {
    const Index start = sources[g].start;
    Index count = 0;
    std::size_t h = g;
    for (; h < sources.size(); ++h) {  // join sources while the wasted part is small
      const bool close = sources[h].start - start <= (nc - start) / 8;
      if (h > g && !close && count >= Index(BlockedFoldMinRank)) break;
      count += sources[h].count;
    }
    if (!fold(Index(first), count, start)) return false;
    first += std::size_t(count);
    g = h;
  }
  return true;
}

/** \internal Folds the W columns of \a sources (in W in the order of the list, sorted by start)
  * into the supernode's kept columns, by groups (forEachSourceGroup()). \returns the flops spent. */
template <typename Scalar, typename StorageIndex, typename Dense>
double foldSources(Supernode<Scalar, StorageIndex>& node, Dense& W, const std::vector<FoldSource>& sources,
                   const char* removed) {
  double flops = 0;
  forEachSourceGroup(sources, node.ncols, [&](Index first, Index count, Index start) {
    flops += foldIntoColumns(node, W, first, count, start, removed);
    return true;
  });
  return flops;
}

/** \internal Removes the permuted columns \a removedNow (whose flags are already set in
  * \a removed, with those of earlier removals) from the factor by a low-rank update of the dirty
  * supernodes \a dirty (increasing, as from dirtySupernodes()), keeping the cached update
  * matrices consistent. \returns the flops spent. */
template <typename Scalar, typename StorageIndex>
double lowRankRemoval(SupernodalFactor<Scalar, StorageIndex>& f, SupernodalNumeric<Scalar, StorageIndex>& numeric,
                      const std::vector<Index>& dirty, const char* removed, UpdateWorkspace<Scalar>& ws) {
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  std::vector<Dense>& carried = ws.carried;  // W passed from a supernode to its parent
  double flops = 0;
  std::vector<Index> removedPositions, removedColumns;
  std::vector<FoldSource> sources;
  for (Index s : dirty) {
    auto& node = f.nodes[s];
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    Scalar* L = node.values.data();
    removedPositions.clear();
    removedColumns.clear();
    for (Index p = 0; p < nr; ++p)
      if (removed[node.rows[p]]) removedPositions.push_back(p);
    // 1. W at this supernode: the children's carried columns, then the removed columns that
    //    are still columns of L (not unit yet). Each source is zero above its first row here (a
    //    child's: its first row below; a removed column p: p + 1); W's columns are ordered by
    //    that start so that a fold touches only the columns from its start on.
    sources.clear();
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c])
      if (carried[c].cols() > 0) sources.push_back(FoldSource{f.nodes[c].parentPosition[0], carried[c].cols(), c});
    for (Index p : removedPositions) {
      if (p >= nc) break;
      bool unit = true;
      for (Index i = p + 1; i < nr && unit; ++i) unit = L[i + p * nr] == Scalar(0);
      if (!unit || L[p + p * nr] != Scalar(1)) removedColumns.push_back(p);
    }
    if (!removedColumns.empty())
      sources.push_back(FoldSource{removedColumns.front() + 1, Index(removedColumns.size()), -1});
    std::sort(sources.begin(), sources.end(), [](const FoldSource& a, const FoldSource& b) { return a.start < b.start; });
    Index rank = 0;
    for (const FoldSource& src : sources) rank += src.count;
    Dense W = Dense::Zero(nr, rank);
    Index q = 0;
    for (const FoldSource& src : sources) {
      if (src.child >= 0) {
        const Dense& wc = carried[src.child];
        const auto& pos = f.nodes[src.child].parentPosition;
        for (Index j = 0; j < wc.cols(); ++j, ++q)
          for (Index k = 0; k < wc.rows(); ++k) W(pos[k], q) = wc(k, j);
        carried[src.child] = Dense();
      } else {
        for (Index p : removedColumns) {
          for (Index i = p + 1; i < nr; ++i) W(i, q) = L[i + p * nr];
          ++q;
        }
      }
    }
    // 2. the removed dofs' rows and columns become those of the identity, in L, U (and its
    //    deferred corrections) and W
    if (!removedPositions.empty()) numeric.clearRemoved(f, s, removed);
    for (Index p : removedPositions) W.row(p).setZero();
    if (rank == 0) continue;
    // 3. fold W into the kept columns, [L(:,J) W] G = [L'(:,J) W'] with G unitary and W' zero on
    //    the supernode's own rows
    flops += foldSources(node, W, sources, removed);
    if (m == 0) continue;
    // 4. what is left of W lives on the rows below: compress, correct U, carry to the parent
    Dense out = W.bottomRows(m);
    if (out.cols() > m) {
      HouseholderQR<Dense> qr(out.adjoint());
      out = qr.matrixQR().topRows(m).template triangularView<Upper>().adjoint();
      flops += double(rank) * double(m) * double(m);
    }
    Dense correction = out;  // U_S += W_out W_out^H, deferred until the cache is read
    numeric.deferCorrection(f, s, correction);
    if (f.parent[s] != -1) carried[s].swap(out);
  }
  return flops;
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_REMOVAL_H
