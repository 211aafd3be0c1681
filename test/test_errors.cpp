// Failure modes: matrices that are not positive definite (negative or zero pivot, negative
// diagonal, NaN entries) give NumericalIssue and a valid failedColumn(); the object recovers on
// the next good factorize(); a pattern other than the analysed one, or an ordering functor that
// returns no permutation, gives InvalidInput; 0x0 and 1x1 matrices; and misuse (solve before
// compute, wrong right-hand side size), which must trip an eigen_assert. Here eigen_assert
// throws, so that the tests can see it (and every other Eigen assertion is active in this file).
#include <stdexcept>
#define eigen_assert(x)                                                     \
  do {                                                                      \
    if (!(x)) throw std::runtime_error("eigen_assert failed: " #x);         \
  } while (false)

#include "test_checks.h"

using namespace uctest;

namespace {

template <typename Cfg>
typename Cfg::FullMatrix withEntry(typename Cfg::FullMatrix A, Index i, Index j, typename Cfg::Scalar v) {
  A.coeffRef(i, j) = v;
  if (i != j) A.coeffRef(j, i) = Eigen::numext::conj(v);
  A.makeCompressed();
  return A;
}

/** Does running f() trip an eigen_assert? */
template <typename F>
bool asserts(F f) {
  try {
    f();
  } catch (const std::runtime_error&) {
    return true;
  }
  return false;
}

}  // namespace

TEST_CASE_TEMPLATE("not positive definite: NumericalIssue and failedColumn", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::RealScalar Real;
  typedef typename Cfg::FullMatrix FullMatrix;
  std::mt19937 g(61);
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Index n = 120;
  const FullMatrix A = spdFromPattern<Scalar, StorageIndex>(
      Cfg::fillReducing ? randomPattern(n, 4, g) : bandedRandomPattern(n, 6, 0.5, g), g);

  SUBCASE("a negative diagonal entry: failedColumn() is that column") {
    for (Index k : {Index(0), Index(37), n - 1}) {
      CAPTURE(k);
      const typename Cfg::MatrixType input = toInput<Cfg>(withEntry<Cfg>(A, k, k, Scalar(-1)));
      typename Cfg::Reference ref(input);
      REQUIRE(ref.info() == Eigen::NumericalIssue);  // SimplicialLLT agrees
      typename Cfg::Solver llt(input);
      CHECK(llt.info() == Eigen::NumericalIssue);
      CHECK(llt.failedColumn() == k);
      // a diagonal matrix with one negative entry
      FullMatrix D = spdFromPattern<Scalar, StorageIndex>(diagonalPattern(n), g);
      typename Cfg::Solver lltD(toInput<Cfg>(withEntry<Cfg>(D, k, k, Scalar(-2))));
      CHECK(lltD.info() == Eigen::NumericalIssue);
      CHECK(lltD.failedColumn() == k);
    }
  }
  SUBCASE("a zero diagonal entry in a diagonal matrix") {
    FullMatrix D = spdFromPattern<Scalar, StorageIndex>(diagonalPattern(10), g);
    typename Cfg::Solver llt(toInput<Cfg>(withEntry<Cfg>(D, 4, 4, Scalar(0))));
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() == 4);
  }
  SUBCASE("indefinite with a positive diagonal (Laplacian - 0.6 I + 0.5 I)") {
    // a connected graph Laplacian has lambda_min = 0; margin 0.5, minus 0.6: lambda_min = -0.1,
    // while every diagonal entry stays positive
    FullMatrix M = spdFromPattern<Scalar, StorageIndex>(gridPattern(11, 9), g, 0.5, Signs::Negative);
    for (Index i = 0; i < M.rows(); ++i) M.coeffRef(i, i) -= Scalar(Real(0.6));
    typename Cfg::Reference ref(toInput<Cfg>(M));
    REQUIRE(ref.info() == Eigen::NumericalIssue);  // the reference agrees that it is not SPD
    typename Cfg::Solver llt(toInput<Cfg>(M));
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() >= 0);
    CHECK(llt.failedColumn() < M.rows());
  }
  SUBCASE("exactly singular: a block of ones gives an exact zero pivot") {
    Pattern p = blockDiagonal({randomPattern(30, 3, g), densePattern(3), tridiagonalPattern(20)});
    FullMatrix M = spdFromPattern<Scalar, StorageIndex>(p, g);
    for (Index i = 30; i < 33; ++i)
      for (Index j = 30; j < 33; ++j) M.coeffRef(i, j) = Scalar(1);
    typename Cfg::Solver llt(toInput<Cfg>(M));
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() >= 30);
    CHECK(llt.failedColumn() < 33);
  }
  SUBCASE("a NaN on the diagonal") {
    typename Cfg::Solver llt(toInput<Cfg>(withEntry<Cfg>(A, 50, 50, Scalar(nan))));
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() == 50);
  }
  SUBCASE("a NaN off the diagonal") {
    // the first pivot it reaches is that of whichever of i, j is eliminated later
    Index i = -1, j = -1;
    for (Index c = 0; c < A.outerSize() && i < 0; ++c)
      for (typename FullMatrix::InnerIterator it(A, c); it; ++it)
        if (it.row() > c && c >= 20) {
          i = it.row();
          j = c;
          break;
        }
    REQUIRE(i >= 0);
    CAPTURE(i);
    CAPTURE(j);
    typename Cfg::Solver llt(toInput<Cfg>(withEntry<Cfg>(A, i, j, Scalar(nan))));
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK((llt.failedColumn() == i || llt.failedColumn() == j));
  }
  SUBCASE("NaN in the values with 2 threads") {
    typename Cfg::Solver llt;
    llt.setThreadCount(2);
    llt.compute(toInput<Cfg>(withEntry<Cfg>(A, 17, 17, Scalar(nan))));
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() == 17);
  }
}

TEST_CASE_TEMPLATE("a failed factorize() is followed by a good one on the same pattern", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::FullMatrix FullMatrix;
  std::mt19937 g(62);
  const FullMatrix A = spdFromPattern<Scalar, StorageIndex>(gridPattern(15, 12), g);
  const FullMatrix bad = withEntry<Cfg>(A, 90, 90, Scalar(-5));
  const FullMatrix nanBad =
      withEntry<Cfg>(A, 3, 3, Scalar(std::numeric_limits<typename Cfg::RealScalar>::quiet_NaN()));
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    typename Cfg::Solver llt;
    llt.setThreadCount(threads);
    llt.analyzePattern(toInput<Cfg>(A));
    llt.factorize(toInput<Cfg>(bad));
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() == 90);
    const FullMatrix good = revalued(A, g);
    llt.factorize(toInput<Cfg>(good));
    typename Cfg::Reference ref;
    computeReference<Cfg>(ref, toInput<Cfg>(good));
    checkAgainstReference<Cfg>(llt, good, ref);
    CHECK(llt.failedColumn() == -1);
    llt.factorize(toInput<Cfg>(nanBad));
    CHECK(llt.info() == Eigen::NumericalIssue);
    llt.factorize(toInput<Cfg>(good));
    checkAgainstReference<Cfg>(llt, good, ref);
    // and compute() of a bad matrix, then of a good one
    llt.compute(toInput<Cfg>(bad));
    CHECK(llt.info() == Eigen::NumericalIssue);
    llt.compute(toInput<Cfg>(good));
    checkAgainstReference<Cfg>(llt, good, ref);
  }
}

TEST_CASE_TEMPLATE("factorize() with another pattern than the analysed one: InvalidInput", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::FullMatrix FullMatrix;
  std::mt19937 g(63);
  Pattern p = gridPattern(10, 10);
  const FullMatrix A = spdFromPattern<Scalar, StorageIndex>(p, g);

  // the changed matrices, each SPD
  std::vector<std::pair<std::string, FullMatrix>> changed;
  {
    Pattern q = p;
    q.add(0, 55);  // one extra off-diagonal pair
    q.normalize();
    changed.emplace_back("one extra entry", spdFromPattern<Scalar, StorageIndex>(q, g));
  }
  {
    Pattern q = p;
    q.edges.erase(q.edges.begin() + 40);  // one entry fewer
    changed.emplace_back("one entry fewer", spdFromPattern<Scalar, StorageIndex>(q, g));
  }
  {
    Pattern q = p;
    q.edges.erase(q.edges.begin() + 40);  // as many entries, one of them elsewhere
    q.add(99, 2);
    q.normalize();
    REQUIRE(q.edges.size() == p.edges.size());
    changed.emplace_back("same number of entries, one moved", spdFromPattern<Scalar, StorageIndex>(q, g));
  }
  {
    Pattern q = gridPattern(10, 10);
    q.n = 101;  // one more (isolated) row and column
    changed.emplace_back("one more row and column", spdFromPattern<Scalar, StorageIndex>(q, g));
  }
  {
    changed.emplace_back("one row and column fewer", spdFromPattern<Scalar, StorageIndex>(gridPattern(11, 9), g));
  }
  for (auto& c : changed) {
    INFO("changed pattern: " << c.first);
    typename Cfg::Solver llt;
    llt.analyzePattern(toInput<Cfg>(A));
    bool threw = asserts([&] { llt.factorize(toInput<Cfg>(c.second)); });
    CHECK_FALSE(threw);
    CHECK(llt.info() == Eigen::InvalidInput);
    // the analysis is still that of A: a matrix with A's pattern factorizes
    const FullMatrix good = revalued(A, g);
    llt.factorize(toInput<Cfg>(good));
    typename Cfg::Reference ref;
    computeReference<Cfg>(ref, toInput<Cfg>(good));
    checkAgainstReference<Cfg>(llt, good, ref);
    // and compute() of the changed matrix works
    llt.compute(toInput<Cfg>(c.second));
    typename Cfg::Reference ref2;
    computeReference<Cfg>(ref2, toInput<Cfg>(c.second));
    checkAgainstReference<Cfg>(llt, c.second, ref2);
  }
}

TEST_CASE_TEMPLATE("0x0 and 1x1 matrices", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::RealScalar Real;
  typedef typename Cfg::MatrixType MatrixType;
  typedef typename Cfg::Vector Vector;
  SUBCASE("0x0") {
    MatrixType A(0, 0);
    typename Cfg::Solver llt(A);
    CHECK(llt.info() == Eigen::Success);
    CHECK(llt.rows() == 0);
    CHECK(llt.cols() == 0);
    CHECK(llt.failedColumn() == -1);
    CHECK(llt.permutationP().size() == 0);
    Vector x = llt.solve(Vector(0));
    CHECK(x.size() == 0);
    CHECK(llt.determinant() == Scalar(1));
    CHECK(llt.logDeterminant() == Real(0));
    CHECK(typename Cfg::FullMatrix(llt.matrixL()).rows() == 0);
    llt.analyzePattern(A);
    llt.factorize(A);
    CHECK(llt.info() == Eigen::Success);
  }
  SUBCASE("1x1") {
    MatrixType A(1, 1);
    A.insert(0, 0) = Scalar(4);
    A.makeCompressed();
    typename Cfg::Solver llt(A);
    REQUIRE(llt.info() == Eigen::Success);
    Vector b(1);
    b << Scalar(2);
    const Vector x = llt.solve(b);
    CHECK(std::abs(x[0] - Scalar(Real(0.5))) <= 4 * Eigen::NumTraits<Real>::epsilon());
    CHECK(std::abs(llt.determinant() - Scalar(4)) <= 16 * Eigen::NumTraits<Real>::epsilon());
    CHECK(std::abs(llt.logDeterminant() - std::log(Real(4))) <= 16 * Eigen::NumTraits<Real>::epsilon());
    CHECK(typename Cfg::FullMatrix(llt.matrixL()).coeff(0, 0) == Scalar(2));
    CHECK(llt.permutationP().indices()[0] == 0);
    // -1, 0: not positive definite
    A.coeffRef(0, 0) = Scalar(-1);
    llt.factorize(A);
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() == 0);
    A.coeffRef(0, 0) = Scalar(0);
    llt.factorize(A);
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() == 0);
    // a 1x1 matrix with no stored entry: zero, unless shifted
    MatrixType E(1, 1);
    typename Cfg::Solver empty(E);
    CHECK(empty.info() == Eigen::NumericalIssue);
    empty.setShift(Real(9));
    empty.compute(E);
    CHECK(empty.info() == Eigen::Success);
    CHECK(std::abs(empty.determinant() - Scalar(9)) <= 64 * Eigen::NumTraits<Real>::epsilon());
  }
}

namespace {

/** A user ordering that can be told to return something that is not a permutation. */
template <typename StorageIndex>
struct BrokenOrdering {
  typedef Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, StorageIndex> PermutationType;
  enum Mode { Valid, RepeatedIndex, IndexOutOfRange, NegativeIndex, WrongSize };
  Mode mode = Valid;
  template <typename MatrixType>
  void operator()(const MatrixType& A, PermutationType& Pinv) {
    const Index n = A.cols();
    Pinv.resize(mode == WrongSize ? n + 1 : n);
    for (Index k = 0; k < Pinv.size(); ++k) Pinv.indices()[k] = StorageIndex(Pinv.size() - 1 - k);
    if (mode == RepeatedIndex) Pinv.indices()[0] = Pinv.indices()[1];
    if (mode == IndexOutOfRange) Pinv.indices()[0] = StorageIndex(n);
    if (mode == NegativeIndex) Pinv.indices()[n / 2] = StorageIndex(-1);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("an ordering functor that returns no permutation: InvalidInput", Cfg, d_int_col_lower_amd,
                   cd_long_row_upper_amd) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef BrokenOrdering<StorageIndex> Ordering;
  typedef Eigen::UpdatableSupernodalLLT<typename Cfg::MatrixType, Cfg::UpLo, Ordering> Solver;
  std::mt19937 g(65);
  const typename Cfg::FullMatrix A = spdFromPattern<Scalar, StorageIndex>(gridPattern(7, 6), g);
  const typename Cfg::MatrixType input = toInput<Cfg>(A);
  Solver llt;
  for (auto mode : {Ordering::RepeatedIndex, Ordering::IndexOutOfRange, Ordering::NegativeIndex, Ordering::WrongSize}) {
    CAPTURE(int(mode));
    llt.ordering().mode = mode;
    CHECK_FALSE(asserts([&] { llt.compute(input); }));
    CHECK(llt.info() == Eigen::InvalidInput);
  }
  llt.ordering().mode = Ordering::Valid;
  llt.compute(input);
  typename Cfg::Reference ref(input);
  checkAgainstReference<Cfg>(llt, A, ref);
}

TEST_CASE_TEMPLATE("misuse trips eigen_assert", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Vector Vector;
  typedef typename Cfg::Scalar Scalar;
  std::mt19937 g(64);
  const typename Cfg::FullMatrix A = spdFromPattern<Scalar, typename Cfg::StorageIndex>(gridPattern(6, 6), g);
  const Vector b = Vector::Ones(A.rows());

  SUBCASE("solve before compute") {
    typename Cfg::Solver llt;
    CHECK(asserts([&] { Vector x = llt.solve(b); }));
  }
  SUBCASE("solve after analyzePattern only") {
    typename Cfg::Solver llt;
    llt.analyzePattern(toInput<Cfg>(A));
    CHECK(asserts([&] { Vector x = llt.solve(b); }));
  }
  SUBCASE("right-hand side of the wrong size") {
    typename Cfg::Solver llt(toInput<Cfg>(A));
    REQUIRE(llt.info() == Eigen::Success);
    CHECK(asserts([&] { Vector x = llt.solve(Vector(Vector::Ones(A.rows() + 1))); }));
  }
  SUBCASE("factorize before analyzePattern: assert or InvalidInput") {
    typename Cfg::Solver llt;
    const bool threw = asserts([&] { llt.factorize(toInput<Cfg>(A)); });
    CHECK((threw || llt.info() == Eigen::InvalidInput));
  }
  SUBCASE("a rectangular matrix: assert or InvalidInput") {
    typename Cfg::MatrixType R(5, 4);
    R.insert(0, 0) = Scalar(1);
    typename Cfg::Solver llt;
    const bool threw = asserts([&] { llt.compute(R); });
    CHECK((threw || llt.info() == Eigen::InvalidInput));
  }
  SUBCASE("a correct use does not assert") {
    typename Cfg::Solver llt;
    CHECK_FALSE(asserts([&] {
      llt.compute(toInput<Cfg>(A));
      Vector x = llt.solve(b);
    }));
  }
}
