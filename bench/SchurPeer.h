// SchurPeer: the Schur-complement route to a Dirichlet solve (Yeung et al. 2018; paper §3.5) as a
// benchmark peer. It keeps the factor of the full matrix A and answers each new set B of
// constrained dofs with a small dense system, computing only the rows of L^{-1} P H_B that are
// not zero: those on the elimination-tree reach of B. Works on CHOLMOD's supernodal layout.

#ifndef UPDATABLE_CHOLESKY_BENCH_SCHURPEER_H
#define UPDATABLE_CHOLESKY_BENCH_SCHURPEER_H

#include "BlasLapack.h"
#include "CholmodPeer.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

/** Dirichlet solves through the Schur complement of the factor P A P^T = L L^T of the full matrix.
  *
  * The Dirichlet system (B the constrained dofs, I the others) is A_II x_I = b_I - A_IB g_B,
  * x_B = g_B. With H = H_B (the columns of the identity at B) it is the saddle-point system
  * [A H; H^T 0] [x; y] = [b; g], whose Schur complement S = H^T A^{-1} H (m x m, m = |B|) gives
  *
  *     S y = H^T A^{-1} b - g,        x = A^{-1} (b - H y).
  *
  * With W = L^{-1} P H and c = L^{-1} P b this is S = W^T W, H^T A^{-1} b = W^T c and
  * x = P^T L^{-T} (c - W y): one forward and one backward solve with L, the columns of W, and a
  * dense Cholesky factorization of S. Column j of W = L^{-1} e_{q_j} (q_j the position of the
  * j-th dof in the factor) is non-zero only on the elimination-tree path from q_j to the root, so
  * W is computed supernode by supernode on the union of those paths (the reach of B), in
  * postorder: at supernode S, with the k_S columns of W whose dof lies in S's subtree,
  * W_S <- L_SS^{-1} W_S (trsm), then the rows below S receive -L_{below,S} W_S (gemm + scatter),
  * and S += W_S^T W_S (syrk). Because the factor is postordered, the dofs of a subtree are a
  * contiguous range once sorted by position, so every block's columns are a slice of its
  * ancestors' columns. W_S is stored transposed (k_S x ncols_S) so that the scatter is contiguous.
  *
  * solve() is the whole update-and-solve; updateFlops() counts its dense flops except the two
  * full triangular solves (which every method's solve has), and factorizationFlops() the dense
  * flops of a full supernodal factorization on the same layout, for the flop fraction.
  *
  * The factor must stay alive and unchanged while this object is in use. The matrix is only
  * positive definite with B removed in the Dirichlet sense; A itself must be positive definite
  * (here: the cotan Laplacian + 1e-8 I, so S inherits A's condition number — this route is less
  * accurate than the others, see the benchmark's error check). */
class SchurComplementDirichlet
{
public:
  /** Prepares the supernodal etree of \a factored's factor (which must be a supernodal LL^T). */
  explicit SchurComplementDirichlet(CholmodSupernodal& factored) : m_chol(factored)
  {
    const cholmod_factor* L = factored.factor();
    if (!L || !L->is_super || !L->is_ll || L->xtype != CHOLMOD_REAL || L->itype != CHOLMOD_INT)
      throw std::runtime_error("SchurComplementDirichlet: needs a real supernodal LL^T factor with int indices");
    m_n = int(L->n);
    m_nsuper = int(L->nsuper);
    m_super = static_cast<const int*>(L->super);
    m_pi = static_cast<const int*>(L->pi);
    m_px = static_cast<const int*>(L->px);
    m_rows = static_cast<const int*>(L->s);
    m_values = static_cast<const double*>(L->x);
    const int* perm = static_cast<const int*>(L->Perm);
    m_position.resize(std::size_t(m_n));
    for (int k = 0; k < m_n; ++k) m_position[std::size_t(perm[k])] = k;

    m_colToSuper.resize(std::size_t(m_n));
    for (int s = 0; s < m_nsuper; ++s)
      for (int c = m_super[s]; c < m_super[s + 1]; ++c) m_colToSuper[std::size_t(c)] = s;
    m_parent.assign(std::size_t(m_nsuper), -1);
    m_firstDescendant.resize(std::size_t(m_nsuper));
    std::vector<int> subtreeSize(std::size_t(m_nsuper), 1);
    for (int s = 0; s < m_nsuper; ++s) m_firstDescendant[std::size_t(s)] = s;
    m_factorFlops = 0;
    for (int s = 0; s < m_nsuper; ++s)
    {
      const double nc = ncols(s), nb = nrows(s) - ncols(s);
      m_factorFlops += nc * nc * nc / 3 + nb * nc * nc + nb * nb * nc;
      if (nrows(s) > ncols(s))
      {
        const int p = m_colToSuper[std::size_t(m_rows[m_pi[s] + ncols(s)])];
        if (p <= s) throw std::runtime_error("SchurComplementDirichlet: supernodes are not in postorder");
        m_parent[std::size_t(s)] = p;
        subtreeSize[std::size_t(p)] += subtreeSize[std::size_t(s)];
        m_firstDescendant[std::size_t(p)] = std::min(m_firstDescendant[std::size_t(p)], m_firstDescendant[std::size_t(s)]);
      }
    }
    for (int s = 0; s < m_nsuper; ++s)
      if (s - m_firstDescendant[std::size_t(s)] + 1 != subtreeSize[std::size_t(s)])
        throw std::runtime_error("SchurComplementDirichlet: the supernodal etree is not postordered");
    m_reachMark.assign(std::size_t(m_nsuper), 0);
  }
  ~SchurComplementDirichlet()
  {
    cholmod_common& c = m_chol.common();
    for (cholmod_dense** d : {&m_x, &m_y, &m_e, &m_c}) cholmod_free_dense(d, &c);
  }
  SchurComplementDirichlet(const SchurComplementDirichlet&) = delete;
  SchurComplementDirichlet& operator=(const SchurComplementDirichlet&) = delete;

  /** \returns x with A_II x_I = b_I - A_IB g_B and x_B = g_B, for the dofs \a dofs (distinct,
    * original numbering); \a b and \a g are n-vectors, only g's entries at \a dofs are read. */
  Eigen::VectorXd solve(const std::vector<int>& dofs, const Eigen::VectorXd& b, const Eigen::VectorXd& g)
  {
    prepare(dofs);
    const int m = int(dofs.size());
    Eigen::VectorXd rhs = forward(b);
    for (int j = 0; j < m; ++j) rhs[j] -= g[m_sortedDofs[std::size_t(j)]];
    // y = S^{-1} rhs
    int info = 0;
    const int nrhs = 1;
    if (m > 0)
    {
      dpotrf_("L", &m, m_S.data(), &m, &info);
      if (info != 0) throw std::runtime_error("SchurComplementDirichlet: the Schur complement is not positive definite (dpotrf info " + std::to_string(info) + ")");
      dpotrs_("L", &m, &nrhs, m_S.data(), &m, rhs.data(), &m, &info);
      m_updateFlops += double(m) * m * m / 3 + 2.0 * m * m;
    }
    return backward(rhs);
  }

  /** The first part of solve(), for other uses of the same blocks (e.g. Sherman-Morrison-Woodbury
    * with H = H_B): computes W = L^{-1} P H on the reach of \a dofs and S = W^T W, whose lower
    * triangle schur() then holds, both in the order of sortedDofs(). Resets updateFlops(). */
  void prepare(const std::vector<int>& dofs)
  {
    const int m = int(dofs.size());
    m_updateFlops = 0;
    // Positions of the dofs in the factor, sorted (postorder: each subtree is a contiguous range).
    std::vector<std::pair<int, int>> byPosition(static_cast<std::size_t>(m));
    for (int j = 0; j < m; ++j) byPosition[std::size_t(j)] = {m_position[std::size_t(dofs[std::size_t(j)])], dofs[std::size_t(j)]};
    std::sort(byPosition.begin(), byPosition.end());
    std::vector<int> q(static_cast<std::size_t>(m));
    m_sortedDofs.resize(std::size_t(m));
    for (int j = 0; j < m; ++j)
    {
      q[std::size_t(j)] = byPosition[std::size_t(j)].first;
      m_sortedDofs[std::size_t(j)] = byPosition[std::size_t(j)].second;
    }

    // The reach: every supernode on a path from a dof to the root, processed in increasing order.
    m_reach.clear();
    for (int j = 0; j < m; ++j)
      for (int s = m_colToSuper[std::size_t(q[std::size_t(j)])]; s != -1 && !m_reachMark[std::size_t(s)];
           s = m_parent[std::size_t(s)])
      {
        m_reachMark[std::size_t(s)] = 1;
        m_reach.push_back(s);
      }
    std::sort(m_reach.begin(), m_reach.end());
    for (int s : m_reach) m_reachMark[std::size_t(s)] = 0;

    // Per reach supernode: the slice [first, first+count) of the sorted dofs in its subtree and the
    // offset of its block Z_S = W_S^T (count x ncols, column-major) in one buffer.
    m_slot.assign(std::size_t(m_nsuper), -1);
    m_first.resize(m_reach.size());
    m_count.resize(m_reach.size());
    m_offset.assign(m_reach.size() + 1, 0);
    for (std::size_t r = 0; r < m_reach.size(); ++r)
    {
      const int s = m_reach[r];
      m_slot[std::size_t(s)] = int(r);
      const auto lo = std::lower_bound(q.begin(), q.end(), m_super[m_firstDescendant[std::size_t(s)]]);
      const auto hi = std::lower_bound(q.begin(), q.end(), m_super[s + 1]);
      m_first[r] = int(lo - q.begin());
      m_count[r] = int(hi - lo);
      m_offset[r + 1] = m_offset[r] + std::size_t(m_count[r]) * std::size_t(ncols(s));
    }
    m_z.assign(m_offset.back(), 0.0);
    for (std::size_t r = 0; r < m_reach.size(); ++r) // unit entries: W(q_j, j) = e before the solve
    {
      const int s = m_reach[r];
      for (int j = m_first[r]; j < m_first[r] + m_count[r]; ++j)
        if (q[std::size_t(j)] >= m_super[s])
          m_z[m_offset[r] + std::size_t(q[std::size_t(j)] - m_super[s]) * std::size_t(m_count[r]) + std::size_t(j - m_first[r])] = 1.0;
    }

    // W = L^{-1} P H on the reach, and S = W^T W (lower triangle), supernode by supernode.
    m_S.setZero(m, m);
    const double one = 1.0, zero = 0.0;
    for (std::size_t r = 0; r < m_reach.size(); ++r)
    {
      const int s = m_reach[r], k = m_count[r], nc = ncols(s), nr = nrows(s), nb = nr - nc;
      double* z = m_z.data() + m_offset[r];
      const double* Lss = m_values + m_px[s];
      // Z_S <- Z_S L_SS^{-T}   (i.e. W_S <- L_SS^{-1} W_S)
      dtrsm_("R", "L", "T", "N", &k, &nc, &one, Lss, &nr, z, &k);
      // S(slice, slice) += Z_S Z_S^T
      dsyrk_("L", "N", &k, &nc, &one, z, &k, &one, m_S.data() + m_first[r] + std::ptrdiff_t(m_first[r]) * m, &m);
      m_updateFlops += double(k) * nc * nc + double(k) * k * nc;
      if (nb == 0) continue;
      // T = Z_S L_{below,S}^T  (k x nb): column i is what row i below S receives, negated
      m_t.resize(std::size_t(k) * std::size_t(nb));
      dgemm_("N", "T", &k, &nb, &nc, &one, z, &k, Lss + nc, &nr, &zero, m_t.data(), &k);
      m_updateFlops += 2.0 * k * nb * nc;
      const int* below = m_rows + m_pi[s] + nc;
      for (int i = 0; i < nb; ++i)
      {
        const int row = below[i], a = m_colToSuper[std::size_t(row)], ra = m_slot[std::size_t(a)];
        double* dst = m_z.data() + m_offset[std::size_t(ra)] + std::size_t(row - m_super[a]) * std::size_t(m_count[std::size_t(ra)]) +
                      std::size_t(m_first[r] - m_first[std::size_t(ra)]);
        const double* src = m_t.data() + std::size_t(i) * std::size_t(k);
        for (int t = 0; t < k; ++t) dst[t] -= src[t];
      }
    }
    m_reachSupernodes = int(m_reach.size());
  }

  /** After prepare(): computes c = L^{-1} P b (kept for backward()) and \returns W^T c, that is
    * H^T A^{-1} b, in the order of sortedDofs(). */
  Eigen::VectorXd forward(const Eigen::VectorXd& b)
  {
    cholmod_common& common = m_chol.common();
    cholmod_factor* L = m_chol.factor();
    cholmod_dense bView = denseView(const_cast<double*>(b.data()), m_n);
    solve2(CHOLMOD_P, L, &bView, &m_x);
    if (m_c) cholmod_free_dense(&m_c, &common);
    solve2(CHOLMOD_L, L, m_x, &m_c);
    const double* cx = static_cast<const double*>(m_c->x);
    Eigen::VectorXd result = Eigen::VectorXd::Zero(Eigen::Index(m_sortedDofs.size()));
    const int inc = 1;
    const double one = 1.0;
    for (std::size_t r = 0; r < m_reach.size(); ++r)
    {
      const int s = m_reach[r], k = m_count[r], nc = ncols(s);
      dgemv_("N", &k, &nc, &one, m_z.data() + m_offset[r], &k, cx + m_super[s], &inc, &one, result.data() + m_first[r], &inc);
      m_updateFlops += 2.0 * k * nc;
    }
    return result;
  }

  /** After forward(): \returns x = A^{-1} (b - H y) = P^T L^{-T} (c - W y), \a y in the order of
    * sortedDofs(). */
  Eigen::VectorXd backward(const Eigen::VectorXd& y)
  {
    cholmod_common& common = m_chol.common();
    cholmod_factor* L = m_chol.factor();
    if (!m_c) throw std::logic_error("SchurComplementDirichlet: backward() before forward()");
    double* cx = static_cast<double*>(m_c->x);
    const double one = 1.0, minusOne = -1.0;
    const int inc = 1;
    for (std::size_t r = 0; r < m_reach.size(); ++r)
    {
      const int s = m_reach[r], k = m_count[r], nc = ncols(s);
      dgemv_("T", &k, &nc, &minusOne, m_z.data() + m_offset[r], &k, y.data() + m_first[r], &inc, &one, cx + m_super[s], &inc);
      m_updateFlops += 2.0 * k * nc;
    }
    solve2(CHOLMOD_Lt, L, m_c, &m_x);
    cholmod_free_dense(&m_c, &common);
    cholmod_dense* x = nullptr;
    solve2(CHOLMOD_Pt, L, m_x, &x);
    Eigen::VectorXd result = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), m_n);
    cholmod_free_dense(&x, &common);
    return result;
  }

  /** \returns the dofs of the last prepare() sorted by their position in the factor. */
  const std::vector<int>& sortedDofs() const { return m_sortedDofs; }
  /** \returns S = W^T W of the last prepare() (lower triangle; solve() overwrites it with its factor). */
  Eigen::MatrixXd& schur() { return m_S; }
  /** Adds \a flops to updateFlops() (for dense work a caller does on schur()). */
  void addUpdateFlops(double flops) { m_updateFlops += flops; }

  /** \returns the dense flops of the last solve(), without its two full triangular solves. */
  double updateFlops() const { return m_updateFlops; }
  /** \returns the dense flops of a full supernodal factorization on this factor's layout. */
  double factorizationFlops() const { return m_factorFlops; }
  /** \returns the number of supernodes on the reach of the last solve()'s dofs. */
  int reachSupernodes() const { return m_reachSupernodes; }
  /** \returns the number of supernodes of the factor. */
  int supernodeCount() const { return m_nsuper; }

private:
  int ncols(int s) const { return m_super[s + 1] - m_super[s]; }
  int nrows(int s) const { return m_pi[s + 1] - m_pi[s]; }

  static cholmod_dense denseView(double* data, int n)
  {
    cholmod_dense d;
    d.nrow = std::size_t(n);
    d.ncol = 1;
    d.nzmax = std::size_t(n);
    d.d = std::size_t(n);
    d.x = data;
    d.z = nullptr;
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    return d;
  }

  void solve2(int system, cholmod_factor* L, cholmod_dense* in, cholmod_dense** out)
  {
    cholmod_common& common = m_chol.common();
    if (!cholmod_solve2(system, L, in, nullptr, out, nullptr, &m_y, &m_e, &common))
      throw std::runtime_error("SchurComplementDirichlet: cholmod_solve2 failed, status " + std::to_string(common.status));
  }

  CholmodSupernodal& m_chol;
  int m_n = 0, m_nsuper = 0, m_reachSupernodes = 0;
  const int *m_super = nullptr, *m_pi = nullptr, *m_px = nullptr, *m_rows = nullptr;
  const double* m_values = nullptr;
  std::vector<int> m_position, m_colToSuper, m_parent, m_firstDescendant, m_slot;
  std::vector<int> m_sortedDofs, m_reach, m_first, m_count; ///< of the last prepare()
  std::vector<std::size_t> m_offset;
  Eigen::MatrixXd m_S;
  std::vector<char> m_reachMark;
  std::vector<double> m_z, m_t;
  double m_updateFlops = 0, m_factorFlops = 0;
  cholmod_dense *m_x = nullptr, *m_y = nullptr, *m_e = nullptr, *m_c = nullptr;
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_SCHURPEER_H
