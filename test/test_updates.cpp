// In-place updates (paper §3.3, §4.1): random sequences of removeDofs / restoreDofs /
// updateColumns on mesh Laplacians and random SPD matrices, each step checked against a fresh
// factorization of the current matrix (A with the removed rows and columns replaced by those of
// the identity) with the same permutation: equal to rounding for the exact routes, to solving
// accuracy for the low-rank route; the solves that reuse the previous forward substitution are
// bitwise full ones. Also the folding routes of updateColumns and restoreDofs (route Mixed),
// Dirichlet solves (B empty, random, all; 1 to 5 right-hand sides), and every error path (bad
// indices, pattern mismatch, an update or a restore that is not positive definite, NaN or
// infinity) leaving a usable object.
#include "test_checks.h"
#include "test_config.h"
#include "test_matrices.h"

#include <unsupported/Eigen/MeshTools>

#include <algorithm>
#include <limits>
#include <cmath>
#include <random>

namespace {
using namespace uctest;

/** An ordering functor that returns a given permutation (to factor afresh in the same order). */
template <typename StorageIndex>
struct GivenOrdering {
  typedef Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, StorageIndex> PermutationType;
  PermutationType pinv;
  template <typename MatrixType>
  void operator()(const MatrixType&, PermutationType& p) {
    p = pinv;
  }
};

/** The cotan Laplacian of (V, F) + 1e-2 I, compressed. */
template <typename Cfg>
typename Cfg::FullMatrix shiftedLaplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  typedef typename Cfg::Scalar Scalar;
  typename Cfg::FullMatrix A = Eigen::cotanLaplacian<Scalar, typename Cfg::StorageIndex>(V, F);
  for (Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += Scalar(1e-2);
  A.makeCompressed();
  return A;
}

template <typename Cfg>
typename Cfg::FullMatrix testLaplacian(unsigned seed) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  if (seed % 2)
    Eigen::gridMesh(23, 19, V, F);
  else
    Eigen::icosphereMesh(2, V, F);
  return shiftedLaplacian<Cfg>(V, F);
}

/** Tolerances: exact routes reproduce a fresh factorization to rounding, the low-rank route to
  * a few hundred roundings. */
template <typename Cfg>
double exactTolerance() {
  return std::is_same<typename Cfg::RealScalar, double>::value ? 1e-14
                                                                : 50 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon());
}
template <typename Cfg>
double lowRankTolerance() {
  return 1e4 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon());
}

/** The shifted Laplacian of a 48 x 40 grid: separators large enough above a few dofs that folding
  * a small change into them beats refactoring them. */
template <typename Cfg>
typename Cfg::FullMatrix foldingGrid() {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(48, 40, V, F);
  return shiftedLaplacian<Cfg>(V, F);
}

/** Factors \a A on one thread with update caching on, then sets \a route for the updates. */
template <typename Cfg>
void startCached(typename Cfg::Solver& llt, const typename Cfg::FullMatrix& A, Eigen::UpdateRoute route) {
  llt.setThreadCount(1);
  llt.setUpdateCaching(true);
  llt.compute(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  llt.setUpdateRoute(route);
}

/** Runs a random sequence of updates with one route and checks every step. */
template <typename Cfg>
void randomSequence(const typename Cfg::FullMatrix& A0, Eigen::UpdateRoute route, int steps, unsigned seed) {
  seed += seedOffset();
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef Eigen::UpdatableSupernodalLLT<typename Cfg::MatrixType, Cfg::UpLo, GivenOrdering<StorageIndex>> Fresh;
  std::mt19937 g(seed);
  const Index n = A0.rows();
  typename Cfg::FullMatrix A = A0;
  typename Cfg::Solver llt;
  llt.setThreadCount(1);
  llt.compute(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  llt.setUpdateRoute(route);
  std::vector<char> removed(n, 0);
  std::vector<int> removedList;
  // the same right-hand side and known values at every step: the solves after an update reuse the
  // previous forward substitution (setSolveCaching()), which must give bitwise a full one's result
  const typename Cfg::Dense bFixed = randomDense<Cfg>(n, 2, g), gFixed = randomDense<Cfg>(n, 2, g);
  const typename Cfg::Dense primed = llt.solve(bFixed);
  (void)primed;
  for (int step = 0; step < steps; ++step) {
    const int op = int(g() % 4);
    std::vector<int> dofs;
    bool lowRankStep = false;
    if (op <= 1 || removedList.empty()) {  // remove a few dofs (a "seam": a run of neighbours or random)
      const int count = 1 + int(g() % 12);
      for (int k = 0; k < count; ++k) {
        const int v = int(g() % n);
        if (!removed[v] && std::find(dofs.begin(), dofs.end(), v) == dofs.end()) dofs.push_back(v);
      }
      llt.removeDofs(dofs);
      for (int v : dofs) {
        removed[v] = 1;
        removedList.push_back(v);
      }
      lowRankStep = llt.lastUpdate().route == Eigen::UpdateRoute::LowRank;
    } else if (op == 2) {  // restore some
      std::shuffle(removedList.begin(), removedList.end(), g);
      const int count = 1 + int(g() % removedList.size());
      dofs.assign(removedList.begin(), removedList.begin() + count);
      removedList.erase(removedList.begin(), removedList.begin() + count);
      llt.restoreDofs(dofs);
      for (int v : dofs) removed[v] = 0;
    } else {  // change the values of a few columns (symmetric change, same pattern)
      const int count = 1 + int(g() % 5);
      for (int k = 0; k < count; ++k) dofs.push_back(int(g() % n));
      std::sort(dofs.begin(), dofs.end());
      dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
      for (int c : dofs)
        for (typename Cfg::FullMatrix::InnerIterator it(A, c); it; ++it)
          if (it.row() == c) it.valueRef() *= Scalar(1.5);  // diagonal: stays positive definite
      llt.updateColumns(toInput<Cfg>(A), dofs);
    }
    CAPTURE(step);
    CAPTURE(op);
    REQUIRE(llt.info() == Eigen::Success);
    const Eigen::UpdateStatistics& st = llt.lastUpdate();
    CHECK(st.flopFraction >= 0);
    // (a forced low-rank or mixed route may cost more than a refactorization: rank-k folds along a
    // long path, e.g. the chain of a natural ordering, cost ~2k/bandwidth of it)
    if (route != Eigen::UpdateRoute::LowRank && route != Eigen::UpdateRoute::Mixed)
      CHECK(st.flopFraction <= 1.0 + 1e-12);
    else
      CHECK(std::isfinite(st.flopFraction));
    CHECK(st.dirtySupernodes <= llt.supernodeCount());
    // fresh factorization of the current matrix in the same order
    typename Cfg::FullMatrix current = withIdentityRows<Cfg>(A, removed);
    Fresh fresh;
    fresh.ordering().pinv = llt.permutationPinv();
    fresh.setThreadCount(1);
    fresh.compute(toInput<Cfg>(current));
    REQUIRE(fresh.info() == Eigen::Success);
    REQUIRE(fresh.permutationP().indices() == llt.permutationP().indices());
    const double diff = factorDifference<Cfg>(llt, fresh);
    const bool exact = route == Eigen::UpdateRoute::PartialRefactorization || route == Eigen::UpdateRoute::Refactorization;
    CHECK(diff <= (exact ? exactTolerance<Cfg>() : lowRankTolerance<Cfg>()));
    CHECK(removedAreIdentity<Cfg>(llt, removed));
    (void)lowRankStep;
    // the kept forward substitution: redone on the dirty supernodes only, equal to a full pass
    const typename Cfg::Dense xKept = llt.solve(bFixed);
    CHECK(llt.lastSolveForwardColumns() == st.dirtyColumns);
    const typename Cfg::Dense xDirichletKept = llt.solveDirichlet(bFixed, gFixed);
    // and it solves the current matrix
    typename Cfg::Dense b = randomDense<Cfg>(n, 2, g);
    typename Cfg::Dense x = llt.solve(b);
    CHECK(llt.lastSolveForwardColumns() == n);  // every row of the right-hand side changed
    const double res = double((current * x - b).norm() / b.norm());
    CHECK(res <= lowRankTolerance<Cfg>());
    CHECK(double((llt.solveDirichlet(bFixed, gFixed) - xDirichletKept).norm()) == 0);
    x = llt.solve(b);
    const typename Cfg::Dense xFull = llt.solve(bFixed);
    CHECK(double((xFull - xKept).norm()) == 0);
  }
}

}  // namespace

TEST_CASE_TEMPLATE("random update sequences match a fresh factorization", Cfg, UC_CORE_CONFIGS) {
  const int steps = Cfg::isPrimary ? 40 : 12;
  for (unsigned seed : {1u, 2u}) {
    const typename Cfg::FullMatrix A = testLaplacian<Cfg>(seed);
    SUBCASE("partial refactorization (exact)") { randomSequence<Cfg>(A, Eigen::UpdateRoute::PartialRefactorization, steps, seed); }
    SUBCASE("full refactorization (exact)") { randomSequence<Cfg>(A, Eigen::UpdateRoute::Refactorization, steps / 2, seed); }
    SUBCASE("low-rank removals") { randomSequence<Cfg>(A, Eigen::UpdateRoute::LowRank, steps, seed); }
    SUBCASE("automatic") { randomSequence<Cfg>(A, Eigen::UpdateRoute::Automatic, steps, seed); }
    SUBCASE("mixed: low-rank below, partial refactorization on top") {
      randomSequence<Cfg>(A, Eigen::UpdateRoute::Mixed, steps, seed);
    }
  }
  SUBCASE("random SPD matrix") {
    std::mt19937 g(7);
    const typename Cfg::FullMatrix A =
        spdFromPattern<typename Cfg::Scalar, typename Cfg::StorageIndex>(randomPattern(300, 4.0, g), g);
    randomSequence<Cfg>(A, Eigen::UpdateRoute::Automatic, steps, 3);
    randomSequence<Cfg>(A, Eigen::UpdateRoute::PartialRefactorization, steps, 4);
  }
}

TEST_CASE_TEMPLATE("partial refactorization is bitwise a fresh factorization", Cfg, uctest::d_int_col_lower_amd) {
  typedef Eigen::UpdatableSupernodalLLT<typename Cfg::MatrixType, Cfg::UpLo, GivenOrdering<int>> Fresh;
  const typename Cfg::FullMatrix A = testLaplacian<Cfg>(1);
  typename Cfg::Solver llt;
  llt.setThreadCount(1);
  llt.setUpdateCaching(true);
  llt.compute(toInput<Cfg>(A));
  llt.setUpdateRoute(Eigen::UpdateRoute::PartialRefactorization);
  std::vector<char> removed(A.rows(), 0);
  const std::vector<int> seam = {3, 4, 5, 27, 28, 100, 101, 102};
  llt.removeDofs(seam);
  for (int v : seam) removed[v] = 1;
  Fresh fresh;
  fresh.ordering().pinv = llt.permutationPinv();
  fresh.setThreadCount(1);
  fresh.compute(toInput<Cfg>(withIdentityRows<Cfg>(A, removed)));
  CHECK(sameFactorBitwise<Cfg>(llt, fresh));
  CHECK(llt.lastUpdate().route == Eigen::UpdateRoute::PartialRefactorization);
  CHECK(llt.lastUpdate().flopFraction < 1.0);
  llt.restoreDofs(seam);
  Fresh original;
  original.ordering().pinv = llt.permutationPinv();
  original.setThreadCount(1);
  original.compute(toInput<Cfg>(A));
  CHECK(sameFactorBitwise<Cfg>(llt, original));
}

TEST_CASE_TEMPLATE("updateColumns: a few changed columns are folded into the separators above them (route Mixed)", Cfg,
                   UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  typedef Eigen::UpdatableSupernodalLLT<typename Cfg::MatrixType, Cfg::UpLo, GivenOrdering<typename Cfg::StorageIndex>> Fresh;
  const typename Cfg::FullMatrix A = foldingGrid<Cfg>();
  const Index n = A.rows();
  const int steps = Cfg::isPrimary ? 12 : 6;
  for (Eigen::UpdateRoute route :
       {Eigen::UpdateRoute::Automatic, Eigen::UpdateRoute::Mixed, Eigen::UpdateRoute::PartialRefactorization}) {
    CAPTURE(int(route));
    std::mt19937 g(11 + seedOffset());
    typename Cfg::Solver llt;
    startCached<Cfg>(llt, A, route);
    typename Cfg::FullMatrix current = A;
    int folded = 0;
    for (int step = 0; step < steps; ++step) {
      CAPTURE(step);
      // a positive semidefinite change (stays positive definite): the diagonal of a few columns
      // grows, or an edge (i, j) changes by d with |d| added to both diagonals, |d| (e_i ± e_j)(e_i ± e_j)^H
      std::vector<int> cols;
      if (step % 2 == 0) {
        const int count = 1 + int(g() % 4);
        for (int k = 0; k < count; ++k) {
          const int c = int(g() % n);
          if (std::find(cols.begin(), cols.end(), c) == cols.end()) cols.push_back(c);
        }
        for (int c : cols) current.coeffRef(c, c) += Scalar(0.5) * current.coeff(c, c);
      } else {
        const int j = int(g() % n);
        typename Cfg::FullMatrix::InnerIterator it(current, j);
        while (it && (it.row() == j || std::abs(it.value()) == 0)) ++it;  // a non-zero off the diagonal
        REQUIRE(it);  // (a grid's diagonal edges have zero cotan weights; the others do not)
        const int i = int(it.row());
        const Scalar d = Scalar(step % 4 == 1 ? 0.3 : -0.3) * it.value();
        current.coeffRef(i, j) += d;
        current.coeffRef(j, i) += d;
        current.coeffRef(i, i) += Scalar(std::abs(d));
        current.coeffRef(j, j) += Scalar(std::abs(d));
        cols.push_back(j);  // (not cols = {j, i}: GCC 12 warns wrongly on that vector assignment)
        cols.push_back(i);
      }
      llt.updateColumns(toInput<Cfg>(current), cols);
      REQUIRE(llt.info() == Eigen::Success);
      const Eigen::UpdateStatistics& st = llt.lastUpdate();
      folded += st.route == Eigen::UpdateRoute::Mixed;
      CHECK(st.changedColumns == Index(cols.size()));
      if (route == Eigen::UpdateRoute::PartialRefactorization) CHECK(st.route == route);
      Fresh fresh;
      fresh.ordering().pinv = llt.permutationPinv();
      fresh.setThreadCount(1);
      fresh.compute(toInput<Cfg>(current));
      REQUIRE(fresh.info() == Eigen::Success);
      const bool exact = st.route == Eigen::UpdateRoute::PartialRefactorization;
      CHECK(factorDifference<Cfg>(llt, fresh) <= (exact ? exactTolerance<Cfg>() : lowRankTolerance<Cfg>()));
      if (exact && Cfg::isPrimary) CHECK(sameFactorBitwise<Cfg>(llt, fresh));
      std::mt19937 gb(step);
      const typename Cfg::Dense b = randomDense<Cfg>(n, 2, gb);
      const typename Cfg::Dense x = llt.solve(b);
      CHECK(double((current * x - b).norm() / b.norm()) <= lowRankTolerance<Cfg>());
    }
    if (route == Eigen::UpdateRoute::Mixed) CHECK(folded == steps);
    // a change of one diagonal entry below the root separator costs a rank-2 fold there, far
    // less than refactoring it: the automatic route folds
    if (route == Eigen::UpdateRoute::Automatic) CHECK(folded > 0);
  }
}

TEST_CASE_TEMPLATE("restoreDofs folds the restored rows and columns into the separators above them (route Mixed)", Cfg,
                   UC_CORE_CONFIGS) {
  typedef Eigen::UpdatableSupernodalLLT<typename Cfg::MatrixType, Cfg::UpLo, GivenOrdering<typename Cfg::StorageIndex>> Fresh;
  const typename Cfg::FullMatrix A = foldingGrid<Cfg>();
  const Index n = A.rows();
  const int steps = Cfg::isPrimary ? 16 : 8;
  // || L - L_fresh || / || L_fresh ||, L_fresh a fresh factorization of \a current in llt's order
  auto differenceFromFresh = [](const typename Cfg::Solver& llt, const typename Cfg::FullMatrix& current) {
    Fresh fresh;
    fresh.ordering().pinv = llt.permutationPinv();
    fresh.setThreadCount(1);
    fresh.compute(toInput<Cfg>(current));
    REQUIRE(fresh.info() == Eigen::Success);
    return factorDifference<Cfg>(llt, fresh);
  };
  for (Eigen::UpdateRoute route : {Eigen::UpdateRoute::Automatic, Eigen::UpdateRoute::Mixed, Eigen::UpdateRoute::LowRank,
                                   Eigen::UpdateRoute::PartialRefactorization}) {
    CAPTURE(int(route));
    std::mt19937 g(13 + seedOffset());
    typename Cfg::Solver llt;
    startCached<Cfg>(llt, A, route);
    std::vector<char> removed(n, 0);
    std::vector<int> removedList;
    int restores = 0, folded = 0;
    for (int step = 0; step < steps; ++step) {
      CAPTURE(step);
      std::vector<int> dofs;
      if (step % 2 == 0 || removedList.empty()) {  // a short run of grid neighbours (a seam) or a few dofs anywhere
        const int start = int(g() % n), count = 1 + int(g() % 6);
        for (int k = 0; k < count; ++k) {
          const int v = step % 4 == 0 ? (start + k) % int(n) : int(g() % n);
          if (!removed[v] && std::find(dofs.begin(), dofs.end(), v) == dofs.end()) dofs.push_back(v);
        }
        llt.removeDofs(dofs);
        REQUIRE(llt.info() == Eigen::Success);
        for (int v : dofs) removed[v] = 1;
        removedList.insert(removedList.end(), dofs.begin(), dofs.end());
      } else {  // some of the removed dofs back (all of them every fourth step)
        std::shuffle(removedList.begin(), removedList.end(), g);
        const std::size_t count = step % 4 == 3 ? removedList.size() : 1 + g() % removedList.size();
        for (std::size_t k = 0; k < count; ++k) dofs.push_back(removedList[k]);
        removedList.erase(removedList.begin(), removedList.begin() + count);
        llt.restoreDofs(dofs);
        REQUIRE(llt.info() == Eigen::Success);
        for (int v : dofs) removed[v] = 0;
        ++restores;
        const Eigen::UpdateStatistics& st = llt.lastUpdate();
        folded += st.route == Eigen::UpdateRoute::Mixed;
        CHECK(st.changedColumns == Index(dofs.size()));
        if (route == Eigen::UpdateRoute::PartialRefactorization) CHECK(st.route == route);
      }
      CHECK(differenceFromFresh(llt, withIdentityRows<Cfg>(A, removed)) <= lowRankTolerance<Cfg>());
      CHECK(removedAreIdentity<Cfg>(llt, removed));
      std::mt19937 gb(step);
      const typename Cfg::Dense b = randomDense<Cfg>(n, 2, gb), known = randomDense<Cfg>(n, 2, gb);
      const typename Cfg::Dense x = llt.solveDirichlet(b, known);
      typename Cfg::Dense r = A * x - b;
      for (Index i = 0; i < n; ++i)
        if (removed[std::size_t(i)]) {
          CHECK(x.row(i) == known.row(i));
          r.row(i).setZero();
        }
      CHECK(double(r.norm() / (b.norm() + (A * x).norm())) <= lowRankTolerance<Cfg>());
    }
    // forced folds fold every restore; the automatic route folds the restore of one dof (a
    // rank-2 change of the separators above it, far less than refactoring them)
    if (route == Eigen::UpdateRoute::Mixed || route == Eigen::UpdateRoute::LowRank) CHECK(folded == restores);
    if (route == Eigen::UpdateRoute::Automatic && Cfg::fillReducing) {
      int single = 0;
      for (int k = 0; k < 4; ++k) {
        const int v = int(g() % n);
        if (removed[v]) continue;
        llt.removeDofs(std::vector<int>{v});
        REQUIRE(llt.info() == Eigen::Success);
        llt.restoreDofs(std::vector<int>{v});
        REQUIRE(llt.info() == Eigen::Success);
        single += llt.lastUpdate().route == Eigen::UpdateRoute::Mixed;
      }
      CHECK(single > 0);
      CHECK(differenceFromFresh(llt, withIdentityRows<Cfg>(A, removed)) <= lowRankTolerance<Cfg>());
    }
  }
}

TEST_CASE_TEMPLATE("updateColumns reads the values of the listed columns only", Cfg, uctest::d_int_col_lower_amd) {
  typedef Eigen::UpdatableSupernodalLLT<typename Cfg::MatrixType, Cfg::UpLo, GivenOrdering<int>> Fresh;
  const typename Cfg::FullMatrix A = testLaplacian<Cfg>(1);
  typename Cfg::Solver llt;
  llt.setThreadCount(1);
  llt.compute(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  // column 10 listed, column 300 (no neighbour of 10) changed too but not listed: the factor is
  // that of A with column 10 changed only (the documented contract: values elsewhere are not read)
  REQUIRE(A.coeff(300, 10) == 0.0);
  typename Cfg::FullMatrix listedOnly = A, both = A;
  listedOnly.coeffRef(10, 10) *= 2;
  both.coeffRef(10, 10) *= 2;
  both.coeffRef(300, 300) *= 3;
  llt.updateColumns(toInput<Cfg>(both), std::vector<int>{10});
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().changedColumns == 1);
  Fresh fresh;
  fresh.ordering().pinv = llt.permutationPinv();
  fresh.setThreadCount(1);
  fresh.compute(toInput<Cfg>(listedOnly));
  CHECK(factorDifference<Cfg>(llt, fresh) <= lowRankTolerance<Cfg>());
  // and restoreDofs gives back the rows of that matrix
  llt.removeDofs(std::vector<int>{300});
  llt.restoreDofs(std::vector<int>{300});
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(factorDifference<Cfg>(llt, fresh) <= lowRankTolerance<Cfg>());
}

TEST_CASE_TEMPLATE("removing most dofs: reduced fronts (paper 6.5)", Cfg, UC_CORE_CONFIGS) {
  typedef Eigen::UpdatableSupernodalLLT<typename Cfg::MatrixType, Cfg::UpLo, GivenOrdering<typename Cfg::StorageIndex>> Fresh;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(36, 30, V, F);
  const typename Cfg::FullMatrix A = shiftedLaplacian<Cfg>(V, F);
  const Index n = A.rows();
  const double x0 = V.col(0).minCoeff(), x1 = V.col(0).maxCoeff();
  // a region of 70% of the mesh, and a band that cuts the mesh into two pieces
  for (const auto& region : {std::make_pair(-1.0, 0.7), std::make_pair(0.25, 0.75)}) {
    std::vector<int> dofs;
    std::vector<char> removed(n, 0);
    for (Index i = 0; i < n; ++i) {
      const double t = (V(i, 0) - x0) / (x1 - x0);
      if (t > region.first && t < region.second) {
        dofs.push_back(int(i));
        removed[i] = 1;
      }
    }
    CAPTURE(region.first);
    const typename Cfg::FullMatrix current = withIdentityRows<Cfg>(A, removed);
    double forcedFlops = 0;
    // (more removed dofs than supernodes: the removed rows left outside the dirty set are found by
    // reading the clean supernodes' rows, not by a row-subtree search per dof)
    for (Eigen::UpdateRoute route : {Eigen::UpdateRoute::Refactorization, Eigen::UpdateRoute::PartialRefactorization,
                                     Eigen::UpdateRoute::Automatic, Eigen::UpdateRoute::LowRank,
                                     Eigen::UpdateRoute::Mixed}) {
      CAPTURE(int(route));
      typename Cfg::Solver llt;
      llt.setThreadCount(1);
      llt.compute(toInput<Cfg>(A));
      REQUIRE(llt.info() == Eigen::Success);
      llt.setUpdateRoute(route);
      llt.removeDofs(dofs);
      REQUIRE(llt.info() == Eigen::Success);
      const Eigen::UpdateStatistics& st = llt.lastUpdate();
      Fresh fresh;
      fresh.ordering().pinv = llt.permutationPinv();
      fresh.setThreadCount(1);
      fresh.compute(toInput<Cfg>(current));
      REQUIRE(fresh.info() == Eigen::Success);
      const bool exact = st.route == Eigen::UpdateRoute::PartialRefactorization || st.route == Eigen::UpdateRoute::Refactorization;
      CHECK(factorDifference<Cfg>(llt, fresh) <= (exact ? exactTolerance<Cfg>() : lowRankTolerance<Cfg>()));
      CHECK(Index(dofs.size()) > llt.supernodeCount());
      CHECK(removedAreIdentity<Cfg>(llt, removed));
      if (route == Eigen::UpdateRoute::Refactorization) {
        // the supernodes are factored on their kept rows and columns: far less than a full factorization
        CHECK(st.route == Eigen::UpdateRoute::Refactorization);
        CHECK(st.flopFraction > 0);
        CHECK(st.flopFraction < 0.5);
        forcedFlops = st.flops;
      }
      if (route == Eigen::UpdateRoute::Automatic) CHECK(st.flops <= forcedFlops * (1 + 1e-12));
      std::mt19937 g(5);
      const typename Cfg::Dense b = randomDense<Cfg>(n, 2, g);
      const typename Cfg::Dense x = llt.solve(b);
      CHECK(double((current * x - b).norm() / b.norm()) <= lowRankTolerance<Cfg>());
      // and back: the original factor
      llt.restoreDofs(dofs);
      REQUIRE(llt.info() == Eigen::Success);
      Fresh original;
      original.ordering().pinv = llt.permutationPinv();
      original.setThreadCount(1);
      original.compute(toInput<Cfg>(A));
      CHECK(factorDifference<Cfg>(llt, original) <= lowRankTolerance<Cfg>());
    }
  }
}

TEST_CASE_TEMPLATE("Dirichlet solves", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Dense Dense;
  const typename Cfg::FullMatrix A = testLaplacian<Cfg>(1);
  const Index n = A.rows();
  std::mt19937 g(11);
  typename Cfg::Solver llt(toInput<Cfg>(A));
  std::vector<int> B;
  for (int i = 0; i < 40; ++i) B.push_back(int((i * 37) % n));
  std::sort(B.begin(), B.end());
  B.erase(std::unique(B.begin(), B.end()), B.end());
  for (Eigen::UpdateRoute route : {Eigen::UpdateRoute::LowRank, Eigen::UpdateRoute::PartialRefactorization}) {
    llt.setUpdateRoute(route);
    llt.removeDofs(B);
    REQUIRE(llt.info() == Eigen::Success);
    const Dense b = randomDense<Cfg>(n, 3, g), known = randomDense<Cfg>(n, 3, g);
    const Dense x = llt.solveDirichlet(b, known);
    std::vector<char> isB(n, 0);
    for (int v : B) isB[v] = 1;
    const Dense r = A * x - b;
    double worstInterior = 0, worstBoundary = 0;
    for (Index i = 0; i < n; ++i)
      for (Index c = 0; c < 3; ++c) {
        if (isB[i])
          worstBoundary = std::max(worstBoundary, double(std::abs(x(i, c) - known(i, c))));
        else
          worstInterior = std::max(worstInterior, double(std::abs(r(i, c))));
      }
    CHECK(worstBoundary == 0);
    CHECK(worstInterior <= lowRankTolerance<Cfg>() * double(b.norm()));
    llt.restoreDofs(B);
    REQUIRE(llt.info() == Eigen::Success);
    CHECK(llt.removedDofs().empty());
  }
}

TEST_CASE_TEMPLATE("Dirichlet solves with B empty, random and all; 1 to 5 right-hand sides", Cfg, UC_CORE_CONFIGS) {
  // On a random Hermitian matrix (complex values for the complex types: the coupling A_IB g
  // must take the conjugate for the entries stored in the other triangle), solveDirichlet must
  // give x_B = g_B exactly and (A x - b)_I = 0 to solving accuracy.
  typedef typename Cfg::Dense Dense;
  typedef typename Cfg::Scalar Scalar;
  std::mt19937 g(29);
  const Index n = 160;
  const typename Cfg::FullMatrix A =
      spdFromPattern<Scalar, typename Cfg::StorageIndex>(randomPattern(n, 5, g), g, 0.5);
  const double normA = double(Dense(A).cwiseAbs().rowwise().sum().maxCoeff());
  typename Cfg::Solver llt(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  std::vector<int> all(n);
  for (Index i = 0; i < n; ++i) all[i] = int(i);
  std::vector<int> random = all;
  std::shuffle(random.begin(), random.end(), g);
  random.resize(n / 5);
  const std::vector<int> none;
  for (const std::vector<int>* B : std::initializer_list<const std::vector<int>*>{&none, &random, &all}) {
    CAPTURE(B->size());
    if (!B->empty()) llt.removeDofs(*B);
    REQUIRE(llt.info() == Eigen::Success);
    std::vector<char> isB(n, 0);
    for (int v : *B) isB[v] = 1;
    for (Index k = 1; k <= 5; ++k) {
      CAPTURE(k);
      const Dense b = randomDense<Cfg>(n, k, g), known = randomDense<Cfg>(n, k, g);
      const Dense x = k == 2 ? llt.solveDirichlet(b, known * Scalar(1)) : llt.solveDirichlet(b, known);
      REQUIRE(x.rows() == n);
      REQUIRE(x.cols() == k);
      const Dense r = A * x - b;
      double worstInterior = 0, worstBoundary = 0;
      for (Index i = 0; i < n; ++i)
        for (Index c = 0; c < k; ++c) {
          if (isB[i])
            worstBoundary = std::max(worstBoundary, double(std::abs(x(i, c) - known(i, c))));
          else
            worstInterior = std::max(worstInterior, double(std::abs(r(i, c))));
        }
      CHECK(worstBoundary == 0);
      CHECK(worstInterior <= lowRankTolerance<Cfg>() * (double(b.norm()) + normA * double(x.norm())));
      if (B->empty()) CHECK(double((x - llt.solve(b)).norm()) == 0);  // no removed dof: a plain solve
    }
    if (!B->empty()) llt.restoreDofs(*B);
    REQUIRE(llt.info() == Eigen::Success);
  }
}

TEST_CASE_TEMPLATE("bad update input gives a clear error and a usable object", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::Scalar Scalar;
  const typename Cfg::FullMatrix A = testLaplacian<Cfg>(1);
  const Index n = A.rows();
  std::mt19937 g(5);
  typename Cfg::Solver llt(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  const typename Cfg::Dense b = randomDense<Cfg>(n, 1, g);
  const typename Cfg::Dense x0 = llt.solve(b);
  auto stillSolvesA = [&]() {
    typename Cfg::Dense x = llt.solve(b);
    CHECK(double((A * x - b).norm() / b.norm()) <= lowRankTolerance<Cfg>());
  };
  SUBCASE("index out of range") {
    llt.removeDofs(std::vector<int>{0, int(n)});
    CHECK(llt.info() == Eigen::InvalidInput);
    llt.removeDofs(std::vector<int>{-1});
    CHECK(llt.info() == Eigen::InvalidInput);
    stillSolvesA();
  }
  SUBCASE("repeated index") {
    llt.removeDofs(std::vector<int>{4, 7, 4});
    CHECK(llt.info() == Eigen::InvalidInput);
    CHECK(llt.removedDofs().empty());
    stillSolvesA();
  }
  SUBCASE("removing a removed dof, restoring a dof that is not removed") {
    llt.removeDofs(std::vector<int>{5});
    REQUIRE(llt.info() == Eigen::Success);
    llt.removeDofs(std::vector<int>{6, 5});
    CHECK(llt.info() == Eigen::InvalidInput);
    CHECK(llt.removedDofs().size() == 1);
    llt.restoreDofs(std::vector<int>{6});
    CHECK(llt.info() == Eigen::InvalidInput);
    llt.restoreDofs(std::vector<int>{5});
    CHECK(llt.info() == Eigen::Success);
    stillSolvesA();
  }
  SUBCASE("pattern mismatch in updateColumns") {
    typename Cfg::FullMatrix other = A;
    other.coeffRef(0, n - 1) = Scalar(0.001);
    other.coeffRef(n - 1, 0) = Scalar(0.001);
    llt.updateColumns(toInput<Cfg>(other), std::vector<int>{0});
    CHECK(llt.info() == Eigen::InvalidInput);
    stillSolvesA();
    // the pattern is checked whole: also where no listed column is
    llt.updateColumns(toInput<Cfg>(other), std::vector<int>{int(n / 2)});
    CHECK(llt.info() == Eigen::InvalidInput);
    stillSolvesA();
    typename Cfg::FullMatrix fewer = A;  // an entry gone (not merely zero) far from the listed column
    fewer.coeffRef(n - 1, n - 1) = Scalar(0);
    fewer.prune([n](Index r, Index c, const Scalar&) { return r != c || r != n - 1; });
    llt.updateColumns(toInput<Cfg>(fewer), std::vector<int>{0});
    CHECK(llt.info() == Eigen::InvalidInput);
    stillSolvesA();
  }
  SUBCASE("an update that makes the matrix indefinite leaves the previous factor") {
    typename Cfg::FullMatrix bad = A;
    bad.coeffRef(3, 3) = Scalar(-1);
    llt.updateColumns(toInput<Cfg>(bad), std::vector<int>{3});
    CHECK(llt.info() == Eigen::NumericalIssue);
    CHECK(llt.failedColumn() >= 0);
    stillSolvesA();
    // and the object goes on updating
    llt.removeDofs(std::vector<int>{1, 2});
    CHECK(llt.info() == Eigen::Success);
  }
  SUBCASE("restoring dofs whose values make the matrix indefinite leaves them removed, on every route") {
    // a removed dof's values are not factored: an update may make it indefinite there, and
    // restoring it must then fail without changing the factor
    typename Cfg::FullMatrix indefinite = A;
    indefinite.coeffRef(3, 3) = Scalar(-1);
    llt.removeDofs(std::vector<int>{3, 40});
    REQUIRE(llt.info() == Eigen::Success);
    llt.updateColumns(toInput<Cfg>(indefinite), std::vector<int>{3});
    REQUIRE(llt.info() == Eigen::Success);
    std::vector<char> removed(n, 0);
    removed[3] = removed[40] = 1;
    const typename Cfg::FullMatrix factored = withIdentityRows<Cfg>(indefinite, removed);
    for (const Eigen::UpdateRoute route : {Eigen::UpdateRoute::Automatic, Eigen::UpdateRoute::Mixed,
                                           Eigen::UpdateRoute::LowRank, Eigen::UpdateRoute::PartialRefactorization,
                                           Eigen::UpdateRoute::Refactorization}) {
      CAPTURE(int(route));
      llt.setUpdateRoute(route);
      llt.restoreDofs(std::vector<int>{40, 3});
      CHECK(llt.info() == Eigen::NumericalIssue);
      CHECK(llt.failedColumn() >= 0);
      CHECK(llt.removedDofs().size() == 2);
      CHECK(removedAreIdentity<Cfg>(llt, removed));
      const typename Cfg::Dense x = llt.solve(b);
      CHECK(double((factored * x - b).norm() / b.norm()) <= lowRankTolerance<Cfg>());
    }
    llt.setUpdateRoute(Eigen::UpdateRoute::Automatic);
    llt.updateColumns(toInput<Cfg>(A), std::vector<int>{3});  // the object goes on updating
    REQUIRE(llt.info() == Eigen::Success);
    llt.restoreDofs(std::vector<int>{3, 40});
    CHECK(llt.info() == Eigen::Success);
    stillSolvesA();
  }
  SUBCASE("NaN or infinity in an updated column, on every route, leaves the previous factor") {
    typedef typename Cfg::RealScalar Real;
    const Scalar badValues[] = {Scalar(std::numeric_limits<Real>::quiet_NaN()), Scalar(std::numeric_limits<Real>::infinity())};
    const Eigen::UpdateRoute routes[] = {Eigen::UpdateRoute::Automatic, Eigen::UpdateRoute::PartialRefactorization,
                                         Eigen::UpdateRoute::Refactorization};
    const Index column = n / 2;
    Index row = -1;  // an entry of that column off the diagonal
    for (typename Cfg::FullMatrix::InnerIterator it(A, column); it && row < 0; ++it)
      if (it.row() != column) row = it.row();
    REQUIRE(row >= 0);
    for (const Eigen::UpdateRoute route : routes)
      for (const Scalar bad : badValues)
        for (const bool diagonal : {true, false}) {
          CAPTURE(int(route));
          CAPTURE(diagonal);
          llt.setUpdateRoute(route);
          typename Cfg::FullMatrix changed = A;
          if (diagonal) {
            changed.coeffRef(column, column) = bad;
          } else {
            changed.coeffRef(row, column) = bad;
            changed.coeffRef(column, row) = bad;
          }
          llt.updateColumns(toInput<Cfg>(changed), diagonal ? std::vector<int>{int(column)}
                                                            : std::vector<int>{int(column), int(row)});
          CHECK(llt.info() == Eigen::NumericalIssue);
          stillSolvesA();
        }
    llt.setUpdateRoute(Eigen::UpdateRoute::Automatic);
    llt.removeDofs(std::vector<int>{1, 2});  // and the object goes on updating
    CHECK(llt.info() == Eigen::Success);
  }
}
