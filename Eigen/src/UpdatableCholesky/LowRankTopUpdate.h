// LowRankTopUpdate.h — after a cut, a merge, a change of values or a restore, dirty supernodes are
// updated by signed low-rank folds instead of being refactored where that is cheaper
// (insertDofs/mergeDofs, paper §4.2 / Algorithm 4; updateColumns, an insertion without copies;
// restoreDofs, whose restored rows and columns go from the identity's to the matrix's, with the
// same structure; Davis & Hager's up- and downdates on the supernodal factor, DESIGN §3).
//
// A structural change makes the supernodes on the paths from the changed columns to the roots
// dirty. Each is refactored (Algorithm 4) or folded. A folded one starts from its previous block,
// extended to its new rows and columns as the factor of the previous matrix extended with a
// diagonal placeholder per copy (zero rows for the copies; a copy's column is its placeholder,
// the square root of its new diagonal entry), and its previous update matrix, extended with zero
// rows and columns (as in the paper's rowadd setup). Its values then change through:
//  - its own input: a column that gained copies or changed values brings the change
//    e_j d^H + d e_j^H (d: new minus previous entries of column j on the supernode's rows, the
//    diagonal halved), split as u u^H − v v^H with u, v = (a e_j ± d / a) / sqrt(2), a² = |d|,
//    zero above the column's own row. A merge folds in the previous structure instead: each merged
//    dof's new column is a diagonal placeholder (its previous diagonal entry), so that after the
//    fold its row is zero and its column the placeholder's, and both are dropped
//    (foldMergedSupernode(); without removed dofs, whose flags are in the new numbering only);
//  - the update matrices its children pass up. The change of a refactored child's update matrix,
//    U' − U = L21' L21'^H − L21 L21^H, has a small rank: written in the variables (last copy,
//    differences to it), a cut that glues back to the uncut matrix only adds one row and column
//    per copy (a row addition, Davis & Hager), so U' − U has rank at most the copies below, plus
//    two per copy row of the child (the unit transform that moves a copy row back onto its
//    origin); a merge removes them again. Each dof where the cut does not glue back adds one
//    (gluingMismatches()). The change is split into P P^H − N N^H (a range sampled with the
//    likely rank, again with the bound if that misses, and an eigendecomposition of the small
//    core; eigenvalues at rounding level are dropped). A folded child passes what its fold left.
// The fold is the update P (Givens rotations or blocked LQ, as for removals), then the downdate N
// (blocked hyperbolic reflections, BlockedDowndate.h, or hyperbolic rotations for small ranks;
// small ranks of both signs: one sweep, Givens then hyperbolic rotations on each column). What it
// leaves on the rows below is compressed to the numerical rank of P P^H − N N^H (the pairs u, v
// of the own changes largely cancel there), passed up, and given to the cached update matrix as
// a deferred ± correction. Each folded supernode costs ~4 · rank · rows · columns instead of its
// refactorization and its children's extend-adds. The folded supernodes need not be closed under
// parents: a cut through the root separator may refactor the root but still fold the separators
// below it, whose deferred corrections the root's refactorization applies. Which supernodes are
// refactored and which are folded is chosen per update by a dynamic program over the dirty tree
// on flop estimates.
//
// In exact arithmetic no pivot of the downdate can vanish when the new matrix is positive
// definite (each intermediate matrix dominates the final one). A pivot that does is reported,
// and the caller refactors every dirty supernode from the caches instead. The factor solves to
// the accuracy of a fresh one but is not bitwise equal to it.

#ifndef EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_TOP_UPDATE_H
#define EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_TOP_UPDATE_H

#include <cstdint>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Random vectors sampled beyond the rank bound of an update-matrix change. */
enum { UpdateChangeOversampling = 8 };
/** \internal Time per flop of the folds (blocked LQ and reflections, rotations for small ranks,
  * with the copies of the previous block) relative to the BLAS-3 flops of a refactorization, as
  * measured on igea and bunny cuts (2-3.5x; more for small supernodes): the plan compares times,
  * not flop counts. */
constexpr double FoldFlopWeight = 2.5;
/** \internal The same for the split of an update-matrix change (matrix products, a thin QR and a
  * small eigenproblem: 1.1x for m ≈ 250, more for small ones). */
constexpr double SplitFlopWeight = 1.5;
/** \internal A fold plan is taken when its modelled time is below this share of the dirty
  * supernodes' refactorization: the route also pays the compare of the cut matrix with the
  * uncut one and the bookkeeping of the folded supernodes, which the flop model leaves out (on
  * bunny and igea cuts a plan saving under ~5% was slower than the partial refactorization). */
constexpr double MixedRouteShare = 0.95;

/** \internal A refactored supernode whose parent is folded: the change of its update matrix is
  * split with at most \a bound columns, \a likely expected (updateMatrixChange()). */
struct FoldBoundary {
  Index supernode, bound, likely;
};

/** \internal Flops of splitting the change of an update matrix (m × m) of rank at most \a rank
  * into P P^H − N N^H (randomized range finder, check, small eigendecomposition). */
inline double updateChangeFlops(double m, double rank) {
  const double k = (std::min)(m, rank + double(UpdateChangeOversampling));
  return 2 * k >= m ? 9.0 * m * m * m : 8.0 * m * m * k + 9.0 * k * k * k;
}

/** \internal Flops of compressSignedChange() on m rows and k columns (a fold that leaves both
  * an update and a downdate on its rows below; at least two columns). */
inline double signedCompressionFlops(double m, double k) {
  if (m <= 0 || k < 2) return 0.0;
  const double r = (std::min)(m, k);
  return 4.0 * m * k * k + 9.0 * r * r * r;
}

/** \internal The signed square-root factors of a small Hermitian \a core = V Λ V^H: \a Vp holds
  * sqrt(λ) v for its eigenvalues λ above \a dropped, \a Vn sqrt(−λ) v for those below −dropped
  * (the others, at rounding level, are dropped), so that core ≈ Vp Vp^H − Vn Vn^H. */
template <typename Dense>
void signedSquareRoots(const Dense& core, typename NumTraits<typename Dense::Scalar>::Real dropped, Dense& Vp,
                       Dense& Vn) {
  SelfAdjointEigenSolver<Dense> eig(core);
  const auto& lambda = eig.eigenvalues();
  Index positive = 0, negative = 0;
  for (Index i = 0; i < lambda.size(); ++i) {
    positive += lambda[i] > dropped;
    negative += lambda[i] < -dropped;
  }
  Vp.resize(core.rows(), positive);
  Vn.resize(core.rows(), negative);
  for (Index i = 0, p = 0, q = 0; i < lambda.size(); ++i) {
    if (lambda[i] > dropped) Vp.col(p++) = eig.eigenvectors().col(i) * numext::sqrt(lambda[i]);
    if (lambda[i] < -dropped) Vn.col(q++) = eig.eigenvectors().col(i) * numext::sqrt(-lambda[i]);
  }
}

/** \internal Splits the change D = U' − U of a cached update matrix (m × m, lower triangles,
  * column-major) into P P^H − N N^H with as few columns as its numerical rank, which is at most
  * \a rankBound (see foldPlan(); a wrong bound is caught by the check below) and is expected to
  * be about \a likelyRank. The range of D is sampled with likelyRank + a few random vectors
  * (deterministic signs) and D is checked to lie in that range; when it does not, it is sampled
  * again with rankBound + a few. The small projected matrix is then diagonalized; eigenvalues at
  * rounding level are dropped. \returns false when D is not captured (the bound did not hold);
  * \a flops gets the work. */
template <typename Scalar>
bool updateMatrixChange(const Scalar* newU, const Scalar* oldU, Index m, Index likelyRank, Index rankBound,
                        Matrix<Scalar, Dynamic, Dynamic>& P, Matrix<Scalar, Dynamic, Dynamic>& N, double& flops) {
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  typedef typename NumTraits<Scalar>::Real RealScalar;
  Dense D(m, m);
  RealScalar scale2 = 0;
  for (Index j = 0; j < m; ++j)
    for (Index i = j; i < m; ++i) {
      const Scalar u = newU[i + j * m], v = oldU[i + j * m];
      const RealScalar weight = i == j ? RealScalar(1) : RealScalar(2);
      scale2 += weight * (numext::abs2(u) + numext::abs2(v));
      D(i, j) = u - v;
      D(j, i) = numext::conj(u - v);
    }
  for (Index j = 0; j < m; ++j) D(j, j) = Scalar(numext::real(D(j, j)));
  const RealScalar scale = numext::sqrt(scale2);
  const RealScalar dropped = RealScalar(64) * NumTraits<RealScalar>::epsilon() * scale;
  const Index kMax = (std::min)(m, rankBound + Index(UpdateChangeOversampling));
  Index k = (std::min)(kMax, (std::min)(likelyRank, rankBound) + Index(UpdateChangeOversampling));
  Dense Q, B;
  while (true) {
    flops += updateChangeFlops(double(m), double(k - Index(UpdateChangeOversampling)));
    if (2 * k >= m) {  // small or not low-rank enough: diagonalize D itself
      Q.resize(0, 0);
      B.swap(D);
      break;
    }
    Dense omega(m, k);
    std::uint64_t state = 0x9E3779B97F4A7C15ull;
    for (Index j = 0; j < k; ++j)
      for (Index i = 0; i < m; ++i) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        omega(i, j) = (state >> 63) ? Scalar(1) : Scalar(-1);
      }
    const Dense Y = D * omega;
    HouseholderQR<Dense> qr(Y);
    Q = qr.householderQ() * Dense::Identity(m, k);
    const Dense Z = D * Q;
    B.noalias() = Q.adjoint() * Z;
    const Dense QB = Q * B;
    Dense missed = D;
    missed.noalias() -= QB * Q.adjoint();  // what the range of Q misses
    if (missed.norm() <= RealScalar(1000) * NumTraits<RealScalar>::epsilon() * scale) break;
    if (k == kMax) return false;
    k = kMax;  // the likely rank was too low: sample up to the bound
  }
  Dense Vp, Vn;
  signedSquareRoots(B, dropped, Vp, Vn);
  if (Q.size() > 0) {
    P.noalias() = Q * Vp;
    N.noalias() = Q * Vn;
  } else {
    P.swap(Vp);
    N.swap(Vn);
  }
  return true;
}

/** \internal Chooses, per dirty supernode of a structural change or a restore (\a dirty,
  * increasing), whether it is refactored or folded, by a dynamic program over the dirty tree on
  * flop estimates. A supernode may be folded when flagged in \a eligible (same columns; its
  * rows may have gained copies, which enter its block and update matrix as zero rows: the old
  * factor extended with identity for the copies). The folded ones need not be closed under
  * parents: a folded supernode under a refactored one leaves its update-matrix change as a
  * deferred correction that the parent's refactorization applies.
  * \a rankColumns: per supernode, how much its columns add to the rank of the change of an
  * update matrix above them: one per copy or merged dof and per dof where the cut does not glue
  * back (gluingMismatches()). \a rowRank: what a supernode's copy rows add to the rank of its
  * own update matrix's change (two per copy row). Both give the bound the split samples with (a
  * restore: one per restored column with a kept neighbour, two per restored row).
  * \a likelyRankColumns: \a rankColumns without the dofs whose mismatch is small (at most
  * sqrt(eps) of its entries), which a change far above mostly drops (below rounding): the rank
  * the costs are estimated with. With \a force, every eligible supernode is folded.
  * On return \a folded (by supernode, all zero on entry) flags the folded supernodes, \a top
  * lists them and \a bottom the refactored ones (both increasing), and \a boundary each
  * refactored supernode whose parent is folded, with the rank bound of its update matrix's
  * change. \a foldOverhead: flops charged per folded supernode besides its fold (the work a fold
  * does that its flops do not show). \returns the estimated cost of the plan in refactorization
  * flops (fold flops weighted by FoldFlopWeight). */
template <typename Scalar, typename StorageIndex>
double foldPlan(const SupernodalFactor<Scalar, StorageIndex>& f, const std::vector<Index>& dirty,
                const std::vector<char>& eligible, const std::vector<Index>& rankColumns,
                const std::vector<Index>& likelyRankColumns, const std::vector<Index>& rowRank, const char* removed,
                bool force, std::vector<char>& folded, std::vector<Index>& bottom, std::vector<Index>& top,
                std::vector<FoldBoundary>& boundary, UpdateWorkspace<Scalar>& ws, double foldOverhead = 0) {
  const Index count = Index(dirty.size());
  const double never = std::numeric_limits<double>::infinity();
  // per position in dirty: the subtree's cost when this supernode is refactored / folded
  std::vector<double> refactor(count, 0.0), fold(count, never), split(count), apply(count), rankBelow(count),
      likelyBelow(count), rankIn(count, 0.0), rankOut(count), rankBoundary(count), likelyBoundary(count),
      underRefactor(count, 0.0), underFold(count, 0.0);
  std::vector<Index> start(count);
  std::vector<Index>& position = ws.local;  // supernode -> 1 + its position in dirty
  for (Index k = 0; k < count; ++k) position[dirty[k]] = k + 1;
  for (Index k = 0; k < count; ++k) {
    start[k] = f.nodes[dirty[k]].ncols;
    rankBelow[k] = double(rankColumns[dirty[k]]);
    likelyBelow[k] = double(likelyRankColumns[dirty[k]]);
  }
  for (Index k = 0; k < count; ++k) {  // children before parents
    const Index s = dirty[k];
    const auto& node = f.nodes[s];
    const double nr = double(node.nrows()), nc = double(node.ncols), m = double(node.below());
    refactor[k] = frontFlops(node, removed) + underRefactor[k];
    rankBoundary[k] = (std::min)(m, rankBelow[k] + double(rowRank[s]));
    likelyBoundary[k] = (std::min)(m, likelyBelow[k] + double(rowRank[s]));
    split[k] = SplitFlopWeight * updateChangeFlops(m, likelyBoundary[k]);
    rankOut[k] = likelyBoundary[k];
    if (eligible[s]) {
      const double own = double(ws.ownRank[s]);
      fold[k] = FoldFlopWeight * (foldFlops(rankIn[k], nr, nc, double(start[k])) +
                                  foldFlops(own, nr, nc, double(ws.ownStart[s]))) +
                signedCompressionFlops(m, rankIn[k] + own) + foldOverhead + underFold[k];
      rankOut[k] = (std::min)(m, rankIn[k] + own);
    }
    apply[k] = m * m * rankOut[k];  // the deferred correction, applied by a refactored parent
    const Index p = f.parent[s];
    if (p == -1) continue;
    const Index q = position[p] - 1;
    rankBelow[q] += rankBelow[k];
    likelyBelow[q] += likelyBelow[k];
    rankIn[q] += (std::min)(rankOut[k], likelyBoundary[k]);
    underRefactor[q] += (std::min)(refactor[k], fold[k] + apply[k]);
    underFold[q] += (std::min)(refactor[k] + split[k], fold[k]);
    start[q] = (std::min)(start[q], Index(node.parentPosition[0]));
  }
  std::vector<char> inTop(count, 0);
  for (Index k = count - 1; k >= 0; --k) {  // parents before children
    const Index s = dirty[k], p = f.parent[s];
    if (!eligible[s]) continue;
    if (force) {
      inTop[k] = 1;
    } else if (p == -1) {
      inTop[k] = fold[k] < refactor[k];
    } else {
      const bool parentFolded = inTop[position[p] - 1] != 0;
      inTop[k] = parentFolded ? fold[k] < refactor[k] + split[k] : fold[k] + apply[k] < refactor[k];
    }
  }
  bottom.clear();
  top.clear();
  boundary.clear();
  double total = 0;
  for (Index k = 0; k < count; ++k) {
    const Index s = dirty[k], p = f.parent[s];
    const auto& node = f.nodes[s];
    const bool parentFolded = p != -1 && inTop[position[p] - 1];
    if (inTop[k]) {
      top.push_back(s);
      folded[s] = 1;
      total += FoldFlopWeight * (foldFlops(rankIn[k], double(node.nrows()), double(node.ncols), double(start[k])) +
                                 foldFlops(double(ws.ownRank[s]), double(node.nrows()), double(node.ncols),
                                           double(ws.ownStart[s]))) +
               signedCompressionFlops(double(node.below()), rankIn[k] + double(ws.ownRank[s])) + foldOverhead;
      if (p != -1 && !parentFolded) total += apply[k];
    } else {
      bottom.push_back(s);
      total += frontFlops(node, removed);
      if (parentFolded) {
        total += split[k];
        boundary.push_back(FoldBoundary{s, Index(rankBoundary[k]), Index(likelyBoundary[k])});
      }
    }
  }
  for (Index s : dirty) position[s] = 0;
  return total;
}

/** \internal Where the \a count previous rows \a oldRows (permuted, before the change, moved by
  * \a newPosition) of a supernode or of its rows below lie among its new rows \a newRows, which
  * hold them all (an insertion only adds copy rows; a merge keeps the rows of the supernodes
  * this is used for). */
template <typename StorageIndex>
void previousRowPositions(const StorageIndex* oldRows, Index count, const StorageIndex* newRows,
                          const std::vector<StorageIndex>& newPosition, std::vector<Index>& at) {
  at.resize(count);
  Index q = 0;
  for (Index k = 0; k < count; ++k) {
    const StorageIndex r = newPosition[oldRows[k]];
    eigen_assert(r >= 0 && "a previous row of a folded supernode or of its refactored child was merged away");
    while (newRows[q] != r) ++q;
    at[k] = q++;
  }
}

/** \internal The deferred corrections \a previous of a previous update matrix, extended as
  * extendUpdateMatrix() extends the matrix (row i to row \a at[i] of \a m, zero rows for the
  * copies), appended to \a out. */
template <typename Correction>
void extendCorrections(const std::vector<Correction>& previous, const std::vector<Index>& at, Index m,
                       std::vector<Correction>& out) {
  for (const Correction& c : previous) {
    eigen_assert(c.W.rows() == Index(at.size()) && "a deferred correction of another shape than its update matrix");
    out.emplace_back();
    out.back().sign = c.sign;
    out.back().W.setZero(m, c.W.cols());
    const Index rows = Index(at.size());
    for (Index j = 0; j < c.W.cols(); ++j) {  // (by columns: W is column-major, a row copy strides over all of it)
      const auto* from = c.W.data() + j * rows;
      auto* to = out.back().W.data() + j * m;
      for (Index i = 0; i < rows; ++i) to[at[i]] = from[i];
    }
  }
}

/** \internal Gives a folded supernode its previous block and update matrix, in its new rows and
  * columns: the rows of the copies it gained are zero and the columns of the copies it gained
  * (an insertion of copies of its own dofs) are those of a diagonal entry
  * sqrt(pivotOf(permuted column)), as in the factor of the previous matrix extended with a
  * diagonal placeholder for each copy (its old columns are the same). The update matrix is taken
  * from the backup (\a oldU), relabeled to the new rows without a copy (CachedUpdate); the block
  * too when the rows are the same (\returns true), else it is copied (\a at, \a runs: scratch).
  * Either way the supernode must be recomputed if the update is reverted. */
template <typename Scalar, typename StorageIndex, typename PivotOf>
bool takePreviousBlock(Supernode<Scalar, StorageIndex>& node, const std::vector<StorageIndex>& oldRows,
                       SupernodeBlock<Scalar>& oldValues, CachedUpdate<Scalar>& oldU,
                       const std::vector<StorageIndex>& newPosition, std::vector<Index>& at, CachedUpdate<Scalar>& U,
                       std::vector<PositionRun>& runs, PivotOf&& pivotOf) {
  const Index nr = node.nrows(), nc = node.ncols, m = nr - nc, oldNr = Index(oldRows.size()), oldNc = oldValues.cols();
  eigen_assert(oldNc <= nc && oldValues.rows() == oldNr && "a folded supernode keeps its columns");
  if (oldNr == nr) {
    node.values.swap(oldValues);
    U.swap(oldU);
    return true;
  }
  previousRowPositions(oldRows.data(), oldNr, node.rows.data(), newPosition, at);
  node.values.resize(nr, nc);
  positionRuns(at.data(), oldNr, runs);
  for (Index j = 0, k = 0; j < nc; ++j) {
    Scalar* column = node.values.data() + j * nr;
    if (k < oldNc && at[k] == j) {  // an old column
      std::size_t first = 0;
      copyByRuns(oldValues.data() + k * oldNr, runs, first, column, Index(0), nr);
      ++k;
    } else {  // a copy's: its placeholder
      std::fill(column, column + nr, Scalar(0));
      column[j] = Scalar(numext::sqrt(pivotOf(Index(node.rows[j]))));
    }
  }
  for (Index k = oldNc; k < oldNr; ++k) at[k - oldNc] = at[k] - nc;  // (the rows below, from the supernode's first one below)
  const Index oldM = oldNr - oldNc;
  at.resize(oldM);
  if (oldM > 0) {
    U.swap(oldU);
    U.relabelRows(oldM, at, m);
  } else {
    extendUpdateMatrix(oldU.data(), at, m, U, runs);
  }
  return false;
}

/** \internal An entry of an input change (the new matrix minus the previous one, as factored) in
  * the lower triangle of the permuted matrix (row >= col), with the supernode of its column. */
template <typename Scalar, typename StorageIndex>
struct InputChangeEntry {
  Index supernode;
  StorageIndex row, col;
  Scalar value;
};

/** \internal Appends entry (\a row, \a col) of an input change, \a value (dofs numbered by \a perm
  * into permuted columns), to \a entries in the lower triangle (conjugated when it crosses the
  * diagonal), when its column's supernode is \a folded and neither dof is \a removed (or null). */
template <typename Scalar, typename StorageIndex>
void appendInputChange(std::vector<InputChangeEntry<Scalar, StorageIndex> >& entries, const StorageIndex* perm,
                       const std::vector<StorageIndex>& colToSuper, const std::vector<char>& folded, const char* removed,
                       Index row, Index col, Scalar value) {
  Index pi = perm[row], pj = perm[col];
  if (pi < pj) {
    std::swap(pi, pj);
    value = numext::conj(value);
  }
  const Index t = colToSuper[pj];
  if (!folded[t] || (removed && (removed[pi] || removed[pj]))) return;
  entries.push_back(InputChangeEntry<Scalar, StorageIndex>{t, StorageIndex(pi), StorageIndex(pj), value});
}

/** \internal Splits the input change of the supernodes named in \a entries (summed where an
  * entry repeats; sorted here) into ws.ownPositive and ws.ownNegative, P P^H − N N^H on the
  * supernode's rows \a rowsOf(t), two columns per changed column: column j's change d (its
  * diagonal halved) gives e_j d^H + d e_j^H = u u^H − v v^H with u, v = (a e_j ± d / a) / sqrt(2),
  * a² = |d| (balanced), both zero above row j (ws.ownPositiveStart/ownNegativeStart).
  * \a position: scratch by permuted row, covering every row, all -1 between uses. */
template <typename Scalar, typename StorageIndex, typename RowsOf>
void splitInputChanges(std::vector<InputChangeEntry<Scalar, StorageIndex> >& entries, RowsOf&& rowsOf,
                       std::vector<StorageIndex>& position, UpdateWorkspace<Scalar>& ws) {
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  typedef typename NumTraits<Scalar>::Real RealScalar;
  typedef InputChangeEntry<Scalar, StorageIndex> Entry;
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.supernode != b.supernode ? a.supernode < b.supernode : a.col != b.col ? a.col < b.col : a.row < b.row;
  });
  const RealScalar half = RealScalar(0.5), rootHalf = numext::sqrt(half);
  for (std::size_t g = 0; g < entries.size();) {
    const Index t = entries[g].supernode;
    std::size_t h = g;
    Index columns = 0;
    for (; h < entries.size() && entries[h].supernode == t; ++h) columns += h == g || entries[h].col != entries[h - 1].col;
    const std::vector<StorageIndex>& rows = rowsOf(t);
    const Index nr = Index(rows.size()), firstCol = Index(rows[0]);
    for (Index k = 0; k < nr; ++k) position[rows[k]] = StorageIndex(k);
    Dense D = Dense::Zero(nr, columns);
    std::vector<Index> local(columns);
    for (Index q = -1; g < h; ++g) {
      if (q < 0 || Index(entries[g].col) != firstCol + local[q]) local[++q] = Index(entries[g].col) - firstCol;
      D(position[entries[g].row], q) += entries[g].value;
    }
    for (Index k = 0; k < nr; ++k) position[rows[k]] = StorageIndex(-1);
    Dense& P = ws.ownPositive[t];
    Dense& N = ws.ownNegative[t];
    std::vector<Index>&startP = ws.ownPositiveStart[t], &startN = ws.ownNegativeStart[t];
    P.resize(nr, columns);
    N.resize(nr, columns);
    startP.clear();
    startN.clear();
    for (Index q = 0; q < columns; ++q) {
      const Index j = local[q];
      auto d = D.col(q);
      d[j] = Scalar(half * numext::real(d[j]));
      const RealScalar norm = d.norm();
      if (!(norm > RealScalar(0))) continue;
      const RealScalar a = numext::sqrt(norm);
      const Index k = Index(startP.size());
      P.col(k) = d * (rootHalf / a);
      N.col(k) = -P.col(k);
      P(j, k) += Scalar(rootHalf * a);
      N(j, k) += Scalar(rootHalf * a);
      startP.push_back(j);
      startN.push_back(j);
    }
    P.conservativeResize(nr, Index(startP.size()));
    N.conservativeResize(nr, Index(startN.size()));
  }
}

/** \internal Rewrites a signed change P P^H − N N^H (both m rows) with as few columns as its
  * numerical rank: a thin QR of [P N] = Q R, the eigendecomposition of the small core
  * R diag(I, −I) R^H, and eigenvalues at rounding level (of |P|² + |N|²) dropped. The update and
  * the downdate that a fold leaves on a supernode's rows below partly cancel (a cut's own
  * changes come as pairs e d^H + d e^H = u u^H − v v^H): without this their columns would add
  * up along the path to the root. \a flops gets the work. */
template <typename Dense>
void compressSignedChange(Dense& P, Dense& N, double& flops) {
  typedef typename Dense::Scalar Scalar;
  typedef typename NumTraits<Scalar>::Real RealScalar;
  const Index m = P.rows(), p = P.cols(), q = N.cols(), k = p + q;
  Dense M(m, k);
  M.leftCols(p) = P;
  M.rightCols(q) = N;
  const RealScalar scale = M.squaredNorm();
  HouseholderQR<Dense> qr(M);
  const Index r = (std::min)(m, k);
  Dense R = qr.matrixQR().topRows(r).template triangularView<Upper>();
  Dense RJ = R;
  RJ.rightCols(q) *= Scalar(-1);
  const Dense core = RJ * R.adjoint();
  Dense Vp, Vn;
  signedSquareRoots(core, RealScalar(64) * NumTraits<RealScalar>::epsilon() * scale, Vp, Vn);
  flops += signedCompressionFlops(double(m), double(k));
  const Index p2 = Vp.cols(), q2 = Vn.cols();
  if (p2 + q2 >= k) return;  // nothing to gain
  // [P N] = Q [Vp Vn]: the QR's reflections applied to the few new columns (padded with zero
  // rows), without forming Q (on 415 rows and 31 columns, 13 left: 224 -> 153 us)
  Dense V = Dense::Zero(m, p2 + q2);
  V.topLeftCorner(r, p2) = Vp;
  V.block(0, p2, r, q2) = Vn;
  V.applyOnTheLeft(qr.householderQ());
  P = V.leftCols(p2);
  N = V.rightCols(q2);
  flops += 4.0 * double(m) * double(r) * double(p2 + q2);
}

/** \internal Folds into the folded supernode \a s the changes of the update matrices passed up
  * by its children: on entry ws.carried[c] and ws.carriedNegative[c] hold P and N of
  * U'_c − U_c = P P^H − N N^H for every child c with a change (a refactored child: see
  * updateMatrixChange(); a folded one: what its fold left). Updates, then downdates, the
  * supernode; the change left on its rows below is deferred as a correction of its cached
  * update matrix and, when \a passUp (the parent is folded too), carried to the parent.
  * \returns false when a downdate loses a pivot (the block is then partly changed). */
template <typename Scalar, typename StorageIndex>
bool foldIntoSupernode(SupernodalFactor<Scalar, StorageIndex>& f, SupernodalNumeric<Scalar, StorageIndex>& numeric,
                       Index s, bool passUp, const char* removed, UpdateWorkspace<Scalar>& ws, double& flops,
                       const std::vector<std::vector<StorageIndex> >* childPositions = nullptr) {
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  typedef typename NumTraits<Scalar>::Real RealScalar;
  std::vector<FoldSource> sources[2];
  std::vector<Dense>* carried[2] = {&ws.carried, &ws.carriedNegative};
  auto& node = f.nodes[s];
  const Index nr = node.nrows(), m = node.below();
  Index rank[2] = {0, 0};
  for (int sign = 0; sign < 2; ++sign) {  // 0: the update P, 1: the downdate N
    std::vector<FoldSource>& src = sources[sign];
    const std::vector<Dense>& from = *carried[sign];
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c])
      if (from[c].cols() > 0)
        src.push_back(FoldSource{(childPositions ? (*childPositions)[c] : f.nodes[c].parentPosition)[0], from[c].cols(), c});
    const Dense& own = sign == 0 ? ws.ownPositive[s] : ws.ownNegative[s];  // the supernode's own input change
    const std::vector<Index>& ownStart = sign == 0 ? ws.ownPositiveStart[s] : ws.ownNegativeStart[s];
    for (Index t = 0; t < own.cols(); ++t) src.push_back(FoldSource{ownStart[t], 1, -2 - t});
    std::sort(src.begin(), src.end(), [](const FoldSource& a, const FoldSource& b) { return a.start < b.start; });
    for (const FoldSource& x : src) rank[sign] += x.count;
  }
  // Writes the sign's sources, in the order of its list, into the zeroed nr-row columns at \a W.
  auto gather = [&](int sign, Scalar* W) {
    std::vector<Dense>& from = *carried[sign];
    Dense& own = sign == 0 ? ws.ownPositive[s] : ws.ownNegative[s];
    for (const FoldSource& x : sources[sign]) {
      if (x.child < 0) {  // an own column
        Map<Matrix<Scalar, Dynamic, 1> >(W, nr) = own.col(-2 - x.child);
        W += nr;
        continue;
      }
      const Dense& wc = from[x.child];
      const auto& pos = childPositions ? (*childPositions)[x.child] : f.nodes[x.child].parentPosition;
      for (Index j = 0; j < wc.cols(); ++j, W += nr) {
        const Scalar* column = wc.data() + j * wc.rows();
        for (Index k = 0; k < wc.rows(); ++k) W[pos[k]] = column[k];
      }
      from[x.child] = Dense();
    }
    own = Dense();
  };
  const Index p = rank[0], q = rank[1];
  Dense out[2];  // what is left lives on the rows below
  if (p > 0 && q > 0 && p < Index(BlockedFoldMinRank) && q < Index(BlockedFoldMinRank)) {
    // small ranks of both signs (each would be folded by rotations): one sweep over the block,
    // Givens rotations then hyperbolic ones on each column (false: a lost pivot), in the
    // workspace's buffer (a fold of a small supernode costs little more than its allocations)
    ws.sweep.assign(std::size_t(nr * (p + q)), Scalar(0));
    gather(0, ws.sweep.data());
    gather(1, ws.sweep.data() + nr * p);
    Map<Dense> both(ws.sweep.data(), nr, p + q);
    const Index start = (std::min)(sources[0].front().start, sources[1].front().start);
    if (!signedRotationSweep(node, both, Index(0), p + q, p, start, removed, flops)) return false;
    if (m == 0) return true;
    out[0] = both.block(nr - m, 0, m, p);
    out[1] = both.block(nr - m, p, m, q);
  } else {
    Dense W[2];
    for (int sign = 0; sign < 2; ++sign) {
      W[sign].setZero(nr, rank[sign]);
      gather(sign, W[sign].data());
    }
    flops += foldSources(node, W[0], sources[0], removed);
    // the downdate L L^H − W W^H (false: a lost pivot, the block partly changed)
    if (!downdateSources(node, W[1], sources[1], removed, flops)) return false;
    if (m == 0) return true;
    for (int sign = 0; sign < 2; ++sign) out[sign] = W[sign].bottomRows(m);
  }
  if (out[0].cols() > 0 && out[1].cols() > 0) {
    compressSignedChange(out[0], out[1], flops);
    if (removed)  // (the rows of removed dofs stay exactly zero: rounding in the new basis is cut off)
      for (Index i = 0; i < m; ++i)
        if (removed[node.rows[node.ncols + i]]) out[0].row(i).setZero(), out[1].row(i).setZero();
  } else {
    for (int sign = 0; sign < 2; ++sign)
      if (out[sign].cols() > m) {
        HouseholderQR<Dense> qr(out[sign].adjoint());
        out[sign] = qr.matrixQR().topRows(m).template triangularView<Upper>().adjoint();
        flops += double(out[sign].cols()) * double(m) * double(m);
      }
  }
  for (int sign = 0; sign < 2; ++sign) {
    if (out[sign].cols() == 0) continue;
    if (passUp) {
      Dense correction = out[sign];
      numeric.deferCorrection(f, s, correction, sign == 0 ? RealScalar(1) : RealScalar(-1));
      (*carried[sign])[s].swap(out[sign]);
    } else {
      numeric.deferCorrection(f, s, out[sign], sign == 0 ? RealScalar(1) : RealScalar(-1));
    }
  }
  return true;
}

/** \internal The positions, among \a count previous rows \a oldRows, of those a merge keeps
  * (newPosition >= 0), in order: the new rows' previous positions. */
template <typename StorageIndex>
void keptRowPositions(const StorageIndex* oldRows, Index count, const std::vector<StorageIndex>& newPosition,
                      std::vector<Index>& kept) {
  kept.clear();
  for (Index k = 0; k < count; ++k)
    if (newPosition[oldRows[k]] >= 0) kept.push_back(k);
}

/** \internal Folds supernode \a s of a merge in its previous structure (rows and columns of the
  * merged dofs included; \a backup holds them): its previous block and update matrix take the
  * changes (its own input change, with each merged dof's row and column made a diagonal
  * placeholder, and those passed up by its children on their previous rows, placed by their
  * previous relative positions), which leave the merged dofs' rows zero (up to rounding) and
  * their columns placeholders; then the block and the update matrix lose them. What is passed up
  * stays on the previous rows below (merges fold so only without removed dofs). \a kept, \a runs: scratch.
  * \returns false on a lost pivot (the block is then partly changed). */
template <typename Scalar, typename StorageIndex, typename Backup>
bool foldMergedSupernode(SupernodalFactor<Scalar, StorageIndex>& f, SupernodalNumeric<Scalar, StorageIndex>& numeric,
                         Index s, bool passUp, Backup& backup, const std::vector<StorageIndex>& newPosition,
                         UpdateWorkspace<Scalar>& ws, std::vector<Index>& kept, std::vector<PositionRun>& runs,
                         double& flops) {
  auto& node = f.nodes[s];
  auto& U = numeric.cache()[s];
  auto previousStructure = [&]() {
    node.rows.swap(backup.rows[s]);
    std::swap(node.ncols, backup.ncols[s]);
    node.values.swap(backup.values[s]);
    U.swap(backup.cache[s]);
  };
  previousStructure();  // (the node now holds its previous rows, block and update matrix)
  numeric.pendingCorrections(s).swap(backup.pending[s]);  // (and its update matrix's deferred corrections)
  const bool ok = foldIntoSupernode(f, numeric, s, passUp, static_cast<const char*>(nullptr), ws, flops,
                                    &backup.parentPosition);
  const Index oldNr = node.nrows(), oldNc = node.ncols, oldM = oldNr - oldNc;
  keptRowPositions(node.rows.data(), oldNr, newPosition, kept);
  const Index nr = Index(kept.size());
  Index nc = 0;  // (kept columns)
  while (nc < nr && kept[nc] < oldNc) ++nc;
  const Index m = nr - nc;
  SupernodeBlock<Scalar> block;
  CachedUpdate<Scalar> cut;
  if (ok) {  // the block, the update matrix and its deferred corrections lose the merged dofs
    // (into the buffers relabelFactor() gave the new structure, set aside in the backup meanwhile)
    block.swap(backup.values[s]);
    cut.swap(backup.cache[s]);
    for (auto& correction : numeric.pendingCorrections(s)) {
      eigen_assert(correction.W.rows() == oldM && "a deferred correction of another shape than its update matrix");
      Matrix<Scalar, Dynamic, Dynamic> W(m, correction.W.cols());
      for (Index j = 0; j < W.cols(); ++j) {  // (by columns, as extendCorrections())
        const Scalar* from = correction.W.data() + j * oldM;
        Scalar* to = W.data() + j * m;
        for (Index i = 0; i < m; ++i) to[i] = from[kept[nc + i] - oldNc];
      }
      correction.W.swap(W);
    }
    gatherRuns(kept.data(), nr, runs);
    block.resize(nr, nc);
    for (Index j = 0; j < nc; ++j) {
      std::size_t first = 0;
      copyByRuns(node.values.data() + kept[j] * oldNr, runs, first, block.data() + j * nr, Index(0), nr);
    }
    for (Index i = 0; i < m; ++i) kept[nc + i] -= oldNc;  // (positions below)
    if (U.keepRows(oldM, kept.data() + nc, m)) {  // (the merged rows are not stored: relabeled, not copied)
      cut.swap(U);
    } else {
      U.layOut();
      gatherRuns(kept.data() + nc, m, runs);
      cut.resize(m * m);
      std::size_t first = 0;
      for (Index j = 0; j < m; ++j) copyByRuns(U.data() + kept[nc + j] * oldM, runs, first, cut.data() + j * m, j, m);
    }
  }
  previousStructure();  // (back to the new rows; the previous block and update matrix are in the backup)
  if (!ok) return false;
  node.values.swap(block);
  U.swap(cut);
  eigen_assert(node.values.rows() == node.nrows() && node.values.cols() == node.ncols && "a merge fold lost its shape");
  return true;
}

/** \internal The refactored-and-folded update of a structural change (see foldPlan()): walks the
  * dirty supernodes children first; the refactored ones are recomputed by \a refactor (given a
  * list, increasing; returns -1 or the permuted column of a bad pivot), in runs, so that a
  * folded supernode finds its children done; a folded one gets its previous block and update
  * matrix extended to its new rows (from \a backup, which keeps them), the changes of its
  * refactored children's update matrices split into signed low-rank parts
  * (updateMatrixChange(), with the bounds of \a boundary), and the fold (foldIntoSupernode()),
  * with its own input change when ws holds one (a copy column's placeholder: \a pivotOf). With
  * \a merging, the changes are taken on the previous rows and a folded supernode that loses
  * merged dofs is folded in its previous structure (foldMergedSupernode()). The folded
  * supernodes whose previous block left \a backup are listed in \a taken.
  * \returns -1 on success, the column of a bad pivot of a refactorization, or -2 when a change
  * was not captured by its bound or a downdate lost a pivot (the caller then refactors every
  * dirty supernode: the folded ones are partly changed). \a flops gets the work. */
template <typename Scalar, typename StorageIndex, typename Backup, typename Refactor, typename PivotOf>
Index refactorAndFold(SupernodalFactor<Scalar, StorageIndex>& f, SupernodalNumeric<Scalar, StorageIndex>& numeric,
                      const std::vector<Index>& dirty, const std::vector<char>& folded,
                      const std::vector<FoldBoundary>& boundary, Backup& backup, std::vector<Index>& taken,
                      const std::vector<StorageIndex>& newPosition, const char* removed, UpdateWorkspace<Scalar>& ws,
                      Refactor&& refactor, PivotOf&& pivotOf, double& flops, bool merging = false) {
  std::vector<Index>& bound = ws.foldBound;  // 1 + position in boundary
  for (std::size_t k = 0; k < boundary.size(); ++k) bound[boundary[k].supernode] = Index(k) + 1;
  std::vector<Index> run, at;
  std::vector<PositionRun> runs;
  UpdateBuffer<Scalar> previousU;
  Index result = -1;
  auto flush = [&]() {
    if (run.empty()) return true;
    const Index failed = refactor(run);
    for (Index s : run) flops += frontFlops(f.nodes[s], removed);
    run.clear();
    if (failed >= 0) result = failed;
    return failed < 0;
  };
  for (Index s : dirty) {
    if (!folded[s]) {
      run.push_back(s);
      continue;
    }
    if (!flush()) break;
    bool captured = true;
    for (Index c = f.firstChild[s]; c != -1 && captured; c = f.nextSibling[c]) {
      if (bound[c] == 0) continue;
      auto& child = f.nodes[c];
      const Index m = child.below(), oldNc = backup.ncols[c], oldM = Index(backup.rows[c].size()) - oldNc;
      backup.applyPendingTo(c, oldM);  // (the fold compares the new update matrix with the exact previous one)
      const Scalar* oldU = backup.cache[c].data();
      const FoldBoundary& b = boundary[bound[c] - 1];
      if (merging) {  // on the previous rows below: the new update matrix gets zero rows at the merged dofs
        keptRowPositions(backup.rows[c].data() + oldNc, oldM, newPosition, at);
        extendUpdateMatrix(numeric.cache()[c].data(), at, oldM, previousU, runs);
        captured = updateMatrixChange(previousU.data(), oldU, oldM, b.likely, b.bound, ws.carried[c],
                                      ws.carriedNegative[c], flops);
        continue;
      }
      if (oldM != m) {  // (copy rows gained below)
        previousRowPositions(backup.rows[c].data() + oldNc, oldM, child.rows.data() + child.ncols, newPosition, at);
        extendUpdateMatrix(oldU, at, m, previousU, runs);
        oldU = previousU.data();
      }
      captured = updateMatrixChange(numeric.cache()[c].data(), oldU, m, b.likely, b.bound, ws.carried[c],
                                    ws.carriedNegative[c], flops);
    }
    if (captured && merging && Index(backup.rows[s].size()) != f.nodes[s].nrows()) {  // (it loses merged dofs)
      const Index p = f.parent[s];
      taken.push_back(s);  // (its previous block is consumed)
      captured = foldMergedSupernode(f, numeric, s, p != -1 && folded[p], backup, newPosition, ws, at, runs, flops);
    } else if (captured) {
      auto& node = f.nodes[s];
      taken.push_back(s);  // (its previous update matrix leaves the backup)
      if (takePreviousBlock(node, backup.rows[s], backup.values[s], backup.cache[s], newPosition, at, numeric.cache()[s],
                            runs, pivotOf)) {
        numeric.pendingCorrections(s).swap(backup.pending[s]);  // (its update matrix's deferred corrections come along)
      } else {  // extended like the update matrix (rows \a at); the backup keeps its own for a revert
        extendCorrections(backup.pending[s], at, node.below(), numeric.pendingCorrections(s));
      }
      const Index p = f.parent[s];
      captured = foldIntoSupernode(f, numeric, s, p != -1 && folded[p], removed, ws, flops);
    }
    if (!captured) {
      result = -2;
      break;
    }
  }
  if (result == -1) flush();
  for (const FoldBoundary& b : boundary) bound[b.supernode] = 0;
  if (result != -1)
    for (Index s : dirty)
      ws.carried[s] = ws.carriedNegative[s] = ws.ownPositive[s] = ws.ownNegative[s] = Matrix<Scalar, Dynamic, Dynamic>();
  return result;
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_TOP_UPDATE_H
