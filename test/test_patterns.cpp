// Awkward sparsity patterns and input forms, each compared with SimplicialLLT: diagonal, dense,
// tridiagonal, arrows pointing both ways, a star, disconnected blocks with isolated vertices, an
// empty off-diagonal column inside a connected matrix, an embedded clique, a deep path, 2x2 and
// tiny cases; inputs holding only the triangle that UpLo names, garbage (and a NaN) in the
// triangle that is not read, explicitly stored zeros, uncompressed input, bad diagonal scaling.
#include "test_checks.h"

using namespace uctest;

namespace {

/** Removes every off-diagonal entry of vertex v: column v of the matrix becomes empty below and
  * above the diagonal. */
Pattern isolate(Pattern p, Index v) {
  Pattern q;
  q.n = p.n;
  for (auto e : p.edges)
    if (e.first != v && e.second != v) q.add(e.first, e.second);
  q.normalize();
  return q;
}

/** Adds a clique on the vertices first..first+k-1. */
Pattern withClique(Pattern p, Index first, Index k) {
  for (Index i = first; i < first + k; ++i)
    for (Index j = first; j < i; ++j) p.add(i, j);
  p.normalize();
  return p;
}

}  // namespace

TEST_CASE_TEMPLATE("awkward patterns", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(31);
  const Index big = Cfg::isPrimary ? 2000 : 300;
  struct Case {
    std::string name;
    Pattern p;
  };
  std::vector<Case> cases = {
      {"1x1", diagonalPattern(1)},
      {"2x2 dense", densePattern(2)},
      {"2x2 diagonal", diagonalPattern(2)},
      {"3x3 dense", densePattern(3)},
      {"diagonal", diagonalPattern(big)},
      {"dense 60", densePattern(60)},
      {"tridiagonal", tridiagonalPattern(big)},
      {"arrow, dense last row/column", arrowPattern(big, true)},
      {"arrow, dense first row/column", arrowPattern(Cfg::fillReducing ? big : 200, false)},
      {"star, hub in the middle", starPattern(big, big / 2)},
      {"scrambled path", scrambledPathPattern(Cfg::fillReducing ? big : 300, g)},
      {"grid 5-point", gridPattern(30, Cfg::isPrimary ? 40 : 10)},
      {"empty off-diagonal column in a connected grid", isolate(gridPattern(12, 12), 77)},
      {"empty off-diagonal first and last columns", isolate(isolate(tridiagonalPattern(50), 0), 49)},
      {"clique inside a sparse graph", withClique(gridPattern(15, 15), 60, 40)},
      {"disconnected blocks and isolated vertices",
       blockDiagonal({densePattern(7), diagonalPattern(3), gridPattern(8, 9), tridiagonalPattern(20),
                      diagonalPattern(1), arrowPattern(15, false), densePattern(1), randomPattern(40, 3, g)})},
      {"disconnected blocks, interleaved numbering",
       shuffled(blockDiagonal({gridPattern(10, 10), densePattern(12), diagonalPattern(5), tridiagonalPattern(30)}),
                g)},
  };
  for (const Case& c : cases) {
    INFO("pattern: " << c.name);
    computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(c.p, g));
  }
  // graph-Laplacian values (all off-diagonals negative) on the same shapes
  for (const Case& c : cases) {
    INFO("pattern (Laplacian values): " << c.name);
    computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(c.p, g, 0.5, Signs::Negative));
  }
}

TEST_CASE_TEMPLATE("input holding one triangle only, or garbage in the other", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(32);
  const std::vector<Pattern> patterns = {randomPattern(200, 4, g), arrowPattern(50, false), densePattern(20),
                                         diagonalPattern(10), tridiagonalPattern(100)};
  for (const Pattern& p : patterns) {
    const typename Cfg::FullMatrix A = spdFromPattern<Scalar, StorageIndex>(p, g);
    computeAndCheck<Cfg>(A, Storage::TriangleOnly);
    computeAndCheck<Cfg>(A, Storage::GarbageElsewhere);
  }
}

TEST_CASE("upper-only input read with Upper, lower-only read with Lower, both give the same factor") {
  typedef Config<double, int, ColMajor, Upper, AMDOrdering<int>> Up;
  typedef Config<double, int, ColMajor, Lower, AMDOrdering<int>> Lo;
  std::mt19937 g(33);
  const Up::FullMatrix A = spdFromPattern<double, int>(randomPattern(500, 5, g), g);
  computeAndCheck<Up>(A, Storage::TriangleOnly);
  computeAndCheck<Lo>(A, Storage::TriangleOnly);
  Up::Solver up(toInput<Up>(A, Storage::TriangleOnly));
  Lo::Solver lo(toInput<Lo>(A, Storage::TriangleOnly));
  REQUIRE(up.info() == Eigen::Success);
  REQUIRE(lo.info() == Eigen::Success);
  CHECK(up.permutationP().indices() == lo.permutationP().indices());
  CHECK(factorDifference<Up>(up, lo) <= 64 * std::numeric_limits<double>::epsilon());
}

TEST_CASE_TEMPLATE("explicitly stored zeros and uncompressed input", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::FullMatrix FullMatrix;
  std::mt19937 g(34);
  FullMatrix A = spdFromPattern<Scalar, StorageIndex>(gridPattern(20, 20), g);
  // stored zeros off the diagonal (a cotan Laplacian of a regular grid has them)
  for (Index j = 0; j < A.outerSize(); ++j)
    for (typename FullMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() != it.col() && (it.row() + it.col()) % 4 == 1) it.valueRef() = Scalar(0);
  computeAndCheck<Cfg>(A);

  // uncompressed input: room reserved in every inner vector, entries inserted one by one
  typename Cfg::MatrixType U(A.rows(), A.cols());
  U.reserve(Eigen::VectorXi::Constant(A.outerSize(), 9));
  for (Index j = 0; j < A.outerSize(); ++j)
    for (typename FullMatrix::InnerIterator it(A, j); it; ++it) U.insert(it.row(), it.col()) = it.value();
  REQUIRE(!U.isCompressed());
  typename Cfg::Solver llt(U);
  typename Cfg::Reference ref;
  computeReference<Cfg>(ref, U);
  checkAgainstReference<Cfg>(llt, A, ref);
  // and factorize() of uncompressed input on a pattern analysed from compressed input
  typename Cfg::Solver llt2;
  llt2.analyzePattern(toInput<Cfg>(A));
  llt2.factorize(U);
  checkAgainstReference<Cfg>(llt2, A, ref);
}

TEST_CASE_TEMPLATE("badly scaled matrices", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(35);
  // D A D with D = diag(10^u): the reference estimate of lambda_min reflects the bad scaling, so
  // keep the condition number within what the scalar can resolve
  const double e = Eigen::NumTraits<typename Cfg::RealScalar>::epsilon() < 1e-10 ? 3 : 1;
  const typename Cfg::FullMatrix A = spdFromPattern<Scalar, StorageIndex>(randomPattern(300, 4, g), g);
  computeAndCheck<Cfg>(diagonallyScaled(A, e, g));
  // uniformly tiny and huge matrices
  computeAndCheck<Cfg>(diagonallyScaled(A, 0, g) * Scalar(typename Cfg::RealScalar(1e-15)));
  computeAndCheck<Cfg>(diagonallyScaled(A, 0, g) * Scalar(typename Cfg::RealScalar(1e15)));
}
