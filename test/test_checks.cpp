// The test suite's own checks: the tolerances of test_checks.h accept SimplicialLLT compared with
// itself under another ordering (they are not too tight for any configuration), and reject
// factorizations that are slightly wrong (a shifted matrix, a wrong permutation), so that the
// comparisons in the other tests can fail.
#include "test_checks.h"

using namespace uctest;

namespace {

/** A stand-in "solver" with the API measure() uses, whose factor and solve come from a
  * SimplicialLLT, but which may report a wrong permutation. */
template <typename Cfg>
struct WrongPermutation {
  typedef typename Cfg::MatrixType MatrixType;
  typename Cfg::Reference inner;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, typename Cfg::StorageIndex> P, Pinv;
  explicit WrongPermutation(const MatrixType& A) : inner(A) {
    P = inner.permutationP();
    std::swap(P.indices()[0], P.indices()[1]);
    Pinv = P.inverse();
  }
  Eigen::ComputationInfo info() const { return inner.info(); }
  const decltype(P)& permutationP() const { return P; }
  const decltype(P)& permutationPinv() const { return Pinv; }
  decltype(std::declval<const typename Cfg::Reference&>().matrixL()) matrixL() const { return inner.matrixL(); }
  decltype(std::declval<const typename Cfg::Reference&>().matrixU()) matrixU() const { return inner.matrixU(); }
  typename Cfg::Scalar determinant() const { return inner.determinant(); }
  template <typename Rhs>
  typename Cfg::Dense solve(const Rhs& b) const {
    return inner.solve(b);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("the checks accept SimplicialLLT against itself", Cfg, UC_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  std::mt19937 g(71);
  typedef Eigen::SimplicialLLT<typename Cfg::MatrixType, Cfg::UpLo, NaturalOrdering<StorageIndex>> Natural;
  const std::vector<typename Cfg::FullMatrix> matrices = {
      spdFromPattern<Scalar, StorageIndex>(randomPattern(200, 4, g), g),
      spdFromPattern<Scalar, StorageIndex>(densePattern(40), g),
      spdFromPattern<Scalar, StorageIndex>(gridPattern(15, 15), g, 1e-3, Signs::Negative)};
  for (const auto& A : matrices) {
    const typename Cfg::MatrixType input = toInput<Cfg>(A);
    typename Cfg::Reference ref(input);
    Natural other(input);
    REQUIRE(other.info() == Eigen::Success);
    const Measure m = measure<Cfg>(other, A, ref, 3, true);
    INFO(m.describe());
    CHECK(m.allPass());
  }
}

TEST_CASE_TEMPLATE("the checks reject a slightly wrong factorization", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef typename Cfg::RealScalar Real;
  std::mt19937 g(72);
  const typename Cfg::FullMatrix A = spdFromPattern<Scalar, StorageIndex>(randomPattern(150, 4, g), g);
  const typename Cfg::MatrixType input = toInput<Cfg>(A);
  typename Cfg::Reference ref(input);

  SUBCASE("the factor of A + delta*I, delta a thousand epsilons of ||A||") {
    double maxDiag = 0;
    for (Index i = 0; i < A.rows(); ++i) maxDiag = std::max(maxDiag, double(Eigen::numext::real(A.coeff(i, i))));
    const double delta = 1e3 * double(Eigen::NumTraits<Real>::epsilon()) * maxDiag * 150;
    typename Cfg::Reference shifted;
    shifted.setShift(Real(delta));
    shifted.compute(input);
    const Measure m = measure<Cfg>(shifted, A, ref, 3, true);
    INFO(m.describe());
    CHECK(m.factor > 1);
    CHECK(m.residual > 1);
    CHECK(m.solution > 1);
    CHECK(m.logDet > 1);
  }
  SUBCASE("two columns of the permutation swapped") {
    WrongPermutation<Cfg> wrong(input);
    const Measure m = measure<Cfg>(wrong, A, ref, 3, true);
    INFO(m.describe());
    CHECK(m.permutationOk);  // still a permutation, but not the one L was computed with
    CHECK(m.factor > 1);
  }
}
