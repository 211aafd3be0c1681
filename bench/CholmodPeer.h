// CholmodPeer: CHOLMOD's supernodal Cholesky (LL^T) as a benchmark peer, driven with a given
// fill-reducing permutation so that it factors the same permuted matrix as the other solvers.
// CHOLMOD is GPL: it is used by the benchmarks only, never by the library. It is the
// refactorization peer of the paper's comparisons (§6.1, Fig. 6).

#ifndef UPDATABLE_CHOLESKY_BENCH_CHOLMODPEER_H
#define UPDATABLE_CHOLESKY_BENCH_CHOLMODPEER_H

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cholmod.h>

#include <stdexcept>
#include <string>

namespace bench {

/** Supernodal CHOLMOD factorization of a symmetric matrix stored in an Eigen SparseMatrix<double,
  * ColMajor, int>, of which CHOLMOD reads the lower triangle.
  *
  * analyze() runs cholmod_analyze_p with the given permutation as the only ordering method
  * (CHOLMOD_GIVEN, weighted etree postorder on, supernodal forced); factorize() runs
  * cholmod_factorize, reusing the analysis; calling it again refactors in place. Errors throw
  * std::runtime_error; a matrix that is not positive definite is reported by factorize() returning
  * false. The matrix given to analyze() must stay alive and unchanged in pattern while in use. */
class CholmodSupernodal
{
public:
  /** Starts a CHOLMOD workspace (cholmod_start) with the options described above. */
  CholmodSupernodal()
  {
    cholmod_start(&m_common);
    m_common.supernodal = CHOLMOD_SUPERNODAL;
    m_common.nmethods = 1;
    m_common.method[0].ordering = CHOLMOD_GIVEN;
    m_common.postorder = 1;
    m_common.print = 0;
  }
  ~CholmodSupernodal()
  {
    if (m_factor) cholmod_free_factor(&m_factor, &m_common);
    cholmod_finish(&m_common);
  }
  CholmodSupernodal(const CholmodSupernodal&) = delete;
  CholmodSupernodal& operator=(const CholmodSupernodal&) = delete;

  /** Symbolic analysis of \a A with the fill-reducing permutation \a perm, where perm[k] is the
    * original index placed at position k (Eigen's ordering functor output, `Pinv.indices()`). */
  void analyze(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A, const int* perm)
  {
    if (!A.isCompressed()) throw std::runtime_error("CholmodSupernodal: the matrix must be compressed");
    if (m_factor) cholmod_free_factor(&m_factor, &m_common);
    m_matrix = view(A);
    m_factor = cholmod_analyze_p(&m_matrix, const_cast<int*>(perm), nullptr, 0, &m_common);
    check("cholmod_analyze_p");
    if (!m_factor->is_super) throw std::runtime_error("CholmodSupernodal: the analysis is not supernodal");
  }

  /** Numeric factorization of the analysed matrix (values may have changed, not the pattern).
    * \returns false if the matrix is not positive definite. */
  bool factorize(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A)
  {
    if (!m_factor) throw std::runtime_error("CholmodSupernodal: factorize() before analyze()");
    m_matrix = view(A);
    cholmod_factorize(&m_matrix, m_factor, &m_common);
    if (m_common.status == CHOLMOD_NOT_POSDEF) return false;
    check("cholmod_factorize");
    return m_factor->minor == m_factor->n;
  }

  /** \returns the solution X of A X = B (any number of columns). */
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B)
  {
    if (!m_factor || !m_factor->is_super || m_factor->minor < m_factor->n)
      throw std::runtime_error("CholmodSupernodal: solve() without a successful factorization");
    cholmod_dense b;
    b.nrow = std::size_t(B.rows());
    b.ncol = std::size_t(B.cols());
    b.nzmax = b.nrow * b.ncol;
    b.d = b.nrow;
    b.x = const_cast<double*>(B.data());
    b.z = nullptr;
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, m_factor, &b, &m_common);
    check("cholmod_solve");
    Eigen::MatrixXd X = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(x->x), B.rows(), B.cols());
    cholmod_free_dense(&x, &m_common);
    return X;
  }

  /** \returns the entries CHOLMOD stores for L below and on the diagonal, relaxed (amalgamation)
    * zeros included: for each supernode of nrows x ncols, nrows*ncols - ncols*(ncols-1)/2 (the
    * trapezoid; L->xsize also counts the unused upper triangle of each diagonal block). */
  double storedNonZerosL() const
  {
    const int* super = static_cast<const int*>(m_factor->super);
    const int* pi = static_cast<const int*>(m_factor->pi);
    double count = 0;
    for (std::size_t s = 0; s < m_factor->nsuper; ++s)
    {
      const double ncols = super[s + 1] - super[s], nrows = pi[s + 1] - pi[s];
      count += nrows * ncols - ncols * (ncols - 1) / 2;
    }
    return count;
  }
  /** \returns the size of CHOLMOD's value array (L->xsize): the trapezoids plus the upper triangles. */
  double valueArraySize() const { return double(m_factor->xsize); }
  /** \returns nnz(L) of the exact (non-amalgamated) factor, Common.lnz from the analysis. */
  double exactNonZerosL() const { return m_common.lnz; }
  /** \returns the flop count CHOLMOD reports for the exact factor (Common.fl: sum of squared column counts). */
  double flops() const { return m_common.fl; }
  /** \returns the number of (relaxed) supernodes. */
  std::size_t supernodeCount() const { return m_factor->nsuper; }
  /** \returns CHOLMOD's own count of its peak memory use in bytes since construction (Common.memory_usage). */
  std::size_t reportedPeakMemory() const { return m_common.memory_usage; }

  /** \returns the factor itself (null before analyze()), for peers that work on CHOLMOD's
    * supernodal layout directly (SchurPeer.h) or convert a copy of it (RowdelPeer.h). */
  cholmod_factor* factor() { return m_factor; }
  /** \returns the CHOLMOD workspace the factor belongs to; pass it to every call on factor(). */
  cholmod_common& common() { return m_common; }

private:
  static cholmod_sparse view(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A)
  {
    cholmod_sparse s;
    s.nrow = std::size_t(A.rows());
    s.ncol = std::size_t(A.cols());
    s.nzmax = std::size_t(A.nonZeros());
    s.p = const_cast<int*>(A.outerIndexPtr());
    s.i = const_cast<int*>(A.innerIndexPtr());
    s.nz = nullptr;
    s.x = const_cast<double*>(A.valuePtr());
    s.z = nullptr;
    s.stype = -1; // symmetric, lower triangle used
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }

  void check(const char* what) const
  {
    if (m_common.status < 0) throw std::runtime_error(std::string(what) + " failed, CHOLMOD status " + std::to_string(m_common.status));
  }

  cholmod_common m_common;
  cholmod_sparse m_matrix{};
  cholmod_factor* m_factor = nullptr;
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_CHOLMODPEER_H
