// The solver's settings, each result compared with SimplicialLLT: setShift(offset, scale), which
// like SimplicialLLT's maps every diagonal coefficient d_ii to offset + scale*d_ii, also with
// structurally missing diagonal entries;
// the updates keep the shift of the factorization they update (a new one takes effect at the next
// factorize());
// setThreadCount (1, 2 and 4 threads give the same factor to rounding, and one thread count
// always the same bits); setRelaxation (fundamental supernodes only, CHOLMOD's defaults,
// everything amalgamated); ordering() (the instance analyzePattern uses; factorize does not
// order again); the statistics nonZerosL(), supernodeCount() and factorizationFlops().
#include "test_checks.h"

#include <unsupported/Eigen/MeshTools>

using namespace uctest;

namespace {

/** A matrix of moderate size with a real elimination tree: D (L + 0.01 I) D with L the cotan
  * Laplacian of an nx x ny grid and D a positive diagonal scaling, converted to Scalar. */
template <typename Cfg>
typename Cfg::FullMatrix treeMatrix(int nx, int ny, unsigned seed) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::RealScalar Real;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(nx, ny, V, F);
  const typename Cfg::FullMatrix L = Eigen::cotanLaplacian<Scalar, typename Cfg::StorageIndex>(V, F);
  typename Cfg::FullMatrix I(L.rows(), L.cols());
  I.setIdentity();
  typename Cfg::FullMatrix A = L + Scalar(Real(0.01)) * I;
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  std::vector<double> d(A.rows());
  for (double& x : d) x = u(g);
  for (Index j = 0; j < A.outerSize(); ++j)
    for (typename Cfg::FullMatrix::InnerIterator it(A, j); it; ++it)
      it.valueRef() *= Scalar(Real(d[it.row()] * d[it.col()]));
  A.makeCompressed();
  return A;
}

}  // namespace

TEST_CASE_TEMPLATE("setShift: diagonal d_ii -> offset + scale*d_ii, as SimplicialLLT", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(51);
  const typename Cfg::FullMatrix A =
      spdFromPattern<Scalar, StorageIndex>(Cfg::fillReducing ? randomPattern(400, 4, g) : gridPattern(20, 20), g);
  SUBCASE("offset only") {
    CheckOptions o;
    o.offset = 2.5;
    computeAndCheck<Cfg>(A, Storage::Full, o);
  }
  SUBCASE("scale only (scaling the diagonal up keeps the matrix positive definite)") {
    CheckOptions o;
    o.scale = 2;
    computeAndCheck<Cfg>(A, Storage::Full, o);
  }
  SUBCASE("offset and scale") {
    CheckOptions o;
    o.offset = 0.75;
    o.scale = 4;
    computeAndCheck<Cfg>(A, Storage::Full, o);
  }
  SUBCASE("a shift that makes an indefinite matrix positive definite") {
    // A - 2*(rowsum+1) I is negative definite; shifting back by offset makes it SPD again
    typename Cfg::FullMatrix I(A.rows(), A.cols());
    I.setIdentity();
    double maxDiag = 0;
    for (Index i = 0; i < A.rows(); ++i) maxDiag = std::max(maxDiag, double(Eigen::numext::real(A.coeff(i, i))));
    const typename Cfg::FullMatrix M = A - Scalar(typename Cfg::RealScalar(maxDiag)) * I;
    CheckOptions o;
    o.offset = maxDiag;
    computeAndCheck<Cfg>(M, Storage::Full, o);
    typename Cfg::Solver unshifted(toInput<Cfg>(M));
    CHECK(unshifted.info() == Eigen::NumericalIssue);
  }
  SUBCASE("the shift is kept across factorize() and can be changed between them") {
    typename Cfg::Solver llt;
    const typename Cfg::MatrixType input = toInput<Cfg>(A);
    llt.analyzePattern(input);
    for (double offset : {0.0, 1.0, 1e-3, 0.0}) {
      CAPTURE(offset);
      llt.setShift(typename Cfg::RealScalar(offset));
      llt.factorize(input);
      typename Cfg::Reference ref;
      computeReference<Cfg>(ref, input, offset);
      CheckOptions o;
      o.offset = offset;
      checkAgainstReference<Cfg>(llt, A, ref, o);
    }
  }
}

TEST_CASE_TEMPLATE("setShift with structurally missing diagonal entries", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::FullMatrix FullMatrix;
  std::mt19937 g(52);
  // off-diagonal part of an SPD matrix (no diagonal stored at all), plus one completely empty
  // column; offset*I makes it diagonally dominant. SimplicialLLT accepts this.
  Pattern p = randomPattern(150, 4, g);
  const FullMatrix A = spdFromPattern<Scalar, StorageIndex>(p, g);
  FullMatrix offDiagonal = A;
  offDiagonal.prune([](Index i, Index j, const Scalar&) { return i != j; });
  for (Index j = 0; j < offDiagonal.outerSize(); ++j)  // empty column/row 40
    for (typename FullMatrix::InnerIterator it(offDiagonal, j); it; ++it)
      if (it.row() == 40 || it.col() == 40) it.valueRef() = Scalar(0);
  offDiagonal.prune(Scalar(0), 0);
  double maxRowSum = 0;
  for (Index j = 0; j < A.outerSize(); ++j) maxRowSum = std::max(maxRowSum, double(Eigen::numext::real(A.coeff(j, j))));
  CheckOptions o;
  o.offset = maxRowSum + 1;
  computeAndCheck<Cfg>(offDiagonal, Storage::Full, o);
  computeAndCheck<Cfg>(offDiagonal, Storage::TriangleOnly, o);
}

TEST_CASE_TEMPLATE("setShift between updates: the updates keep the factor's shift, factorize() takes the new one", Cfg,
                   UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::RealScalar Real;
  typedef typename Cfg::FullMatrix FullMatrix;
  FullMatrix A = Cfg::fillReducing ? treeMatrix<Cfg>(40, 30, 4) : treeMatrix<Cfg>(20, 15, 4);
  const Index n = A.rows();
  typename Cfg::Solver llt;
  llt.setShift(Real(0.5), Real(2));
  llt.compute(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  CheckOptions first;
  first.offset = 0.5;
  first.scale = 2;
  // value changes on the diagonal of a few columns, before and after a new shift is set: the
  // folds and partial refactorizations change the factor of the first shift's matrix
  auto change = [&](std::vector<int> columns) {
    for (int j : columns) A.coeffRef(j, j) += Scalar(Real(1));
    llt.updateColumns(toInput<Cfg>(A), columns);
    REQUIRE(llt.info() == Eigen::Success);
  };
  change({3, int(n / 2)});
  llt.setShift(Real(4), Real(1));
  for (Eigen::UpdateRoute route : {Eigen::UpdateRoute::Automatic, Eigen::UpdateRoute::Mixed,
                                   Eigen::UpdateRoute::PartialRefactorization}) {
    llt.setUpdateRoute(route);
    change({int(n / 3), int(n / 3) + 1, int(n - 2)});
    typename Cfg::Reference ref;
    computeReference<Cfg>(ref, toInput<Cfg>(A), first.offset, first.scale);
    checkAgainstReference<Cfg>(llt, A, ref, first);
    const std::vector<int> dofs = {int(n / 4), int(n / 4) + 2, int(n - 1)};
    llt.removeDofs(dofs);
    REQUIRE(llt.info() == Eigen::Success);
    llt.restoreDofs(dofs);
    REQUIRE(llt.info() == Eigen::Success);
    checkAgainstReference<Cfg>(llt, A, ref, first);
  }
  // the next factorization takes the shift set last
  llt.factorize(toInput<Cfg>(A));
  typename Cfg::Reference ref;
  computeReference<Cfg>(ref, toInput<Cfg>(A), 4, 1);
  CheckOptions second;
  second.offset = 4;
  checkAgainstReference<Cfg>(llt, A, ref, second);
}

TEST_CASE_TEMPLATE("thread counts 1 and 2 give the same answer", Cfg, UC_CORE_CONFIGS) {
  std::mt19937 g(53);
  const typename Cfg::FullMatrix A = Cfg::fillReducing ? treeMatrix<Cfg>(70, 60, 1) : treeMatrix<Cfg>(25, 20, 1);
  const typename Cfg::MatrixType input = toInput<Cfg>(A);
  typename Cfg::Reference ref;
  computeReference<Cfg>(ref, input);

  typename Cfg::Solver one, two, twoAgain;
  one.setThreadCount(1);
  two.setThreadCount(2);
  twoAgain.setThreadCount(2);
  CHECK(one.threadCount() == 1);
  CHECK(two.threadCount() == 2);
  one.compute(input);
  two.compute(input);
  twoAgain.compute(input);
  checkAgainstReference<Cfg>(one, A, ref);
  checkAgainstReference<Cfg>(two, A, ref);
  // 1 and 2 threads: the same factor to rounding (2 threads use threaded BLAS on the top
  // separators, which may sum in another order); the same thread count: the same bits
  CHECK(factorDifference<Cfg>(one, two) <= 1e3 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon()));
  MESSAGE("1 and 2 threads give " << std::string(sameFactorBitwise<Cfg>(one, two) ? "bitwise identical" : "different (to rounding)")
                                  << " factors");
  CHECK(sameFactorBitwise<Cfg>(two, twoAgain));

  // a refactorization with 2 threads, then switching the count on the same object
  two.factorize(input);
  CHECK(sameFactorBitwise<Cfg>(two, twoAgain));
  two.setThreadCount(1);
  two.factorize(input);
  CHECK(sameFactorBitwise<Cfg>(one, two));
  one.setThreadCount(2);
  one.factorize(input);
  CHECK(sameFactorBitwise<Cfg>(one, twoAgain));
  // more threads than cores, and a 3-D grid whose top separators are large dense blocks
  if (Cfg::fillReducing) {
    typedef typename Cfg::Scalar Scalar;
    const typename Cfg::FullMatrix G = spdFromPattern<Scalar, typename Cfg::StorageIndex>(
        Cfg::isPrimary ? grid3dPattern(17, 17, 16) : grid3dPattern(13, 13, 12), g, 0.01, Signs::Negative);
    const typename Cfg::MatrixType gridInput = toInput<Cfg>(G);
    typename Cfg::Reference gridRef;
    computeReference<Cfg>(gridRef, gridInput);
    typename Cfg::Solver g1, g2, g4;
    g1.setThreadCount(1);
    g2.setThreadCount(2);
    g4.setThreadCount(4);
    g1.compute(gridInput);
    g2.compute(gridInput);
    g4.compute(gridInput);
    checkAgainstReference<Cfg>(g1, G, gridRef);
    checkAgainstReference<Cfg>(g2, G, gridRef);
    checkAgainstReference<Cfg>(g4, G, gridRef);
    CHECK(factorDifference<Cfg>(g1, g2) <= 1e3 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon()));
    g2.factorize(gridInput);
    typename Cfg::Solver g2Again;
    g2Again.setThreadCount(2);
    g2Again.compute(gridInput);
    CHECK(sameFactorBitwise<Cfg>(g2, g2Again));
  }
  // solves agree as well
  const typename Cfg::Vector b = randomDense<Cfg>(A.rows(), 1, g);
  const typename Cfg::Vector x1 = one.solve(b), x2 = two.solve(b);
  CHECK(double((x1 - x2).norm()) <= 1e3 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon()) * double(x2.norm()));
}

TEST_CASE_TEMPLATE("supernode relaxation settings", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(54);
  const std::vector<typename Cfg::FullMatrix> matrices = {
      // (with the huge relaxation each is one dense supernode: keep them small)
      Cfg::fillReducing ? treeMatrix<Cfg>(24, 22, 2) : treeMatrix<Cfg>(20, 15, 2),
      spdFromPattern<Scalar, StorageIndex>(Cfg::fillReducing ? randomPattern(300, 3, g) : tridiagonalPattern(300), g),
      spdFromPattern<Scalar, StorageIndex>(blockDiagonal({diagonalPattern(5), densePattern(9), arrowPattern(30, true)}),
                                           g)};
  for (const typename Cfg::FullMatrix& A : matrices) {
    CAPTURE(A.rows());
    const typename Cfg::MatrixType input = toInput<Cfg>(A);
    typename Cfg::Reference ref;
    computeReference<Cfg>(ref, input);

    Eigen::SupernodeRelaxation fundamental;
    for (int k = 0; k < 3; ++k) {
      fundamental.nrelax[k] = 0;
      fundamental.zrelax[k] = 0;
    }
    Eigen::SupernodeRelaxation huge;
    for (int k = 0; k < 3; ++k) {
      huge.nrelax[k] = 1 << 30;
      huge.zrelax[k] = 1e30;
    }
    typename Cfg::Solver f, d, h;
    f.setRelaxation(fundamental);
    h.setRelaxation(huge);
    f.compute(input);
    d.compute(input);
    h.compute(input);
    INFO("supernodes fundamental/default/huge: " << f.supernodeCount() << " / " << d.supernodeCount() << " / "
                                                 << h.supernodeCount() << "; nonZerosL " << f.nonZerosL() << " / "
                                                 << d.nonZerosL() << " / " << h.nonZerosL());
    checkAgainstReference<Cfg>(f, A, ref);
    checkAgainstReference<Cfg>(d, A, ref);
    checkAgainstReference<Cfg>(h, A, ref);
    // more relaxation: fewer, larger supernodes holding more (explicit zero) entries
    CHECK(f.supernodeCount() >= d.supernodeCount());
    CHECK(d.supernodeCount() >= h.supernodeCount());
    CHECK(f.nonZerosL() <= d.nonZerosL());
    CHECK(d.nonZerosL() <= h.nonZerosL());
    // the factor's values do not depend on the relaxation beyond rounding
    CHECK(factorDifference<Cfg>(f, d) <= 1e3 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon()));
    CHECK(factorDifference<Cfg>(h, d) <= 1e3 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon()));
    // relaxation set after analyzePattern takes effect at the next analyzePattern
    d.setRelaxation(fundamental);
    d.compute(input);
    CHECK(d.supernodeCount() == f.supernodeCount());
    CHECK(sameFactorBitwise<Cfg>(d, f));
  }
}

TEST_CASE("stored entries of L against the fill of SimplicialLLT with the same ordering; flop count") {
  typedef Config<double, int, ColMajor, Lower, ReverseOrdering<int>> Rev;
  typedef Config<double, int, ColMajor, Lower, NaturalOrdering<int>> Nat;
  std::mt19937 g(55);
  const Rev::FullMatrix A = treeMatrix<Rev>(20, 20, 3);
  Eigen::SupernodeRelaxation fundamental;
  for (int k = 0; k < 3; ++k) {
    fundamental.nrelax[k] = 0;
    fundamental.zrelax[k] = 0;
  }
  // a postorder of the elimination tree does not change the fill, so a supernodal factor (which
  // may hold extra zeros) stores at least SimplicialLLT's entries (both with the same ordering)
  Rev::Solver rev;
  rev.setRelaxation(fundamental);
  rev.compute(A);
  Eigen::SimplicialLLT<Rev::MatrixType, Lower, ReverseOrdering<int>> revRef(A);
  CHECK(rev.nonZerosL() >= revRef.matrixL().nestedExpression().nonZeros());
  Nat::Solver nat;
  nat.setRelaxation(fundamental);
  nat.compute(A);
  Eigen::SimplicialLLT<Nat::MatrixType, Lower, NaturalOrdering<int>> natRef(A);
  CHECK(nat.nonZerosL() >= natRef.matrixL().nestedExpression().nonZeros());
  MESSAGE("fundamental supernodes: nonZerosL " << nat.nonZerosL() << " vs SimplicialLLT's "
                                               << natRef.matrixL().nestedExpression().nonZeros());
  // with the default relaxation there are fewer supernodes than with none
  Nat::Solver relaxed(A);
  CHECK(relaxed.supernodeCount() <= nat.supernodeCount());
  // flop count of a dense matrix: about n^3/3
  const Nat::FullMatrix D = spdFromPattern<double, int>(densePattern(60), g);
  Nat::Solver dense(D);
  CHECK(dense.factorizationFlops() >= 60.0 * 60 * 60 / 6);
  CHECK(dense.factorizationFlops() <= 60.0 * 60 * 60);
}

TEST_CASE_TEMPLATE("ordering(): the functor instance analyzePattern uses", Cfg, d_int_row_upper_rev,
                   f_long_row_upper_rev) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(56);
  const typename Cfg::FullMatrix A = spdFromPattern<Scalar, StorageIndex>(gridPattern(12, 9), g);
  const typename Cfg::MatrixType input = toInput<Cfg>(A);
  typename Cfg::Solver llt;
  CHECK(llt.ordering().calls == 0);
  llt.analyzePattern(input);
  CHECK(llt.ordering().calls == 1);
  for (int k = 0; k < 3; ++k) llt.factorize(toInput<Cfg>(revalued(A, g)));
  CHECK(llt.ordering().calls == 1);  // factorize reuses the analysis
  llt.compute(input);
  CHECK(llt.ordering().calls == 2);
  typename Cfg::Reference ref;
  computeReference<Cfg>(ref, input);
  checkAgainstReference<Cfg>(llt, A, ref);
}
