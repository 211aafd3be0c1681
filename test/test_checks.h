// Comparison machinery shared by the tests: runs a matrix through the solver under test and
// through Eigen::SimplicialLLT, and measures every error as a ratio to its tolerance (<= 1 passes).
// B = scale*A + offset*I is the matrix factored; eps the scalar's epsilon; c the largest number of
// stored entries in a row of L (the longest dot product); M = |L| |L|^T (moduli); rho an upper
// bound of ||M||_2 (Collatz-Wielandt); k the most entries in a row of B; lambda_min estimated by
// inverse iteration with the reference. Cholesky's backward error is |L L^H - B| <= c eps M
// componentwise (Higham, ch. 10), and a solve's is 3c eps M, hence:
//  - factor:   || L L^H - P B P^T ||_F  <= 3 (c+1) eps ||M||_F     (incl. the test's own product)
//  - residual: || B x - b ||            <= 1.5 [(3c+1) eps rho ||x|| + (k+1) eps (||B||_inf ||x|| + ||b||)]
//  - solution: || x - x_ref ||          <= 2 [(3c+1) eps (rho ||x|| + rho_ref ||x_ref||)] / lambda_min
//  - logDet:   | logdet - logdet_ref |  <= 8 sqrt(c+2) eps (sqrt(n) rho / lambda_min + n)
//                                           + n eps sum|log L_ii^2|
//    (a statistical model of the factor's rounding errors, whose worst case bound is useless here,
//    plus the worst case error of summing n logarithms in the scalar type)
//  - determinant (n <= 120, where it neither overflows nor underflows): relative error within
//    the logDet tolerance.
// A wrong factor, permutation or solve gives errors of the order of ||B||, far above these bounds
// (test_checks.cpp shows that each check fails on a slightly wrong factorization).
#ifndef UC_TEST_CHECKS_H
#define UC_TEST_CHECKS_H

#include "test_matrices.h"
#include "test_seed.h"

#include <sstream>
#include <string>

namespace uctest {

/** B = A with its diagonal d_ii replaced by offset + scale*d_ii (A full, both triangles): the
  * matrix Eigen's setShift(offset, scale) factors. */
template <typename Cfg>
typename Cfg::FullMatrix shiftedMatrix(const typename Cfg::FullMatrix& A, double offset, double scale) {
  typedef typename Cfg::FullMatrix FullMatrix;
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::RealScalar Real;
  FullMatrix I(A.rows(), A.cols());
  I.setIdentity();
  FullMatrix B = A + Scalar(Real(offset)) * I;  // (structurally missing diagonal entries get the offset)
  B.makeCompressed();
  for (Index j = 0; j < B.outerSize(); ++j)
    for (typename FullMatrix::InnerIterator it(B, j); it; ++it)
      if (it.row() == it.col()) it.valueRef() += Scalar(Real(scale - 1)) * A.coeff(j, j);
  return B;
}

/** A SimplicialLLT factor with the same shift (d_ii -> offset + scale*d_ii). */
template <typename Cfg>
void computeReference(typename Cfg::Reference& ref, const typename Cfg::MatrixType& input, double offset = 0,
                      double scale = 1) {
  typedef typename Cfg::RealScalar Real;
  ref.setShift(Real(offset), Real(scale));
  ref.compute(input);
}

template <typename S, typename = void>
struct HasLogDeterminant : std::false_type {};
template <typename S>
struct HasLogDeterminant<S, decltype(void(std::declval<const S&>().logDeterminant()))> : std::true_type {};

/** log det from the diagonal of a factor L: 2 sum log |L_ii|, summed in long double (which holds
  * every scalar type's precision). */
template <typename SparseL>
long double logDetFromFactor(const SparseL& L) {
  long double s = 0;
  for (Index j = 0; j < L.cols(); ++j) s += 2.0L * std::log((long double)(std::abs(L.coeff(j, j))));
  return s;
}

template <typename Solver>
long double solverLogDet(const Solver& llt, std::true_type) {
  return (long double)(llt.logDeterminant());
}
template <typename Solver>
long double solverLogDet(const Solver& llt, std::false_type) {
  typedef typename Solver::MatrixType::Scalar Scalar;
  typedef typename Solver::MatrixType::StorageIndex StorageIndex;
  Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex> L = llt.matrixL();
  return logDetFromFactor(L);
}

/** Largest number of stored entries in a row of L. */
template <typename SparseL>
Index maxRowCount(const SparseL& L) {
  std::vector<Index> count(L.rows(), 0);
  for (Index j = 0; j < L.outerSize(); ++j)
    for (typename SparseL::InnerIterator it(L, j); it; ++it) ++count[it.row()];
  Index c = 0;
  for (Index v : count) c = std::max(c, v);
  return c;
}

/** Is p a permutation of 0..n-1? */
template <typename Perm>
bool isPermutation(const Perm& p, Index n) {
  if (p.size() != n) return false;
  std::vector<char> seen(n, 0);
  for (Index k = 0; k < n; ++k) {
    const Index v = Index(p.indices()[k]);
    if (v < 0 || v >= n || seen[v]) return false;
    seen[v] = 1;
  }
  return true;
}

/** Smallest eigenvalue of B, estimated by inverse iteration with a factor of B (from above). */
template <typename Cfg, typename Factor>
double estimateLambdaMin(const Factor& factor, Index n, unsigned seed) {
  if (n == 0) return 1;
  std::mt19937 g(seed);
  typename Cfg::Vector v = randomDense<Cfg>(n, 1, g);
  v /= v.norm();
  double lambda = 1;
  for (int it = 0; it < 20; ++it) {
    typename Cfg::Vector w = factor.solve(v);
    const double nw = double(w.norm());
    if (!(nw > 0) || !std::isfinite(nw)) break;
    lambda = 1.0 / nw;
    v = w / typename Cfg::RealScalar(nw);
  }
  return lambda;
}

/** What the tolerances of one factor are made of (see the top of this file). */
struct FactorBounds {
  double c = 0;    // most stored entries in a row of L
  double rho = 0;  // upper bound of || |L| |L|^T ||_2
  double absProductNorm = 0;  // || |L| |L|^T ||_F
};

template <typename SparseL>
FactorBounds factorBounds(const SparseL& L) {
  FactorBounds f;
  f.c = double(maxRowCount(L));
  typedef Eigen::SparseMatrix<double, Eigen::ColMajor, typename SparseL::StorageIndex> SparseD;
  const SparseD absL = L.unaryExpr([](const typename SparseL::Scalar& v) { return double(std::abs(v)); });
  const SparseD absLt = absL.transpose();
  const SparseD M = absL * absLt;
  f.absProductNorm = M.norm();
  // Collatz-Wielandt: for x > 0, rho(M) <= max_i (M x)_i / x_i; M has a positive diagonal, so
  // the power iterates stay positive
  Eigen::VectorXd x = Eigen::VectorXd::Ones(L.rows());
  f.rho = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 12 && L.rows() > 0; ++it) {
    const Eigen::VectorXd y = absL * (absLt * x);
    double r = 0;
    for (Index i = 0; i < y.size(); ++i) r = std::max(r, y[i] / x[i]);
    f.rho = std::min(f.rho, r);
    const double ymax = y.maxCoeff();
    if (!(ymax > 0) || !std::isfinite(ymax)) break;
    x = y / ymax;
    for (Index i = 0; i < x.size(); ++i) x[i] = std::max(x[i], 1e-200);
  }
  return f;
}

/** Tolerances for solves with B, one factor under test and the reference. */
template <typename Cfg>
struct SolveBounds {
  double eps = 0, lambdaMin = 1, normInf = 0, k = 0;
  FactorBounds mine, ref;
  template <typename Solver>
  SolveBounds(const Solver& llt, const typename Cfg::Reference& reference, const typename Cfg::FullMatrix& B,
              unsigned seed) {
    eps = double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon());
    if (B.rows() == 0) return;
    const typename Cfg::FullMatrix L = llt.matrixL(), Lref = reference.matrixL();
    mine = factorBounds(L);
    ref = factorBounds(Lref);
    std::vector<double> rowSum(B.rows(), 0.0), rowCount(B.rows(), 0.0);
    for (Index j = 0; j < B.outerSize(); ++j)
      for (typename Cfg::FullMatrix::InnerIterator it(B, j); it; ++it) {
        rowSum[it.row()] += double(std::abs(it.value()));
        rowCount[it.row()] += 1;
      }
    normInf = *std::max_element(rowSum.begin(), rowSum.end());
    k = *std::max_element(rowCount.begin(), rowCount.end());
    lambdaMin = estimateLambdaMin<Cfg>(reference, B.rows(), seed);
  }
  /** bound of || B x - b || for a solution x of norm xnorm computed with factor f */
  double residual(const FactorBounds& f, double xnorm, double bnorm) const {
    return 1.5 * ((3 * f.c + 1) * eps * f.rho * xnorm + (k + 1) * eps * (normInf * xnorm + bnorm));
  }
  /** bound of || x - x_ref || */
  double solution(double xnorm, double xrefnorm) const {
    return 2 * (3 * std::max(mine.c, ref.c) + 1) * eps * (mine.rho * xnorm + ref.rho * xrefnorm) / lambdaMin;
  }
};

/** Every error of a factorization as a ratio to its tolerance, and what the tolerances were made of. */
struct Measure {
  Index n = 0;
  bool permutationOk = true;   // P and Pinv are permutations of 0..n-1 (or empty = identity) and P*Pinv = I
  bool diagonalOk = true;      // diag(L) real and positive
  bool upperOk = true;         // matrixU() == matrixL().adjoint()
  double factor = 0, residual = 0, solution = 0, logDet = 0, det = 0;
  double lambdaMin = 0, rho = 0, rowCount = 0;
  long double logDetValue = 0, logDetRef = 0;
  std::string describe() const {
    std::ostringstream s;
    s << "n=" << n << " errors/tolerance: factor " << factor << ", residual " << residual << ", solution "
      << solution << ", logDet " << logDet << " (" << logDetValue << " vs " << logDetRef << "), det " << det
      << "; permutationOk " << permutationOk << ", diagonalOk " << diagonalOk << ", upperOk " << upperOk
      << "; lambda_min~" << lambdaMin << ", || |L||L|^T || <= " << rho << ", max row count of L " << rowCount;
    return s.str();
  }
  bool allPass() const {
    return permutationOk && diagonalOk && upperOk && factor <= 1 && residual <= 1 && solution <= 1 && logDet <= 1 &&
           det <= 1;
  }
};

inline double finiteOrInf(double v) { return std::isfinite(v) ? v : std::numeric_limits<double>::infinity(); }

/** Measures a successful factorization `llt` of B = scale*A + offset*I against the reference `ref`
  * (a successful SimplicialLLT of the same B). */
template <typename Cfg, typename Solver>
Measure measure(const Solver& llt, const typename Cfg::FullMatrix& B, const typename Cfg::Reference& ref,
                unsigned seed, bool checkDeterminant) {
  typedef typename Cfg::FullMatrix FullMatrix;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::Vector Vector;
  typedef Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, StorageIndex> Perm;
  Measure m;
  const Index n = B.rows();
  m.n = n;
  if (n == 0) return m;
  const SolveBounds<Cfg> bounds(llt, ref, B, seed + 1);
  const double eps = bounds.eps;
  m.lambdaMin = bounds.lambdaMin;
  m.rho = bounds.mine.rho;
  m.rowCount = bounds.mine.c;

  // the factor: L L^H = P B P^T
  FullMatrix L = llt.matrixL();
  FullMatrix Lref = ref.matrixL();
  for (Index j = 0; j < n; ++j) {
    const typename Cfg::Scalar d = L.coeff(j, j);
    if (!(Eigen::numext::real(d) > 0) || Eigen::numext::imag(d) != 0) m.diagonalOk = false;
  }
  FullMatrix U = llt.matrixU();
  FullMatrix LH = L.adjoint();
  m.upperOk = U.rows() == n && U.cols() == n && double((U - LH).norm()) == 0.0;
  Perm P = llt.permutationP(), Pinv = llt.permutationPinv();
  if (P.size() == 0 && Pinv.size() == 0) {  // Eigen's convention for "no permutation"
    P.setIdentity(n);
    Pinv.setIdentity(n);
  }
  m.permutationOk = isPermutation(P, n) && isPermutation(Pinv, n);
  if (m.permutationOk) {
    Perm I = P * Pinv;
    for (Index k = 0; k < n; ++k)
      if (Index(I.indices()[k]) != k) m.permutationOk = false;
  }
  if (m.permutationOk) {
    FullMatrix PBPt;
    PBPt = B.twistedBy(P);
    FullMatrix LLH = L * LH;
    m.factor = finiteOrInf(double((LLH - PBPt).norm()) / (3 * (bounds.mine.c + 1) * eps * bounds.mine.absProductNorm));
  } else {
    m.factor = std::numeric_limits<double>::infinity();
  }

  // one solve with a random right-hand side
  std::mt19937 g(seed);
  const Vector b = randomDense<Cfg>(n, 1, g);
  const Vector x = llt.solve(b);
  const Vector xref = ref.solve(b);
  m.residual = finiteOrInf(double((B * x - b).norm()) / bounds.residual(bounds.mine, double(x.norm()), double(b.norm())));
  m.solution = finiteOrInf(double((x - xref).norm()) / bounds.solution(double(x.norm()), double(xref.norm())));

  // log-determinant and determinant
  double sumLogDiag = 0;
  for (Index i = 0; i < n; ++i) sumLogDiag += std::abs(2 * std::log(double(Eigen::numext::real(Lref.coeff(i, i)))));
  const double c = std::max(bounds.mine.c, bounds.ref.c);
  const double ldTol =
      8 * std::sqrt(c + 2) * eps * (std::sqrt(double(n)) * std::max(bounds.mine.rho, bounds.ref.rho) / m.lambdaMin + n) +
      double(n) * eps * sumLogDiag;  // + the error of summing n logarithms in the scalar type
  m.logDetValue = solverLogDet(llt, HasLogDeterminant<Solver>());
  m.logDetRef = logDetFromFactor(Lref);
  m.logDet = finiteOrInf(double(std::abs(m.logDetValue - m.logDetRef)) / ldTol);
  if (checkDeterminant) {
    const typename Cfg::Scalar det = llt.determinant(), detRef = ref.determinant();
    const double aref = double(std::abs(detRef));
    const double realMin = double(std::numeric_limits<typename Cfg::RealScalar>::min());
    const double realMax = double(std::numeric_limits<typename Cfg::RealScalar>::max());
    if (aref > 1e3 * realMin && aref < 1e-3 * realMax)  // representable: compare
      m.det = finiteOrInf(double(std::abs(det - detRef)) / (aref * std::min(ldTol, 0.1) * 2));
  }
  return m;
}

/** Options of a check. */
struct CheckOptions {
  double offset = 0, scale = 1;  // setShift(offset, scale) on both solvers
  bool determinant = true;       // compare determinant() (only done where it does not over/underflow)
  unsigned seed = 7;
};

/** Plain statistics every successful factorization must satisfy. */
template <typename Solver>
void checkStatistics(const Solver& llt, Index n) {
  CHECK(llt.rows() == n);
  CHECK(llt.cols() == n);
  CHECK(llt.failedColumn() == -1);
  if (n > 0) {
    CHECK(llt.nonZerosL() >= n);
    CHECK(llt.supernodeCount() >= 1);
    CHECK(llt.supernodeCount() <= n);
    CHECK(llt.factorizationFlops() > 0);
  }
}

/** CHECKs a computed solver against the reference on B = scale*A + offset*I. */
template <typename Cfg, typename Solver>
Measure checkAgainstReference(const Solver& llt, const typename Cfg::FullMatrix& A,
                              const typename Cfg::Reference& ref, const CheckOptions& o = CheckOptions()) {
  REQUIRE(ref.info() == Eigen::Success);  // the test matrix itself must be SPD
  CHECK(llt.info() == Eigen::Success);
  if (llt.info() != Eigen::Success) return Measure();
  checkStatistics(llt, A.rows());
  const typename Cfg::FullMatrix B = shiftedMatrix<Cfg>(A, o.offset, o.scale);
  Measure m = measure<Cfg>(llt, B, ref, o.seed, o.determinant && A.rows() <= 120);
  INFO(m.describe());
  CHECK(m.permutationOk);
  CHECK(m.diagonalOk);
  CHECK(m.upperOk);
  CHECK(m.factor <= 1);
  CHECK(m.residual <= 1);
  CHECK(m.solution <= 1);
  CHECK(m.logDet <= 1);
  CHECK(m.det <= 1);
  return m;
}

/** The whole round trip: converts A to the configuration's input form, computes the solver under
  * test and the reference, and checks. Returns the measure for callers that want more. */
template <typename Cfg>
Measure computeAndCheck(const typename Cfg::FullMatrix& A, Storage s = Storage::Full,
                        const CheckOptions& o = CheckOptions()) {
  INFO("input: " << storageName(s) << ", n=" << A.rows() << ", nnz=" << A.nonZeros() << ", shift offset "
                 << o.offset << " scale " << o.scale);
  const typename Cfg::MatrixType input = toInput<Cfg>(A, s, o.seed);
  typename Cfg::Solver llt;
  llt.setShift(typename Cfg::RealScalar(o.offset), typename Cfg::RealScalar(o.scale));
  llt.compute(input);
  typename Cfg::Reference ref;
  computeReference<Cfg>(ref, input, o.offset, o.scale);
  return checkAgainstReference<Cfg>(llt, A, ref, o);
}

/** Bitwise equality of two factors (same solver type, same pattern). */
template <typename Cfg, typename SolverA, typename SolverB>
bool sameFactorBitwise(const SolverA& a, const SolverB& b) {
  if (a.rows() != b.rows()) return false;
  if (a.rows() == 0) return true;  // (nonZeros() of an empty SparseMatrix is not safe in Eigen 3.4)
  typename Cfg::FullMatrix La = a.matrixL(), Lb = b.matrixL();
  if (La.nonZeros() != Lb.nonZeros()) return false;
  if (a.permutationP().indices() != b.permutationP().indices()) return false;
  for (Index j = 0; j < La.outerSize(); ++j) {
    typename Cfg::FullMatrix::InnerIterator ia(La, j), ib(Lb, j);
    for (; ia && ib; ++ia, ++ib)
      if (ia.index() != ib.index() || !(ia.value() == ib.value())) return false;
    if (ia || ib) return false;
  }
  return true;
}

/** A (both triangles stored) with the rows and columns of the removed dofs replaced by those of the identity. */
template <typename Cfg>
typename Cfg::FullMatrix withIdentityRows(const typename Cfg::FullMatrix& A, const std::vector<char>& removed) {
  typename Cfg::FullMatrix B = A;
  for (Index j = 0; j < B.outerSize(); ++j)
    for (typename Cfg::FullMatrix::InnerIterator it(B, j); it; ++it)
      if (removed[it.row()] || removed[it.col()])
        it.valueRef() = it.row() == it.col() ? typename Cfg::Scalar(1) : typename Cfg::Scalar(0);
  return B;
}

/** True when the removed dofs' rows and columns of the solver's factor are exactly those of the
  * identity (zero rows, unit columns), as a Dirichlet solve needs to return the known values
  * unchanged: the folds of the low-rank routes keep them only up to rounding unless cleared. */
template <typename Cfg, typename Solver>
bool removedAreIdentity(const Solver& llt, const std::vector<char>& removed) {
  const typename Cfg::FullMatrix L = llt.matrixL();
  std::vector<char> permuted(removed.size(), 0);
  for (std::size_t i = 0; i < removed.size(); ++i)
    if (removed[i]) permuted[std::size_t(llt.permutationP().indices()[Index(i)])] = 1;
  for (Index j = 0; j < L.outerSize(); ++j)
    for (typename Cfg::FullMatrix::InnerIterator it(L, j); it; ++it) {
      if (!permuted[std::size_t(it.row())] && !permuted[std::size_t(it.col())]) continue;
      const typename Cfg::Scalar expected(it.row() == it.col() ? 1 : 0);
      if (!(it.value() == expected)) return false;
    }
  return true;
}

/** || La - Lb ||_F / ||Lb||_F for two factors with the same permutation. */
template <typename Cfg, typename SolverA, typename SolverB>
double factorDifference(const SolverA& a, const SolverB& b) {
  typename Cfg::FullMatrix La = a.matrixL(), Lb = b.matrixL();
  if (La.rows() == 0) return 0;
  return double((La - Lb).norm()) / double(Lb.norm());
}

}  // namespace uctest

#endif  // UC_TEST_CHECKS_H
