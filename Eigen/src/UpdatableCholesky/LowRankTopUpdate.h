// LowRankTopUpdate.h — after a cut or a merge, the top of the dirty tree is updated by signed
// low-rank folds instead of being refactored (insertDofs/mergeDofs, paper §4.2 / Algorithm 4,
// with Davis & Hager's up- and downdates on the supernodal factor, DESIGN §3).
//
// A structural change makes the supernodes on the paths from the changed columns to the roots
// dirty. Near the change they gain or lose rows and columns and are refactored (Algorithm 4).
// Higher up, a dirty supernode often keeps its rows, its columns and its input: its values
// change only through the update matrices its refactored children pass up. The change of a
// child's update matrix, U' − U = L21' L21'^H − L21 L21^H, has a small rank: written in the
// variables (last copy, differences to it), a cut that glues back to the uncut matrix only adds
// one row and column per copy (a row addition, Davis & Hager), so U' − U is one-signed of rank
// at most the copies below; a merge removes them again. Each dof where the cut does not glue
// back adds one (gluingMismatches()). The change is split into P P^H − N N^H (a sampled range
// and an eigendecomposition of the small core; eigenvalues at rounding level are dropped) and
// folded into that top part: first the update P (Givens rotations or blocked LQ,
// as for removals), then the downdate N (hyperbolic rotations), along the paths to the roots.
// The cached update matrices of the top get the matching ± corrections, deferred. Each top
// supernode then costs ~4 · rank · rows · columns instead of its refactorization and its
// children's extend-adds: the root separators, which every path crosses, are not recomputed for
// a short seam. Which part is refactored and which is folded is chosen per update by a dynamic
// program over the dirty tree on flop estimates.
//
// In exact arithmetic no pivot of the downdate can vanish when the new matrix is positive
// definite (each intermediate matrix dominates the final one). A pivot that does is reported,
// and the caller refactors the top from the caches instead. The factor solves to the accuracy
// of a fresh one but is not bitwise equal to it.

#ifndef EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_TOP_UPDATE_H
#define EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_TOP_UPDATE_H

#include <cstdint>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Random vectors sampled beyond the rank bound of an update-matrix change. */
enum { UpdateChangeOversampling = 8 };
/** \internal Time per flop of the folds and of the split of an update-matrix change (rotations,
  * small eigenproblems) relative to the BLAS-3 flops of a refactorization, as measured on igea
  * cuts (2.4-3x): the plan compares times, not flop counts. */
enum { FoldFlopWeight = 3 };

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

/** \internal Downdates the supernode's kept columns from row \a start on by the W columns
  * [first, first+count): L L^H − W W^H = L' L'^H − W' W'^H with W' zero on the supernode's own
  * rows. \returns false (the block partly changed) when a pivot is lost. */
template <typename Scalar, typename StorageIndex, typename Dense>
bool downdateByHyperbolicRotations(Supernode<Scalar, StorageIndex>& node, Dense& W, Index first, Index count,
                                   Index start, const char* removed, double& flops) {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  const Index nr = node.nrows(), nc = node.ncols;
  Scalar* L = node.values.data();
  for (Index j = start; j < nc; ++j) {
    if (removed[node.rows[j]]) continue;
    Scalar* lj = L + j * nr;
    for (Index t = first; t < first + count; ++t) {
      Scalar* w = W.data() + t * nr;
      const Scalar wj = w[j];
      if (wj == Scalar(0)) continue;
      const RealScalar ljj = numext::real(lj[j]), aw = numext::abs(wj);
      const RealScalar r2 = (ljj - aw) * (ljj + aw);
      if (!(r2 > RealScalar(0)) || !(r2 < NumTraits<RealScalar>::highest())) return false;
      const RealScalar r = numext::sqrt(r2);
      const RealScalar cosine = r / ljj, invCos = ljj / r;
      const Scalar sine = wj / ljj, conjSine = numext::conj(sine);
      lj[j] = Scalar(r);
      w[j] = Scalar(0);
      rotateColumnsHyperbolic(nr - j - 1, lj + j + 1, w + j + 1, cosine, invCos, sine, conjSine);
      flops += 4.0 * double(nr - j);
    }
  }
  return true;
}

/** \internal Flops of splitting the change of an update matrix (m × m) of rank at most \a rank
  * into P P^H − N N^H (randomized range finder, check, small eigendecomposition). */
inline double updateChangeFlops(double m, double rank) {
  const double k = (std::min)(m, rank + double(UpdateChangeOversampling));
  return 2 * k >= m ? 9.0 * m * m * m : 8.0 * m * m * k + 9.0 * k * k * k;
}

/** \internal Splits the change D = U' − U of a cached update matrix (m × m, lower triangles,
  * column-major) into P P^H − N N^H with as few columns as its numerical rank, which is at most
  * \a rankBound (see topUpdatePlan(); a wrong bound is caught by the check below). The range of D is sampled with rankBound + a few random
  * vectors (deterministic signs), D is checked to lie in that range, and the small projected
  * matrix is diagonalized; eigenvalues at rounding level are dropped. \returns false when D is
  * not captured (the bound did not hold); \a flops gets the work. */
template <typename Scalar>
bool updateMatrixChange(const Scalar* newU, const Scalar* oldU, Index m, Index rankBound,
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
  const Index k = (std::min)(m, rankBound + Index(UpdateChangeOversampling));
  flops += updateChangeFlops(double(m), double(rankBound));
  Dense Q, B;
  if (2 * k >= m) {  // small or not low-rank enough: diagonalize D itself
    B.swap(D);
  } else {
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
    D.noalias() -= QB * Q.adjoint();  // what the range of Q misses
    if (!(D.norm() <= RealScalar(1000) * NumTraits<RealScalar>::epsilon() * scale)) return false;
  }
  SelfAdjointEigenSolver<Dense> eig(B);
  const auto& lambda = eig.eigenvalues();
  Index positive = 0, negative = 0;
  for (Index i = 0; i < lambda.size(); ++i) {
    positive += lambda[i] > dropped;
    negative += lambda[i] < -dropped;
  }
  Dense Vp(B.rows(), positive), Vn(B.rows(), negative);
  for (Index i = 0, p = 0, q = 0; i < lambda.size(); ++i) {
    if (lambda[i] > dropped) Vp.col(p++) = eig.eigenvectors().col(i) * numext::sqrt(lambda[i]);
    if (lambda[i] < -dropped) Vn.col(q++) = eig.eigenvectors().col(i) * numext::sqrt(-lambda[i]);
  }
  if (Q.size() > 0) {
    P.noalias() = Q * Vp;
    N.noalias() = Q * Vn;
  } else {
    P.swap(Vp);
    N.swap(Vn);
  }
  return true;
}

/** \internal Splits the dirty supernodes \a dirty (increasing) of a structural change into a
  * \a bottom part to refactor and a \a top part (closed under taking parents, every supernode of
  * it flagged in \a eligible: same rows, columns and input as before) to update by signed folds,
  * by a dynamic program on flop estimates. \a rankColumns: per supernode, how much its columns
  * add to the rank of the change of an update matrix above them (read on dirty supernodes only):
  * one per copy or merged dof and per dof where the cut does not glue back (gluingMismatches()):
  * the bound the split samples with. \a likelyRankColumns: the same without the dofs whose
  * mismatch is small (at most sqrt(eps) of its entries), which a change far above mostly drops
  * (below rounding): the rank the costs are estimated with. With \a force,
  * the top is as large as allowed. Lists in \a boundary each refactored child c of the top with
  * the rank bound of its update matrix's change. \returns the estimated
  * cost of the plan in refactorization flops (fold flops weighted by FoldFlopWeight). */
template <typename Scalar, typename StorageIndex>
double topUpdatePlan(const SupernodalFactor<Scalar, StorageIndex>& f, const std::vector<Index>& dirty,
                     const std::vector<char>& eligible, const std::vector<Index>& rankColumns,
                     const std::vector<Index>& likelyRankColumns,
                     const char* removed, bool force,
                     std::vector<Index>& bottom, std::vector<Index>& top,
                     std::vector<std::pair<Index, Index> >& boundary, UpdateWorkspace<Scalar>& ws) {
  const Index count = Index(dirty.size());
  const double never = std::numeric_limits<double>::infinity();
  std::vector<double> refactor(count), folded(count), split(count), rankBelow(count), likelyBelow(count),
      rankIn(count, 0.0), rankOut(count), rankBoundary(count), likelyBoundary(count), childPart(count, 0.0);
  std::vector<Index> start(count);
  std::vector<Index>& position = ws.local;  // supernode -> 1 + its position in dirty
  for (Index k = 0; k < count; ++k) position[dirty[k]] = k + 1;
  for (Index k = 0; k < count; ++k) start[k] = f.nodes[dirty[k]].ncols;
  for (Index k = 0; k < count; ++k) rankBelow[k] = double(rankColumns[dirty[k]]);
  for (Index k = 0; k < count; ++k) likelyBelow[k] = double(likelyRankColumns[dirty[k]]);
  for (Index k = 0; k < count; ++k) refactor[k] = 0;
  for (Index k = 0; k < count; ++k) {  // children before parents
    const Index s = dirty[k];
    const auto& node = f.nodes[s];
    const double nr = double(node.nrows()), nc = double(node.ncols), m = double(node.below());
    refactor[k] += frontFlops(node, removed);
    rankBoundary[k] = (std::min)(m, rankBelow[k]);
    likelyBoundary[k] = (std::min)(m, likelyBelow[k]);
    split[k] = FoldFlopWeight * updateChangeFlops(m, rankBoundary[k]);
    if (eligible[s]) {
      folded[k] = FoldFlopWeight * foldFlops(rankIn[k], nr, nc, double(start[k])) + childPart[k];
      rankOut[k] = (std::min)(m, rankIn[k]);
    } else {
      folded[k] = never;
      rankOut[k] = likelyBoundary[k];
    }
    const Index p = f.parent[s];
    if (p == -1) continue;
    const Index q = position[p] - 1;
    refactor[q] += refactor[k];
    rankBelow[q] += rankBelow[k];
    likelyBelow[q] += likelyBelow[k];
    rankIn[q] += (std::min)(rankOut[k], likelyBoundary[k]);
    childPart[q] += (std::min)(folded[k], refactor[k] + split[k]);
    start[q] = (std::min)(start[q], Index(node.parentPosition[0]));
  }
  std::vector<char> inTop(count, 0);
  for (Index k = count - 1; k >= 0; --k) {  // parents before children
    const Index s = dirty[k], p = f.parent[s];
    if (!eligible[s] || (p != -1 && !inTop[position[p] - 1])) continue;
    inTop[k] = force || folded[k] < (p == -1 ? refactor[k] : refactor[k] + split[k]);
  }
  bottom.clear();
  top.clear();
  boundary.clear();
  double total = 0;
  for (Index k = 0; k < count; ++k) {
    const Index s = dirty[k], p = f.parent[s];
    const auto& node = f.nodes[s];
    if (inTop[k]) {
      top.push_back(s);
      total += FoldFlopWeight * foldFlops(rankIn[k], double(node.nrows()), double(node.ncols), double(start[k]));
    } else {
      bottom.push_back(s);
      total += frontFlops(node, removed);
      if (p != -1 && inTop[position[p] - 1]) {
        total += split[k];
        boundary.emplace_back(s, Index(rankBoundary[k]));
      }
    }
  }
  for (Index s : dirty) position[s] = 0;
  return total;
}

/** \internal Folds the changes of the update matrices passed up from the refactored part into
  * the \a top supernodes (increasing): on entry ws.carried[c] and ws.carriedNegative[c] hold
  * P and N of U'_c − U_c = P P^H − N N^H for every refactored child c of a top supernode
  * (updateMatrixChange()). Updates, then downdates, each supernode, defers the matching
  * corrections of its cached update matrix and passes the rest to its parent. \returns false
  * when a downdate loses a pivot (the top is then partly changed: refactor it). */
template <typename Scalar, typename StorageIndex>
bool lowRankTopUpdate(SupernodalFactor<Scalar, StorageIndex>& f, SupernodalNumeric<Scalar, StorageIndex>& numeric,
                      const std::vector<Index>& top, const char* removed, UpdateWorkspace<Scalar>& ws, double& flops) {
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  typedef typename NumTraits<Scalar>::Real RealScalar;
  std::vector<FoldSource> sources[2];
  Dense W[2];
  std::vector<Dense>* carried[2] = {&ws.carried, &ws.carriedNegative};
  for (Index s : top) {
    auto& node = f.nodes[s];
    const Index nr = node.nrows(), m = node.below();
    for (int sign = 0; sign < 2; ++sign) {  // 0: the update P, 1: the downdate N
      std::vector<FoldSource>& src = sources[sign];
      std::vector<Dense>& from = *carried[sign];
      src.clear();
      for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c])
        if (from[c].cols() > 0) src.push_back(FoldSource{f.nodes[c].parentPosition[0], from[c].cols(), c});
      std::sort(src.begin(), src.end(), [](const FoldSource& a, const FoldSource& b) { return a.start < b.start; });
      Index rank = 0;
      for (const FoldSource& x : src) rank += x.count;
      W[sign].setZero(nr, rank);
      Index q = 0;
      for (const FoldSource& x : src) {
        const Dense& wc = from[x.child];
        const auto& pos = f.nodes[x.child].parentPosition;
        for (Index j = 0; j < wc.cols(); ++j, ++q)
          for (Index k = 0; k < wc.rows(); ++k) W[sign](pos[k], q) = wc(k, j);
        from[x.child] = Dense();
      }
    }
    flops += foldSources(node, W[0], sources[0], removed);
    Index first = 0;
    for (const FoldSource& x : sources[1]) {
      if (!downdateByHyperbolicRotations(node, W[1], first, x.count, x.start, removed, flops)) {
        for (Index t : top) ws.carried[t] = ws.carriedNegative[t] = Dense();
        return false;
      }
      first += x.count;
    }
    if (m == 0) continue;
    for (int sign = 0; sign < 2; ++sign) {  // what is left lives on the rows below
      if (W[sign].cols() == 0) continue;
      Dense out = W[sign].bottomRows(m);
      if (out.cols() > m) {
        HouseholderQR<Dense> qr(out.adjoint());
        out = qr.matrixQR().topRows(m).template triangularView<Upper>().adjoint();
        flops += double(out.cols()) * double(m) * double(m);
      }
      Dense correction = out;
      numeric.deferCorrection(f, s, correction, sign == 0 ? RealScalar(1) : RealScalar(-1));
      if (f.parent[s] != -1) (*carried[sign])[s].swap(out);
    }
  }
  return true;
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_LOW_RANK_TOP_UPDATE_H
