// UpdatableSupernodalLLT.h — the public solver class: a supernodal LL^T (LL^H) factorization
// of a sparse symmetric (Hermitian) positive definite matrix with the API of Eigen's
// SimplicialLLT. It ties together the symbolic analysis (SupernodalSymbolic.h), the factor
// storage (SupernodalFactor.h), the input assembly (MatrixAssembly.h), the numeric
// factorization (SupernodalNumeric.h) and the solve (SupernodalSolve.h). Paper §3.
// It also drives the in-place updates: updateColumns/removeDofs/restoreDofs (paper §3.3 and §4.1,
// Algorithm 3) and insertDofs/mergeDofs (§4.2, Algorithm 4; updateColumns is carried out as an
// insertion without copies, restoreDofs folds like one where that is cheaper) check their input here, pick the
// update route and call DofUpdates.h, LowRankRemoval.h, DofInsertion.h, DofInsertionInput.h and
// LowRankTopUpdate.h. solveDirichlet (§4.1) is here too, and solves use the forward
// substitution kept between them (IncrementalForwardSolve.h).

#ifndef EIGEN_UPDATABLE_SUPERNODAL_LLT_H
#define EIGEN_UPDATABLE_SUPERNODAL_LLT_H

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <vector>

namespace Eigen {

template <typename MatrixType_, int UpLo_ = Lower,
          typename Ordering_ = AMDOrdering<typename MatrixType_::StorageIndex> >
class UpdatableSupernodalLLT;

/** \ingroup UpdatableCholesky_Module
  * \class UpdatableSupernodalLLT
  * \brief A supernodal sparse Cholesky factorization LL^T of a selfadjoint positive definite
  * matrix, stored one supernode per object so that it can be updated in place.
  *
  * The factorization is of \f$ P A P^{-1} \f$ where P is the fill-reducing ordering given by
  * \c Ordering_ composed with a postorder of the elimination tree. Columns with similar
  * patterns are grouped into relaxed supernodes (see SupernodeRelaxation) and factored with
  * dense BLAS-3 kernels; independent subtrees are factored on several threads.
  *
  * It is a drop-in replacement for SimplicialLLT:
  * \code
  * UpdatableSupernodalLLT<SparseMatrix<double> > llt(A);
  * if (llt.info() != Success) { ... }
  * x = llt.solve(b);
  * \endcode
  *
  * \tparam MatrixType_ the type of the sparse matrix A (SparseMatrix, row- or column-major)
  * \tparam UpLo_ the triangle of A that is read: Lower or Upper
  * \tparam Ordering_ the fill-reducing ordering: AMDOrdering (default), NaturalOrdering,
  *         MetisOrdering, or any functor with `void operator()(const Matrix&, PermutationMatrix&)`
  *
  * \implsparsesolverconcept
  * \sa SimplicialLLT
  */
template <typename MatrixType_, int UpLo_, typename Ordering_>
class UpdatableSupernodalLLT : public SparseSolverBase<UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_> > {
  typedef SparseSolverBase<UpdatableSupernodalLLT> Base;
  using Base::m_isInitialized;

 public:
  /** The type of the input matrix A. */
  typedef MatrixType_ MatrixType;
  /** The fill-reducing ordering functor. */
  typedef Ordering_ OrderingType;
  /** The triangle of A that is read (Lower or Upper, the template argument UpLo_). */
  enum { UpLo = UpLo_ };
  /** The scalar type of A and of the factor. */
  typedef typename MatrixType::Scalar Scalar;
  /** The real type of Scalar (that of logDeterminant()). */
  typedef typename MatrixType::RealScalar RealScalar;
  /** The index type of A, of the factor and of the permutations. */
  typedef typename MatrixType::StorageIndex StorageIndex;
  /** Column-major sparse matrix type in which matrixL() and matrixU() return the factor. */
  typedef SparseMatrix<Scalar, ColMajor, StorageIndex> CholMatrixType;
  /** The return type of matrixL(). */
  typedef TriangularView<const CholMatrixType, Eigen::Lower> MatrixL;
  /** The return type of matrixU(). */
  typedef TriangularView<const typename CholMatrixType::AdjointReturnType, Eigen::Upper> MatrixU;
  /** The type of permutationP() and permutationPinv(). */
  typedef PermutationMatrix<Dynamic, Dynamic, StorageIndex> PermutationType;
  /** The compile-time column counts of MatrixType; Eigen's Solve expression sizes the result of solve() by them. */
  enum { ColsAtCompileTime = MatrixType::ColsAtCompileTime, MaxColsAtCompileTime = MatrixType::MaxColsAtCompileTime };
  /** Solves with at most this many right-hand sides keep their forward substitution (setSolveCaching()). */
  enum { MaxCachedRightHandSides = 8 };

  EIGEN_STATIC_ASSERT((UpLo_ & (Lower | Upper)) == Lower || (UpLo_ & (Lower | Upper)) == Upper,
                      UPLO_MUST_BE_LOWER_OR_UPPER)

  /** Default constructor: call compute() or analyzePattern()/factorize() before solving. */
  UpdatableSupernodalLLT() { init(); }

  /** Constructs and computes the factorization of \a matrix (see compute()). */
  explicit UpdatableSupernodalLLT(const MatrixType& matrix) {
    init();
    compute(matrix);
  }

  /** Analyses the pattern of \a matrix and factors it. \returns a reference to *this. */
  UpdatableSupernodalLLT& compute(const MatrixType& matrix) {
    analyzePattern(matrix);
    if (m_analysisIsOk) factorize(matrix);
    return *this;
  }

  /** Symbolic analysis: fill-reducing ordering, elimination tree, postorder, column counts,
    * relaxed supernodes and their row structures. The result serves every factorize() of a
    * matrix with the same pattern. */
  void analyzePattern(const MatrixType& matrix);

  /** Numeric factorization of \a matrix, which must have the pattern given to analyzePattern().
    * Sets info() to Success, to NumericalIssue when the matrix is not positive definite (or
    * holds NaN/Inf; see failedColumn()), or to InvalidInput when the pattern differs. */
  void factorize(const MatrixType& matrix);

  /** \returns Success, NumericalIssue or InvalidInput for the last analysis/factorization. */
  ComputationInfo info() const {
    eigen_assert(m_isInitialized && "UpdatableSupernodalLLT is not initialized: call compute() first.");
    return m_info;
  }

  /** \returns the number of rows of the factored matrix. */
  Index rows() const { return m_n; }
  /** \returns the number of columns of the factored matrix. */
  Index cols() const { return m_n; }

  /** \returns the lower triangular factor L of \f$ P A P^{-1} = L L^* \f$, as a triangular view
    * of a sparse matrix assembled from the supernodes on first call after each factorization. */
  const MatrixL matrixL() const {
    eigen_assert(m_factorizationIsOk && "UpdatableSupernodalLLT::matrixL(): no valid factorization.");
    buildSparseL();
    return MatrixL(m_sparseL);
  }

  /** \returns the upper triangular factor \f$ U = L^* \f$. */
  const MatrixU matrixU() const {
    eigen_assert(m_factorizationIsOk && "UpdatableSupernodalLLT::matrixU(): no valid factorization.");
    buildSparseL();
    return MatrixU(m_sparseL.adjoint());
  }

  /** \returns the permutation P such that the factor is that of \f$ P A P^{-1} \f$ (after
    * insertDofs() or mergeDofs(), built on first call after each of them). */
  const PermutationType& permutationP() const {
    buildPublicPermutation();
    return m_publicP;
  }
  /** \returns the inverse of permutationP(). */
  const PermutationType& permutationPinv() const {
    buildPublicPermutation();
    return m_publicPinv;
  }

  /** \returns the determinant of the (shifted) matrix. */
  Scalar determinant() const {
    eigen_assert(m_factorizationIsOk && "UpdatableSupernodalLLT::determinant(): no valid factorization.");
    RealScalar det(1);
    forEachDiagonal([&](RealScalar d) { det *= d * d; });
    return Scalar(det);
  }

  /** \returns the natural logarithm of the determinant (no overflow for large matrices). */
  RealScalar logDeterminant() const {
    eigen_assert(m_factorizationIsOk && "UpdatableSupernodalLLT::logDeterminant(): no valid factorization.");
    RealScalar sum(0);
    forEachDiagonal([&](RealScalar d) { sum += std::log(d); });
    return RealScalar(2) * sum;
  }

  /** Sets the shift of the diagonal used by the next factorizations, as SimplicialLLT does:
    * every diagonal coefficient d_ii becomes \f$ offset + scale \cdot d_{ii} \f$ (off-diagonal
    * coefficients are not scaled). The updates (updateColumns(), removeDofs(), insertDofs(), ...)
    * keep the shift of the factorization they update: a new shift takes effect at the next
    * compute() or factorize(). \returns a reference to *this. */
  UpdatableSupernodalLLT& setShift(const RealScalar& offset, const RealScalar& scale = 1) {
    m_shiftOffset = offset;
    m_shiftScale = scale;
    return *this;
  }

  /** \returns the ordering functor used by analyzePattern(), to configure it beforehand. */
  OrderingType& ordering() { return m_ordering; }

  /** \returns the index (in A's numbering) of the column whose pivot was not positive and finite
    * in the last failed factorization, or -1. */
  Index failedColumn() const { return m_failedColumn; }

  /** \returns the number of stored entries of L (relaxed supernodes store some explicit zeros). */
  Index nonZerosL() const { return m_factor.nonZeros(); }

  /** \returns the number of supernodes. */
  Index supernodeCount() const { return m_factor.count(); }

  /** \returns the floating-point operations of one numeric factorization (dense kernels). */
  double factorizationFlops() const { return m_factor.flops(); }

  /** Sets the number of threads of factorize() and of the updates' refactorizations
    * (independent subtrees at once, threaded BLAS on the top separators). 0 means
    * Eigen::nbThreads(). */
  void setThreadCount(int threads) { m_threads = threads < 0 ? 0 : threads; }
  /** \returns the number of threads factorize() and the updates use. */
  int threadCount() const { return m_threads > 0 ? m_threads : Eigen::nbThreads(); }

  /** Sets the relaxed-amalgamation thresholds used by the next analyzePattern(). */
  void setRelaxation(const SupernodeRelaxation& relaxation) { m_relaxation = relaxation; }
  /** \returns the relaxed-amalgamation thresholds. */
  const SupernodeRelaxation& relaxation() const { return m_relaxation; }

  /** \name In-place updates (paper §3.3 and §4.1)
    * Every update leaves the object holding the factor of the current matrix: the matrix last
    * given to compute()/factorize()/updateColumns(), with the rows and columns of the removed
    * dofs replaced by those of the identity. The first update after a factorization without
    * update caching (setUpdateCaching()) refactors once to build the cache.
    * On bad input (indices out of range or repeated, a pattern mismatch, removing a removed dof,
    * restoring a dof that is not removed) info() is InvalidInput and nothing changes; when the
    * updated matrix is not positive definite info() is NumericalIssue and the object keeps the
    * factor it had before the call. */
  //@{

  /** The values of A changed in the columns \a columns (and, by symmetry, in the same rows);
    * \a matrix has the analysed pattern and is the new matrix. \a columns is any container of
    * indices with size() and operator[] (std::vector<int>, VectorXi, ...).
    *
    * The pattern of \a matrix is checked whole; its values are read only in the listed columns
    * (and, by symmetry, where the other triangle holds their rows): an entry that changed
    * elsewhere is not seen. The supernodes on the paths from the changed columns to the roots
    * are refactored from the cached update matrices of the others (partial refactorization) or,
    * where the cost model finds it cheaper, updated by signed low-rank folds of the change
    * (route Mixed: a few changed columns below the large separators near the root then cost a
    * fraction of refactoring those separators). */
  template <typename Indices>
  UpdatableSupernodalLLT& updateColumns(const MatrixType& matrix, const Indices& columns);

  /** Replaces the rows and columns of the dofs \a dofs by those of the identity (Dirichlet
    * constraints; the paper's A^B, eq. 14), updating the factor in place. */
  template <typename Indices>
  UpdatableSupernodalLLT& removeDofs(const Indices& dofs);

  /** Gives the removed dofs \a dofs their original rows and columns back (those of the matrix
    * last given; a row's entries at dofs still removed stay out). The dirty supernodes are
    * refactored or, where the cost model finds it cheaper, updated by signed low-rank folds of
    * the change (route Mixed: each restored column and row goes from the identity's to the
    * matrix's, two columns of P P^H − N N^H per changed column, LowRankTopUpdate.h). */
  template <typename Indices>
  UpdatableSupernodalLLT& restoreDofs(const Indices& dofs);

  /** Adds dofs that copy existing ones, as when a mesh is cut along a seam (paper §4.2,
    * Algorithm 4), without a new analysis or ordering.
    *
    * \param matrix the new (n+m)×(n+m) matrix; its dofs 0..n-1 are the current ones.
    * \param origin n+m indices as libigl's cut_mesh returns them: origin[i] == i for i < n, and
    *        origin[n+j] in [0, n) is the dof that new dof n+j copies.
    *
    * Each new dof is eliminated right after its origin, in its origin's supernode; the
    * supernodes on the paths from the changed columns to the roots get the copies' rows and are
    * refactored or updated by signed low-rank folds, whichever the cost model finds cheaper per
    * supernode (route Mixed; the others keep their values). Every entry of \a matrix must lie in the
    * duplicated pattern: entry (i, j) needs origin[i] == origin[j] or an entry of the current
    * pattern at (origin[i], origin[j]); otherwise info() is InvalidInput and nothing changes.
    * Removed (Dirichlet) dofs stay removed; the new dofs are not removed. */
  template <typename Indices>
  UpdatableSupernodalLLT& insertDofs(const MatrixType& matrix, const Indices& origin);

  /** insertDofs() told which old dofs may have changed, as updateColumns() is: every entry that
    * differs from the current matrix lies in the row or column of a copy, of an origin or of a
    * dof in \a changed (one of an entry's two dofs is enough; a cut tool knows them: the seam's
    * vertices). Only the outer vectors of \a matrix that can hold such an entry are read (those
    * of these dofs, of the copies, and of the neighbours that store their entries), so the call
    * costs what the cut costs, not what the whole matrix costs. An entry that differs elsewhere
    * is not seen: the factor would not be that of \a matrix. \a changed out of range or
    * repeated: info() is InvalidInput. */
  template <typename Indices, typename ChangedIndices>
  UpdatableSupernodalLLT& insertDofs(const MatrixType& matrix, const Indices& origin, const ChangedIndices& changed);

  /** Merges dofs into others, the reverse of insertDofs() (a cut undone): the merged dofs leave
    * the numbering, the kept ones are renumbered in their order.
    *
    * \param matrix the new matrix on the kept dofs.
    * \param origin n indices (n = current size): origin[i] == i keeps dof i, origin[i] == k != i
    *        merges dof i into the kept dof k. The vector given to insertDofs() undoes that call.
    *
    * Every entry of \a matrix must lie in the merged pattern (an entry of the current pattern
    * between dofs merged into its row and column) and in the factor's structure, which holds
    * for copies made by insertDofs(); otherwise info() is InvalidInput and nothing changes. */
  template <typename Indices>
  UpdatableSupernodalLLT& mergeDofs(const MatrixType& matrix, const Indices& origin);

  /** mergeDofs() told which kept dofs may have changed (current numbering), as insertDofs() with
    * a changed list: every entry that differs lies in the row or column of a merged dof, of a
    * dof they merge into or of a dof in \a changed (one of an entry's two dofs is enough). When
    * the merged dofs are the last ones (a cut undone), only the outer vectors of \a matrix that
    * can hold such an entry are read. An entry that differs elsewhere is not seen. \a changed
    * out of range or repeated: info() is InvalidInput. */
  template <typename Indices, typename ChangedIndices>
  UpdatableSupernodalLLT& mergeDofs(const MatrixType& matrix, const Indices& origin, const ChangedIndices& changed);

  /** \returns the removed dofs, in the order they were removed. */
  const std::vector<StorageIndex>& removedDofs() const { return m_removedList; }

  /** \returns true when dof \a i is removed. */
  bool isRemoved(Index i) const { return !m_removedOriginal.empty() && m_removedOriginal[i] != 0; }

  /** Dirichlet solve: with B the removed dofs and I the others, returns x with
    * \f$ A_{II} x_I = b_I - A_{IB} g_B \f$ and \f$ x_B = g_B \f$, for every column of \a b.
    * \a b and \a g are n×k; only the rows of B are read from \a g. (solve() with the same b
    * instead treats b_B as the known values.) */
  template <typename Rhs, typename Known>
  Matrix<Scalar, Dynamic, Dynamic> solveDirichlet(const MatrixBase<Rhs>& b, const MatrixBase<Known>& g) const;

  /** Forces the algorithm of the next updates (UpdateRoute::Automatic picks by cost). */
  void setUpdateRoute(UpdateRoute route) { m_route = route; }
  /** \returns the forced update route, or UpdateRoute::Automatic. */
  UpdateRoute updateRoute() const { return m_route; }

  /** Keep every supernode's update matrix after factorize() (about the memory of L again), so
    * that the first update needs no refactorization. Updates turn it on by themselves. */
  void setUpdateCaching(bool cache) { m_numeric.setCacheUpdates(cache); }

  /** \returns what the last update did: route, dirty supernodes and columns, flops, time. */
  const UpdateStatistics& lastUpdate() const { return m_lastUpdate; }

  /** Keep the forward substitution of the last solve (its right-hand side, result and the
    * update vector of every supernode: about (2n + rows below the supernodes)·k scalars), so
    * that the next solve with at most MaxCachedRightHandSides columns substitutes again only the
    * supernodes whose block changed in an update or whose right-hand side rows changed, and
    * their ancestors: after a small update with the same right-hand side, a solve reads L about
    * once instead of twice. On by default; off frees the memory. */
  void setSolveCaching(bool cache) {
    m_solveCaching = cache;
    if (!cache) m_solveCache.release();
  }
  /** \returns whether solves keep their forward substitution (setSolveCaching()). */
  bool solveCaching() const { return m_solveCaching; }
  /** \returns the columns of L that the last solve's forward substitution went through: n for a
    * full pass, fewer when it reused the previous solve's (setSolveCaching()). */
  Index lastSolveForwardColumns() const { return m_lastSolveForwardColumns.load(); }
  //@}

  /** \returns the bytes held by the factor (values and row indices), its copy of the matrix and
    * its workspace (including the scratch and spare buffers that insertDofs()/mergeDofs() keep
    * between calls, and the kept forward substitution of setSolveCaching()). */
  Index memoryBytes() const {
    Index b = m_numeric.workspaceBytes() + m_solveCache.bytes() + m_inputDiff.bytes() + m_store.bytes() + m_transposed.bytes() +
              m_insertChange.bytes() + m_mergeChange.bytes() + m_structureBackup.bytes();
    for (const auto& node : m_factor.nodes)
      b += Index(node.values.capacity() * sizeof(Scalar) + node.rows.capacity() * sizeof(StorageIndex) +
                 node.parentPosition.capacity() * sizeof(StorageIndex) +
                 (node.assemblySource.capacity() + node.assemblyTarget.capacity()) * sizeof(Index));
    return b;
  }

#ifndef EIGEN_PARSED_BY_DOXYGEN
  using Base::_solve_impl;
  /** \internal dense right-hand sides */
  template <typename Rhs, typename Dest>
  void _solve_impl(const MatrixBase<Rhs>& b, MatrixBase<Dest>& dest) const {
    eigen_assert(m_factorizationIsOk &&
                 "UpdatableSupernodalLLT::solve(): the factorization is missing or failed; check info().");
    eigen_assert(m_n == b.rows());
    Matrix<Scalar, Dynamic, Dynamic> x = permutedCopy(b);
    solveInPlacePermuted(x);
    unpermuteInto(x, dest);
  }
#endif

  /** \returns b in the permuted numbering, x(P(i), :) = b(i, :), written in order of x (a plain
    * gather: Eigen's permutation product costs several times more on large systems). */
  template <typename Rhs>
  Matrix<Scalar, Dynamic, Dynamic> permutedCopy(const MatrixBase<Rhs>& b) const {
    const Ref<const Matrix<Scalar, Dynamic, Dynamic> > from(b.derived());
    const Index positions = m_factor.n;  // (zeros at the free positions, which no row names)
    Matrix<Scalar, Dynamic, Dynamic> x(positions, from.cols());
    const StorageIndex* inverse = m_Pinv.data();
    const bool gaps = hasFreePositions();
    for (Index c = 0; c < from.cols(); ++c) {
      const Scalar* bc = from.col(c).data();
      Scalar* xc = x.col(c).data();
      if (!gaps)
        for (Index p = 0; p < positions; ++p) xc[p] = bc[inverse[p]];
      else
        for (Index p = 0; p < positions; ++p) xc[p] = inverse[p] >= 0 ? bc[inverse[p]] : Scalar(0);
    }
    return x;
  }

  /** Writes the permuted block \a x back in the original numbering: dest(i, :) = x(P(i), :). */
  template <typename Dest>
  void unpermuteInto(const Matrix<Scalar, Dynamic, Dynamic>& x, MatrixBase<Dest>& dest) const {
    dest.derived().resize(m_n, x.cols());
    const StorageIndex* perm = m_P.data();
    for (Index c = 0; c < x.cols(); ++c) {
      const Scalar* xc = x.col(c).data();
      for (Index i = 0; i < m_n; ++i) dest.coeffRef(i, c) = xc[perm[i]];
    }
  }

  /** Solves \f$ L L^* x = b \f$ in place for a block already in the permuted numbering. With
    * solve caching on and at most MaxCachedRightHandSides columns, the forward substitution
    * reuses the previous solve's where neither the factor nor the right-hand side changed
    * (internal::updatable_cholesky::ForwardSolveCache); a solve running concurrently with
    * another on the same object does a plain one. */
  void solveInPlacePermuted(Matrix<Scalar, Dynamic, Dynamic>& x) const {
    const Index k = x.cols();
    if (m_n == 0 || k == 0) return;
    const bool cached = m_solveCaching && k <= MaxCachedRightHandSides && !m_solveCacheBusy.exchange(true);
    std::vector<Scalar> work(m_maxRows * k * (cached ? 2 : 1) + 1);
    if (cached) {
      m_solveCache.forward(m_factor, x.data(), x.rows(), k, work.data());
      m_lastSolveForwardColumns.store(m_solveCache.substitutedColumns());
      m_solveCacheBusy.store(false);
    } else {
      internal::updatable_cholesky::forwardSolve(m_factor, x.data(), x.rows(), k, work.data());
      m_lastSolveForwardColumns.store(m_n);
    }
    internal::updatable_cholesky::backwardSolve(m_factor, x.data(), x.rows(), k, work.data());
  }

 protected:
  void init() {
    m_info = Success;
    m_analysisIsOk = false;
    m_factorizationIsOk = false;
    m_n = 0;
    m_maxRows = 0;
    m_shiftOffset = m_factoredOffset = 0;
    m_shiftScale = m_factoredScale = 1;
    m_threads = 0;
    m_failedColumn = -1;
    m_sparseLIsValid = false;
    m_publicPermutationIsValid = false;
  }

  template <typename F>
  void forEachDiagonal(F&& f) const {
    for (const auto& node : m_factor.nodes)
      for (Index c = 0; c < node.ncols; ++c) f(numext::real(node.values(c, c)));
  }

  void buildSparseL() const;
  /** True when the factor's numbering has free positions (after insertDofs() or mergeDofs()):
    * m_factor.n > m_n, and m_P is not a permutation of 0..n-1. */
  bool hasFreePositions() const { return m_analysisIsOk && m_factor.n != m_n; }
  /** Builds m_publicP, m_publicPinv and m_compressedIndex from m_P and m_Pinv (once per structure;
    * m_compressedIndex only with free positions). */
  void buildPublicPermutation() const;

  typedef internal::updatable_cholesky::SupernodalFactor<Scalar, StorageIndex> Factor;
  Factor m_factor;
  internal::updatable_cholesky::SupernodalNumeric<Scalar, StorageIndex> m_numeric;
  internal::updatable_cholesky::InputStore<Scalar, StorageIndex> m_store;  ///< kept triangle of the current matrix
  /** The factor's numbering: m_P maps dof i to its position m_P[i] (its row and column of the
    * factor), m_Pinv maps each of the m_factor.n positions to its dof, or -1 at a free position
    * (room kept after a supernode's columns for the copies of later insertions, paper §4.2).
    * Without free positions both are the permutation and its inverse. */
  std::vector<StorageIndex> m_P, m_Pinv;
  /** permutationP() and its inverse: m_P with the free positions squeezed out (built lazily), and
    * the map from position to that contiguous numbering. */
  mutable PermutationType m_publicP, m_publicPinv;
  mutable std::vector<StorageIndex> m_compressedIndex;
  mutable bool m_publicPermutationIsValid;
  OrderingType m_ordering;
  SupernodeRelaxation m_relaxation;
  ComputationInfo m_info;
  bool m_analysisIsOk, m_factorizationIsOk;
  Index m_n, m_failedColumn;
  Index m_maxRows;  ///< at least the rows of any supernode (the solve's workspace), kept by the updates
  RealScalar m_shiftOffset, m_shiftScale;
  /** the shift of the factor held: set by factorize(), kept by the updates (which change a factor
    * of offset + scale d on the diagonal, whatever setShift() said since) */
  RealScalar m_factoredOffset, m_factoredScale;
  int m_threads;
  mutable CholMatrixType m_sparseL;
  mutable bool m_sparseLIsValid;
  mutable internal::updatable_cholesky::ForwardSolveCache<Scalar, StorageIndex> m_solveCache;
  mutable std::atomic<bool> m_solveCacheBusy{false};  ///< a solve is using m_solveCache
  mutable std::atomic<Index> m_lastSolveForwardColumns{0};
  bool m_solveCaching = true;
  // state of in-place updates
  internal::updatable_cholesky::TransposedPattern<StorageIndex> m_transposed;  ///< the store's pattern, by inner index
  std::vector<char> m_removedPermuted, m_removedOriginal;       ///< removed flags, both numberings
  std::vector<StorageIndex> m_removedList;
  UpdateRoute m_route = UpdateRoute::Automatic;
  UpdateStatistics m_lastUpdate;
  std::chrono::steady_clock::time_point m_updateStart;  ///< when the current update call began (beginUpdate())
  /** Seconds from \a from to \a to (lastUpdate()'s times). */
  static double secondsBetween(std::chrono::steady_clock::time_point from,
                               std::chrono::steady_clock::time_point to = std::chrono::steady_clock::now()) {
    return std::chrono::duration<double>(to - from).count();
  }
  internal::updatable_cholesky::UpdateWorkspace<Scalar> m_workspace;
  internal::updatable_cholesky::InputDiff<Scalar, StorageIndex> m_inputDiff;  ///< scratch of insertDofs/mergeDofs
  double m_totalFlops = 0;

  internal::updatable_cholesky::NumericInput<Scalar> numericInput() const {
    internal::updatable_cholesky::NumericInput<Scalar> input;
    input.values = m_store.values.data();
    input.offset = m_factoredOffset;
    input.scale = m_factoredScale;
    input.removed = m_removedList.empty() ? nullptr : m_removedPermuted.data();
    return input;
  }
  /** The input itself when compressed, else a compressed copy of it in \a copy. */
  static const MatrixType* compressedInput(const MatrixType& a, MatrixType& copy) {
    if (a.isCompressed()) return &a;
    copy = a;
    copy.makeCompressed();
    return &copy;
  }
  bool beginUpdate();
  /** Checks dofs to remove (removed=false) or restore (removed=true); fills their A-numbered
    * and permuted lists, or sets InvalidInput. */
  template <typename Indices>
  bool checkDofs(const Indices& dofs, bool removed, std::vector<StorageIndex>& list,
                 std::vector<StorageIndex>& permuted);
  void setRemovedFlags(const std::vector<StorageIndex>& list, char flag);
  /** What insertDofs()/mergeDofs() hand to replaceDofs(), all in user numbering except where said. */
  struct DofChange {
    std::vector<StorageIndex> oldOfNew;   ///< new dof -> current dof, or -1 for a copy
    std::vector<StorageIndex> newOfOld;   ///< current dof -> new dof, or -1 when merged away
    std::vector<StorageIndex> preStart, preList;  ///< per new dof, the current dofs it stands for
    /** the four arrays above hold i at every i below this (an insertion rewrites only the rest) */
    Index identityLength = 0;
    std::vector<StorageIndex> newPerm;  ///< new dof -> new position (then the previous one); not for a local insertion
    std::vector<StorageIndex> newPinv;  ///< its inverse (then the previous one); not for a local insertion
    /** A local insertion (relabel.local): m_P and m_Pinv are changed in place. copyPositions holds
      * the new dofs' positions (the old dofs': relabel.newPosition of their current one, see
      * newPositionOf()); the previous values of what changes are kept for a revert. */
    std::vector<StorageIndex> copyPositions;
    std::vector<std::pair<StorageIndex, StorageIndex> > movedDofs;  ///< (dof, previous position)
    std::vector<StorageIndex> previousDofAt;  ///< m_Pinv over the windows, in their order
    /** m_P and m_Pinv are changed in place (a local insertion) rather than swapped with newPerm and newPinv. */
    bool inPlace() const { return !merging && relabel.local; }
    /** The new position of new dof \a x, before the new permutation is in place (\a perm: the current one). */
    StorageIndex newPositionOf(Index x, const StorageIndex* perm) const {
      const Index n = Index(newOfOld.size());
      if (!inPlace()) return newPerm[x];
      return x >= n ? copyPositions[x - n] : relabel.newPosition[perm[x]];
    }
    std::vector<StorageIndex> touched;    ///< current dofs dirty in any case (origins, merged)
    std::vector<StorageIndex> placed;     ///< insertion: copies placed per old permuted column, 0 between calls
    std::vector<StorageIndex> originsAt;  ///< insertion: the origins' old permuted columns, increasing, once each
    std::vector<StorageIndex> merged;        ///< merge: the merged dofs, increasing
    std::vector<StorageIndex> mergedTarget;  ///< merge: the new dof each of them merges into
    std::vector<StorageIndex> droppedAt;     ///< merge: the merged dofs' old permuted columns, increasing
    Index firstMerged = 0;  ///< merge: the first merged dof (n if none); newOfOld is the identity below it
    /** merge: the new dof that current dof \a i becomes or merges into */
    Index keptOf(Index i) const {
      if (newOfOld[i] >= 0) return newOfOld[i];
      const auto it = std::lower_bound(merged.begin(), merged.end(), StorageIndex(i));
      return mergedTarget[it - merged.begin()];
    }
    std::vector<StorageIndex> previousRemoved;  ///< the removed dofs before the call (for a revert)
    internal::updatable_cholesky::DofRelabeling<StorageIndex> relabel;
    bool merging = false;
    bool layoutReady = false;  ///< relabel and newPerm are built (buildInsertionLayout())
    double layoutSeconds = 0;  ///< the time spent building them before replaceDofs() (a structure phase)
    bool compareAll = true;    ///< false: the input diff reads only the outer vectors in compared
    std::vector<StorageIndex> compared;  ///< sorted, new numbering (a changed list was given)
    std::vector<char> listed;            ///< scratch by dof, zero between calls
    std::vector<StorageIndex> hint;      ///< the changed list given to insertDofs()/mergeDofs() (current numbering)
    /** Bytes held. */
    Index bytes() const {
      return Index((oldOfNew.capacity() + newOfOld.capacity() + preStart.capacity() + preList.capacity() +
                    touched.capacity() + placed.capacity() + originsAt.capacity() + previousRemoved.capacity() +
                    merged.capacity() + mergedTarget.capacity() + droppedAt.capacity() +
                    relabel.newPosition.capacity() +
                    relabel.copies.capacity() + relabel.oldPosition.capacity() + newPerm.capacity() + newPinv.capacity() +
                    copyPositions.capacity() + 2 * movedDofs.capacity() + previousDofAt.capacity()) *
                   sizeof(StorageIndex));
    }
  };
  /** Scratch of insertDofs() and of mergeDofs(), kept so that their arrays are reused: an
    * insertion's renumbering is the identity on the old dofs, which its arrays keep between calls. */
  DofChange m_insertChange, m_mergeChange;
  std::vector<char> m_restoredScratch;  ///< restoreByFolds(): flags by permuted column, zero between calls
  std::vector<std::pair<StorageIndex, StorageIndex> > m_mergeInto;  ///< mergeDofs() scratch
  internal::updatable_cholesky::FactorStructureBackup<Scalar, StorageIndex> m_structureBackup;  ///< their revert
  void replaceDofs(const MatrixType& matrix, DofChange& change);
  /** insertDofs() with the outer vectors to compare given by m_insertChange (compareAll, hint). */
  template <typename Indices>
  UpdatableSupernodalLLT& insertCopies(const MatrixType& matrix, const Indices& origin);
  /** insertCopies() once its input is checked: \a total dofs, dof i >= n a copy of originOf(i).
    * With total == n (no copies) it is updateColumns(): only values change. */
  template <typename OriginOf>
  void replaceWithCopies(const MatrixType& matrix, Index total, OriginOf&& originOf);
  /** mergeDofs() with the outer vectors to compare given by m_mergeChange (compareAll, hint). */
  template <typename Indices>
  UpdatableSupernodalLLT& mergeCopies(const MatrixType& matrix, const Indices& origin);
  /** Fills change.compared (the outer vectors the input diff reads) from change.hint, the
    * origins or merged dofs in change.touched and the new dofs up to \a total. */
  void collectCompared(DofChange& change, Index total);
  /** The relabeling of the permuted columns and the new permutation of an insertion (each copy
    * right after its origin), from the copies counted in \a change. */
  void buildInsertionLayout(DofChange& change);
  /** After the input diff of replaceDofs(): the dofs (new numbering) where the cut matrix, glued
    * back, differs from the uncut one (internal::updatable_cholesky::gluingMismatches()), both as
    * factored (setShift(): with an offset, every origin). */
  const std::vector<StorageIndex>& gluingMismatchesOf(const DofChange& change);
  /** After the input diff and the relabeling of an insertion or a merge: splits the input change
    * of each \a folded supernode's own columns (new minus previous matrix; a copy's previous
    * column, or a merged dof's new one, being a diagonal placeholder) into P P^H − N N^H, two
    * columns per changed column, into m_workspace.ownPositive/ownNegative, on the supernode's new
    * rows (insertion) or previous rows (merge); \a copyPivots gets each copy's placeholder
    * (permuted column, value; sorted; insertion only). */
  void splitOwnInputChanges(const DofChange& change, const std::vector<char>& folded,
                            std::vector<std::pair<StorageIndex, RealScalar> >& copyPivots);
  /** restoreDofs() by signed low-rank folds (route Mixed, LowRankTopUpdate.h): each restored
    * column and row goes from the identity's to the matrix's; each dirty supernode (\a dirty,
    * increasing) is refactored or folded, by the plan of foldPlan(). \returns false, having
    * changed nothing, when the plan saves too little against refactoring \a dirtyFlops (or a
    * refactorization's \a totalFlops); else the update is done, or failed and undone with
    * \a revert (info() says which). */
  template <typename Revert>
  bool restoreByFolds(const std::vector<StorageIndex>& permutedColumns, const std::vector<Index>& dirty,
                      double dirtyFlops, double totalFlops, Revert&& revert, std::chrono::steady_clock::time_point start);
  /** Fills lastUpdate() for an update that took \a route over the supernodes \a dirty and spent
    * \a flops (all of a refactorization's, reduced fronts counted on their kept rows), and tells
    * the kept forward substitution which blocks were rewritten: every update ends here. */
  void recordUpdate(UpdateRoute route, Index changedColumns, const std::vector<Index>& dirty, double flops,
                    std::chrono::steady_clock::time_point start) {
    UpdateStatistics& st = m_lastUpdate;
    const bool all = route == UpdateRoute::Refactorization;
    st.route = route;
    st.changedColumns = changedColumns;
    st.dirtySupernodes = all ? m_factor.count() : Index(dirty.size());
    st.dirtyColumns = all ? m_n : 0;
    if (!all)
      for (Index s : dirty) st.dirtyColumns += m_factor.nodes[s].ncols;
    st.flops = flops;
    st.flopFraction = m_totalFlops > 0 ? st.flops / m_totalFlops : 0;
    st.seconds = secondsBetween(start);
    if (all)
      m_solveCache.invalidate();
    else
      m_solveCache.markChanged(dirty);
  }
  /** For removeDofs(), before a partial or mixed refactorization (which reads the clean
    * supernodes' cached update matrices) or after the low-rank folds: the dirty supernodes are
    * those of the removed columns' row subtrees in
    * the matrix's pattern and their ancestors, but a supernode outside them may still hold a
    * removed row in its structure (amalgamation, or a cut's duplicated pattern) whose values are
    * zero only up to rounding (left by earlier folds). Those rows are zeroed too, and the
    * supernodes whose blocks changed join \a dirty (increasing) with their ancestors up to the
    * dirty path they hang from (the removed row's supernode), so that a Dirichlet solve returns
    * the known values exactly and \a dirty stays closed under parents: the kept forward
    * substitution passes a changed update vector up through those ancestors, and lastUpdate()
    * counts what it substitutes again. Only reads the structure unless such a value is found:
    * the row subtree of each removed dof, or, with more removed dofs than supernodes, the rows of
    * every clean supernode once. */
  void clearRemovedRowsOutside(const std::vector<StorageIndex>& removedNow, std::vector<Index>& dirty) {
    std::vector<char>& mark = m_workspace.mark;  // 1: dirty, 2: searched here (all 0 between calls)
    for (Index s : dirty) mark[s] = 1;
    std::vector<Index> holding, stack, cleared;
    const Index count = m_factor.count();
    if (Index(removedNow.size()) > count) {
      // more removed dofs than supernodes (a region constrained, as in ARAP): their row-subtree
      // searches would walk most of the tree again and again, so the clean supernodes' rows are
      // read once instead (a removed row there, of this call or an earlier one, is one to clear)
      const char* removed = m_removedPermuted.data();
      for (Index s = 0; s < count; ++s) {
        if (mark[s]) continue;
        const auto& node = m_factor.nodes[s];
        Index held = 0;  // (counted without an early exit: it vectorizes)
        for (Index k = node.ncols; k < node.nrows(); ++k) held += removed[node.rows[k]] != 0;
        if (held > 0) holding.push_back(s);
      }
    } else {
      for (StorageIndex b : removedNow) internal::updatable_cholesky::supernodesHoldingRow(m_factor, b, holding, stack);
    }
    const std::size_t before = dirty.size();
    for (Index s : holding)
      if (!mark[s]) {
        mark[s] = 2;
        if (m_numeric.clearRemoved(m_factor, s, m_removedPermuted.data())) cleared.push_back(s);
      }
    for (Index s : holding)
      if (mark[s] == 2) mark[s] = 0;
    for (Index s : cleared)  // (the walk ends at the removed row's supernode, dirty, at the latest)
      internal::updatable_cholesky::markPathToRoot(m_factor, s, mark, dirty);
    for (Index s : dirty) mark[s] = 0;
    if (dirty.size() != before) std::sort(dirty.begin(), dirty.end());
  }
  template <typename Revert>
  void applyUpdate(const std::vector<StorageIndex>& permutedColumns, bool isRemoval, Revert&& revert);
};

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::analyzePattern(const MatrixType& a) {
  using namespace internal::updatable_cholesky;
  eigen_assert(a.rows() == a.cols() && "UpdatableSupernodalLLT: the matrix must be square.");
  m_isInitialized = true;
  m_analysisIsOk = false;
  m_factorizationIsOk = false;
  m_sparseLIsValid = false;
  m_publicPermutationIsValid = false;
  m_solveCache.release();
  m_failedColumn = -1;
  if (a.rows() != a.cols()) {
    m_info = InvalidInput;
    return;
  }
  const Index n = a.rows();
  m_n = n;
  // A compressed view of the input (copied only when the user's matrix is not compressed).
  MatrixType copy;
  const MatrixType* pa = compressedInput(a, copy);
  constexpr bool rowMajor = bool(MatrixType::IsRowMajor);
  m_store.template assign<UpLo_>(*pa);
  m_inputDiff.posMapIsIdentity = false;

  // 1. fill-reducing ordering on the full symmetric pattern, as Eigen's solvers do
  PermutationType orderingPinv;
  if (n > 1) {  // (METIS divides by zero on an empty graph; nothing to order anyway)
    CholMatrixType full;
    full = pa->template selfadjointView<UpLo_>();
    m_ordering(full, orderingPinv);
  }
  std::vector<StorageIndex> perm(n, StorageIndex(-1));
  if (orderingPinv.size() == n) {
    for (Index k = 0; k < n; ++k) {
      const Index old = orderingPinv.indices()[k];
      if (old < 0 || old >= n || perm[old] != -1) {  // the ordering functor returned no permutation
        m_info = InvalidInput;
        return;
      }
      perm[old] = StorageIndex(k);
    }
  } else if (orderingPinv.size() == 0) {  // as in Eigen: an empty permutation means "natural order"
    for (Index k = 0; k < n; ++k) perm[k] = StorageIndex(k);
  } else {
    m_info = InvalidInput;
    return;
  }
  // 2. elimination tree of the ordered matrix, composed with its postorder
  PermutedLowerEntries<StorageIndex> lower;
  CompressedPattern<StorageIndex> upper;
  std::vector<StorageIndex> parent, post;
  permuteTriangle<rowMajor>(m_store, perm, lower, &upper);
  eliminationTree(upper, parent);
  postorder(parent, post);
  std::vector<StorageIndex> postInverse(n);
  for (Index k = 0; k < n; ++k) postInverse[post[k]] = StorageIndex(k);
  for (Index i = 0; i < n; ++i) perm[i] = postInverse[perm[i]];
  std::vector<StorageIndex> postParent(n);
  for (Index k = 0; k < n; ++k) postParent[k] = parent[post[k]] == -1 ? StorageIndex(-1) : postInverse[parent[post[k]]];
  permuteTriangle<rowMajor>(m_store, perm, lower, static_cast<CompressedPattern<StorageIndex>*>(nullptr));
  m_transposed.assign(m_store);
  // 3. column counts, relaxed supernodes, row structures, factor storage and assembly maps
  std::vector<StorageIndex> colCount;
  columnCounts(lower.pattern, postParent, colCount);
  SupernodalPartition<StorageIndex> partition;
  relaxedSupernodes(postParent, colCount, m_relaxation, partition.start);
  supernodeRowStructure(lower.pattern, postParent, partition);
  m_factor = Factor();
  m_factor.build(partition);
  buildAssemblyMaps(lower, m_factor);
  m_numeric.reset();
  // (contiguous positions: the first cut lays them out anew with room for copies, see
  // buildInsertionLayout(); room from here on would cost every solve the wider vectors)
  m_P.assign(perm.begin(), perm.end());
  m_Pinv.resize(n);
  for (Index i = 0; i < n; ++i) m_Pinv[m_P[i]] = StorageIndex(i);
  m_removedPermuted.assign(n, 0);
  m_removedOriginal.assign(n, 0);
  m_workspace.resize(m_factor.count());
  m_totalFlops = m_factor.flops();
  m_maxRows = m_factor.maxRows();
  m_removedList.clear();
  m_info = Success;
  m_analysisIsOk = true;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::factorize(const MatrixType& a) {
  eigen_assert(m_analysisIsOk && "UpdatableSupernodalLLT::factorize(): call analyzePattern() first.");
  m_isInitialized = true;
  m_factorizationIsOk = false;
  m_sparseLIsValid = false;
  m_solveCache.invalidate();
  m_failedColumn = -1;
  if (!m_analysisIsOk) {
    m_info = InvalidInput;
    return;
  }
  MatrixType copy;
  const MatrixType* pa = compressedInput(a, copy);
  if (!m_store.template matchesPattern<UpLo_>(*pa)) {
    m_info = InvalidInput;
    return;
  }
  m_store.template copyValues<UpLo_>(*pa);
  m_factoredOffset = m_shiftOffset;  // (the updates of this factor keep its shift)
  m_factoredScale = m_shiftScale;
  const Index bad = m_numeric.factorize(m_factor, numericInput(), threadCount());
  if (bad >= 0) {
    m_info = NumericalIssue;
    m_failedColumn = m_Pinv[bad];
    return;
  }
  m_info = Success;
  m_factorizationIsOk = true;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::buildSparseL() const {
  if (m_sparseLIsValid) return;
  // (with free positions, every position is written in the contiguous numbering of permutationP())
  const bool gaps = hasFreePositions();
  if (gaps) buildPublicPermutation();
  auto index = [&](Index position) { return gaps ? m_compressedIndex[position] : StorageIndex(position); };
  m_sparseL.resize(m_n, m_n);
  m_sparseL.resizeNonZeros(0);
  m_sparseL.reserve(m_factor.nonZeros());
  Index nnz = 0;
  StorageIndex* outer = m_sparseL.outerIndexPtr();
  m_sparseL.resizeNonZeros(m_factor.nonZeros());
  for (const auto& node : m_factor.nodes) {
    const Index nr = node.nrows();
    for (Index c = 0; c < node.ncols; ++c) {
      outer[index(node.firstCol + c)] = StorageIndex(nnz);
      for (Index r = c; r < nr; ++r) {
        m_sparseL.innerIndexPtr()[nnz] = index(node.rows[r]);
        m_sparseL.valuePtr()[nnz] = node.values(r, c);
        ++nnz;
      }
    }
  }
  outer[m_n] = StorageIndex(nnz);
  m_sparseLIsValid = true;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::buildPublicPermutation() const {
  if (m_publicPermutationIsValid) return;
  const Index positions = Index(m_Pinv.size());
  const StorageIndex* dofAt = m_Pinv.data();
  if (!hasFreePositions()) {  // (m_P is the permutation; after a failed analysis, the previous one)
    m_publicP.resize(Index(m_P.size()));
    m_publicPinv.resize(Index(m_Pinv.size()));
    std::copy(m_P.begin(), m_P.end(), m_publicP.indices().data());
    std::copy(m_Pinv.begin(), m_Pinv.end(), m_publicPinv.indices().data());
    m_publicPermutationIsValid = true;
    return;
  }
  m_publicP.resize(m_n);
  m_publicPinv.resize(m_n);
  m_compressedIndex.assign(positions, StorageIndex(-1));
  for (Index p = 0, k = 0; p < positions; ++p) {  // (the positions' order is the elimination order)
    if (dofAt[p] < 0) continue;
    m_compressedIndex[p] = StorageIndex(k);
    m_publicP.indices()[dofAt[p]] = StorageIndex(k);
    m_publicPinv.indices()[k++] = dofAt[p];
  }
  m_publicPermutationIsValid = true;
}


template <typename MatrixType_, int UpLo_, typename Ordering_>
bool UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::beginUpdate() {
  eigen_assert(m_factorizationIsOk && "UpdatableSupernodalLLT: updates need a successful factorization first.");
  m_lastUpdate = UpdateStatistics();
  m_updateStart = std::chrono::steady_clock::now();  // (lastUpdate().seconds: the whole call, its checks included)
  m_failedColumn = -1;
  if (!m_factorizationIsOk) {
    m_info = InvalidInput;
    return false;
  }
  return true;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Revert>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::applyUpdate(
    const std::vector<StorageIndex>& permutedColumns, bool isRemoval, Revert&& revert) {
  using namespace internal::updatable_cholesky;
  const auto start = m_updateStart;
  m_sparseLIsValid = false;
  std::vector<Index> dirty = dirtySupernodes(m_factor, m_store, m_transposed, m_P.data(),
                                             m_Pinv.data(), permutedColumns, m_workspace);
  const char* removedFlags = m_removedList.empty() ? nullptr : m_removedPermuted.data();
  const double totalFlops = refactorizationFlops(m_factor, m_totalFlops, removedFlags, Index(m_removedList.size()));
  const double dirtyFlops = supernodeFlops(m_factor, dirty, removedFlags);
  UpdateRoute route = m_route;
  if (!isRemoval && route != UpdateRoute::PartialRefactorization && route != UpdateRoute::Refactorization &&
      m_numeric.hasCachedUpdates() && !dirty.empty() &&
      restoreByFolds(permutedColumns, dirty, dirtyFlops, totalFlops, revert, start))
    return;
  if ((route == UpdateRoute::LowRank || route == UpdateRoute::Mixed) && !isRemoval) route = UpdateRoute::Automatic;
  if (!m_numeric.hasCachedUpdates()) route = UpdateRoute::Refactorization;
  double mixedFlops = 0;  // the best plan of low-rank folds below and refactorization on top
  std::vector<Index> lowPart, topPart;
  if (isRemoval && (route == UpdateRoute::Automatic || route == UpdateRoute::Mixed)) {
    lowRankRemovalFlops(m_factor, dirty, permutedColumns, m_workspace);  // per-supernode costs
    mixedFlops = mixedRemovalPlan(m_factor, dirty, m_workspace, lowPart, topPart, removedFlags);
  }
  if (route == UpdateRoute::Automatic) {  // (both refactorizations run on all threads: compared by flops)
    route = dirtyFlops > 0.9 * totalFlops ? UpdateRoute::Refactorization : UpdateRoute::PartialRefactorization;
    if (isRemoval && mixedFlops < (std::min)(dirtyFlops, totalFlops))
      route = topPart.empty() ? UpdateRoute::LowRank : lowPart.empty() ? UpdateRoute::PartialRefactorization
                                                                         : UpdateRoute::Mixed;
  }
  if (route == UpdateRoute::LowRank) {  // cannot fail: removal keeps A positive definite
    const double flops = lowRankRemoval(m_factor, m_numeric, dirty, m_removedPermuted.data(), m_workspace);
    m_info = Success;
    clearRemovedRowsOutside(permutedColumns, dirty);
    recordUpdate(route, Index(permutedColumns.size()), dirty, flops, start);
    return;
  }
  if (route == UpdateRoute::Mixed) {  // folds below, then the top refactored from the caches they keep valid
    // the removed rows that earlier folds left at rounding level in clean supernodes are cleared
    // first: the top's refactorization reads those supernodes' cached update matrices
    std::vector<Index> changed = dirty;  // and the supernodes whose blocks the clearing changed
    clearRemovedRowsOutside(permutedColumns, changed);
    double flops = lowRankRemoval(m_factor, m_numeric, lowPart, m_removedPermuted.data(), m_workspace);
    for (Index s : lowPart) m_workspace.carried[s] = typename UpdateWorkspace<Scalar>::Dense();
    flops += supernodeFlops(m_factor, topPart, removedFlags);
    const Index bad = m_numeric.refactorize(m_factor, numericInput(), topPart, threadCount());
    m_info = Success;
    if (bad >= 0) {  // (not expected for a removal, e.g. NaN) the previous matrix and a full factorization
      m_failedColumn = m_Pinv[bad];
      revert();
      m_factorizationIsOk = m_numeric.factorize(m_factor, numericInput(), threadCount()) < 0;
      m_solveCache.invalidate();
      m_info = NumericalIssue;
    }
    recordUpdate(route, Index(permutedColumns.size()), changed, flops, start);
    return;
  }
  // a partial refactorization of a removal reads the clean supernodes' cached update matrices:
  // their removed rows are cleared first (as above)
  std::vector<Index> changed = dirty;
  if (isRemoval && route != UpdateRoute::Refactorization) clearRemovedRowsOutside(permutedColumns, changed);
  auto run = [&]() {
    m_numeric.setCacheUpdates(true);
    return route == UpdateRoute::Refactorization ? m_numeric.factorize(m_factor, numericInput(), threadCount())
                                                 : m_numeric.refactorize(m_factor, numericInput(), dirty, threadCount());
  };
  const Index bad = run();
  if (bad >= 0) {  // not positive definite: put the previous matrix back and its factor with it
    m_failedColumn = m_Pinv[bad];
    revert();
    const Index again = run();
    eigen_assert(again < 0 && "UpdatableSupernodalLLT: the previous factor could not be restored");
    m_factorizationIsOk = again < 0;
    m_info = NumericalIssue;
  } else {
    m_info = Success;
  }
  recordUpdate(route, Index(permutedColumns.size()), changed,
               route == UpdateRoute::Refactorization ? totalFlops : dirtyFlops, start);
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Revert>
bool UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::restoreByFolds(
    const std::vector<StorageIndex>& permutedColumns, const std::vector<Index>& dirty, double dirtyFlops,
    double totalFlops, Revert&& revert, std::chrono::steady_clock::time_point start) {
  using namespace internal::updatable_cholesky;
  typedef InputChangeEntry<Scalar, StorageIndex> Entry;
  UpdateWorkspace<Scalar>& ws = m_workspace;
  const Index ns = m_factor.count();
  const StorageIndex* perm = m_P.data();
  const StorageIndex* pinv = m_Pinv.data();
  const char* removed = m_removedList.empty() ? nullptr : m_removedPermuted.data();  // (without the restored dofs)
  const bool force = m_route == UpdateRoute::Mixed || m_route == UpdateRoute::LowRank;
  constexpr bool rowMajor = bool(MatrixType::IsRowMajor);
  std::vector<char>& restoredFlag = m_restoredScratch;  // by permuted column (zero between calls)
  restoredFlag.resize(m_factor.n, 0);
  for (StorageIndex b : permutedColumns) restoredFlag[b] = 1;
  auto isRestored = [&restoredFlag](Index column) { return (restoredFlag[column] & 1) != 0; };
  struct ClearFlags {  // (on every way out)
    std::vector<char>& flag;
    const std::vector<StorageIndex>& columns;
    ~ClearFlags() {
      for (StorageIndex b : columns) flag[b] = 0;
    }
  } clearFlags{restoredFlag, permutedColumns};
  // 1. The plan (foldPlan()), made before the change is read: when it saves too little, the
  //    caller refactors (partly or fully). Every dirty supernode keeps its structure and may be
  //    folded. Rank bounds of the change of an update matrix U' − U above a subtree: restoring
  //    the set R, U' = U + S_XR S_RR^-1 S_RX with S_XR = A_XR − A_XK K^-1 A_KR (K the kept dofs
  //    of the subtree), whose column r vanishes on the kept rows X unless r has a kept neighbour
  //    (one neither removed nor restored): one per such restored column below, and two per
  //    restored row among its rows below (that row and column of U appear). Each changed column
  //    (a restored one, or a kept one before a restored row) brings two of its own: counted once
  //    each, flagged by bit 2 meanwhile.
  std::vector<Index>&rankColumns = ws.rankColumns, &likelyRankColumns = ws.likelyRankColumns, &rowRank = ws.rowRank;
  std::vector<Index>&ownRank = ws.ownRank, &ownStart = ws.ownStart;
  std::vector<char>& eligible = ws.eligible;
  auto countOwn = [&](Index column) {  // (two per changed column)
    const Index t = m_factor.colToSuper[column], local = column - m_factor.nodes[t].firstCol;
    ownStart[t] = ownRank[t] == 0 ? local : (std::min)(ownStart[t], local);
    ownRank[t] += 2;
  };
  auto own = [&](Index column) {  // (once each)
    if (restoredFlag[column] & 2) return;
    restoredFlag[column] |= 2;
    countOwn(column);
  };
  std::vector<Index> bottom, top;
  std::vector<FoldBoundary> boundary;
  std::vector<char> folded(ns, 0);
  const double limit = MixedRouteShare * (std::min)(dirtyFlops, totalFlops);
  auto reset = [&]() {
    for (Index s : dirty) eligible[s] = rankColumns[s] = likelyRankColumns[s] = rowRank[s] = ownRank[s] = ownStart[s] = 0;
  };
  // first on lower bounds read off the restored columns alone (their own changes): every cost of
  // a plan grows with the ranks, so when this one saves too little, so does the whole one (a
  // restore of regions, whose own changes cover whole supernodes, ends here at O(restored) cost)
  for (Index s : dirty) eligible[s] = 1;
  for (StorageIndex b : permutedColumns) countOwn(b);
  double planned = foldPlan(m_factor, dirty, eligible, rankColumns, likelyRankColumns, rowRank, removed, force, folded,
                            bottom, top, boundary, ws, RemovalFoldOverheadFlops);
  if (top.empty() || (!force && planned >= limit)) {
    reset();
    return false;
  }
  for (Index s : dirty) folded[s] = ownRank[s] = ownStart[s] = 0;
  std::vector<StorageIndex> ownColumns;  // (to clear their bit 2)
  for (StorageIndex b : permutedColumns) {
    const Index d = pinv[b];
    bool coupled = false;  // (to a kept dof)
    auto neighbour = [&](Index y) {  // (user numbering)
      const Index py = perm[y];
      if (isRestored(py) || (removed && removed[py])) return;
      coupled = true;
      if (py < b && !(restoredFlag[py] & 2)) {
        own(py);
        ownColumns.push_back(StorageIndex(py));
      }
    };
    for (Index p = m_store.begin[d]; p < m_store.end[d]; ++p)
      if (Index(m_store.inner[p]) != d) neighbour(m_store.inner[p]);
    for (Index q = m_transposed.begin[d]; q < m_transposed.end[d]; ++q) neighbour(m_transposed.pool[q]);
    rankColumns[m_factor.colToSuper[b]] += coupled;
    own(b);
  }
  for (StorageIndex c : ownColumns) restoredFlag[c] &= 1;
  for (StorageIndex b : permutedColumns) restoredFlag[b] &= 1;
  for (Index s : dirty) {
    const auto& node = m_factor.nodes[s];
    likelyRankColumns[s] = rankColumns[s];
    for (Index k = node.ncols; k < node.nrows(); ++k) rowRank[s] += 2 * isRestored(node.rows[k]);
  }
  planned = foldPlan(m_factor, dirty, eligible, rankColumns, likelyRankColumns, rowRank, removed, force, folded, bottom,
                     top, boundary, ws, RemovalFoldOverheadFlops);
  reset();
  if (top.empty() || (!force && planned >= limit)) return false;

  // 2. The change in the folded supernodes, as factored: each restored column and row goes from
  //    the identity's to the matrix's (the still removed dofs' entries left out), in the lower
  //    triangle of the permuted matrix. Each entry is read once: a restored dof's outer vector,
  //    and the entries at it in the outer vectors of its neighbours that are not restored.
  std::vector<Entry> entries;
  auto add = [&](Index row, Index col, Scalar value) {  // (user numbering)
    appendInputChange(entries, perm, m_factor.colToSuper, folded, removed, row, col, value);
  };
  auto addEntry = [&](Index outer, Index p) {
    const Index inner = m_store.inner[p];
    if (rowMajor)
      add(outer, inner, m_store.values[p]);
    else
      add(inner, outer, m_store.values[p]);
  };
  for (StorageIndex b : permutedColumns) {
    const Index d = pinv[b];
    Scalar diagonal(m_factoredOffset);  // (offset + scale a_dd, the offset alone when A lacks it)
    for (Index p = m_store.begin[d]; p < m_store.end[d]; ++p) {
      if (Index(m_store.inner[p]) == d)
        diagonal += m_factoredScale * m_store.values[p];
      else
        addEntry(d, p);
    }
    add(d, d, diagonal - Scalar(1));  // (the identity's diagonal)
    for (Index q = m_transposed.begin[d]; q < m_transposed.end[d]; ++q) {
      const Index x = m_transposed.pool[q];
      if (isRestored(perm[x])) continue;  // (read with x's own outer vector)
      for (Index p = m_store.begin[x]; p < m_store.end[x]; ++p)
        if (Index(m_store.inner[p]) == d) addEntry(x, p);
    }
  }

  // 3. The dirty supernodes' blocks and update matrices set aside (the folded ones take theirs
  //    back; the refactored children of folded ones are compared with theirs), the own changes
  //    split, then the refactorizations and folds children first (refactorAndFold()).
  FactorStructureBackup<Scalar, StorageIndex>& backup = m_structureBackup;
  backup.rows.resize(ns);
  backup.values.resize(ns);
  backup.cache.resize(ns);
  backup.parentPosition.resize(ns);
  backup.firstCol.resize(ns);
  backup.ncols.resize(ns);
  backup.takePending(m_numeric, ns, dirty);  // (with the update matrices, unapplied)
  for (Index s : dirty) {
    auto& node = m_factor.nodes[s];
    backup.firstCol[s] = node.firstCol;
    backup.ncols[s] = node.ncols;
    backup.rows[s].assign(node.rows.begin(), node.rows.end());
    backup.values[s].swap(node.values);
    backup.cache[s].swap(m_numeric.cache()[s]);
    backup.takeSpare(node.nrows(), node.ncols, node.values);
    backup.takeSpare(node.below() * node.below(), m_numeric.cache()[s]);
  }
  {
    std::vector<StorageIndex>& position = m_inputDiff.position;  // (by permuted row, all -1 between uses)
    if (Index(position.size()) < m_factor.n) position.resize(m_factor.n, StorageIndex(-1));
    splitInputChanges(entries, [&](Index t) -> const std::vector<StorageIndex>& { return m_factor.nodes[t].rows; },
                      position, ws);
  }
  std::vector<Index> taken;
  double flops = 0;
  UpdateRoute route = UpdateRoute::Mixed;
  m_numeric.setCacheUpdates(true);
  const std::vector<StorageIndex> unmoved;  // (no row moves: every block is taken back as it is)
  Index bad = refactorAndFold(
      m_factor, m_numeric, dirty, folded, boundary, backup, taken, unmoved, removed, ws,
      [&](const std::vector<Index>& list) { return m_numeric.refactorize(m_factor, numericInput(), list, threadCount()); },
      [](Index) -> RealScalar {
        eigen_assert(false && "a restore has no placeholder columns");
        return RealScalar(1);
      },
      flops);
  if (bad == -2) {  // a change not captured by its bound, or a downdate lost a pivot: refactor instead
    for (Index s : dirty) m_numeric.discardCorrections(s);
    route = UpdateRoute::PartialRefactorization;
    flops = dirtyFlops;
    bad = m_numeric.refactorize(m_factor, numericInput(), dirty, threadCount());
  }
  if (bad >= 0) {  // not positive definite: the dofs removed again and their supernodes recomputed
    m_failedColumn = m_Pinv[bad];
    revert();
    for (Index s : dirty) m_numeric.discardCorrections(s);
    const Index again = m_numeric.refactorize(m_factor, numericInput(), dirty, threadCount());
    eigen_assert(again < 0 && "UpdatableSupernodalLLT: the previous factor could not be restored");
    m_factorizationIsOk = again < 0;
    m_info = NumericalIssue;
  } else {
    m_info = Success;
    if (route == UpdateRoute::Mixed && removed)  // (rounding the folds leave in removed rows)
      for (Index s : dirty) m_numeric.clearRemoved(m_factor, s, removed);
  }
  backup.release(m_factor, dirty);
  recordUpdate(route, Index(permutedColumns.size()), dirty, flops, start);
  return true;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::updateColumns(
    const MatrixType& a, const Indices& columns) {
  if (!beginUpdate()) return *this;
  MatrixType copy;
  const MatrixType* pa = compressedInput(a, copy);
  const char* why = nullptr;
  if (!m_store.template matchesPattern<UpLo_>(*pa) ||
      !internal::updatable_cholesky::checkIndices(columns, m_n, m_insertChange.hint, why)) {
    m_info = InvalidInput;
    return *this;
  }
  // an insertion of no copies told the changed dofs: only their columns (and those holding their
  // rows) are read, and the dirty supernodes are refactored or, where cheaper, updated by
  // low-rank folds of the change (route Mixed), as for a cut
  m_insertChange.compareAll = false;
  replaceWithCopies(*pa, m_n, [](Index) { return StorageIndex(-1); });
  return *this;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
bool UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::checkDofs(const Indices& dofs, bool removed,
                                                                      std::vector<StorageIndex>& list,
                                                                      std::vector<StorageIndex>& permuted) {
  const char* why = nullptr;
  bool ok = internal::updatable_cholesky::checkIndices(dofs, m_n, list, why);
  for (Index k = 0; ok && k < Index(list.size()); ++k) ok = (m_removedOriginal[list[k]] != 0) == removed;
  if (!ok) {
    m_info = InvalidInput;
    return false;
  }
  permuted.resize(list.size());
  for (Index k = 0; k < Index(list.size()); ++k) permuted[k] = m_P[list[k]];
  return true;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::setRemovedFlags(const std::vector<StorageIndex>& list,
                                                                            char flag) {
  for (StorageIndex i : list) {
    m_removedOriginal[i] = flag;
    m_removedPermuted[m_P[i]] = flag;
  }
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::removeDofs(
    const Indices& dofs) {
  std::vector<StorageIndex> list, cols;
  if (!beginUpdate() || !checkDofs(dofs, false, list, cols)) return *this;
  const Index previousCount = Index(m_removedList.size());
  setRemovedFlags(list, 1);
  m_removedList.insert(m_removedList.end(), list.begin(), list.end());
  applyUpdate(cols, true, [&]() {
    setRemovedFlags(list, 0);
    m_removedList.resize(previousCount);
  });
  return *this;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::restoreDofs(
    const Indices& dofs) {
  std::vector<StorageIndex> list, cols;
  if (!beginUpdate() || !checkDofs(dofs, true, list, cols)) return *this;
  const std::vector<StorageIndex> previousList = m_removedList;
  setRemovedFlags(list, 0);
  m_removedList.erase(std::remove_if(m_removedList.begin(), m_removedList.end(),
                                     [&](StorageIndex i) { return !m_removedOriginal[i]; }),
                      m_removedList.end());
  applyUpdate(cols, false, [&]() {
    setRemovedFlags(list, 1);
    m_removedList = previousList;
  });
  return *this;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::insertDofs(
    const MatrixType& a, const Indices& origin) {
  m_insertChange.compareAll = true;
  return insertCopies(a, origin);
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::insertCopies(
    const MatrixType& a, const Indices& origin) {
  if (!beginUpdate()) return *this;
  const Index n = m_n, total = Index(origin.size());
  bool ok = a.rows() == a.cols() && a.rows() == total && total >= n;
  if (ok) {  // (counted without an early exit, so that the pass over the old dofs vectorizes)
    Index moved = 0;
    for (Index i = 0; i < n; ++i) moved += Index(origin[i]) != i;
    ok = moved == 0;
  }
  for (Index i = n; ok && i < total; ++i) ok = Index(origin[i]) >= 0 && Index(origin[i]) < n;
  if (!ok) {
    m_info = InvalidInput;
    return *this;
  }
  replaceWithCopies(a, total, [&origin](Index i) { return StorageIndex(origin[i]); });
  return *this;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename OriginOf>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::replaceWithCopies(const MatrixType& a, Index total,
                                                                              OriginOf&& originOf) {
  const Index n = m_n;
  DofChange& change = m_insertChange;
  change.merging = false;
  change.touched.clear();
  // the old dofs keep their numbers: the arrays are the identity below n, which they keep
  // between insertions, so only the copies' entries (and those of the previous call's) are written
  change.oldOfNew.resize(total);
  change.newOfOld.resize(n);
  change.preStart.resize(total + 1);
  change.preList.resize(total);
  for (Index i = (std::min)(change.identityLength, n); i < n; ++i)
    change.oldOfNew[i] = change.newOfOld[i] = change.preStart[i] = change.preList[i] = StorageIndex(i);
  change.identityLength = n;
  const StorageIndex* perm = m_P.data();
  auto& relabel = change.relabel;
  relabel.copies.resize(m_factor.n, 0);  // (by position; zero between calls)
  for (Index i = n; i < total; ++i) {
    const StorageIndex o = originOf(i);
    change.oldOfNew[i] = StorageIndex(-1);
    change.preStart[i] = StorageIndex(i);
    change.preList[i] = o;  // a copy stands for its origin
    ++relabel.copies[perm[o]];
    change.touched.push_back(o);
  }
  change.preStart[total] = StorageIndex(total);
  if (!change.compareAll) collectCompared(change, total);
  change.layoutReady = false;
  change.layoutSeconds = 0;
  if (total > n) {  // (without copies, only once the matrix is known to differ)
    const auto layoutStart = std::chrono::steady_clock::now();
    buildInsertionLayout(change);
    change.layoutSeconds = secondsBetween(layoutStart);
  }
  std::vector<StorageIndex> originPositions(change.touched.size());
  for (std::size_t k = 0; k < originPositions.size(); ++k) originPositions[k] = perm[change.touched[k]];
  replaceDofs(a, change);
  for (StorageIndex po : originPositions) relabel.copies[po] = change.placed[po] = 0;  // zero again
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices, typename ChangedIndices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::insertDofs(
    const MatrixType& a, const Indices& origin, const ChangedIndices& changed) {
  const char* why = nullptr;
  if (!internal::updatable_cholesky::checkIndices(changed, m_n, m_insertChange.hint, why)) {
    if (beginUpdate()) m_info = InvalidInput;
    return *this;
  }
  m_insertChange.compareAll = false;
  return insertCopies(a, origin);
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::collectCompared(DofChange& change, Index total) {
  // the outer vectors (new numbering) that may hold a changed entry. An entry lives in one outer
  // vector; when a listed dof is its other index (its inner one), that outer vector is among
  // the listed dof's transposed neighbours, as the entry was in the current pattern at the same
  // place (both its dofs are old and keep their order). So: the listed dofs and their
  // transposed neighbours; the origins or merged dofs and the dofs they merge into with all
  // their neighbours (an entry at a copy or a merged dof replaces one at its origin, which the
  // current pattern holds in either triangle); and the new dofs
  std::vector<StorageIndex>& compared = change.compared;
  std::vector<char>& listed = change.listed;
  compared.clear();
  listed.resize((std::max)(Index(listed.size()), total), 0);
  auto add = [&](Index x) {  // (x: new numbering, -1 for a dof that goes)
    if (x < 0 || listed[x]) return;
    listed[x] = 1;
    compared.push_back(StorageIndex(x));
  };
  auto addWithTransposed = [&](Index i) {  // (i: a current dof)
    add(change.newOfOld[i]);
    for (Index q = m_transposed.begin[i]; q < m_transposed.end[i]; ++q) add(change.newOfOld[m_transposed.pool[q]]);
  };
  for (std::size_t k = 0; k < change.hint.size(); ++k) {
    if (k + internal::updatable_cholesky::AssemblyPrefetchDistance < change.hint.size())  // (scattered lists: loads miss the cache)
      internal::prefetch(m_transposed.pool.data() +
                         m_transposed.begin[change.hint[k + internal::updatable_cholesky::AssemblyPrefetchDistance]]);
    addWithTransposed(change.hint[k]);
  }
  for (StorageIndex i : change.touched) {
    addWithTransposed(i);
    for (Index p = m_store.begin[i]; p < m_store.end[i]; ++p) add(change.newOfOld[m_store.inner[p]]);
  }
  for (Index x = m_n; x < total; ++x) add(x);  // the copies of an insertion
  if (Index(compared.size()) * 16 < total) {  // few: sorted
    for (StorageIndex x : compared) listed[x] = 0;
    std::sort(compared.begin(), compared.end());
    return;
  }
  compared.clear();  // many (a long seam): read off the flags in order, cheaper than a sort
  for (Index x = 0; x < total; ++x)
    if (listed[x]) {
      listed[x] = 0;
      compared.push_back(StorageIndex(x));
    }
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::buildInsertionLayout(DofChange& change) {
  const Index n = m_n, total = Index(change.oldOfNew.size());
  const StorageIndex* perm = m_P.data();
  auto& relabel = change.relabel;
  std::vector<StorageIndex>& at = change.originsAt;  // the origins' permuted columns, increasing, once each
  at.clear();
  for (StorageIndex o : change.touched) at.push_back(perm[o]);
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  // local when every origin's supernode has free positions for its copies (paper §4.2: a copy
  // joins its origin's supernode); else every position is laid out anew, with room
  bool room = true;
  for (std::size_t q = 0; q < at.size() && room;) {
    const Index owner = m_factor.colToSuper[at[q]];
    Index copies = 0;
    for (; q < at.size() && m_factor.colToSuper[at[q]] == owner; ++q) copies += relabel.copies[at[q]];
    room = copies <= m_factor.freePositions(owner);
  }
  if (room) {  // the old dofs keep their positions but in the windows (m_P changed in place, later)
    relabel.buildLocalCopies(at, m_factor);
  } else {
    relabel.buildWithRoom(at, m_factor, &internal::updatable_cholesky::copyRoomFor);
    change.newPerm.resize(total);
    const StorageIndex* to = relabel.newPosition.data();
    for (Index i = 0; i < n; ++i) change.newPerm[i] = to[perm[i]];
  }
  // each copy right after its origin, copies of one origin in increasing order
  change.placed.resize(m_factor.n, 0);  // (by position; zero between calls)
  change.copyPositions.resize(total - n);
  for (Index i = n; i < total; ++i) {
    const StorageIndex po = perm[change.preList[i]];
    change.copyPositions[i - n] = StorageIndex(relabel.newPosition[po] + 1 + change.placed[po]++);
  }
  if (!room) std::copy(change.copyPositions.begin(), change.copyPositions.end(), change.newPerm.begin() + n);
  change.layoutReady = true;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::mergeDofs(
    const MatrixType& a, const Indices& origin) {
  m_mergeChange.compareAll = true;
  return mergeCopies(a, origin);
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices, typename ChangedIndices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::mergeDofs(
    const MatrixType& a, const Indices& origin, const ChangedIndices& changed) {
  const char* why = nullptr;
  if (!internal::updatable_cholesky::checkIndices(changed, m_n, m_mergeChange.hint, why)) {
    if (beginUpdate()) m_info = InvalidInput;
    return *this;
  }
  m_mergeChange.compareAll = false;
  return mergeCopies(a, origin);
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Indices>
UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::mergeCopies(
    const MatrixType& a, const Indices& origin) {
  if (!beginUpdate()) return *this;
  const Index n = m_n;
  DofChange& change = m_mergeChange;
  std::vector<StorageIndex>& merged = change.merged;
  merged.clear();
  bool ok = Index(origin.size()) == n;
  for (Index i = 0; ok && i < n; ++i) {
    const Index o = Index(origin[i]);
    ok = o >= 0 && o < n && (o == i || Index(origin[o]) == o);
    if (o != i) merged.push_back(StorageIndex(i));
  }
  const Index total = n - Index(merged.size());
  if (!ok || a.rows() != a.cols() || a.rows() != total) {
    m_info = InvalidInput;
    return *this;
  }
  change.merging = true;
  change.touched.clear();
  // the kept dofs keep their order; below the first merged dof, their numbers. The arrays keep
  // the identity prefix between merges (identityLength), so only the rest is written
  const Index firstMerged = merged.empty() ? n : Index(merged.front());
  change.firstMerged = firstMerged;
  change.oldOfNew.resize(total);
  change.newOfOld.resize(n);
  for (Index i = (std::min)(change.identityLength, firstMerged); i < firstMerged; ++i)
    change.oldOfNew[i] = change.newOfOld[i] = StorageIndex(i);
  for (Index i = firstMerged, next = firstMerged; i < n; ++i) {
    const bool kept = Index(origin[i]) == i;
    change.newOfOld[i] = kept ? StorageIndex(next) : StorageIndex(-1);
    if (kept) change.oldOfNew[next++] = StorageIndex(i);
  }
  const StorageIndex* perm = m_P.data();
  change.mergedTarget.resize(merged.size());
  change.droppedAt.resize(merged.size());
  std::vector<std::pair<StorageIndex, StorageIndex> >& into = m_mergeInto;  // (kept new dof, merged dof)
  into.resize(merged.size());
  Index prefix = firstMerged;  // the four arrays are the identity below it
  for (std::size_t k = 0; k < merged.size(); ++k) {
    const StorageIndex i = merged[k], o = StorageIndex(origin[i]), x = change.newOfOld[o];
    change.mergedTarget[k] = x;
    change.droppedAt[k] = perm[i];
    into[k] = std::make_pair(x, i);
    prefix = (std::min)(prefix, Index(x));
    change.touched.push_back(i);
    change.touched.push_back(o);
  }
  std::sort(into.begin(), into.end());
  std::sort(change.droppedAt.begin(), change.droppedAt.end());
  // each kept dof stands for itself and the dofs merged into it, in increasing order
  change.preStart.resize(total + 1);
  change.preList.resize(n);
  for (Index x = (std::min)(change.identityLength, prefix); x < prefix; ++x)
    change.preStart[x] = change.preList[x] = StorageIndex(x);
  {
    Index at = prefix;
    std::size_t q = 0;
    for (Index x = prefix; x < total; ++x) {
      change.preStart[x] = StorageIndex(at);
      const StorageIndex own = change.oldOfNew[x];
      for (; q < into.size() && into[q].first == x && into[q].second < own; ++q) change.preList[at++] = into[q].second;
      change.preList[at++] = own;
      for (; q < into.size() && into[q].first == x; ++q) change.preList[at++] = into[q].second;
    }
    change.preStart[total] = StorageIndex(at);
  }
  change.identityLength = prefix;
  const auto layoutStart = std::chrono::steady_clock::now();
  auto& relabel = change.relabel;
  relabel.copies.resize(m_factor.n, 0);  // (by position; a merge makes no copies: zero, always)
  relabel.buildLocalDrops(change.droppedAt, m_factor);
  // the new permutation: in the windows, each kept dof's column moves down by the dropped
  // columns before it; the other dofs keep their positions
  change.newPerm.resize(total);
  const StorageIndex* oldOfNew = change.oldOfNew.data();
  StorageIndex* newPerm = change.newPerm.data();
  for (Index x = 0; x < total; ++x) newPerm[x] = perm[oldOfNew[x]];
  const StorageIndex* dofAt = m_Pinv.data();
  for (const auto& w : relabel.windows)
    for (Index k = w.first; k < w.second; ++k)
      if (relabel.newPosition[k] >= 0) newPerm[change.newOfOld[dofAt[k]]] = relabel.newPosition[k];
  change.layoutReady = true;
  change.layoutSeconds = secondsBetween(layoutStart);
  if (!change.compareAll) collectCompared(change, total);
  replaceDofs(a, change);
  return *this;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
const std::vector<typename MatrixType_::StorageIndex>& UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::gluingMismatchesOf(
    const DofChange& change) {
  using namespace internal::updatable_cholesky;
  InputDiff<Scalar, StorageIndex>& diff = m_inputDiff;
  const Index total = m_store.outerSize(), n = Index(change.newOfOld.size());
  // the new store holds the new matrix; the previous one is in the spare (rebuilt) or, for the
  // outer vectors rewritten in place, still at their previous ranges of the pool
  const InputStore<Scalar, StorageIndex>& previous = diff.inPlace ? m_store : diff.spare;
  std::vector<OuterRange> newRanges, oldRanges;
  if (diff.inPlace) {
    for (const auto& r : diff.rewrites) {
      oldRanges.push_back(OuterRange{r.outer, r.begin, r.end});
      if (r.outer < total) newRanges.push_back(OuterRange{r.outer, m_store.begin[r.outer], m_store.end[r.outer]});
    }
  } else {
    for (StorageIndex o : diff.changedList) {
      oldRanges.push_back(OuterRange{o, previous.begin[o], previous.end[o]});
      const Index x = change.newOfOld[o];
      if (x >= 0) newRanges.push_back(OuterRange{x, m_store.begin[x], m_store.end[x]});
    }
  }
  diff.mismatch.resize((std::max)(n, total), 0);
  diff.mismatchList.clear();
  constexpr bool rowMajor = bool(MatrixType::IsRowMajor);
  if (!change.merging) {  // the new matrix is cut: old dofs glue onto themselves, copies onto their origins
    for (Index x = n; x < total; ++x) newRanges.push_back(OuterRange{x, m_store.begin[x], m_store.end[x]});
    gluingMismatches<rowMajor>(m_store, newRanges, [&change](Index x) { return Index(change.preList[x]); },
                               previous, oldRanges, diff.mismatch, diff.mismatchList, diff.gluing);
  } else {  // the previous matrix is cut: each previous dof glues onto the kept dof it stands for
    gluingMismatches<rowMajor>(previous, oldRanges, [&change](Index i) { return change.keptOf(i); }, m_store,
                               newRanges, diff.mismatch, diff.mismatchList, diff.gluing);
  }
  // the matrices factored have offset + scale d on their diagonals (setShift()): with an offset,
  // the cut's diagonals glued back hold it once more per copy at each origin
  if (m_factoredOffset != RealScalar(0)) {
    auto flag = [&diff](Index g) {
      if (!diff.mismatch[g]) diff.mismatchList.push_back(StorageIndex(g));
      diff.mismatch[g] = 2;
    };
    if (!change.merging)
      for (Index x = n; x < total; ++x) flag(change.preList[x]);
    else
      for (StorageIndex i : change.merged) flag(change.keptOf(i));
  }
  return diff.mismatchList;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::splitOwnInputChanges(
    const DofChange& change, const std::vector<char>& folded, std::vector<std::pair<StorageIndex, RealScalar> >& copyPivots) {
  using namespace internal::updatable_cholesky;
  InputDiff<Scalar, StorageIndex>& diff = m_inputDiff;
  const Index total = m_store.outerSize(), n = Index(change.newOfOld.size());
  constexpr bool rowMajor = bool(MatrixType::IsRowMajor);
  // an insertion folds in the new structure (new numbering); a merge in the previous one (the
  // merged dofs' rows and columns still there, previous numbering)
  const bool previousStructure = change.merging;
  const StorageIndex* perm = previousStructure ? change.newPerm.data() : m_P.data();
  const std::vector<StorageIndex>& colToSuper =
      previousStructure ? m_structureBackup.previousColToSuper(m_factor) : m_factor.colToSuper;
  const char* removed = previousStructure ? nullptr : m_removedPermuted.data();  // (a merge folds only without removed dofs)
  typedef InputChangeEntry<Scalar, StorageIndex> Entry;
  std::vector<Entry> entries;
  // entry (row, col) of the new matrix minus the previous one (dofs in the folding numbering),
  // in the lower triangle of the permuted matrix, when its column belongs to a folded supernode
  auto add = [&](Index row, Index col, Scalar value) {
    appendInputChange(entries, perm, colToSuper, folded, removed, row, col, value);
  };
  // the entries of an outer vector \a outer of the new store (\a previous false) or of the
  // previous one, added with their sign, as factored: a diagonal entry d is offset + scale d
  // (setShift()), whose offset cancels between the two matrices (a diagonal entry the store
  // lacks is factored as the offset alone)
  const RealScalar offset = m_factoredOffset, scale = m_factoredScale;
  auto addRange = [&](const InputStore<Scalar, StorageIndex>& store, Index outer, Index begin, Index end, bool previous) {
    auto dof = [&](Index d) {  // -> the folding numbering
      if (previousStructure) return previous ? d : Index(change.oldOfNew[d]);
      return previous ? Index(change.newOfOld[d]) : d;
    };
    const Index x = dof(outer);
    for (Index p = begin; p < end; ++p) {
      const Index y = dof(Index(store.inner[p]));
      const Scalar stored = Index(store.inner[p]) == outer ? Scalar(scale * store.values[p]) : store.values[p];
      const Scalar value = previous ? Scalar(-stored) : stored;
      if (rowMajor)
        add(x, y, value);
      else
        add(y, x, value);
    }
  };
  // the diagonal entry of outer vector x (its range [begin, end)) as factored (offset + scale d,
  // the offset alone when the store lacks it) when positive, else 1
  auto positiveDiagonal = [offset, scale](const InputStore<Scalar, StorageIndex>& store, Index x, Index begin, Index end) {
    RealScalar d = offset;
    for (Index p = begin; p < end; ++p)
      if (Index(store.inner[p]) == x) d = offset + scale * numext::real(store.values[p]);
    return d > RealScalar(0) && d < NumTraits<RealScalar>::highest() ? d : RealScalar(1);
  };
  const InputStore<Scalar, StorageIndex>& previousStore = diff.inPlace ? m_store : diff.spare;
  // the placeholders: each copy's previous column (insertion) and each merged dof's new one is a
  // diagonal entry, that of its matrix as factored when positive (so that the change has no
  // diagonal part there), else 1; addRange() leaves out the offset of the copy's (merged dof's)
  // factored diagonal, added here
  copyPivots.clear();
  if (!previousStructure)
    for (Index x = n; x < total; ++x) {
      const RealScalar pivot = positiveDiagonal(m_store, x, m_store.begin[x], m_store.end[x]);
      copyPivots.emplace_back(perm[x], pivot);
      add(x, x, Scalar(offset - pivot));
      addRange(m_store, x, m_store.begin[x], m_store.end[x], false);
    }
  std::sort(copyPivots.begin(), copyPivots.end());
  auto mergedPlaceholder = [&](Index o, Index begin, Index end) {  // (merge: a merged dof's new column)
    if (previousStructure && change.newOfOld[o] < 0)
      add(o, o, Scalar(positiveDiagonal(previousStore, o, begin, end) - offset));
  };
  if (diff.inPlace) {  // (a merged dof's outer vector is among the rewrites)
    for (const auto& r : diff.rewrites) {
      mergedPlaceholder(r.outer, r.begin, r.end);
      if (previousStructure || change.newOfOld[r.outer] >= 0) addRange(previousStore, r.outer, r.begin, r.end, true);
      if (r.outer < total) addRange(m_store, r.outer, m_store.begin[r.outer], m_store.end[r.outer], false);
    }
  } else {
    for (StorageIndex o : diff.changedList) {
      const Index x = change.newOfOld[o];
      if (x < 0 && !previousStructure) continue;
      mergedPlaceholder(o, previousStore.begin[o], previousStore.end[o]);
      addRange(previousStore, o, previousStore.begin[o], previousStore.end[o], true);
      if (x >= 0) addRange(m_store, x, m_store.begin[x], m_store.end[x], false);
    }
  }
  std::vector<StorageIndex>& position = diff.position;  // (by permuted row, all -1 between uses)
  const Index positions = (std::max)(m_factor.n, m_structureBackup.n);  // (a merge's previous numbering)
  if (Index(position.size()) < positions) position.resize(positions, StorageIndex(-1));
  splitInputChanges(entries, [&](Index t) -> const std::vector<StorageIndex>& {
    return previousStructure ? m_structureBackup.rows[t] : m_factor.nodes[t].rows;
  }, position, m_workspace);
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
void UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::replaceDofs(const MatrixType& a, DofChange& change) {
  using namespace internal::updatable_cholesky;
  const auto start = m_updateStart;
  m_sparseLIsValid = false;
  m_publicPermutationIsValid = false;
  MatrixType copy;
  const MatrixType* pa = compressedInput(a, copy);
  const Index n = m_n, total = pa->rows();
  constexpr bool rowMajor = bool(MatrixType::IsRowMajor);
  const StorageIndex* outer = pa->outerIndexPtr();
  const StorageIndex* inner = pa->innerIndexPtr();
  const Scalar* values = pa->valuePtr();
  const StorageIndex* perm = m_P.data();

  // 1. Compare with the current matrix (changed dofs, where the kept entries move, the entries
  //    it lacks) and check the pattern of the new entries.
  auto foldAllowed = [&](Index x, Index y) {
    for (Index p = change.preStart[x]; p < change.preStart[x + 1]; ++p)
      for (Index q = change.preStart[y]; q < change.preStart[y + 1]; ++q) {
        const Index u = change.preList[p], v = change.preList[q];
        if (u == v || m_transposed.holds(u, v)) return true;
      }
    return false;
  };
  InputDiff<Scalar, StorageIndex>& diff = m_inputDiff;
  if (!diffInput<UpLo_, rowMajor>(m_store, outer, inner, values, total, change.oldOfNew, change.newOfOld, diff,
                                  foldAllowed, change.compareAll ? nullptr : &change.compared,
                                  change.merging ? change.firstMerged : n)) {  // (the store is as it was)
    m_info = diff.nonFinite >= 0 ? NumericalIssue : InvalidInput;  // (NaN or infinity: as compute() says)
    if (diff.nonFinite >= 0) m_failedColumn = diff.nonFinite;
    return;
  }
  const std::vector<char>& changed = diff.changed;
  // 2. A merge keeps the structure: it must hold every entry the current matrix lacks.
  bool ok = true;
  for (Index k = 0; k < Index(diff.fresh.size()) && ok && change.merging; ++k) {
    const Index x = diff.freshOuter[k], y = m_store.inner[diff.fresh[k]];
    if (x == y) continue;
    const Index px = perm[change.oldOfNew[x]], py = perm[change.oldOfNew[y]];
    ok = structureHolds(m_factor, (std::max)(px, py), (std::min)(px, py));
  }
  if (!ok) {
    diff.revert(m_store);
    m_info = InvalidInput;
    return;
  }
  if (total == n && diff.inPlace && diff.rewrites.empty()) {  // the same matrix, no dof added or merged (a cut
    diff.commit(m_store);                                        // with no interior vertex): nothing to do
    m_info = Success;
    recordUpdate(UpdateRoute::PartialRefactorization, 0, std::vector<Index>(), 0.0, start);
    m_lastUpdate.compareSeconds = m_lastUpdate.seconds;
    return;
  }
  const auto compared = std::chrono::steady_clock::now();  // (the phases of lastUpdate())
  if (!change.layoutReady) buildInsertionLayout(change);
  // 3. Dirty supernodes: the paths from the changed columns, origins and merged dofs to the roots.
  std::vector<char>& mark = m_workspace.mark;
  std::vector<Index> dirty;
  auto markPath = [&](Index s) { markPathToRoot(m_factor, s, mark, dirty); };
  for (StorageIndex o : diff.changedList) markPath(m_factor.colToSuper[perm[o]]);
  for (StorageIndex o : change.touched) markPath(m_factor.colToSuper[perm[o]]);
  if (change.merging) {
    // the supernodes that lose a merged dof's row: every one that holds it below its columns lies
    // under the supernode of its column, and so do all between them (a row passes from child to
    // parent): found from that supernode down, each child that does not hold it ending the search
    std::vector<Index> below;
    for (StorageIndex d : change.droppedAt) {
      const Index own = m_factor.colToSuper[d];
      for (Index c = m_factor.firstChild[own]; c != -1; c = m_factor.nextSibling[c]) below.push_back(c);
      while (!below.empty()) {
        const Index c = below.back();
        below.pop_back();
        const auto& node = m_factor.nodes[c];
        if (!std::binary_search(node.rows.begin() + node.ncols, node.rows.end(), d)) continue;
        markPath(c);
        for (Index g = m_factor.firstChild[c]; g != -1; g = m_factor.nextSibling[g]) below.push_back(g);
      }
    }
    // a supernode may not lose all its columns (the dropped columns are increasing: a supernode's are consecutive)
    for (std::size_t k = 0; k < change.droppedAt.size() && ok;) {
      const Index own = m_factor.colToSuper[change.droppedAt[k]];
      std::size_t lost = 0;
      for (; k < change.droppedAt.size() && m_factor.colToSuper[change.droppedAt[k]] == own; ++k) ++lost;
      ok = Index(lost) < m_factor.nodes[own].ncols;
    }
  }
  std::sort(dirty.begin(), dirty.end());
  if (!ok) {
    for (Index s : dirty) mark[s] = 0;
    diff.revert(m_store);
    m_info = InvalidInput;
    return;
  }
  Index changedCount = change.merging ? 0 : total - n;  // the copies, and the kept dofs that changed
  for (StorageIndex o : diff.changedList) changedCount += change.newOfOld[o] >= 0;

  // 4. The new structure and input; the previous ones kept aside for a revert.
  FactorStructureBackup<Scalar, StorageIndex>& backup = m_structureBackup;
  if (m_numeric.hasCachedUpdates())  // the dirty caches' deferred corrections are set aside with them, unapplied
    backup.takePending(m_numeric, m_factor.count(), dirty);
  std::vector<FreshEntry<StorageIndex> >& fresh = diff.freshEntries;
  fresh.resize(diff.fresh.size());
  for (Index k = 0; k < Index(fresh.size()); ++k) {  // in the lower triangle of the new C
    const Index p = diff.fresh[k], x = diff.freshOuter[k], y = m_store.inner[p];
    const StorageIndex pi = change.newPositionOf(rowMajor ? x : y, perm), pj = change.newPositionOf(rowMajor ? y : x, perm);
    fresh[k] = pi >= pj ? FreshEntry<StorageIndex>{p, pi, pj} : FreshEntry<StorageIndex>{~p, pj, pi};
  }
  // the transposed pattern follows the store: in place, each changed dof and copy gets its list
  // anew (its unchanged neighbours kept, the changed ones read from the new store); otherwise, or
  // when its pool holds too much garbage, it is rebuilt (the previous one becomes the spare)
  const bool transposedInPlace = diff.inPlace && !m_transposed.wasteful();
  if (transposedInPlace) {
    m_transposed.followInPlaceRewrite(m_store, diff.changedList, changed, n);
  } else {
    diff.spareTransposed.assign(m_store);
    std::swap(m_transposed, diff.spareTransposed);
  }
  std::vector<Index> movedOwners;  // clean supernodes whose entries moved in the store
  if (diff.inPlace) ownersOfRewrites(m_factor, m_store, diff, perm, movedOwners);
  relabelFactor(m_factor, m_numeric.cache(), change.relabel, mark, dirty, backup, diff.position);
  sortFreshEntries(fresh, m_factor.n, diff.freshCount, diff.freshSorted);
  remapAssemblyMaps(m_factor, backup, change.relabel, mark, dirty, diff.posMap, diff.freshSorted, diff.position,
                    diff.inPlace ? &movedOwners : nullptr);
  // the removed flags follow (only the removed dofs' entries are written)
  std::vector<StorageIndex>& oldRemovedList = change.previousRemoved;
  oldRemovedList.swap(m_removedList);
  m_removedList.clear();
  for (StorageIndex i : oldRemovedList) m_removedOriginal[i] = m_removedPermuted[perm[i]] = 0;
  m_removedOriginal.resize(total, 0);
  m_removedPermuted.resize(m_factor.n, 0);  // (by position)
  for (StorageIndex i : oldRemovedList) {
    const StorageIndex x = change.newOfOld[i];
    if (x < 0) continue;  // a removed dof merged away
    m_removedList.push_back(x);
    m_removedOriginal[x] = m_removedPermuted[change.newPositionOf(x, perm)] = 1;
  }
  // the new permutation and its inverse; the previous ones stay in change for a revert. The
  // inverse is read off the previous one in order (the relabeling keeps the old columns' order).
  if (change.inPlace()) {  // a local insertion: only the windows' dofs move, and the copies come
    const DofRelabeling<StorageIndex>& relabel = change.relabel;
    change.movedDofs.clear();
    change.previousDofAt.clear();
    for (const auto& w : relabel.windows)
      for (Index k = w.first; k < w.second; ++k) {
        const StorageIndex d = m_Pinv[k];
        change.previousDofAt.push_back(d);
        if (d >= 0 && relabel.newPosition[k] != StorageIndex(k)) change.movedDofs.emplace_back(d, StorageIndex(k));
      }
    for (const auto& moved : change.movedDofs) m_P[moved.first] = relabel.newPosition[moved.second];
    m_P.insert(m_P.end(), change.copyPositions.begin(), change.copyPositions.end());
    const StorageIndex* previous = change.previousDofAt.data();
    for (const auto& w : relabel.windows) {
      for (Index j = w.first; j < w.second; ++j) {  // (a window's old positions lie in it)
        const StorageIndex k = relabel.oldPosition[j];
        m_Pinv[j] = k < 0 ? StorageIndex(-1) : previous[k - w.first];
      }
      previous += w.second - w.first;
    }
    for (Index x = n; x < total; ++x) m_Pinv[m_P[x]] = StorageIndex(x);  // the copies
  } else {
    const StorageIndex* oldPinv = m_Pinv.data();
    change.newPinv.resize(change.relabel.newSize);
    auto newDof = [&change](StorageIndex o) {  // (a merge renumbers only from its first merged dof on)
      return o < 0 || !change.merging || o < change.firstMerged ? o : change.newOfOld[o];
    };
    const Index unmoved = (std::min)(change.relabel.firstMoved, change.relabel.newSize);  // (below it, no column moves)
    for (Index j = 0; j < unmoved; ++j) change.newPinv[j] = newDof(oldPinv[j]);
    for (Index j = unmoved; j < change.relabel.newSize; ++j) {
      const StorageIndex k = change.relabel.oldPosition[j];
      change.newPinv[j] = newDof(k < 0 ? StorageIndex(-1) : oldPinv[k]);
    }
    for (Index x = n; x < total; ++x) change.newPinv[change.newPerm[x]] = StorageIndex(x);  // the copies
    m_P.swap(change.newPerm);
    m_Pinv.swap(change.newPinv);
  }
  const Index oldN = m_n, oldMaxRows = m_maxRows;
  const double oldTotalFlops = m_totalFlops;
  m_n = total;
  for (Index s : dirty) {  // (only the dirty supernodes gain or lose rows and columns; after a merge,
    const auto& node = m_factor.nodes[s];  // m_maxRows may be more than needed)
    m_maxRows = (std::max)(m_maxRows, node.nrows());
    m_totalFlops += node.flops() - node.flopsOf(backup.ncols[s], Index(backup.rows[s].size()) - backup.ncols[s]);
  }
  m_numeric.structureChanged();
  const auto relabeled = std::chrono::steady_clock::now();

  // 5. Refactor the dirty supernodes (or everything, when that is as cheap); or refactor the
  //    lower dirty supernodes and fold the change into the top ones (LowRankTopUpdate.h).
  const char* removedFlags = m_removedList.empty() ? nullptr : m_removedPermuted.data();
  const double dirtyFlops = supernodeFlops(m_factor, dirty, removedFlags);
  // a merge folds supernodes that lose dofs or whose input changed in their previous structure,
  // where no removed flags are at hand: only without removed dofs
  const bool mergeFolds = change.merging && m_removedList.empty() && oldRemovedList.empty();
  const double totalFlops = refactorizationFlops(m_factor, m_totalFlops, removedFlags, Index(m_removedList.size()));
  std::vector<Index> bottom, top;
  std::vector<internal::updatable_cholesky::FoldBoundary> boundary;
  std::vector<char> folded;  // by supernode: folded rather than refactored (route Mixed)
  std::vector<Index> taken;  // folded supernodes whose previous block and update matrix left the backup
  double plannedFlops = dirtyFlops;
  if (m_route != UpdateRoute::PartialRefactorization && m_route != UpdateRoute::Refactorization &&
      m_numeric.hasCachedUpdates() && !dirty.empty()) {
    // a dirty supernode may be folded when it keeps its columns and no column of it changed;
    // an insertion may add copy rows to it (zero rows of the previous factor extended with
    // identity). The change it gets from below has at most the rank of the copies (merged dofs)
    // below, plus the dofs where the cut matrix does not glue back to the uncut one, plus two
    // per copy row of the refactored child it comes from.
    const Index ns = m_factor.count();
    std::vector<char>& eligible = m_workspace.eligible;  // (all zero between calls, as the three below)
    std::vector<Index>&rankColumns = m_workspace.rankColumns, &likelyRankColumns = m_workspace.likelyRankColumns,
                       &rowRank = m_workspace.rowRank;
    double eligibleFlops = 0;
    for (Index s : dirty) {
      const auto& node = m_factor.nodes[s];
      bool same = true;
      for (Index c = node.firstCol; c < node.firstCol + node.ncols && same; ++c) {
        const StorageIndex o = change.oldOfNew[m_Pinv[c]];
        same = o >= 0 && !changed[o];
      }
      const bool sameRows = !change.merging || Index(backup.rows[s].size()) == node.nrows();
      // a supernode whose own columns changed or gained copies (insertion) or lose merged dofs
      // (merge) may be folded too: its own input change is folded with the children's
      // (splitOwnInputChanges()); a merge does so in the previous structure, without removed dofs
      eligible[s] = !change.merging || mergeFolds || (sameRows && backup.ncols[s] == node.ncols && same);
      if (eligible[s]) eligibleFlops += internal::updatable_cholesky::frontFlops(node, removedFlags);
    }
    const bool force = m_route == UpdateRoute::Mixed || m_route == UpdateRoute::LowRank;
    // a fold saves at most the refactorization of the supernodes it may fold, and a plan is
    // taken only when it saves more than (1 - MixedRouteShare) of the dirty work: below that,
    // the plan (and the compare it needs) is not made
    if (force || eligibleFlops > (1 - internal::updatable_cholesky::MixedRouteShare) * dirtyFlops) {
      for (Index s : dirty) {  // the copies and merged dofs: a lower bound of the ranks
        const auto& node = m_factor.nodes[s];
        for (Index c = node.firstCol; c < node.firstCol + node.ncols; ++c)
          rankColumns[s] += change.oldOfNew[m_Pinv[c]] < 0;
        if (!change.merging)
          for (Index k = node.ncols; k < node.nrows(); ++k)
            rowRank[s] += 2 * (change.oldOfNew[m_Pinv[node.rows[k]]] < 0);
        else if (mergeFolds)  // (its change is taken on its previous rows below, the merged ones included)
          for (Index k = backup.ncols[s]; k < Index(backup.rows[s].size()); ++k)
            rowRank[s] += 2 * (change.relabel.newPosition[backup.rows[s][k]] < 0);
        rankColumns[s] += (std::max)(Index(0), backup.ncols[s] - node.ncols);  // merged away
        likelyRankColumns[s] = rankColumns[s];
      }
      if (!change.merging || mergeFolds) {  // the own input changes: two per changed, new or merged column
        std::vector<Index>&ownRank = m_workspace.ownRank, &ownStart = m_workspace.ownStart;
        auto own = [&](Index t, Index local) {
          ownStart[t] = ownRank[t] == 0 ? local : (std::min)(ownStart[t], local);
          ownRank[t] += 2;
        };
        auto ownNew = [&](Index x) {  // (new numbering)
          const Index j = m_P[x];
          if (m_removedPermuted[j]) return;
          const Index t = m_factor.colToSuper[j];
          own(t, j - m_factor.nodes[t].firstCol);
        };
        for (StorageIndex o : diff.changedList) {
          if (change.newOfOld[o] >= 0) {
            ownNew(change.newOfOld[o]);
          } else {  // a merged dof: its previous column (its supernode's numbering is kept)
            const Index j = change.newPerm[o], t = backup.previousColToSuper(m_factor)[j];
            own(t, j - backup.firstCol[t]);
          }
        }
        for (Index x = n; x < total; ++x) ownNew(x);
      }
      // every cost of a plan grows with the ranks: when the plan on that lower bound saves
      // nothing, neither does the one with the mismatches, and the compare is not made (a
      // forced route makes the plan in any case)
      folded.assign(ns, 0);
      const double mixedLimit = internal::updatable_cholesky::MixedRouteShare * dirtyFlops;
      double planned = 0;
      if (!force)
        planned = foldPlan(m_factor, dirty, eligible, rankColumns, likelyRankColumns, rowRank,
                           m_removedPermuted.data(), force, folded, bottom, top, boundary, m_workspace);
      if (force || (!top.empty() && planned < mixedLimit)) {
        const std::vector<StorageIndex>& mismatched = gluingMismatchesOf(change);  // (flags in diff.mismatch)
        for (Index s : dirty) {
          const auto& node = m_factor.nodes[s];
          for (Index c = node.firstCol; c < node.firstCol + node.ncols; ++c) {
            const StorageIndex x = m_Pinv[c];
            rankColumns[s] += diff.mismatch[x] > 0;
            likelyRankColumns[s] += diff.mismatch[x] > 1;
          }
        }
        for (StorageIndex x : mismatched) diff.mismatch[x] = 0;
        for (Index s : dirty) folded[s] = 0;
        planned = foldPlan(m_factor, dirty, eligible, rankColumns, likelyRankColumns, rowRank,
                           m_removedPermuted.data(), force, folded, bottom, top, boundary, m_workspace);
      }
      if (top.empty() || (!force && planned >= mixedLimit)) {
        top.clear();
        bottom.clear();
      } else {
        plannedFlops = planned;
      }
    }
    for (Index s : dirty)
      eligible[s] = rankColumns[s] = likelyRankColumns[s] = rowRank[s] = m_workspace.ownRank[s] = m_workspace.ownStart[s] = 0;
  }
  UpdateRoute route = top.empty() ? UpdateRoute::PartialRefactorization : UpdateRoute::Mixed;
  const bool forced = m_route != UpdateRoute::Automatic;  // (a forced Mixed or partial route stays)
  if (m_route == UpdateRoute::Refactorization || !m_numeric.hasCachedUpdates() ||
      (!forced && plannedFlops > 0.9 * totalFlops))
    route = UpdateRoute::Refactorization;
  double spentFlops = route == UpdateRoute::Refactorization ? totalFlops : dirtyFlops;
  auto run = [&]() -> Index {
    m_numeric.setCacheUpdates(true);
    if (route == UpdateRoute::Refactorization) return m_numeric.factorize(m_factor, numericInput(), threadCount());
    if (route == UpdateRoute::PartialRefactorization)
      return m_numeric.refactorize(m_factor, numericInput(), dirty, threadCount());
    // Mixed: the folded supernodes start from their previous blocks and update matrices
    // (extended to their new rows, or taken from the backup: listed in taken), the others are refactored
    spentFlops = 0;
    std::vector<std::pair<StorageIndex, RealScalar> > copyPivots;
    if (!change.merging || mergeFolds) splitOwnInputChanges(change, folded, copyPivots);
    auto pivotOf = [&copyPivots](Index column) {
      const auto it = std::lower_bound(copyPivots.begin(), copyPivots.end(), column,
                                       [](const std::pair<StorageIndex, RealScalar>& e, Index c) { return Index(e.first) < c; });
      eigen_assert(it != copyPivots.end() && Index(it->first) == column && "a new column without its placeholder");
      return it->second;
    };
    const Index result = refactorAndFold(
        m_factor, m_numeric, dirty, folded, boundary, backup, taken, change.relabel.newPosition, m_removedPermuted.data(),
        m_workspace,
        [&](const std::vector<Index>& list) { return m_numeric.refactorize(m_factor, numericInput(), list, threadCount()); },
        pivotOf, spentFlops, mergeFolds);
    if (result != -2) return result;
    // a change not captured by its rank bound, or a downdate lost a pivot: refactor every dirty supernode instead
    for (Index s : dirty) m_numeric.discardCorrections(s);
    route = UpdateRoute::PartialRefactorization;
    spentFlops = dirtyFlops;
    return m_numeric.refactorize(m_factor, numericInput(), dirty, threadCount());
  };
  const auto planned = std::chrono::steady_clock::now();
  const Index bad = run();
  const auto computed = std::chrono::steady_clock::now();
  if (bad >= 0) {  // not positive definite: everything goes back as it was
    m_failedColumn = m_Pinv[bad];
    restoreFactor(m_factor, m_numeric.cache(), change.relabel, mark, dirty, backup);
    diff.revert(m_store);
    if (transposedInPlace)
      m_transposed.revert();
    else
      std::swap(m_transposed, diff.spareTransposed);
    for (StorageIndex x : m_removedList) m_removedOriginal[x] = m_removedPermuted[m_P[x]] = 0;
    if (change.inPlace()) {
      m_P.resize(n);
      for (const auto& moved : change.movedDofs) m_P[moved.first] = moved.second;
      const StorageIndex* previous = change.previousDofAt.data();
      for (const auto& w : change.relabel.windows)
        for (Index j = w.first; j < w.second; ++j) m_Pinv[j] = *previous++;
    } else {
      m_P.swap(change.newPerm);
      m_Pinv.swap(change.newPinv);
    }
    m_removedOriginal.resize(oldN, 0);
    m_removedPermuted.resize(m_factor.n, 0);
    m_removedList.swap(oldRemovedList);
    for (StorageIndex i : m_removedList) m_removedOriginal[i] = m_removedPermuted[m_P[i]] = 1;
    {  // (the rare failure path rebuilds the assembly maps from the previous matrix)
      std::vector<StorageIndex> previousPerm(m_P.data(), m_P.data() + oldN);
      PermutedLowerEntries<StorageIndex> lower;
      permuteTriangle<rowMajor>(m_store, previousPerm, lower, static_cast<CompressedPattern<StorageIndex>*>(nullptr),
                                m_factor.n);
      buildAssemblyMaps(lower, m_factor);
    }
    m_n = oldN;
    m_maxRows = oldMaxRows;
    m_totalFlops = oldTotalFlops;
    m_numeric.structureChanged();
    for (Index s : dirty) {  // (a taken supernode is recomputed below: its list does not matter)
      m_numeric.discardCorrections(s);
      if (!backup.pending[s].empty()) m_numeric.pendingCorrections(s).swap(backup.pending[s]);
    }
    if (!taken.empty() && route != UpdateRoute::Refactorization) {  // their previous values left the backup
      m_numeric.cacheRestored();
      const Index again = m_numeric.refactorize(m_factor, numericInput(), taken, threadCount());
      eigen_assert(again < 0 && "UpdatableSupernodalLLT: the previous folded supernodes could not be recomputed");
      m_factorizationIsOk = again < 0;
      m_numeric.cacheRestored();
    } else if (route != UpdateRoute::Refactorization) {
      m_numeric.cacheRestored();
    } else {
      const Index again = m_numeric.factorize(m_factor, numericInput(), threadCount());
      eigen_assert(again < 0 && "UpdatableSupernodalLLT: the previous factor could not be restored");
      m_factorizationIsOk = again < 0;
    }
    m_info = NumericalIssue;
    m_solveCache.invalidate();
  } else {
    diff.commit(m_store);
    m_info = Success;
    // (the signed folds split changes of update matrices by eigenvectors and rotate by hyperbolic
    // rotations: the removed dofs' rows come out at 1e-17 where they were exactly zero)
    if (route == UpdateRoute::Mixed && !m_removedList.empty())
      for (Index s : dirty) m_numeric.clearRemoved(m_factor, s, m_removedPermuted.data());
    // (only the dirty supernodes gain or lose rows; recordUpdate() marks them to be substituted)
    m_solveCache.followStructure(m_factor, dirty, !change.relabel.local);
  }
  for (Index s : dirty) mark[s] = 0;
  backup.release(m_factor, dirty);  // the previous blocks are not kept past the call
  recordUpdate(route, changedCount, dirty, spentFlops, start);
  // (the layout an insertion or merge built before the compare is structure work)
  const double beforeCompare = secondsBetween(start, compared), layout = (std::min)(change.layoutSeconds, beforeCompare);
  m_lastUpdate.compareSeconds = beforeCompare - layout;
  m_lastUpdate.structureSeconds = secondsBetween(compared, relabeled) + layout;
  m_lastUpdate.planSeconds = secondsBetween(relabeled, planned);
  m_lastUpdate.numericSeconds = secondsBetween(planned, computed);
  m_lastUpdate.movedPositions = change.relabel.moved;
  m_lastUpdate.renumberedSupernodes = backup.renumberedCount;
}

template <typename MatrixType_, int UpLo_, typename Ordering_>
template <typename Rhs, typename Known>
Matrix<typename MatrixType_::Scalar, Dynamic, Dynamic> UpdatableSupernodalLLT<MatrixType_, UpLo_, Ordering_>::solveDirichlet(
    const MatrixBase<Rhs>& b, const MatrixBase<Known>& g) const {
  eigen_assert(m_factorizationIsOk && "UpdatableSupernodalLLT::solveDirichlet(): no valid factorization.");
  eigen_assert(b.rows() == m_n && g.rows() == m_n && b.cols() == g.cols() &&
               "UpdatableSupernodalLLT::solveDirichlet(): b and g must both be n x k");
  // Everything happens in the permuted numbering: b is permuted once, the removed rows take g,
  // the kept rows lose A_IB g_B (read from the columns of B only), then one solve.
  Matrix<Scalar, Dynamic, Dynamic> x = permutedCopy(b);
  if (!m_removedList.empty()) {
    const Ref<const Matrix<Scalar, Dynamic, Dynamic> > known(g.derived());
    std::vector<StorageIndex> columns(m_removedList.size());
    for (Index r = 0; r < Index(m_removedList.size()); ++r) {
      columns[r] = m_P[m_removedList[r]];
      x.row(columns[r]) = known.row(m_removedList[r]);
    }
    internal::updatable_cholesky::subtractDirichletCoupling<bool(MatrixType::IsRowMajor)>(
        m_store, m_transposed, m_P.data(), m_Pinv.data(), m_removedPermuted.data(), columns,
        x.data(), x.rows(), x.cols());
  }
  solveInPlacePermuted(x);
  Matrix<Scalar, Dynamic, Dynamic> result;
  unpermuteInto(x, result);
  return result;
}

}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_SUPERNODAL_LLT_H
