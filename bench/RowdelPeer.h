// RowdelPeer: CHOLMOD's row deletion (cholmod_rowdel, Davis & Hager 2005) as a benchmark peer for
// removing dofs: one rank-2 modification of a simplicial LDL^T factor per dof, each given the
// pattern of the row it deletes (cholmod_row_lsubtree), which is what makes it fast. It is the
// Davis & Hager peer of the paper's Fig. 6 (§6.1).

#ifndef UPDATABLE_CHOLESKY_BENCH_ROWDELPEER_H
#define UPDATABLE_CHOLESKY_BENCH_ROWDELPEER_H

#include "CholmodPeer.h"
#include "Timing.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

/** Dof removal by cholmod_rowdel on a simplicial LDL^T copy of a CHOLMOD supernodal factor.
  *
  * The constructor copies \a factored's factor (the full matrix A, same permutation as every other
  * solver) and converts the copy to simplicial LDL^T (cholmod_change_factor; the time is
  * conversionMs(), reported apart from the updates). reset() makes the working factor a fresh
  * copy of that converted original, so every seam starts from the factor of A. removeDofs() then
  * deletes the dofs one after the other: for dof d at position k of the factor it finds the
  * pattern of row k of L with cholmod_row_lsubtree (from column k of triu(P A P^T), built once
  * here) and calls cholmod_rowdel(k, pattern). Row and column k of the factored matrix become
  * those of the identity, so after all of them the factor is that of A^B, and solve() with a
  * right-hand side whose B entries hold g answers the Dirichlet system.
  *
  * updateFlops() is the sum of CHOLMOD's own count (Common.modfl) over the deletions. Errors throw
  * std::runtime_error. */
class CholmodRowdel
{
public:
  /** Copies and converts \a factored's factor; \a A is the matrix it factors (lower triangle read). */
  CholmodRowdel(CholmodSupernodal& factored, const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A)
  {
    cholmod_start(&m_common);
    m_common.print = 0;
    if (!factored.factor()) throw std::runtime_error("CholmodRowdel: the source has no factor");
    Stopwatch watch;
    m_original = cholmod_copy_factor(factored.factor(), &m_common);
    check("cholmod_copy_factor");
    cholmod_change_factor(CHOLMOD_REAL, /*to_ll=*/0, /*to_super=*/0, /*to_packed=*/1, /*to_monotonic=*/1, m_original,
                          &m_common);
    check("cholmod_change_factor");
    m_conversionMs = watch.ms();

    // triu(P A P^T) in the factor's numbering, as CHOLMOD's symmetric-upper input of row_lsubtree.
    const int n = int(m_original->n);
    const int* perm = static_cast<const int*>(m_original->Perm);
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(n);
    for (int k = 0; k < n; ++k) P.indices()[perm[k]] = k; // P maps an original index to its position
    m_position.assign(P.indices().data(), P.indices().data() + n);
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> full;
    full = A.selfadjointView<Eigen::Lower>().twistedBy(P);
    m_upper = full.triangularView<Eigen::Upper>();
    m_upper.makeCompressed();
    m_upperView.nrow = m_upperView.ncol = std::size_t(n);
    m_upperView.nzmax = std::size_t(m_upper.nonZeros());
    m_upperView.p = m_upper.outerIndexPtr();
    m_upperView.i = m_upper.innerIndexPtr();
    m_upperView.nz = nullptr;
    m_upperView.x = m_upper.valuePtr();
    m_upperView.z = nullptr;
    m_upperView.stype = 1;
    m_upperView.itype = CHOLMOD_INT;
    m_upperView.xtype = CHOLMOD_REAL;
    m_upperView.dtype = CHOLMOD_DOUBLE;
    m_upperView.sorted = 1;
    m_upperView.packed = 1;
    m_rowPattern = cholmod_allocate_sparse(std::size_t(n), 1, std::size_t(n), 0, 1, 0, CHOLMOD_PATTERN, &m_common);
    check("cholmod_allocate_sparse");
  }
  ~CholmodRowdel()
  {
    if (m_rowPattern) cholmod_free_sparse(&m_rowPattern, &m_common);
    if (m_working) cholmod_free_factor(&m_working, &m_common);
    if (m_original) cholmod_free_factor(&m_original, &m_common);
    cholmod_finish(&m_common);
  }
  CholmodRowdel(const CholmodRowdel&) = delete;
  CholmodRowdel& operator=(const CholmodRowdel&) = delete;

  /** \returns the milliseconds of the supernodal LL^T to simplicial LDL^T conversion (with the copy). */
  double conversionMs() const { return m_conversionMs; }

  /** Makes the working factor a fresh copy of the converted factor of A (not part of an update). */
  void reset()
  {
    if (m_working) cholmod_free_factor(&m_working, &m_common);
    m_working = cholmod_copy_factor(m_original, &m_common);
    check("cholmod_copy_factor");
  }

  /** Deletes the rows and columns of \a dofs (original numbering) from the working factor. */
  void removeDofs(const std::vector<int>& dofs)
  {
    if (!m_working) throw std::logic_error("CholmodRowdel: removeDofs() before reset()");
    m_updateFlops = 0;
    for (int d : dofs)
    {
      const std::size_t k = std::size_t(m_position[std::size_t(d)]);
      cholmod_row_lsubtree(&m_upperView, nullptr, 0, k, m_working, m_rowPattern, &m_common);
      check("cholmod_row_lsubtree");
      m_common.modfl = 0;
      cholmod_rowdel(k, m_rowPattern, m_working, &m_common);
      check("cholmod_rowdel");
      m_updateFlops += m_common.modfl;
    }
  }

  /** \returns the solution of (the current matrix) x = \a b. */
  Eigen::VectorXd solve(const Eigen::VectorXd& b)
  {
    cholmod_dense view;
    view.nrow = std::size_t(b.size());
    view.ncol = 1;
    view.nzmax = view.d = std::size_t(b.size());
    view.x = const_cast<double*>(b.data());
    view.z = nullptr;
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, m_working, &view, &m_common);
    check("cholmod_solve");
    Eigen::VectorXd result = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), b.size());
    cholmod_free_dense(&x, &m_common);
    return result;
  }

  /** \returns CHOLMOD's flop count (Common.modfl) summed over the last removeDofs(). */
  double updateFlops() const { return m_updateFlops; }

  /** \returns the working factor (null before reset()), for further modifications (RowaddPeer.h). */
  cholmod_factor* working() { return m_working; }
  /** \returns the CHOLMOD workspace of the working factor; pass it to every call on working(). */
  cholmod_common& common() { return m_common; }
  /** \returns the position of dof \a d in the factor. */
  int position(int d) const { return m_position[std::size_t(d)]; }

private:
  void check(const char* what) const
  {
    if (m_common.status < 0) throw std::runtime_error(std::string(what) + " failed, CHOLMOD status " + std::to_string(m_common.status));
  }

  cholmod_common m_common;
  cholmod_factor* m_original = nullptr;
  cholmod_factor* m_working = nullptr;
  cholmod_sparse* m_rowPattern = nullptr;
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> m_upper;
  cholmod_sparse m_upperView{};
  std::vector<int> m_position;
  double m_conversionMs = 0, m_updateFlops = 0;
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_ROWDELPEER_H
