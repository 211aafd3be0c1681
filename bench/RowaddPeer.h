// RowaddPeer: CHOLMOD's row addition (cholmod_rowadd, Davis & Hager 2005) as a benchmark peer for
// adding dofs (a mesh cut): the new dofs are anticipated as identity placeholder rows and columns
// in the initial factorization, and the cut replaces rows with cholmod_rowdel and cholmod_rowadd
// (one rank-2 modification of a simplicial LDL^T factor per row; the paper's setup, §6).

#ifndef UPDATABLE_CHOLESKY_BENCH_ROWADDPEER_H
#define UPDATABLE_CHOLESKY_BENCH_ROWADDPEER_H

#include "CholmodPeer.h"
#include "RowdelPeer.h"
#include "Timing.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

/** Rows of a matrix replaced in place in a simplicial LDL^T factor by cholmod_rowdel + cholmod_rowadd.
  *
  * The constructor factors \a placeholders (N x N, both triangles stored: the matrix before the
  * change, with identity rows and columns for the dofs still to come) with the given permutation
  * (supernodal CHOLMOD, factorizeMs()), and converts it to simplicial LDL^T (a CholmodRowdel,
  * conversionMs()). This is the setup, outside any timed region.
  *
  * replaceRows(Anew, changed, added) then turns the factor into that of \a Anew when the rows and
  * columns that differ are \a changed (rows present in the old matrix: deleted first, each with
  * cholmod_rowdel and the row pattern of L from cholmod_row_lsubtree) and \a added (identity rows of
  * the old matrix: the placeholders). All of them are then added with cholmod_rowadd, in order of
  * their position in the factor; each one's column holds its entries of \a Anew in rows already
  * present (unchanged rows and those added before it), so that every intermediate matrix is
  * blkdiag(Anew restricted to the rows present, I), positive definite when Anew is.
  *
  * updateFlops() is CHOLMOD's own count (Common.modfl) summed over the deletions and additions.
  * Errors throw std::runtime_error. */
class CholmodRowadd
{
public:
  using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /** Factors and converts \a placeholders with the permutation \a perm (perm[k] = dof at position k). */
  CholmodRowadd(const SpMat& placeholders, const std::vector<int>& perm)
  {
    if (perm.size() != std::size_t(placeholders.rows())) throw std::runtime_error("CholmodRowadd: permutation size");
    CholmodSupernodal chol;
    Stopwatch watch;
    chol.analyze(placeholders, perm.data());
    if (!chol.factorize(placeholders)) throw std::runtime_error("CholmodRowadd: the placeholder matrix is not positive definite");
    m_factorizeMs = watch.ms();
    m_rowdel.reset(new CholmodRowdel(chol, placeholders));
    m_rowdel->reset();
    const int n = int(placeholders.rows());
    m_present.assign(std::size_t(n), 1);
    m_column = cholmod_allocate_sparse(std::size_t(n), 1, std::size_t(n), 0, 1, 0, CHOLMOD_REAL, &m_rowdel->common());
    if (!m_column) throw std::runtime_error("CholmodRowadd: cholmod_allocate_sparse failed");
  }
  ~CholmodRowadd()
  {
    if (m_column) cholmod_free_sparse(&m_column, &m_rowdel->common());
  }
  CholmodRowadd(const CholmodRowadd&) = delete;
  CholmodRowadd& operator=(const CholmodRowadd&) = delete;

  /** \returns the milliseconds of the supernodal analysis + factorization of the placeholder matrix. */
  double factorizeMs() const { return m_factorizeMs; }
  /** \returns the milliseconds of the supernodal LL^T to simplicial LDL^T conversion (with the copy). */
  double conversionMs() const { return m_rowdel->conversionMs(); }

  /** Replaces the rows and columns \a changed and \a added (see the class comment) by those of
    * \a Anew (both triangles stored, same size). */
  void replaceRows(const SpMat& Anew, const std::vector<int>& changed, const std::vector<int>& added)
  {
    cholmod_common& common = m_rowdel->common();
    m_rowdel->removeDofs(changed);
    m_updateFlops = m_rowdel->updateFlops();
    std::vector<std::pair<int, int>> order; // (position, dof)
    order.reserve(changed.size() + added.size());
    for (int d : changed) order.push_back({m_rowdel->position(d), d});
    for (int d : added) order.push_back({m_rowdel->position(d), d});
    std::sort(order.begin(), order.end());
    for (const auto& entry : order) m_present[std::size_t(entry.second)] = 0;
    int* rows = static_cast<int*>(m_column->i);
    double* values = static_cast<double*>(m_column->x);
    int* outer = static_cast<int*>(m_column->p);
    for (const auto& entry : order)
    {
      const int d = entry.second;
      m_present[std::size_t(d)] = 1;
      int count = 0;
      for (SpMat::InnerIterator it(Anew, d); it; ++it)
        if (m_present[std::size_t(it.row())])
        {
          rows[count] = m_rowdel->position(int(it.row()));
          values[count++] = it.value();
        }
      outer[0] = 0;
      outer[1] = count;
      common.modfl = 0;
      if (!cholmod_rowadd(std::size_t(entry.first), m_column, m_rowdel->working(), &common) || common.status < 0)
        throw std::runtime_error("cholmod_rowadd failed, CHOLMOD status " + std::to_string(common.status));
      m_updateFlops += common.modfl;
    }
  }

  /** \returns the solution of (the current matrix) x = \a b. */
  Eigen::VectorXd solve(const Eigen::VectorXd& b) { return m_rowdel->solve(b); }

  /** \returns CHOLMOD's flop count (Common.modfl) summed over the last replaceRows(). */
  double updateFlops() const { return m_updateFlops; }

private:
  std::unique_ptr<CholmodRowdel> m_rowdel;
  cholmod_sparse* m_column = nullptr;
  std::vector<char> m_present;
  double m_factorizeMs = 0, m_updateFlops = 0;
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_ROWADDPEER_H
