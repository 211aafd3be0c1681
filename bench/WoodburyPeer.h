// WoodburyPeer: solving with a cut matrix through the factor of the uncut one, by the
// Sherman-Morrison-Woodbury formula on the bordered matrix (the low-rank/Schur-complement approach
// of Yeung et al. 2018, paper §3.5, for added dofs). Uses SchurPeer.h's blocks W = L^{-1} P H.

#ifndef UPDATABLE_CHOLESKY_BENCH_WOODBURYPEER_H
#define UPDATABLE_CHOLESKY_BENCH_WOODBURYPEER_H

#include "BlasLapack.h"
#include "SchurPeer.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

/** Solves Acut x = b with Acut ((n+m) x (n+m), a cut of the n x n matrix A: m new dofs) through
  * CHOLMOD's factor P A P^T = L L^T of the uncut A, without touching the factor.
  *
  * Bordered: Aext = blkdiag(A, I_m), whose inverse is blkdiag(A^{-1}, I). The cut changes the rows
  * and columns of a set K only: the new dofs and the old dofs whose column of Acut differs from
  * that of Aext (\a changed). So Acut = Aext + H D H^T with H = H_K (columns of the identity at K,
  * k = |K|) and D = Acut(K,K) - Aext(K,K) (sparse, symmetric, indefinite), and by Woodbury
  *
  *     x = Aext^{-1} b - Aext^{-1} H (I + D S)^{-1} D H^T Aext^{-1} b,    S = H^T Aext^{-1} H.
  *
  * S = blkdiag(W^T W, I) with W = L^{-1} P H_{K_old} computed on the elimination-tree reach of the
  * changed old dofs (SchurComplementDirichlet::prepare), H^T Aext^{-1} b = (W^T L^{-1} P b, b_new)
  * and Aext^{-1} (b - H t) = (P^T L^{-T} (L^{-1} P b - W t_old), b_new - t_new): one forward and
  * one backward solve with L. The capacity matrix I + D S (k x k, not symmetric) is factored by
  * LAPACK's dgetrf (stored transposed, I + S D^T, so that it is assembled by column updates).
  *
  * updateFlops() counts the dense flops of W, S, the capacity matrix and its LU factorization (not
  * the two full triangular solves); the factor must stay alive and unchanged while in use. */
class WoodburyCutSolve
{
public:
  using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /** \a schur works on the factor of \a A (both triangles stored), which must outlive this object. */
  WoodburyCutSolve(SchurComplementDirichlet& schur, const SpMat& A) : m_schur(schur), m_A(A) {}

  /** \returns x with \a Acut x = \a b; \a changed are the old dofs (< n) whose columns differ. */
  Eigen::VectorXd solve(const SpMat& Acut, const std::vector<int>& changed, const Eigen::VectorXd& b)
  {
    const int n = int(m_A.rows()), total = int(Acut.rows()), m = total - n;
    m_schur.prepare(changed);
    const std::vector<int>& sorted = m_schur.sortedDofs();
    const int ko = int(sorted.size()), k = ko + m;
    m_rank = k;

    // Slots of K: the changed old dofs in the order of sortedDofs(), then the new dofs.
    if (int(m_slot.size()) < total) m_slot.resize(std::size_t(total), -1);
    for (int j = 0; j < ko; ++j) m_slot[std::size_t(sorted[std::size_t(j)])] = j;
    for (int j = 0; j < m; ++j) m_slot[std::size_t(n + j)] = ko + j;
    auto dofOf = [&](int slot) { return slot < ko ? sorted[std::size_t(slot)] : n + slot - ko; };

    // D = Acut(K,K) - Aext(K,K), by columns: (row slot, value).
    std::vector<std::vector<std::pair<int, double>>> D(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j)
    {
      const int d = dofOf(j);
      std::vector<std::pair<int, double>>& col = D[std::size_t(j)];
      for (SpMat::InnerIterator it(Acut, d); it; ++it)
        if (m_slot[std::size_t(it.row())] >= 0) col.push_back({m_slot[std::size_t(it.row())], it.value()});
      if (d < n)
      {
        for (SpMat::InnerIterator it(m_A, d); it; ++it)
          if (m_slot[std::size_t(it.row())] >= 0) col.push_back({m_slot[std::size_t(it.row())], -it.value()});
      }
      else col.push_back({j, -1.0});
    }
    for (int j = 0; j < k; ++j) m_slot[std::size_t(dofOf(j))] = -1;

    // r = H^T Aext^{-1} b, then rhs = D r.
    Eigen::VectorXd r(k);
    r.head(ko) = m_schur.forward(b.head(n));
    r.tail(m) = b.tail(m);
    Eigen::VectorXd t = Eigen::VectorXd::Zero(k);
    double nnzD = 0;
    for (int j = 0; j < k; ++j)
      for (const auto& e : D[std::size_t(j)])
      {
        t[e.first] += e.second * r[j];
        ++nnzD;
      }

    if (k > 0)
    {
      // C^T = I + S D^T: column i gets D(i,j) S(:,j) for every entry D(i,j); S = blkdiag(W^T W, I).
      Eigen::MatrixXd& S = m_schur.schur();
      S.triangularView<Eigen::StrictlyUpper>() = S.transpose();
      m_capacity.setIdentity(k, k);
      for (int j = 0; j < k; ++j)
        for (const auto& e : D[std::size_t(j)])
        {
          if (j < ko) m_capacity.col(e.first).head(ko) += e.second * S.col(j);
          else m_capacity(j, e.first) += e.second;
        }
      m_pivots.resize(std::size_t(k));
      int info = 0;
      dgetrf_(&k, &k, m_capacity.data(), &k, m_pivots.data(), &info);
      if (info != 0) throw std::runtime_error("WoodburyCutSolve: the capacity matrix is singular (dgetrf info " + std::to_string(info) + ")");
      const int nrhs = 1;
      dgetrs_("T", &k, &nrhs, m_capacity.data(), &k, m_pivots.data(), t.data(), &k, &info);
      m_schur.addUpdateFlops(2.0 * nnzD * ko + 2.0 * double(k) * k * k / 3 + 2.0 * double(k) * k);
    }

    Eigen::VectorXd x(total);
    x.head(n) = m_schur.backward(t.head(ko));
    x.tail(m) = b.tail(m) - t.tail(m);
    return x;
  }

  /** \returns the dense flops of the last solve(), without its two full triangular solves. */
  double updateFlops() const { return m_schur.updateFlops(); }
  /** \returns k = |K| of the last solve(): the size of the capacity matrix. */
  int rank() const { return m_rank; }

private:
  SchurComplementDirichlet& m_schur;
  const SpMat& m_A;
  std::vector<int> m_slot;
  std::vector<int> m_pivots;
  Eigen::MatrixXd m_capacity;
  int m_rank = 0;
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_WOODBURYPEER_H
