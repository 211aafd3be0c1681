// solve(): dense right-hand sides of 1, 3 and 17 columns (dynamic and fixed-size, column- and
// row-major), results written into a block, a column, a Map and the right-hand side itself, a
// right-hand side that is an expression or a Map, and sparse right-hand sides giving sparse and
// dense results, each compared with SimplicialLLT's solve of the same system; 1 to 5 right-hand
// sides on factors of many tiny supernodes and of one huge one (every kernel of the solve); the
// kept forward substitution (setSolveCaching()): a partly changed right-hand side substitutes only
// above the change and gives bitwise a full pass's result; solves running concurrently.
#include "test_checks.h"

#include <memory>
#include <thread>

using namespace uctest;

namespace {

template <typename Cfg>
struct Fixture {
  typename Cfg::FullMatrix A;
  typename Cfg::MatrixType input;
  typename Cfg::Solver llt;
  typename Cfg::Reference ref;
  std::unique_ptr<SolveBounds<Cfg>> bounds;  // what the tolerances are made of (see test_checks.h)
  explicit Fixture(const Pattern& p, unsigned seed = 1) {
    std::mt19937 g(seed);
    A = spdFromPattern<typename Cfg::Scalar, typename Cfg::StorageIndex>(p, g);
    input = toInput<Cfg>(A);
    llt.compute(input);
    computeReference<Cfg>(ref, input);
    REQUIRE(llt.info() == Eigen::Success);
    REQUIRE(ref.info() == Eigen::Success);
    bounds.reset(new SolveBounds<Cfg>(llt, ref, A, seed + 1));
  }
};

/** A pattern factored with a given supernode relaxation. */
struct RelaxedCase {
  const char* what;
  Pattern pattern;
  Eigen::SupernodeRelaxation relaxation;
};

/** A relaxation with the same nrelax and zrelax at all three levels (0, 0: fundamental supernodes). */
inline Eigen::SupernodeRelaxation uniformRelaxation(int nrelax, double zrelax) {
  Eigen::SupernodeRelaxation r;
  for (int k = 0; k < 3; ++k) {
    r.nrelax[k] = nrelax;
    r.zrelax[k] = zrelax;
  }
  return r;
}

/** The fixture of \a c, refactored with its relaxation. */
template <typename Cfg>
void refactorWithRelaxation(Fixture<Cfg>& f, const RelaxedCase& c) {
  f.llt.setRelaxation(c.relaxation);
  f.llt.compute(f.input);
  REQUIRE(f.llt.info() == Eigen::Success);
}

/** Every column: || A x - r || within the backward-error tolerance, and x agrees with the
  * reference's solution of the same right-hand side. */
template <typename Cfg, typename DenseX, typename DenseR>
void checkSolution(const Fixture<Cfg>& f, const DenseX& X, const DenseR& R) {
  typedef typename Cfg::Dense Dense;
  REQUIRE(X.rows() == R.rows());
  REQUIRE(X.cols() == R.cols());
  if (f.A.rows() == 0) return;
  const Dense Xref = f.ref.solve(Dense(R));
  for (Index j = 0; j < R.cols(); ++j) {
    CAPTURE(j);
    const double xnorm = double(X.col(j).norm()), xrefnorm = double(Xref.col(j).norm());
    const double residual = double((f.A * X.col(j) - R.col(j)).norm());
    const double difference = double((X.col(j) - Xref.col(j)).norm());
    CHECK(residual <= f.bounds->residual(f.bounds->mine, xnorm, double(R.col(j).norm())));
    CHECK(difference <= f.bounds->solution(xnorm, xrefnorm));
  }
}

}  // namespace

TEST_CASE_TEMPLATE("dense right-hand sides of 1, 3 and 17 columns", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Dense Dense;
  std::mt19937 g(41);
  for (Index n : {Index(0), Index(1), Index(5), Index(400)}) {
    CAPTURE(n);
    Fixture<Cfg> f(Cfg::fillReducing ? randomPattern(n, 4, g) : bandedRandomPattern(n, 8, 0.5, g));
    for (Index k : {Index(1), Index(3), Index(17)}) {
      CAPTURE(k);
      const Dense B = randomDense<Cfg>(n, k, g);
      const Dense X = f.llt.solve(B);
      checkSolution<Cfg>(f, X, B);
      // the columns solved one by one give the same result as the block solve
      Dense Xcols(n, k);
      for (Index j = 0; j < k; ++j) Xcols.col(j) = f.llt.solve(B.col(j));
      checkSolution<Cfg>(f, Xcols, B);
    }
  }
}

TEST_CASE_TEMPLATE("1 to 5 right-hand sides on factors of many tiny supernodes and of one huge one", Cfg, UC_CONFIGS) {
  // The solve has inline kernels for up to 4 right-hand sides on supernodes of up to
  // SmallSolveColumns (128) columns, blocks of 4 columns, and BLAS above: every path and every
  // remainder of 4 appears here.
  typedef typename Cfg::Dense Dense;
  std::mt19937 g(73);
  const Eigen::SupernodeRelaxation fundamental = uniformRelaxation(0, 0), huge = uniformRelaxation(1 << 30, 1e30);
  const RelaxedCase cases[] = {
      {"tridiagonal, fundamental supernodes (one or two columns each)", tridiagonalPattern(97), fundamental},
      {"random, fundamental supernodes", randomPattern(120, 3, g), fundamental},
      {"dense 101: one supernode solved inline", densePattern(101), Eigen::SupernodeRelaxation()},
      {"dense 203: one supernode solved with BLAS", densePattern(203), Eigen::SupernodeRelaxation()},
      {"random 300, everything amalgamated", randomPattern(300, 4, g), huge},
      {"banded 250, default relaxation", bandedRandomPattern(250, 9, 0.4, g), Eigen::SupernodeRelaxation()}};
  for (const RelaxedCase& c : cases) {
    CAPTURE(c.what);
    Fixture<Cfg> f(c.pattern, 7);
    refactorWithRelaxation(f, c);
    const Index n = f.A.rows();
    if (c.relaxation.nrelax[0] == 0 && c.pattern.edges.size() < std::size_t(n)) CHECK(f.llt.supernodeCount() >= n / 2);
    if (c.pattern.edges.size() == std::size_t(n * (n - 1) / 2)) CHECK(f.llt.supernodeCount() == 1);
    for (Index k = 1; k <= 5; ++k) {
      CAPTURE(k);
      const Dense B = randomDense<Cfg>(n, k, g);
      const Dense X = f.llt.solve(B);
      checkSolution<Cfg>(f, X, B);
      if (k == 5) {  // each column alone (one-rhs kernels) agrees with the block
        Dense Xcols(n, k);
        for (Index j = 0; j < k; ++j) Xcols.col(j) = f.llt.solve(B.col(j));
        checkSolution<Cfg>(f, Xcols, B);
      }
    }
  }
}

TEST_CASE_TEMPLATE("a solve reuses the previous forward substitution where its right-hand side did not change", Cfg,
                   UC_CONFIGS) {
  typedef typename Cfg::Dense Dense;
  std::mt19937 g(91);
  const RelaxedCase cases[] = {{"tridiagonal, fundamental supernodes", tridiagonalPattern(97), uniformRelaxation(0, 0)},
                               {"random 300, default relaxation", randomPattern(300, 4, g), Eigen::SupernodeRelaxation()},
                               {"dense 203: one supernode solved with BLAS", densePattern(203), Eigen::SupernodeRelaxation()}};
  for (const RelaxedCase& c : cases) {
    CAPTURE(c.what);
    Fixture<Cfg> f(c.pattern, 5);
    refactorWithRelaxation(f, c);
    REQUIRE(f.llt.solveCaching());
    const Index n = f.A.rows();
    // the row eliminated last lies in a root supernode: changing it redoes that supernode only
    const Index lastRow = Index(f.llt.permutationPinv().indices()[n - 1]);
    for (Index k : {Index(1), Index(2), Index(5), Index(9)}) {
      CAPTURE(k);
      const bool kept = k <= Index(Cfg::Solver::MaxCachedRightHandSides);
      Dense B = randomDense<Cfg>(n, k, g);
      const Dense X0 = f.llt.solve(B);  // (solve() is lazy: evaluated here, once)
      CHECK(f.llt.lastSolveForwardColumns() == n);
      checkSolution<Cfg>(f, X0, B);
      B.row(lastRow) = randomDense<Cfg>(1, k, g);
      const Dense X = f.llt.solve(B);
      checkSolution<Cfg>(f, X, B);
      if (kept && f.llt.supernodeCount() > 1) CHECK(f.llt.lastSolveForwardColumns() < n);
      if (!kept) CHECK(f.llt.lastSolveForwardColumns() == n);
      const Dense again = f.llt.solve(B);  // the same right-hand side: nothing to substitute
      CHECK(f.llt.lastSolveForwardColumns() == (kept ? 0 : n));
      CHECK(double((again - X).norm()) == 0);
      const Dense other = f.llt.solve(randomDense<Cfg>(n, k, g));  // a full pass, then B again: a full pass
      (void)other;
      const Dense full = f.llt.solve(B);
      CHECK(f.llt.lastSolveForwardColumns() == n);
      CHECK(double((full - X).norm()) == 0);
    }
    f.llt.setSolveCaching(false);  // plain solves, no memory kept
    const Dense B = randomDense<Cfg>(n, 2, g);
    const Dense X1 = f.llt.solve(B), X2 = f.llt.solve(B);
    CHECK(f.llt.lastSolveForwardColumns() == n);
    checkSolution<Cfg>(f, X1, B);
    checkSolution<Cfg>(f, X2, B);
    f.llt.setSolveCaching(true);
  }
}

TEST_CASE_TEMPLATE("solves running concurrently on one object", Cfg, UC_CORE_CONFIGS) {
  // solve() is const: concurrent calls must all be right (one of them uses the kept substitution)
  typedef typename Cfg::Dense Dense;
  std::mt19937 g(17);
  Fixture<Cfg> f(randomPattern(400, 4, g), 3);
  const Index n = f.A.rows();
  const int threads = 4, solves = 12;
  std::vector<Dense> B(threads * solves), X(threads * solves);
  for (auto& b : B) b = randomDense<Cfg>(n, 1 + Index(g() % 3), g);
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t]() {
      for (int s = 0; s < solves; ++s) X[t * solves + s] = f.llt.solve(B[t * solves + s]);
    });
  for (auto& th : pool) th.join();
  for (int i = 0; i < threads * solves; ++i) {
    CAPTURE(i);
    checkSolution<Cfg>(f, X[i], B[i]);
  }
}

TEST_CASE_TEMPLATE("solve into blocks, columns, Maps and in place; from expressions", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::Dense Dense;
  typedef typename Cfg::Vector Vector;
  std::mt19937 g(42);
  const Index n = 300;
  Fixture<Cfg> f(Cfg::fillReducing ? randomPattern(n, 4, g) : bandedRandomPattern(n, 8, 0.5, g));
  const Dense B = randomDense<Cfg>(n, 2, g);
  const Vector b = B.col(0);

  SUBCASE("into a block of columns: X.middleCols(1,2) = llt.solve(B)") {
    Dense X = Dense::Constant(n, 5, Scalar(7));
    X.middleCols(1, 2) = f.llt.solve(B);
    checkSolution<Cfg>(f, Dense(X.middleCols(1, 2)), B);
    CHECK((X.col(0).array() == Scalar(7)).all());  // the other columns are untouched
    CHECK((X.middleCols(3, 2).array() == Scalar(7)).all());
  }
  SUBCASE("into a block of rows of a taller matrix") {
    Dense X = Dense::Constant(n + 4, 2, Scalar(7));
    X.middleRows(2, n) = f.llt.solve(B);
    checkSolution<Cfg>(f, Dense(X.middleRows(2, n)), B);
    CHECK((X.topRows(2).array() == Scalar(7)).all());
    CHECK((X.bottomRows(2).array() == Scalar(7)).all());
  }
  SUBCASE("into a column: x.col(0) = llt.solve(b)") {
    Dense X = Dense::Zero(n, 3);
    X.col(2) = f.llt.solve(b);
    checkSolution<Cfg>(f, Dense(X.col(2)), Dense(b));
    CHECK(X.leftCols(2).norm() == 0);
  }
  SUBCASE("into a Map over a plain buffer") {
    std::vector<Scalar> buffer(2 * n + 1, Scalar(7));
    Eigen::Map<Dense> X(buffer.data(), n, 2);
    X = f.llt.solve(B);
    checkSolution<Cfg>(f, Dense(X), B);
    CHECK(buffer[2 * n] == Scalar(7));
  }
  SUBCASE("into a strided Map (every other row of a buffer)") {
    std::vector<Scalar> buffer(2 * n, Scalar(7));
    Eigen::Map<Vector, 0, Eigen::InnerStride<2>> x(buffer.data(), n);
    x = f.llt.solve(b);
    checkSolution<Cfg>(f, Dense(Vector(x)), Dense(b));
    bool untouched = true;
    for (Index i = 0; i < n; ++i) untouched = untouched && buffer[2 * i + 1] == Scalar(7);
    CHECK(untouched);
  }
  SUBCASE("from a Map and from an expression") {
    std::vector<Scalar> buffer(b.data(), b.data() + n);
    Eigen::Map<const Vector> bm(buffer.data(), n);
    Vector x1 = f.llt.solve(bm);
    checkSolution<Cfg>(f, Dense(x1), Dense(b));
    Vector x2 = f.llt.solve(Scalar(2) * b - b);
    checkSolution<Cfg>(f, Dense(x2), Dense(b));
    Dense X3 = f.llt.solve(B.transpose().transpose());
    checkSolution<Cfg>(f, X3, B);
  }
  SUBCASE("in place: x = llt.solve(x)") {
    Vector x = b;
    x = f.llt.solve(x);
    checkSolution<Cfg>(f, Dense(x), Dense(b));
    Dense X = B;
    X = f.llt.solve(X);
    checkSolution<Cfg>(f, X, B);
  }
  SUBCASE("row-major and fixed-column right-hand sides") {
    Eigen::Matrix<Scalar, Eigen::Dynamic, 3, Eigen::RowMajor> Br = randomDense<Cfg>(n, 3, g);
    Eigen::Matrix<Scalar, Eigen::Dynamic, 3, Eigen::RowMajor> Xr = f.llt.solve(Br);
    checkSolution<Cfg>(f, Dense(Xr), Dense(Br));
    Eigen::Matrix<Scalar, Eigen::Dynamic, 2> Xf = f.llt.solve(B);
    checkSolution<Cfg>(f, Dense(Xf), B);
  }
  SUBCASE("repeated solves give the same answer") {
    const Vector x1 = f.llt.solve(b);
    const Vector x2 = f.llt.solve(b);
    CHECK(x1 == x2);
  }
}

TEST_CASE_TEMPLATE("sparse right-hand sides", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::Dense Dense;
  typedef Eigen::SparseMatrix<Scalar, Eigen::ColMajor, typename Cfg::StorageIndex> SparseCol;
  std::mt19937 g(43);
  for (Index n : {Index(1), Index(6), Index(500)}) {
    CAPTURE(n);
    Fixture<Cfg> f(Cfg::fillReducing ? randomPattern(n, 4, g) : bandedRandomPattern(n, 8, 0.5, g));
    for (Index k : {Index(1), Index(3), Index(17), Index(70)}) {
      CAPTURE(k);
      // a few entries per column, one empty column
      SparseCol Bs(n, k);
      std::uniform_int_distribution<Index> row(0, n - 1);
      for (Index j = 0; j < k; ++j)
        if (j != 1)
          for (int e = 0; e < 3; ++e) Bs.coeffRef(row(g), j) = randomOffDiagonal<Scalar>(g);
      Bs.makeCompressed();
      const Dense Bd = Dense(Bs);
      SparseCol Xs = f.llt.solve(Bs);
      REQUIRE(Xs.rows() == n);
      REQUIRE(Xs.cols() == k);
      checkSolution<Cfg>(f, Dense(Xs), Bd);
      // the sparse result equals the dense solve of the same right-hand side (to rounding)
      const Dense Xd = f.llt.solve(Bd);
      CHECK(double((Dense(Xs) - Xd).norm()) <=
            1e3 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon()) * double(Xd.norm()));
      // a sparse right-hand side with a dense result
      const Dense XfromSparse = f.llt.solve(Bs);
      checkSolution<Cfg>(f, XfromSparse, Bd);
      // a sparse block of columns as right-hand side (Eigen's sparse solve takes column-major only)
      if (k >= 3) {
        SparseCol Xb = f.llt.solve(SparseCol(Bs.middleCols(1, 2)));
        checkSolution<Cfg>(f, Dense(Xb), Dense(Bd.middleCols(1, 2)));
      }
    }
  }
}

TEST_CASE_TEMPLATE("solve of a 0x0 system", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Dense Dense;
  typename Cfg::MatrixType A(0, 0);
  typename Cfg::Solver llt(A);
  CHECK(llt.info() == Eigen::Success);
  Dense X = llt.solve(Dense(0, 3));
  CHECK(X.rows() == 0);
  CHECK(X.cols() == 3);
}
