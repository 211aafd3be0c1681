// FactorSchurComplement: S = E^T A^{-1} E for a set of unit vectors E = [e_d1 ... e_ds], read off a
// sparse Cholesky factor P A P^T = L L^T without solving with A: S = G^T G with G = L^{-1} P E.
// Column d of G is non-zero only on the elimination-tree path from P(d) to the root, so G is
// computed on the union of these paths only (the "reach"; Yeung et al. 2018, the Schur complement
// route of Herholz & Sorkine-Hornung §3.5), and S is summed from dense blocks of G's rows.
// This is the C = B blkdiag(A^{-1}, A^{-1}) B^T of the orbifold Tutte embedding (paper §5.2,
// eq. 21) for constraints B that touch few vertices.

#ifndef EIGEN_MESHPARAMETERIZATION_FACTORSCHURCOMPLEMENT_H
#define EIGEN_MESHPARAMETERIZATION_FACTORSCHURCOMPLEMENT_H

namespace Eigen {
namespace internal {
namespace mesh_parameterization {

/** \internal Computes \a S = E^T A^{-1} E (s x s, in the order of \a dofs) from the lower
  * triangular factor \a L (column-major, CSC, diagonal present) of P A P^T and the permutation
  * \a perm (perm[d] is the row of L of dof d, as UpdatableSupernodalLLT::permutationP().indices()).
  *
  * With the columns of L in any topological order of the elimination tree (parent(j) = the first
  * off-diagonal row of column j), the reach of the columns {perm[d]} is walked to the roots,
  * ordered by a depth-first postorder, and the right-hand sides are sorted by the postorder of
  * their start column: then row j of G is non-zero exactly on a contiguous range of them (those
  * starting in j's subtree) and is stored as that range only. Consecutive rows with the same range
  * (chains up the tree, long near the root) are handled as dense blocks: forward substitution
  * runs over these runs in postorder (a dense triangular solve, then one product for the rows
  * below), and S is the sum over the runs of G_run^T G_run.
  * \returns false if a diagonal entry of L is missing or not positive. */
template <typename FactorMatrix, typename PermutationIndices>
bool unitVectorSchurComplement(const FactorMatrix& L, const PermutationIndices& perm, const std::vector<int>& dofs,
                               MatrixXd& S)
{
  typedef typename FactorMatrix::StorageIndex StorageIndex;
  const Index n = L.cols(), s = Index(dofs.size());
  S.setZero(s, s);
  if (s == 0) return true;
  const StorageIndex* outer = L.outerIndexPtr();
  const StorageIndex* inner = L.innerIndexPtr();
  const double* value = L.valuePtr();

  // Reach: walk from each start column to the root, stopping at columns seen before.
  std::vector<int> parent(std::size_t(n), -2);  // -2: not in the reach
  std::vector<int> reach;
  auto parentOf = [&](Index j) {
    Index best = n;
    for (StorageIndex p = outer[j]; p < outer[j + 1]; ++p)
      if (inner[p] > j && inner[p] < best) best = inner[p];
    return best == n ? -1 : int(best);
  };
  for (int d : dofs)
    for (int j = int(perm[d]); j >= 0 && parent[std::size_t(j)] == -2;)
    {
      reach.push_back(j);
      parent[std::size_t(j)] = parentOf(j);
      j = parent[std::size_t(j)];
    }

  // Postorder of the reach forest (children in increasing column order), subtree sizes.
  std::sort(reach.begin(), reach.end());
  const std::size_t r = reach.size();
  std::vector<int> localOf(std::size_t(n), -1);
  for (std::size_t k = 0; k < r; ++k) localOf[std::size_t(reach[k])] = int(k);
  std::vector<int> childStart(r + 1, 0), children(r);
  for (std::size_t k = 0; k < r; ++k)
    if (parent[std::size_t(reach[k])] >= 0) ++childStart[std::size_t(localOf[std::size_t(parent[std::size_t(reach[k])])]) + 1];
  for (std::size_t k = 0; k < r; ++k) childStart[k + 1] += childStart[k];
  {
    std::vector<int> fill(childStart.begin(), childStart.end() - 1);
    for (std::size_t k = 0; k < r; ++k)
      if (parent[std::size_t(reach[k])] >= 0)
        children[std::size_t(fill[std::size_t(localOf[std::size_t(parent[std::size_t(reach[k])])])]++)] = int(k);
  }
  std::vector<int> post;  // post[t] = local node at postorder position t
  post.reserve(r);
  std::vector<int> postOf(r), subtreeFirst(r);
  {
    std::vector<std::pair<int, int>> stack;  // (node, next child)
    for (std::size_t root = 0; root < r; ++root)
    {
      if (parent[std::size_t(reach[root])] >= 0) continue;
      stack.emplace_back(int(root), childStart[root]);
      while (!stack.empty())
      {
        auto& top = stack.back();
        if (top.second < childStart[std::size_t(top.first) + 1])
        {
          const int child = children[std::size_t(top.second++)];
          stack.emplace_back(child, childStart[std::size_t(child)]);
        }
        else
        {
          const int node = top.first;
          stack.pop_back();
          postOf[std::size_t(node)] = int(post.size());
          int first = int(post.size());
          for (int c = childStart[std::size_t(node)]; c < childStart[std::size_t(node) + 1]; ++c)
            first = std::min(first, subtreeFirst[std::size_t(children[std::size_t(c)])]);
          subtreeFirst[std::size_t(node)] = first;
          post.push_back(node);
        }
      }
    }
  }

  // Right-hand sides sorted by the postorder position of their start column.
  std::vector<int> rhsOrder(static_cast<std::size_t>(s));
  for (Index a = 0; a < s; ++a) rhsOrder[std::size_t(a)] = int(a);
  auto startPost = [&](int a) { return postOf[std::size_t(localOf[std::size_t(perm[dofs[std::size_t(a)]])])]; };
  std::sort(rhsOrder.begin(), rhsOrder.end(), [&](int a, int b) { return startPost(a) < startPost(b); });
  std::vector<int> sortedStart(static_cast<std::size_t>(s));
  for (Index t = 0; t < s; ++t) sortedStart[std::size_t(t)] = startPost(rhsOrder[std::size_t(t)]);

  // Row ranges [lo, hi) of G in the sorted right-hand sides, and the offsets of the stored rows.
  std::vector<int> lo(r), hi(r);
  std::vector<std::size_t> offset(r + 1, 0);
  for (std::size_t t = 0; t < r; ++t)
  {
    const int node = post[t];
    lo[t] = int(std::lower_bound(sortedStart.begin(), sortedStart.end(), subtreeFirst[std::size_t(node)]) - sortedStart.begin());
    hi[t] = int(std::upper_bound(sortedStart.begin(), sortedStart.end(), int(t)) - sortedStart.begin());
    offset[t + 1] = offset[t] + std::size_t(hi[t] - lo[t]);
  }
  std::vector<double> G(offset[r], 0.0);
  for (Index t = 0; t < s; ++t)
  {
    const std::size_t row = std::size_t(sortedStart[std::size_t(t)]);
    G[offset[row] + std::size_t(t - lo[row])] = 1.0;
  }

  // Runs: consecutive postorder rows with the same range. They form parent chains (the reach's
  // leaves all start a right-hand side, so a new subtree brings a disjoint range): the top of the
  // tree, where the work is, comes in long runs, solved as dense blocks.
  std::vector<std::size_t> runStart(1, 0);
  for (std::size_t t = 1; t < r; ++t)
    if (lo[t] != lo[t - 1] || hi[t] != hi[t - 1]) runStart.push_back(t);
  runStart.push_back(r);

  // Forward substitution over the reach in postorder, one run at a time: G_T = L_TT^-1 G_T, then
  // the rows U below the run (ancestors, later in postorder) get G_U -= L_UT G_T.
  std::vector<int> slot(std::size_t(n), -1);
  std::vector<int> below;
  MatrixXd dense, update;
  for (std::size_t q = 0; q + 1 < runStart.size(); ++q)
  {
    const std::size_t t0 = runStart[q], t1 = runStart[q + 1];
    const Index b = Index(t1 - t0), len = hi[t0] - lo[t0];
    for (std::size_t t = t0; t < t1; ++t) slot[std::size_t(reach[std::size_t(post[t])])] = int(t - t0);
    below.clear();
    for (std::size_t t = t0; t < t1; ++t)
    {
      const Index j = reach[std::size_t(post[t])];
      for (StorageIndex p = outer[j]; p < outer[j + 1]; ++p)
        if (inner[p] > j && slot[std::size_t(inner[p])] < 0)
        {
          slot[std::size_t(inner[p])] = int(b + Index(below.size()));
          below.push_back(int(inner[p]));
        }
    }
    dense.setZero(b + Index(below.size()), b);
    for (std::size_t t = t0; t < t1; ++t)
    {
      const Index j = reach[std::size_t(post[t])];
      for (StorageIndex p = outer[j]; p < outer[j + 1]; ++p)
        if (inner[p] >= j) dense(slot[std::size_t(inner[p])], Index(t - t0)) = value[p];
    }
    for (std::size_t t = t0; t < t1; ++t) slot[std::size_t(reach[std::size_t(post[t])])] = -1;
    for (int i : below) slot[std::size_t(i)] = -1;
    if (!(dense.diagonal().minCoeff() > 0)) return false;
    Map<Matrix<double, Dynamic, Dynamic, RowMajor>> GT(G.data() + offset[t0], b, len);
    dense.topRows(b).triangularView<Lower>().solveInPlace(GT);
    if (below.empty()) continue;
    update.noalias() = dense.bottomRows(Index(below.size())) * GT;
    for (std::size_t u = 0; u < below.size(); ++u)
    {
      const std::size_t ti = std::size_t(postOf[std::size_t(localOf[std::size_t(below[u])])]);
      Map<RowVectorXd>(G.data() + offset[ti] + std::size_t(lo[t0] - lo[ti]), len) -= update.row(Index(u));
    }
  }

  // S = sum over the runs of G_run^T G_run (lower triangle).
  MatrixXd Ssorted = MatrixXd::Zero(s, s);
  for (std::size_t q = 0; q + 1 < runStart.size(); ++q)
  {
    const std::size_t t0 = runStart[q], t1 = runStart[q + 1];
    const Index len = hi[t0] - lo[t0];
    Map<const Matrix<double, Dynamic, Dynamic, RowMajor>> run(G.data() + offset[t0], Index(t1 - t0), len);
    Ssorted.block(lo[t0], lo[t0], len, len).selfadjointView<Lower>().rankUpdate(run.transpose());
  }
  for (Index a = 0; a < s; ++a)
    for (Index b = 0; b <= a; ++b)
    {
      const double v = Ssorted(a, b);
      S(rhsOrder[std::size_t(a)], rhsOrder[std::size_t(b)]) = v;
      S(rhsOrder[std::size_t(b)], rhsOrder[std::size_t(a)]) = v;
    }
  return true;
}

} // namespace mesh_parameterization
} // namespace internal
} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_FACTORSCHURCOMPLEMENT_H
