// Factorization of random Hermitian positive definite matrices: many sizes (0 to 3000) and densities
// (diagonal to dense), well and badly conditioned, for every configuration; many small matrices of
// random shapes, storage forms and shifts (fuzzing; the primary configuration also draws relaxation
// settings and thread counts); then one analyzePattern followed by many factorize() calls with new
// values on the same pattern, compared with a fresh compute() (which must give the same factor bit
// for bit) and with SimplicialLLT; and the dense kernels' blocked paths (potrf by halves, the
// triangular solve by panels) on their own.
#include "test_checks.h"

using namespace uctest;

namespace {

/** Random pattern of n vertices and about `degree` off-diagonal entries per row; for orderings
  * that do not reduce fill, large sizes get a banded pattern instead (natural/reverse order of a
  * random graph of 3000 vertices is a dense factor). */
template <typename Cfg>
Pattern randomOrBanded(Index n, double degree, std::mt19937& g) {
  if (Cfg::fillReducing || n <= 500) return randomPattern(n, degree, g);
  return bandedRandomPattern(n, 12, std::min(1.0, degree / 12), g);
}

}  // namespace

TEST_CASE_TEMPLATE("random SPD matrices of many sizes and densities", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(2024);
  const Index sizes[] = {0, 1, 2, 5, 50, 500, 3000};
  for (Index n : sizes) {
    // average off-diagonal entries per row: none, sparse, denser; dense for the small sizes
    std::vector<double> degrees = {0, 2.5};
    if (n <= 500) degrees.push_back(8);
    if (n <= 50 || (n == 500 && Cfg::isPrimary)) degrees.push_back(double(n));
    for (double degree : degrees) {
      CAPTURE(n);
      CAPTURE(degree);
      const Pattern p = randomOrBanded<Cfg>(n, degree, g);
      computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(p, g, 1.0));
    }
  }
}

TEST_CASE_TEMPLATE("random SPD matrices: conditioning, banding, relabelling", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(77);
  // weighted graph Laplacians + margin*I: lambda_min ~ margin, lambda_max ~ 2*degree
  const double margin = Eigen::NumTraits<typename Cfg::RealScalar>::epsilon() < 1e-10 ? 1e-6 : 1e-2;
  for (Index n : {Index(20), Index(400)}) {
    CAPTURE(n);
    const Pattern p = randomOrBanded<Cfg>(n, 4, g);
    computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(p, g, margin, Signs::Negative));
  }
  // banded with long-range entries, and the same matrix relabelled at random
  const Pattern band = bandedRandomPattern(Cfg::isPrimary ? 2000 : 600, 15, 0.4, g);
  computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(band, g));
  if (Cfg::fillReducing) computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(shuffled(band, g), g));
  if (Cfg::isPrimary) {
    // the primary configuration also sees larger, denser random graphs
    computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(randomPattern(1500, 6, g), g));
    computeAndCheck<Cfg>(spdFromPattern<Scalar, StorageIndex>(randomPattern(300, 60, g), g, 1e-3));
  }
}

TEST_CASE_TEMPLATE("many small random matrices of random shapes (fuzzing)", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(99);
  const int count = Cfg::isPrimary ? 1500 : 200;
  std::uniform_int_distribution<int> size(1, 90), kind(0, 5), storage(0, 2), coin(0, 1);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < count; ++trial) {
    CAPTURE(trial);
    const Index n = size(g);
    Pattern p;
    switch (kind(g)) {
      case 0: p = randomPattern(n, unit(g) * double(n) * 0.5, g); break;
      case 1: p = bandedRandomPattern(n, 1 + n / 8, unit(g), g); break;
      case 2: p = blockDiagonal({randomPattern(n / 2, 3, g), densePattern(n / 4), diagonalPattern(n - n / 2 - n / 4)}); break;
      case 3: p = shuffled(arrowPattern(n, coin(g) == 1), g); break;
      case 4: p = shuffled(gridPattern(1 + n / 9, 9), g); break;
      default: p = shuffled(randomPattern(n, 2, g), g); break;
    }
    const bool laplacian = coin(g) == 1;
    const typename Cfg::FullMatrix A = spdFromPattern<Scalar, StorageIndex>(
        p, g, laplacian ? 0.05 : 1.0, laplacian ? Signs::Negative : Signs::Random);
    CheckOptions o;
    o.seed = unsigned(trial);
    if (coin(g) == 1) o.offset = unit(g);
    const Storage s = Storage(storage(g));
    if (!Cfg::isPrimary) {
      computeAndCheck<Cfg>(A, s, o);
      continue;
    }
    // the primary configuration also draws relaxation settings and the thread count
    Eigen::SupernodeRelaxation r;
    for (int k = 0; k < 3; ++k) {
      r.nrelax[k] = std::uniform_int_distribution<int>(0, 64)(g);
      r.zrelax[k] = unit(g);
    }
    const int threads = 1 + coin(g);
    CAPTURE(threads);
    INFO("relaxation nrelax " << r.nrelax[0] << " " << r.nrelax[1] << " " << r.nrelax[2] << ", zrelax " << r.zrelax[0]
                              << " " << r.zrelax[1] << " " << r.zrelax[2]);
    const typename Cfg::MatrixType input = toInput<Cfg>(A, s, o.seed);
    typename Cfg::Solver llt;
    llt.setRelaxation(r);
    llt.setThreadCount(threads);
    llt.setShift(o.offset);
    llt.compute(input);
    typename Cfg::Reference ref;
    computeReference<Cfg>(ref, input, o.offset);
    checkAgainstReference<Cfg>(llt, A, ref, o);
  }
}

TEST_CASE_TEMPLATE("one analyzePattern, many factorize calls on the same pattern", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::FullMatrix FullMatrix;
  std::mt19937 g(5);
  const Index n = Cfg::isPrimary ? 1200 : 300;
  const Pattern p = randomOrBanded<Cfg>(n, 5, g);
  const FullMatrix A0 = spdFromPattern<Scalar, StorageIndex>(p, g);

  typename Cfg::Solver llt;
  llt.analyzePattern(toInput<Cfg>(A0));
  std::vector<FullMatrix> values;
  for (int k = 0; k < 6; ++k) {
    CAPTURE(k);
    FullMatrix Ak = revalued(A0, g);
    if (k == 3) {  // explicit zeros on the pattern are still the same pattern
      int z = 0;
      for (Index j = 0; j < Ak.outerSize(); ++j)
        for (typename FullMatrix::InnerIterator it(Ak, j); it; ++it)
          if (it.row() != it.col() && (it.row() + it.col()) % 3 == 0) {
            it.valueRef() = Scalar(0);
            ++z;
          }
      CAPTURE(z);
    }
    values.push_back(Ak);
    const typename Cfg::MatrixType input = toInput<Cfg>(Ak);
    llt.factorize(input);
    typename Cfg::Reference ref;
    computeReference<Cfg>(ref, input);
    checkAgainstReference<Cfg>(llt, Ak, ref);

    // a fresh compute() of the same matrix: the same permutation and the same factor, bit for bit
    typename Cfg::Solver fresh(input);
    REQUIRE(fresh.info() == Eigen::Success);
    CHECK(sameFactorBitwise<Cfg>(llt, fresh));
    CHECK(factorDifference<Cfg>(llt, fresh) <= 0.0);
  }
  // going back to earlier values gives the earlier factor again
  typename Cfg::Solver first(toInput<Cfg>(values[0]));
  llt.factorize(toInput<Cfg>(values[0]));
  CHECK(llt.info() == Eigen::Success);
  CHECK(sameFactorBitwise<Cfg>(llt, first));
}

TEST_CASE_TEMPLATE("the same object computes matrices of different patterns and sizes", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(11);
  typename Cfg::Solver llt;
  for (Index n : {Index(40), Index(300), Index(0), Index(7), Index(40)}) {
    CAPTURE(n);
    const typename Cfg::FullMatrix A = spdFromPattern<Scalar, StorageIndex>(randomPattern(n, 3, g), g);
    const typename Cfg::MatrixType input = toInput<Cfg>(A);
    llt.compute(input);
    typename Cfg::Reference ref;
    computeReference<Cfg>(ref, input);
    checkAgainstReference<Cfg>(llt, A, ref);
    // analyzePattern + factorize spelled out does the same
    typename Cfg::Solver twoStep;
    twoStep.analyzePattern(input);
    twoStep.factorize(input);
    CHECK(twoStep.info() == Eigen::Success);
    CHECK(sameFactorBitwise<Cfg>(llt, twoStep));
  }
}

TEST_CASE_TEMPLATE("dense kernels: potrf by halves and the triangular solve by panels", Cfg, UC_CORE_CONFIGS) {
  // potrf() splits blocks above PotrfLeafColumns columns in two (with BLAS), trsmRightLowerAdjoint()
  // goes by panels of TrsmPanelColumns columns: the factor reproduces the block, a bad pivot in
  // either half (negative or NaN) is reported at its own column, and the panel solve agrees with
  // Eigen's triangular solve.
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::RealScalar Real;
  typedef Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> Dense;
  namespace uc = Eigen::internal::updatable_cholesky;
  const Real eps = Eigen::NumTraits<Real>::epsilon();
  for (Index n : {Index(100), Index(130), Index(300)}) {
    CAPTURE(n);
    const Dense B = Dense::Random(n, n);
    Dense A = B * B.adjoint();
    A.diagonal().array() += Scalar(Real(n));
    Dense L = A;
    REQUIRE(uc::potrf(n, L.data(), n) == -1);
    L = L.template triangularView<Eigen::Lower>();
    CHECK((L * L.adjoint() - A).norm() <= Real(10) * Real(n) * eps * A.norm());
    for (Index bad : {Index(3), n / 2 + 7, n - 2}) {  // (first half, second half, last leaf)
      CAPTURE(bad);
      Dense C = A;
      C(bad, bad) = Scalar(Real(-1));
      CHECK(uc::potrf(n, C.data(), n) == bad);
      C = A;
      C(bad, bad) = Scalar(std::numeric_limits<Real>::quiet_NaN());
      CHECK(uc::potrf(n, C.data(), n) == bad);
    }
    const Index m = 70;
    const Dense R = Dense::Random(m, n);
    Dense X = R;
    uc::trsmRightLowerAdjoint(m, n, L.data(), n, X.data(), m);
    CHECK((X * L.adjoint() - R).norm() <= Real(10) * Real(n) * eps * R.norm() * (L.norm() / L.diagonal().cwiseAbs().minCoeff()));
  }
}
