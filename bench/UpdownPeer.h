// UpdownPeer: CHOLMOD's rank-k update of a simplicial LDL^T factor (cholmod_updown, Davis & Hager
// 1999/2001) as a benchmark peer for value changes that add a positive semidefinite term
// C C^T to the matrix, as soft (penalty) constraints at k dofs do: A + sum_j w_j e_j e_j^T.

#ifndef UPDATABLE_CHOLESKY_BENCH_UPDOWNPEER_H
#define UPDATABLE_CHOLESKY_BENCH_UPDOWNPEER_H

#include "CholmodPeer.h"
#include "RowdelPeer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bench {

/** Rank-k updates by cholmod_updown on a simplicial LDL^T copy of a CHOLMOD supernodal factor.
  *
  * The copy and its conversion are a CholmodRowdel's (RowdelPeer.h, untimed): reset() makes the
  * working factor a fresh copy of the factor of A, solve() solves with it. update() adds
  * sum_j w_j e_j e_j^T for the given (dof j, w_j > 0) pairs by one cholmod_updown call with the
  * n x k matrix C of columns sqrt(w_j) e_{position of j}. Errors throw std::runtime_error. */
class CholmodUpdown
{
public:
  /** Copies and converts \a factored's factor; \a A is the matrix it factors (lower triangle read). */
  CholmodUpdown(CholmodSupernodal& factored, const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A)
      : m_simplicial(factored, A)
  {
  }

  /** The working factor becomes a fresh copy of the converted factor of A. */
  void reset() { m_simplicial.reset(); }

  /** Adds sum w e_j e_j^T over \a terms (dof j, weight w > 0) to the factored matrix. */
  void update(const std::vector<std::pair<int, double>>& terms)
  {
    cholmod_common& common = m_simplicial.common();
    cholmod_factor* L = m_simplicial.working();
    if (!L) throw std::logic_error("CholmodUpdown: update() before reset()");
    // C in the factor's numbering, one entry per column, columns in increasing row order
    std::vector<std::pair<int, double>> entries;
    for (const auto& t : terms) entries.push_back({m_simplicial.position(t.first), std::sqrt(t.second)});
    std::sort(entries.begin(), entries.end());
    const std::size_t k = entries.size();
    cholmod_sparse* C = cholmod_allocate_sparse(L->n, k, k, /*sorted=*/1, /*packed=*/1, /*stype=*/0, CHOLMOD_REAL, &common);
    if (!C) throw std::runtime_error("cholmod_allocate_sparse failed");
    int* p = static_cast<int*>(C->p);
    int* i = static_cast<int*>(C->i);
    double* x = static_cast<double*>(C->x);
    for (std::size_t c = 0; c < k; ++c)
    {
      p[c] = int(c);
      i[c] = entries[c].first;
      x[c] = entries[c].second;
    }
    p[k] = int(k);
    common.modfl = 0;
    const int ok = cholmod_updown(/*update=*/1, C, L, &common);
    cholmod_free_sparse(&C, &common);
    if (!ok) throw std::runtime_error("cholmod_updown failed, CHOLMOD status " + std::to_string(common.status));
    m_flops = common.modfl;
  }

  /** \returns the solution of (the current matrix) x = \a b. */
  Eigen::VectorXd solve(const Eigen::VectorXd& b) { return m_simplicial.solve(b); }

  /** CHOLMOD's flop count of the last update (Common.modfl). */
  double updateFlops() const { return m_flops; }

private:
  CholmodRowdel m_simplicial;
  double m_flops = 0;
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_UPDOWNPEER_H
