// insertDofs / mergeDofs (paper §4.2, Algorithm 4): random sequences of vertex splits (the
// matrix grows by copies of existing dofs, as when a mesh is cut), merges (a cut undone),
// Dirichlet removals and restores and value changes, on weighted graph Laplacians and mesh
// Laplacians. After every step the factor equals a fresh factorization of the current matrix
// with the solver's own (extended) permutation, and it solves the current matrix (the solve right
// after the update reusing the kept forward substitution on the clean supernodes only, bitwise
// equal to a full pass). Bad input
// (wrong sizes, an origin out of range or pointing at a new dof, entries outside the duplicated
// pattern, a matrix that is not positive definite, NaN or infinite entries) leaves the object as
// it was.
#include "test_checks.h"
#include "test_config.h"
#include "test_matrices.h"

#include <unsupported/Eigen/MeshTools>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <random>

namespace {
using namespace uctest;

/** A weighted graph whose Laplacian plus a positive margin per vertex is the test matrix
  * (Hermitian positive definite by diagonal dominance). Splitting a vertex moves some of its
  * edges to a new copy, which is what cutting a mesh does to its Laplacian's pattern. */
template <typename Scalar>
struct SplitGraph {
  typedef typename Eigen::NumTraits<Scalar>::Real Real;
  Index n = 0;
  std::map<std::pair<Index, Index>, Scalar> edges;  ///< (i < j) -> weight of entry (j, i)
  std::vector<Real> margin;

  template <typename FullMatrix>
  FullMatrix matrix() const {
    typedef typename FullMatrix::StorageIndex StorageIndex;
    std::vector<Eigen::Triplet<Scalar, StorageIndex>> t;
    std::vector<Real> diag(margin);
    for (const auto& e : edges) {
      const Index i = e.first.first, j = e.first.second;
      t.emplace_back(StorageIndex(j), StorageIndex(i), e.second);
      t.emplace_back(StorageIndex(i), StorageIndex(j), Eigen::numext::conj(e.second));
      diag[i] += std::abs(e.second);
      diag[j] += std::abs(e.second);
    }
    for (Index i = 0; i < n; ++i) t.emplace_back(StorageIndex(i), StorageIndex(i), Scalar(diag[i]));
    FullMatrix A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    return A;
  }

  /** Splits the vertices \a origins: each gets a copy (n, n+1, ...) that takes a random half of
    * its edges, and sometimes an edge to its origin, and the origin's margin. With \a pure, the
    * copy gets half of the origin's margin and no edge to it: glued back (copies added onto their origins)
    * the matrix is the one before, as when a mesh is cut. \returns the origin vector (cut_mesh's I). */
  std::vector<int> split(const std::vector<int>& origins, std::mt19937& g, bool pure = false) {
    std::vector<int> origin(n + origins.size());
    for (Index i = 0; i < n; ++i) origin[i] = int(i);
    std::vector<Index> copyOf(n, -1);
    for (std::size_t k = 0; k < origins.size(); ++k) {
      copyOf[origins[k]] = n + Index(k);
      origin[n + k] = origins[k];
      if (pure) margin[origins[k]] /= 2;  // (shared out: each keeps a positive margin)
      margin.push_back(margin[origins[k]]);
    }
    std::map<std::pair<Index, Index>, Scalar> next;
    for (const auto& e : edges) {
      Index i = e.first.first, j = e.first.second;
      if (copyOf[i] >= 0 && g() % 2) i = copyOf[i];
      if (copyOf[j] >= 0 && g() % 2) j = copyOf[j];
      next[std::make_pair((std::min)(i, j), (std::max)(i, j))] += e.second;
    }
    for (int o : origins)
      if (!pure && g() % 2) next[std::make_pair(Index(o), copyOf[o])] = Scalar(0.5);
    edges.swap(next);
    n += Index(origins.size());
    return origin;
  }
};

/** Merges every copy \a c with \a copyOf[c] >= 0 back into that dof (its edges move there; the dofs
  * after it move down). \returns mergeDofs()'s origin vector (by current dof). */
template <typename Scalar>
std::vector<int> mergeCopies(SplitGraph<Scalar>& G, const std::vector<Index>& copyOf) {
  std::vector<int> origin(G.n);
  std::vector<Index> newIndex(G.n, -1);
  Index next = 0;
  for (Index i = 0; i < G.n; ++i) {
    origin[i] = copyOf[i] >= 0 ? int(copyOf[i]) : int(i);
    if (copyOf[i] < 0) newIndex[i] = next++;
  }
  auto target = [&](Index i) { return newIndex[copyOf[i] >= 0 ? copyOf[i] : i]; };
  std::map<std::pair<Index, Index>, Scalar> edges;
  for (const auto& e : G.edges) {
    const Index i = target(e.first.first), j = target(e.first.second);
    if (i != j) edges[std::make_pair((std::min)(i, j), (std::max)(i, j))] += e.second;
  }
  std::vector<typename SplitGraph<Scalar>::Real> margin(next);
  for (Index i = 0; i < G.n; ++i)
    if (copyOf[i] < 0) margin[newIndex[i]] = G.margin[i];
  G.edges.swap(edges);
  G.margin.swap(margin);
  G.n = next;
  return origin;
}

template <typename Cfg>
SplitGraph<typename Cfg::Scalar> graphOf(const typename Cfg::FullMatrix& A) {
  SplitGraph<typename Cfg::Scalar> G;
  G.n = A.rows();
  G.margin.assign(G.n, typename Cfg::RealScalar(0.05));
  for (Index j = 0; j < A.outerSize(); ++j)
    for (typename Cfg::FullMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() > j) G.edges[std::make_pair(j, Index(it.row()))] = it.value();
  return G;
}

template <typename Cfg>
double exactTolerance() {
  return std::is_same<typename Cfg::RealScalar, double>::value ? 1e-14
                                                                : 50 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon());
}

/** Tolerance of the routes that fold low-rank changes (not bitwise): a few hundred roundings. */
template <typename Cfg>
double lowRankTolerance() {
  return 1e4 * double(Eigen::NumTraits<typename Cfg::RealScalar>::epsilon());
}

/** Checks the solver against a fresh simplicial factorization of P·current·Pᵀ in natural order
  * (the solver's own permutation P, no new ordering or postorder), and a solve; \a tolerance:
  * exactTolerance() for the exact routes. */
template <typename Cfg>
void checkAgainstFresh(const typename Cfg::Solver& llt, const typename Cfg::FullMatrix& current, std::mt19937& g,
                       double tolerance = exactTolerance<Cfg>()) {
  typedef typename Cfg::FullMatrix FullMatrix;
  REQUIRE(llt.rows() == current.rows());
  FullMatrix C;
  C = current.template selfadjointView<Eigen::Lower>().twistedBy(llt.permutationP());
  Eigen::SimplicialLLT<FullMatrix, Eigen::Lower, Eigen::NaturalOrdering<typename Cfg::StorageIndex>> fresh(C);
  REQUIRE(fresh.info() == Eigen::Success);
  const FullMatrix L = llt.matrixL(), Lf = fresh.matrixL();
  CHECK(double((L - Lf).norm() / Lf.norm()) <= tolerance);
  const typename Cfg::Dense b = randomDense<Cfg>(current.rows(), 2, g);
  const typename Cfg::Dense x = llt.solve(b);
  CHECK(double((current * x - b).norm() / b.norm()) <= 100 * tolerance);
}

template <typename Cfg>
typename Cfg::FullMatrix meshLaplacian(bool closed) {
  typedef typename Cfg::Scalar Scalar;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  if (closed)
    Eigen::icosphereMesh(2, V, F);
  else
    Eigen::gridMesh(21, 17, V, F);
  typename Cfg::FullMatrix A = Eigen::cotanLaplacian<Scalar, typename Cfg::StorageIndex>(V, F);
  return A;
}

/** The dofs below \a nb whose column differs between \a small (nb × nb) and \a large (its
  * leading block, and zero below it), as a cut tool knows them. */
template <typename Dense>
std::vector<int> changedColumns(const Dense& small, const Dense& large, Index nb) {
  std::vector<int> changed;
  for (Index j = 0; j < nb; ++j)
    if (small.col(j) != large.col(j).head(nb) || !large.col(j).tail(large.rows() - nb).isZero(0))
      changed.push_back(int(j));
  return changed;
}

/** A shorter changed list that still names a dof of every changed entry between dofs below
  * \a nb, one of the two picked at random (as updateColumns() takes the columns of an entry:
  * its row is found by symmetry); entries at the other dofs (copies, merged dofs) are found
  * through their origins. */
template <typename Dense>
std::vector<int> oneDofPerChangedEntry(const Dense& small, const Dense& large, Index nb, std::mt19937& coin) {
  std::vector<char> named(nb, 0);
  for (Index j = 0; j < nb; ++j)
    for (Index i = j; i < nb; ++i)
      if (small(i, j) != large(i, j) && !named[i] && !named[j]) named[coin() % 2 ? i : j] = 1;
  std::vector<int> changed;
  for (Index j = 0; j < nb; ++j)
    if (named[j]) changed.push_back(int(j));
  return changed;
}

/** Negates the weights of up to two edges of \a G between old dofs that are not split (\a origin:
  * cut_mesh's I of the last split): their entries change, their diagonals do not, so a changed
  * list naming one dof of each such entry (oneDofPerChangedEntry()) names only one of the two. */
template <typename Scalar>
void flipEdgesAwayFrom(SplitGraph<Scalar>& G, const std::vector<int>& origin, std::mt19937& coin) {
  std::vector<char> split(G.n, 0);
  for (std::size_t x = 0; x < origin.size(); ++x)
    if (Index(origin[x]) != Index(x)) split[x] = split[origin[x]] = 1;
  std::vector<std::pair<Index, Index> > candidates;
  for (const auto& e : G.edges)
    if (!split[e.first.first] && !split[e.first.second]) candidates.push_back(e.first);
  for (int k = 0; k < 2 && !candidates.empty(); ++k) G.edges[candidates[coin() % candidates.size()]] *= Scalar(-1);
}

/** The diagonal shift a sequence factors with (setShift(offset, scale): d_ii -> offset + scale d_ii). */
struct Shift {
  double offset = 0, scale = 1;
};

/** Random sequence of splits, merges (undo of the latest split), removals, restores and value
  * changes, checking every step against a fresh factorization of the current matrix (with
  * \a shift applied to its diagonal). \returns how many splits and merges took the Mixed route
  * (refactorization below, signed low-rank folds on top). */
template <typename Cfg>
int randomSequence(const typename Cfg::FullMatrix& A0, Eigen::UpdateRoute route, int steps, unsigned seed,
                   bool pureCuts = false, Shift shift = Shift()) {
  typedef typename Cfg::FullMatrix FullMatrix;
  seed += seedOffset();
  std::mt19937 g(seed);
  SplitGraph<typename Cfg::Scalar> G = graphOf<Cfg>(A0);
  typename Cfg::Solver llt;
  llt.setThreadCount(1);
  llt.setShift(typename Cfg::RealScalar(shift.offset), typename Cfg::RealScalar(shift.scale));
  llt.compute(toInput<Cfg>(G.template matrix<FullMatrix>()));
  REQUIRE(llt.info() == Eigen::Success);
  llt.setUpdateRoute(route);
  std::vector<char> removed(G.n, 0);
  struct Split {
    SplitGraph<typename Cfg::Scalar> before;
    std::vector<int> origin;
  };
  std::vector<Split> splits;
  int inserts = 0, merges = 0, mixed = 0;
  const bool exactRoute =
      route == Eigen::UpdateRoute::PartialRefactorization || route == Eigen::UpdateRoute::Refactorization;
  const double tolerance = exactRoute ? exactTolerance<Cfg>() : lowRankTolerance<Cfg>();
  // a right-hand side that stays the same on the dofs that stay (its first n rows): the solve right
  // after each update reuses the kept forward substitution, renumbered by the cuts and merges
  typedef typename Cfg::Dense Dense;
  std::mt19937 gFixed(seed + 100);
  Dense bFixed = randomDense<Cfg>(G.n, 2, gFixed);
  auto fixedRhs = [&](Index rows) {
    while (bFixed.rows() < rows) {
      const Dense more = randomDense<Cfg>(rows - bFixed.rows(), 2, gFixed);
      bFixed.conservativeResize(rows, Eigen::NoChange);
      bFixed.bottomRows(more.rows()) = more;
    }
    return Dense(bFixed.topRows(rows));
  };
  {
    const Dense primed = llt.solve(fixedRhs(G.n));
    (void)primed;
  }
  for (int step = 0; step < steps; ++step) {
    int op = int(g() % 6);
    if (step + 1 == steps && merges == 0) op = splits.empty() ? 0 : 2;  // every run merges at least once
    if (step + 2 == steps && splits.empty()) op = 0;
    CAPTURE(step);
    CAPTURE(op);
    if (op <= 1) {  // split a few vertices
      std::vector<int> origins;
      const int count = 1 + int(g() % 6);
      for (int k = 0; k < count; ++k) {
        const int v = int(g() % G.n);
        if (std::find(origins.begin(), origins.end(), v) == origins.end()) origins.push_back(v);
      }
      splits.push_back(Split{G, {}});
      splits.back().origin = G.split(origins, g, pureCuts);
      const bool told = g() % 2 == 0;
      std::mt19937 coin(unsigned(seed + 7919 * step));  // (its own stream: g's stays as it was)
      if (told && !pureCuts && coin() % 2) flipEdgesAwayFrom(G, splits.back().origin, coin);
      const FullMatrix cut = G.template matrix<FullMatrix>();
      if (!told) {
        llt.insertDofs(toInput<Cfg>(cut), splits.back().origin);
      } else {  // told the changed old dofs: those whose column differs (as a cut tool knows them)
        typedef Eigen::Matrix<typename Cfg::Scalar, Eigen::Dynamic, Eigen::Dynamic> DenseMatrix;
        const DenseMatrix before = DenseMatrix(splits.back().before.template matrix<FullMatrix>()), after = DenseMatrix(cut);
        const Index nb = before.rows();
        const std::vector<int> changed =
            coin() % 2 ? changedColumns(before, after, nb)
                       : oneDofPerChangedEntry(before, after, nb, coin);
        llt.insertDofs(toInput<Cfg>(cut), splits.back().origin, changed);
      }
      REQUIRE(llt.info() == Eigen::Success);
      CHECK(llt.lastUpdate().changedColumns >= Index(origins.size()));
      removed.resize(G.n, 0);
      ++inserts;
      mixed += llt.lastUpdate().route == Eigen::UpdateRoute::Mixed;
      if (exactRoute) CHECK(llt.lastUpdate().route != Eigen::UpdateRoute::Mixed);
    } else if (op == 2 && !splits.empty()) {  // undo the latest split
      const Split s = splits.back();
      splits.pop_back();
      const FullMatrix cut = G.template matrix<FullMatrix>();
      G = s.before;
      const FullMatrix merged = G.template matrix<FullMatrix>();
      if (g() % 2) {
        llt.mergeDofs(toInput<Cfg>(merged), s.origin);
      } else {  // told the changed kept dofs: those whose column differs
        typedef Eigen::Matrix<typename Cfg::Scalar, Eigen::Dynamic, Eigen::Dynamic> DenseMatrix;
        const DenseMatrix before = DenseMatrix(cut), after = DenseMatrix(merged);
        const Index nb = after.rows();
        std::mt19937 coin(unsigned(seed + 7919 * step));
        const std::vector<int> changed =
            coin() % 2 ? changedColumns(after, before, nb)
                       : oneDofPerChangedEntry(after, before, nb, coin);
        llt.mergeDofs(toInput<Cfg>(merged), s.origin, changed);
      }
      REQUIRE(llt.info() == Eigen::Success);
      removed.resize(G.n);
      ++merges;
      mixed += llt.lastUpdate().route == Eigen::UpdateRoute::Mixed;
    } else if (op == 3) {  // Dirichlet removal of a few dofs
      std::vector<int> dofs;
      for (int k = 0; k < 4; ++k) {
        const int v = int(g() % G.n);
        if (!removed[v] && std::find(dofs.begin(), dofs.end(), v) == dofs.end()) dofs.push_back(v);
      }
      llt.removeDofs(dofs);
      REQUIRE(llt.info() == Eigen::Success);
      for (int v : dofs) removed[v] = 1;
    } else if (op == 4) {  // restore all removed dofs
      std::vector<int> dofs;
      for (Index v = 0; v < G.n; ++v)
        if (removed[v]) dofs.push_back(int(v));
      llt.restoreDofs(dofs);
      REQUIRE(llt.info() == Eigen::Success);
      std::fill(removed.begin(), removed.end(), 0);
    } else {  // new values in a few columns
      std::vector<int> cols;
      for (int k = 0; k < 3; ++k) {
        const int v = int(g() % G.n);
        if (std::find(cols.begin(), cols.end(), v) == cols.end()) cols.push_back(v);
        G.margin[v] *= 1.5;
      }
      llt.updateColumns(toInput<Cfg>(G.template matrix<FullMatrix>()), cols);
      REQUIRE(llt.info() == Eigen::Success);
    }
    const Eigen::UpdateStatistics& st = llt.lastUpdate();
    {  // only the dirty supernodes substituted again, and bitwise what a full pass gives
      const Dense kept = llt.solve(fixedRhs(G.n));
      CHECK(llt.lastSolveForwardColumns() == st.dirtyColumns);
      const Dense other = llt.solve(randomDense<Cfg>(G.n, 2, g));
      CHECK(llt.lastSolveForwardColumns() == G.n);
      const Dense full = llt.solve(fixedRhs(G.n));
      CHECK(double((full - kept).norm()) == 0);
      (void)other;
    }
    CHECK(st.flopFraction >= 0);
    if (route != Eigen::UpdateRoute::Mixed)  // (a forced Mixed route may cost more than a refactorization)
      CHECK(st.flopFraction <= 1.0 + 1e-12);
    // the matrix factored: the current (cut) one, its diagonal shifted
    const FullMatrix A = shiftedMatrix<Cfg>(G.template matrix<FullMatrix>(), shift.offset, shift.scale);
    checkAgainstFresh<Cfg>(llt, withIdentityRows<Cfg>(A, removed), g, tolerance);
    CHECK(removedAreIdentity<Cfg>(llt, removed));
    // Dirichlet solve on it: A_II x_I = b_I - A_IB g, x_B = g
    const typename Cfg::Dense b = randomDense<Cfg>(A.rows(), 2, g), known = randomDense<Cfg>(A.rows(), 2, g);
    const typename Cfg::Dense x = llt.solveDirichlet(b, known);
    typename Cfg::Dense r = A.template selfadjointView<Eigen::Lower>() * x - b;
    for (Index i = 0; i < A.rows(); ++i)
      if (removed[std::size_t(i)]) {
        CHECK(x.row(i) == known.row(i));
        r.row(i).setZero();
      }
    CHECK(double(r.norm() / (b.norm() + (A.template selfadjointView<Eigen::Lower>() * x).norm())) <=
          100 * tolerance);
    const Dense primed = llt.solve(fixedRhs(G.n));  // what the next step's solve starts from
    (void)primed;
  }
  CHECK(inserts > 0);
  CHECK(merges > 0);
  return mixed;
}

}  // namespace

TEST_CASE_TEMPLATE("insertDofs/mergeDofs sequences match a fresh factorization", Cfg, UC_CORE_CONFIGS) {
  const int steps = Cfg::isPrimary ? 60 : 20;
  SUBCASE("grid Laplacian, partial refactorization") {
    randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::PartialRefactorization, steps, 1);
  }
  SUBCASE("sphere Laplacian, automatic") {
    randomSequence<Cfg>(meshLaplacian<Cfg>(true), Eigen::UpdateRoute::Automatic, steps, 2);
  }
  SUBCASE("random sparse matrix") {
    std::mt19937 g(5);
    const typename Cfg::FullMatrix A =
        spdFromPattern<typename Cfg::Scalar, typename Cfg::StorageIndex>(randomPattern(250, 4.0, g), g);
    randomSequence<Cfg>(A, Eigen::UpdateRoute::Automatic, steps, 3);
  }
  SUBCASE("full refactorization route") {
    randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::Refactorization, steps / 3, 4);
  }
  SUBCASE("grid Laplacian, mixed route: refactorization below, signed folds on top") {
    const int mixed = randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::Mixed, steps, 6);
    if (Cfg::isPrimary) CHECK(mixed > 0);  // (a natural or reversed order has no top to fold into)
  }
  SUBCASE("grid Laplacian, mixed route, a sequence whose folds leave rounding in removed rows elsewhere") {
    // (a removal visits the row subtrees of the matrix's pattern; this one removes a dof whose
    // row also sits, at 1e-16 from earlier folds, in a supernode outside them)
    randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::Mixed, steps, 606);
  }
  SUBCASE("grid Laplacian, cuts that glue back (one-signed changes of the copies' rank), automatic") {
    randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::Automatic, steps, 9, true);
  }
  SUBCASE("grid Laplacian, cuts that glue back, mixed route") {
    const int mixed = randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::Mixed, steps, 10, true);
    if (Cfg::isPrimary) CHECK(mixed > 0);
  }
  SUBCASE("random sparse matrix, mixed route") {
    std::mt19937 g(7);
    const typename Cfg::FullMatrix A =
        spdFromPattern<typename Cfg::Scalar, typename Cfg::StorageIndex>(randomPattern(250, 4.0, g), g);
    const int mixed = randomSequence<Cfg>(A, Eigen::UpdateRoute::Mixed, steps, 8);
    if (Cfg::isPrimary) CHECK(mixed > 0);
  }
  SUBCASE("setShift(offset, scale), grid Laplacian, mixed and automatic routes") {
    // the folds take the change of the factored diagonal (offset + scale d), a copy's placeholder
    // included; with an offset a cut no longer glues back at its origins
    for (const Shift shift : {Shift{0.5, 1}, Shift{0, 3}, Shift{0.25, 2}}) {
      CAPTURE(shift.offset);
      CAPTURE(shift.scale);
      const int mixed = randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::Mixed, steps / 2, 11, false, shift);
      if (Cfg::isPrimary) CHECK(mixed > 0);
      randomSequence<Cfg>(meshLaplacian<Cfg>(false), Eigen::UpdateRoute::Automatic, steps / 2, 12, true, shift);
    }
  }
}

TEST_CASE_TEMPLATE("merges of older copies and long cut/merge chains", Cfg, UC_CORE_CONFIGS) {
  // Merging a copy that is not among the last dofs renumbers the dofs after it (the solver then
  // rebuilds its copy of the matrix); long chains of cuts and merges leave garbage in that copy
  // until it is compacted. Both are checked against fresh factorizations at every step.
  typedef typename Cfg::FullMatrix FullMatrix;
  std::mt19937 g(11);
  SplitGraph<typename Cfg::Scalar> G = graphOf<Cfg>(meshLaplacian<Cfg>(false));
  typename Cfg::Solver llt;
  llt.compute(toInput<Cfg>(G.template matrix<FullMatrix>()));
  REQUIRE(llt.info() == Eigen::Success);
  std::vector<Index> copyOf(G.n, -1);  // per dof: the dof it copies, or -1
  const int steps = Cfg::isPrimary ? 40 : 12;
  int olderMerges = 0;
  for (int step = 0; step < steps; ++step) {
    CAPTURE(step);
    std::vector<Index> copies;
    for (Index i = 0; i < G.n; ++i)
      if (copyOf[i] >= 0) copies.push_back(i);
    if (copies.empty() || g() % 3 != 0) {  // cut a few more vertices (never a copy)
      std::vector<int> origins;
      for (int k = 0; k < 4; ++k) {
        const int v = int(g() % G.n);
        if (copyOf[v] < 0 && std::find(origins.begin(), origins.end(), v) == origins.end()) origins.push_back(v);
      }
      const std::vector<int> origin = G.split(origins, g);
      copyOf.resize(G.n, -1);
      for (Index c = Index(copyOf.size() - origins.size()); c < G.n; ++c) copyOf[c] = origin[c];
      llt.insertDofs(toInput<Cfg>(G.template matrix<FullMatrix>()), origin);
    } else {  // merge a random half of the copies, old ones included
      std::vector<Index> merge(G.n, -1);
      bool older = false;
      for (Index c : copies)
        if (g() % 2) {
          merge[c] = copyOf[c];
          older = older || c + 8 < G.n;
        }
      olderMerges += older;
      const std::vector<int> origin = mergeCopies(G, merge);
      std::vector<Index> next;
      for (Index i = 0; i < Index(copyOf.size()); ++i)
        if (merge[i] < 0) next.push_back(copyOf[i]);
      // a copy's origin never moves down past a merged dof: renumber the survivors' origins
      std::vector<Index> shift(copyOf.size() + 1, 0);
      for (Index i = 0; i < Index(copyOf.size()); ++i) shift[i + 1] = shift[i] + (merge[i] >= 0);
      for (Index& o : next)
        if (o >= 0) o -= shift[o];
      copyOf.swap(next);
      llt.mergeDofs(toInput<Cfg>(G.template matrix<FullMatrix>()), origin);
    }
    REQUIRE(llt.info() == Eigen::Success);
    checkAgainstFresh<Cfg>(llt, G.template matrix<FullMatrix>(), g, lowRankTolerance<Cfg>());
  }
  if (Cfg::isPrimary) CHECK(olderMerges > 0);
}

TEST_CASE_TEMPLATE("gluing a cut back finds where it differs from the uncut matrix", Cfg, UC_CORE_CONFIGS) {
  // The rank bound of the mixed route (LowRankTopUpdate.h) counts the copies, plus the dofs
  // where the cut matrix, glued back, is not the uncut one: a cut that only shares out entries
  // has none; a changed diagonal is a small or a large mismatch; a changed edge flags both ends.
  typedef typename Cfg::FullMatrix FullMatrix;
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::StorageIndex StorageIndex;
  typedef Eigen::internal::updatable_cholesky::InputStore<Scalar, StorageIndex> Store;
  typedef Eigen::internal::updatable_cholesky::OuterRange Range;
  constexpr int UpLo = Cfg::UpLo;
  constexpr bool rowMajor = bool(FullMatrix::IsRowMajor);
  std::mt19937 g(21);
  SplitGraph<Scalar> G = graphOf<Cfg>(meshLaplacian<Cfg>(false));
  const FullMatrix A = G.template matrix<FullMatrix>();
  const Index n = A.rows();
  const std::vector<int> origin = G.split({3, 40, 41, 100}, g, true);
  FullMatrix C = G.template matrix<FullMatrix>();
  auto mismatches = [&](const FullMatrix& cut) {
    FullMatrix compressed = cut;
    compressed.makeCompressed();
    Store cutStore, uncutStore;
    cutStore.template assign<UpLo>(compressed);
    uncutStore.template assign<UpLo>(A);
    std::vector<Range> cutRanges, uncutRanges;
    for (Index o = 0; o < cutStore.outerSize(); ++o) cutRanges.push_back(Range{o, cutStore.begin[o], cutStore.end[o]});
    for (Index o = 0; o < uncutStore.outerSize(); ++o)
      uncutRanges.push_back(Range{o, uncutStore.begin[o], uncutStore.end[o]});
    std::vector<char> flag(n, 0);
    std::vector<StorageIndex> out;
    Eigen::internal::updatable_cholesky::GluingScratch<Scalar> scratch;
    Eigen::internal::updatable_cholesky::gluingMismatches<rowMajor>(
        cutStore, cutRanges, [&](Index x) { return Index(origin[x]); }, uncutStore, uncutRanges, flag, out, scratch);
    CHECK(std::count(scratch.bucket.begin(), scratch.bucket.end(), Index(-1)) == Index(scratch.bucket.size()));  // left as it came
    std::map<Index, int> result;
    for (StorageIndex x : out) result[Index(x)] = flag[x];
    return result;
  };
  CHECK(mismatches(C).empty());
  typedef typename Cfg::RealScalar Real;
  FullMatrix D = C;
  // above 64 roundings, below sqrt(eps): a small mismatch at the origin of the copy (40)
  const Real tiny = Real(1000) * Eigen::NumTraits<Real>::epsilon();
  D.coeffRef(n + 1, n + 1) += Scalar(tiny * Eigen::numext::real(D.coeff(n + 1, n + 1)));
  std::map<Index, int> small = mismatches(D);
  CHECK(small.size() == 1);
  CHECK(small[40] == 1);
  FullMatrix E = C;
  const Index u = 3, v = 2;  // an edge of the grid from an origin to a vertex that is not cut
  REQUIRE(A.coeff(u, v) != Scalar(0));
  E.coeffRef(u, v) += Scalar(Real(0.25));
  E.coeffRef(v, u) += Scalar(Real(0.25));
  if (C.coeff(u, v) == Scalar(0)) {  // the edge went to the copy of 3
    E.coeffRef(u, v) = Scalar(0);
    E.coeffRef(v, u) = Scalar(0);
    E.coeffRef(n, v) += Scalar(Real(0.25));
    E.coeffRef(v, n) += Scalar(Real(0.25));
  }
  std::map<Index, int> large = mismatches(E);
  CHECK(large.size() == 2);
  CHECK(large[u] == 2);
  CHECK(large[v] == 2);
}

TEST_CASE_TEMPLATE("the blocked downdate keeps L L^H - W W^H and agrees with hyperbolic rotations", Cfg, UC_CORE_CONFIGS) {
  // The negative half of a fold (BlockedDowndate.h): a supernode's block L (rows x columns) and W
  // (zero above its start row) become L' and W' with L' L'^H - W' W'^H = L L^H - W W^H, W' zero on
  // the supernode's own rows; L' is the unique factor, so the rotations give it too. Too large a
  // W loses a pivot, which is reported.
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::Dense Dense;
  typedef typename Cfg::RealScalar Real;
  typedef Eigen::internal::updatable_cholesky::Supernode<Scalar, typename Cfg::StorageIndex> Node;
  const Real eps = Eigen::NumTraits<Real>::epsilon();
  struct Shape { Index rows, cols, rank, start, removedColumn; };
  for (const Shape& shape : {Shape{90, 40, 12, 0, -1}, Shape{150, 70, 9, 11, 30}, Shape{40, 40, 20, 3, -1}, Shape{75, 33, 40, 0, 5}}) {
    CAPTURE(shape.rows);
    Node node;
    node.ncols = shape.cols;
    for (Index i = 0; i < shape.rows; ++i) node.rows.push_back(typename Cfg::StorageIndex(i));
    std::vector<char> removed(shape.rows, 0);
    Dense L = Dense::Random(shape.rows, shape.cols);
    for (Index j = 0; j < shape.cols; ++j) {
      L.col(j).head(j).setZero();
      L(j, j) = Scalar(Real(2 + shape.rows / 4));
    }
    Dense W = Dense::Random(shape.rows, shape.rank) * Scalar(Real(0.5));
    W.topRows(shape.start).setZero();
    if (shape.removedColumn >= 0) {  // a removed dof: a unit column, zero rows of W
      const Index r = shape.removedColumn;
      removed[r] = 1;
      L.col(r).setZero();
      L.row(r).setZero();
      L(r, r) = Scalar(1);
      W.row(r).setZero();
    }
    const Dense before = L * L.adjoint() - W * W.adjoint();
    node.values = L;
    Dense Wb = W;
    double flops = 0;
    REQUIRE(Eigen::internal::updatable_cholesky::downdateByBlockedReflections(node, Wb, 0, shape.rank, shape.start,
                                                                               removed.data(), flops));
    const Dense after = node.values.matrix() * node.values.matrix().adjoint() - Wb * Wb.adjoint();
    CHECK((after - before).norm() <= Real(100) * eps * before.norm());
    CHECK(Wb.topRows(shape.cols).norm() == Real(0));
    for (Index j = 0; j < shape.cols; ++j) {
      CHECK(Eigen::numext::real(node.values(j, j)) > Real(0));
      CHECK(Eigen::numext::imag(node.values(j, j)) == Real(0));
      CHECK(node.values.col(j).head(j).norm() == Real(0));
    }
    if (shape.removedColumn >= 0) CHECK(node.values.col(shape.removedColumn) == L.col(shape.removedColumn));
    Node rotated = node;
    rotated.values = L;
    Dense Wr = W;
    REQUIRE(Eigen::internal::updatable_cholesky::rotationSweep<true>(rotated, Wr, 0, shape.rank, shape.start,
                                                                     removed.data(), flops));
    CHECK((rotated.values.matrix() - node.values.matrix()).norm() <= Real(100) * eps * L.norm());
    CHECK(flops > 0);
    // a downdate past positive definiteness: reported, not a NaN factor
    node.values = L;
    Dense big = W * Scalar(Real(4 * shape.rows));
    CHECK_FALSE(Eigen::internal::updatable_cholesky::downdateByBlockedReflections(node, big, 0, shape.rank, shape.start,
                                                                                  removed.data(), flops));
  }
}

TEST_CASE_TEMPLATE("a relabeling moves positions only inside the supernodes that change", StorageIndex, int, long) {
  // DofRelabeling (DofInsertion.h) on synthetic layouts of supernodes with free positions after
  // their columns: a local insertion (buildLocalCopies()) puts each origin's copies right after
  // it and moves only the columns after the first origin of a supernode, into its free
  // positions; a local merge (buildLocalDrops()) gives the dropped positions back as free ones;
  // a layout anew (buildWithRoom()) keeps the order and leaves every supernode room. The same
  // object is reused from call to call (it writes back only its previous windows), as the solver does.
  typedef Eigen::internal::updatable_cholesky::DofRelabeling<StorageIndex> Relabeling;
  typedef Eigen::internal::updatable_cholesky::SupernodalFactor<double, StorageIndex> Factor;
  std::mt19937 g(17);
  Relabeling reused;
  for (int trial = 0; trial < 200; ++trial) {
    CAPTURE(trial);
    Factor f;
    const Index ns = 1 + Index(g() % 40);
    f.nodes.resize(ns);
    std::vector<Index> freeOf(ns);
    for (Index s = 0; s < ns; ++s) {
      f.nodes[s].firstCol = f.n;
      f.nodes[s].ncols = 1 + Index(g() % 6);
      freeOf[s] = Index(g() % 4);
      f.n += f.nodes[s].ncols + freeOf[s];
      for (Index k = f.nodes[s].firstCol; k < f.n; ++k) f.colToSuper.push_back(StorageIndex(s));
    }
    for (Index s = 0; s < ns; ++s) REQUIRE(f.freePositions(s) == freeOf[s]);
    const int kind = int(g() % 3);  // 0 local insertion, 1 local merge, 2 layout anew
    CAPTURE(kind);
    std::vector<StorageIndex> at;
    std::vector<Index> gained(ns, 0);  // copies (or drops) per supernode
    Relabeling fresh;
    fresh.copies.assign(f.n, 0);
    reused.copies.assign(f.n, 0);
    for (Index s = 0; s < ns; ++s) {
      const auto& node = f.nodes[s];
      for (Index c = 0; c < node.ncols; ++c) {
        if (g() % 3 != 0) continue;
        const Index k = node.firstCol + c;
        if (kind == 1) {  // a supernode keeps one column at least
          if (gained[s] + 1 >= node.ncols) continue;
          gained[s] += 1;
        } else {
          const Index count = 1 + Index(g() % 2);
          if (kind == 0 && gained[s] + count > freeOf[s]) continue;
          gained[s] += count;
          fresh.copies[k] = reused.copies[k] = StorageIndex(count);
        }
        at.push_back(StorageIndex(k));
      }
    }
    auto room = [](Index columns) { return (std::max)(Index(2), columns / 4); };
    for (Relabeling* r : {&fresh, &reused}) {
      if (kind == 0) r->buildLocalCopies(at, f);
      if (kind == 1) r->buildLocalDrops(at, f);
      if (kind == 2) r->buildWithRoom(at, f, room);
    }
    REQUIRE(fresh.newSize == reused.newSize);
    CHECK(fresh.newPosition == reused.newPosition);
    CHECK(std::vector<StorageIndex>(reused.oldPosition.begin(), reused.oldPosition.begin() + reused.newSize) ==
          std::vector<StorageIndex>(fresh.oldPosition.begin(), fresh.oldPosition.begin() + fresh.newSize));
    const Relabeling& r = reused;
    CHECK(r.local == (kind != 2));
    if (kind != 2) CHECK(r.newSize == f.n);
    std::vector<char> dropped(f.n, 0);
    if (kind == 1)
      for (StorageIndex k : at) dropped[k] = 1;
    // every used position lands in order, inside its supernode's new range, copies right after it
    Index previous = -1, wrong = 0, outside = 0, notCopies = 0, inverse = 0, moved = 0;
    std::vector<Index> newFirst(ns), newUsed(ns, 0);
    for (Index s = 0; s < ns; ++s) {
      const auto& node = f.nodes[s];
      newFirst[s] = kind == 2 ? Index(r.newPosition[node.firstCol]) : node.firstCol;  // (a local call keeps it)
      for (Index k = node.firstCol; k < node.firstCol + node.ncols; ++k) {
        const Index p = r.newPosition[k];
        if (dropped[k]) {
          wrong += p != -1;
          continue;
        }
        wrong += p <= previous;
        previous = p + r.copies[k];
        newUsed[s] += 1 + r.copies[k];
        inverse += r.oldPosition[p] != StorageIndex(k);
        for (Index t = 1; t <= r.copies[k]; ++t) notCopies += r.oldPosition[p + t] != -1;
        if (kind != 2) {
          const bool inWindow = std::any_of(r.windows.begin(), r.windows.end(), [&](const std::pair<StorageIndex, StorageIndex>& w) {
            return Index(w.first) <= k && k < Index(w.second);
          });
          moved += p != k && !inWindow;
          outside += p < node.firstCol || p + r.copies[k] >= f.ownedEnd(s);
        }
      }
    }
    CHECK(wrong == 0);
    CHECK(inverse == 0);
    CHECK(notCopies == 0);
    CHECK(moved == 0);
    CHECK(outside == 0);
    // the free positions: each supernode's range ends where the next one's begins
    for (Index s = 0; s < ns; ++s) {
      CAPTURE(s);
      const Index end = s + 1 < ns ? newFirst[s + 1] : r.newSize, freeNow = end - newFirst[s] - newUsed[s];
      if (kind == 0) CHECK(freeNow == freeOf[s] - gained[s]);
      if (kind == 1) CHECK(freeNow == freeOf[s] + gained[s]);
      if (kind == 2) CHECK(freeNow == (std::max)(freeOf[s] - gained[s], room(newUsed[s])));
      // new positions without an old one: the copies or the freed positions, and in a layout
      // anew the free positions beyond the old ones (the old free positions are kept, in place)
      Index unnamed = 0;
      for (Index j = newFirst[s]; j < end; ++j) unnamed += r.oldPosition[j] < 0;
      CHECK(unnamed == gained[s] + (kind == 2 ? freeNow - (std::min)(freeOf[s], freeNow) : Index(0)));
    }
    Index firstMoved = f.n;
    for (Index k = 0; k < f.n && firstMoved == f.n; ++k)
      if (r.newPosition[k] != StorageIndex(k)) firstMoved = k;
    CHECK(r.firstMoved <= firstMoved);
  }
}

TEST_CASE_TEMPLATE("splitting an update-matrix change samples the likely rank, then the bound", Cfg, UC_CORE_CONFIGS) {
  // updateMatrixChange() (LowRankTopUpdate.h): D = U' - U = P P^H - N N^H with as many columns as
  // D's rank, whether the likely rank it starts from is right, too low (it samples again up to
  // the bound) or the bound itself is too low (reported).
  typedef typename Cfg::Dense Dense;
  typedef typename Cfg::RealScalar Real;
  const Index m = 120, positive = 5, negative = 9;
  const Dense X = Dense::Random(m, m), Y = Dense::Random(m, positive), Z = Dense::Random(m, negative);
  const Dense U = X * X.adjoint(), Unew = U + Y * Y.adjoint() - Z * Z.adjoint();
  const Real tol = Real(1e4) * Eigen::NumTraits<Real>::epsilon() * U.norm();
  for (Index likely : {Index(14), Index(2)}) {
    CAPTURE(likely);
    Dense P, N;
    double flops = 0;
    REQUIRE(Eigen::internal::updatable_cholesky::updateMatrixChange(Unew.data(), U.data(), m, likely, Index(20), P, N,
                                                                      flops));
    CHECK(P.cols() == positive);
    CHECK(N.cols() == negative);
    const Dense D = P * P.adjoint() - N * N.adjoint();
    CHECK((D - (Unew - U)).norm() <= tol);
    CHECK(flops > 0);
  }
  Dense P, N;
  double flops = 0;
  CHECK_FALSE(Eigen::internal::updatable_cholesky::updateMatrixChange(Unew.data(), U.data(), m, Index(2), Index(3), P, N,
                                                                      flops));
}

/** The dofs that \a llt eliminates at the permuted \a positions, in their order. */
template <typename Solver>
std::vector<int> dofsEliminatedAt(const Solver& llt, const std::vector<Index>& positions) {
  std::vector<int> dofs(positions.size(), -1);
  for (Index i = 0; i < llt.rows(); ++i)
    for (std::size_t k = 0; k < positions.size(); ++k)
      if (Index(llt.permutationP().indices()[i]) == positions[k]) dofs[k] = int(i);
  for (int d : dofs) REQUIRE(d >= 0);
  return dofs;
}

TEST_CASE_TEMPLATE("insertDofs folds below a refactored root (the previous factor extended with identity)", Cfg,
                   uctest::d_int_col_lower_amd) {
  // a copy of the dof eliminated last changes a column of the root supernode; a copy of the dof
  // eliminated first makes the supernodes on its path dirty, and those without a changed column
  // take copy rows (zero in the previous factor). With the route forced to Mixed every dirty
  // supernode is folded, the root with its own input change (the copy's column)
  typedef typename Cfg::FullMatrix FullMatrix;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(60, 60, V, F);
  FullMatrix A = Eigen::cotanLaplacian<double, int>(V, F);
  SplitGraph<double> G = graphOf<Cfg>(A);
  const FullMatrix A0 = G.template matrix<FullMatrix>();
  typename Cfg::Solver llt;
  llt.setUpdateCaching(true);
  llt.compute(toInput<Cfg>(A0));
  REQUIRE(llt.info() == Eigen::Success);
  const Index n = A.rows();
  std::mt19937 g(11);
  const std::vector<int> origin = G.split(dofsEliminatedAt(llt, {n - 1, 0}), g, true);  // (the last, the first)
  const FullMatrix Acut = G.template matrix<FullMatrix>();
  llt.setUpdateRoute(Eigen::UpdateRoute::Mixed);
  llt.insertDofs(toInput<Cfg>(Acut), origin);
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().route == Eigen::UpdateRoute::Mixed);  // (a top closed under parents would be empty)
  checkAgainstFresh<Cfg>(llt, Acut, g, lowRankTolerance<Cfg>());
  llt.setUpdateRoute(Eigen::UpdateRoute::Automatic);
  llt.mergeDofs(toInput<Cfg>(A0), origin);
  REQUIRE(llt.info() == Eigen::Success);
  checkAgainstFresh<Cfg>(llt, A0, g, lowRankTolerance<Cfg>());
}

TEST_CASE_TEMPLATE("insertDofs/mergeDofs fold a cut through the root separator instead of refactoring the root", Cfg,
                   UC_CORE_CONFIGS) {
  // copies of dofs of the root supernode (the last three eliminated): their own input changes
  // (the copies' columns, the changed columns of their neighbours) are folded like the changes
  // passed up from below, so that under a nested-dissection ordering (where refactoring the
  // dirty supernodes costs much, the root's front most of it) the automatic route costs far
  // less; the factor matches a fresh one under every ordering. The merge that undoes the cut
  // likewise (folded in the previous structure, the merged dofs then dropped)
  typedef typename Cfg::FullMatrix FullMatrix;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(70, 70, V, F);
  const FullMatrix A = Eigen::cotanLaplacian<typename Cfg::Scalar, typename Cfg::StorageIndex>(V, F);
  std::mt19937 g(5);
  double flops[2] = {0, 0}, mergeFlops[2] = {0, 0};
  Eigen::UpdateRoute route = Eigen::UpdateRoute::Automatic, mergeRoute = Eigen::UpdateRoute::Automatic;
  for (int partial = 0; partial < 2; ++partial) {
    CAPTURE(partial);
    SplitGraph<typename Cfg::Scalar> G = graphOf<Cfg>(A);
    const FullMatrix A0 = G.template matrix<FullMatrix>();
    typename Cfg::Solver llt;
    llt.setUpdateCaching(true);
    llt.compute(toInput<Cfg>(A0));
    REQUIRE(llt.info() == Eigen::Success);
    const Index n = A.rows();
    std::mt19937 coin(11);
    const std::vector<int> origin = G.split(dofsEliminatedAt(llt, {n - 3, n - 2, n - 1}), coin, true);
    const FullMatrix Acut = G.template matrix<FullMatrix>();
    if (partial) llt.setUpdateRoute(Eigen::UpdateRoute::PartialRefactorization);
    llt.insertDofs(toInput<Cfg>(Acut), origin);
    REQUIRE(llt.info() == Eigen::Success);
    flops[partial] = llt.lastUpdate().flopFraction;
    if (!partial) route = llt.lastUpdate().route;
    checkAgainstFresh<Cfg>(llt, Acut, g, partial ? exactTolerance<Cfg>() : lowRankTolerance<Cfg>());
    llt.mergeDofs(toInput<Cfg>(A0), origin);
    REQUIRE(llt.info() == Eigen::Success);
    REQUIRE(llt.rows() == n);
    mergeFlops[partial] = llt.lastUpdate().flopFraction;
    if (!partial) mergeRoute = llt.lastUpdate().route;
    checkAgainstFresh<Cfg>(llt, A0, g, partial ? exactTolerance<Cfg>() : lowRankTolerance<Cfg>());
  }
  CAPTURE(mergeFlops[0]);
  CAPTURE(mergeFlops[1]);
  if (mergeFlops[1] > 0.05) {
    CHECK(mergeRoute == Eigen::UpdateRoute::Mixed);
    CHECK(mergeFlops[0] < 0.5 * mergeFlops[1]);
  }
  CAPTURE(flops[0]);
  CAPTURE(flops[1]);
  if (flops[1] > 0.05) {  // (a banded ordering's dirty supernodes are cheap to refactor: nothing to show there)
    CHECK(route == Eigen::UpdateRoute::Mixed);
    CHECK(flops[0] < 0.5 * flops[1]);
  }
}

TEST_CASE_TEMPLATE("insertDofs refactors only the dirty part", Cfg, uctest::d_int_col_lower_amd) {
  typedef typename Cfg::FullMatrix FullMatrix;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(80, 80, V, F);
  FullMatrix A = Eigen::cotanLaplacian<double, int>(V, F);
  SplitGraph<double> G = graphOf<Cfg>(A);
  typename Cfg::Solver llt;
  llt.setUpdateCaching(true);  // (else the first update refactors once to build the cache)
  llt.compute(toInput<Cfg>(G.template matrix<FullMatrix>()));
  REQUIRE(llt.info() == Eigen::Success);
  std::mt19937 g(3);
  const std::vector<int> origin = G.split({3000, 3001, 3002}, g);
  llt.insertDofs(toInput<Cfg>(G.template matrix<FullMatrix>()), origin);
  REQUIRE(llt.info() == Eigen::Success);
  const Eigen::UpdateStatistics& st = llt.lastUpdate();
  // its phases are parts of its time, in order: none negative, together at most the whole
  const double phases = st.compareSeconds + st.structureSeconds + st.planSeconds + st.numericSeconds;
  CHECK(st.compareSeconds >= 0);
  CHECK(st.structureSeconds >= 0);
  CHECK(st.planSeconds >= 0);
  CHECK(st.numericSeconds > 0);  // (the dirty supernodes were refactored or folded)
  CHECK(phases <= st.seconds + 1e-12);
  CHECK((st.route == Eigen::UpdateRoute::PartialRefactorization || st.route == Eigen::UpdateRoute::Mixed));
  CHECK(st.flopFraction < 0.8);
  CHECK(st.dirtySupernodes < llt.supernodeCount() / 4);
  CHECK(llt.rows() == A.rows() + 3);
  // each copy is eliminated right after its origin
  for (Index k = A.rows(); k < llt.rows(); ++k)
    CHECK(llt.permutationP().indices()[k] > llt.permutationP().indices()[origin[k]]);
  checkAgainstFresh<Cfg>(llt, G.template matrix<FullMatrix>(), g);
  // a cut with nothing to duplicate and the same matrix (a seam without interior vertex): no work
  const FullMatrix same = G.template matrix<FullMatrix>();
  std::vector<int> identity(std::size_t(same.rows()));
  for (std::size_t i = 0; i < identity.size(); ++i) identity[i] = int(i);
  llt.insertDofs(toInput<Cfg>(same), identity);
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().dirtySupernodes == 0);
  CHECK(llt.lastUpdate().flops == 0);
  CHECK(llt.lastUpdate().numericSeconds == 0);  // (only the compare)
  CHECK(llt.lastUpdate().compareSeconds == llt.lastUpdate().seconds);
  checkAgainstFresh<Cfg>(llt, same, g);
  llt.mergeDofs(toInput<Cfg>(same), identity);
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().dirtySupernodes == 0);
  // one value changed: not nothing
  FullMatrix changed = same;
  changed.coeffRef(3000, 3000) *= 2;
  llt.insertDofs(toInput<Cfg>(changed), identity);
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().dirtySupernodes > 0);
  CHECK(llt.lastUpdate().numericSeconds > 0);
  checkAgainstFresh<Cfg>(llt, changed, g);
  // a removal has no such phases: they are zero, not left from the call before
  llt.removeDofs(std::vector<int>{3000});
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().seconds > 0);
  CHECK(llt.lastUpdate().compareSeconds == 0);
  CHECK(llt.lastUpdate().structureSeconds == 0);
  CHECK(llt.lastUpdate().planSeconds == 0);
  CHECK(llt.lastUpdate().numericSeconds == 0);
}

TEST_CASE_TEMPLATE("a cut whose supernodes have room moves only their columns", Cfg, UC_CORE_CONFIGS) {
  // The factor keeps free positions after each supernode's columns (SupernodalFactor). The first
  // cut lays the positions out anew with room; a merge gives its copies' positions back; a cut
  // of the same seam then fits in its origins' supernodes: it moves only the columns after the
  // origins there and renumbers only the supernodes below them that hold those columns as rows.
  // A cut with more copies than a supernode has room for lays the positions out anew again.
  // Every step must still be the factor of the current matrix, with the public permutation and
  // matrixL() free of the gaps, and Dirichlet solves must see the copies where they now are.
  typedef typename Cfg::FullMatrix FullMatrix;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(40, 40, V, F);
  const FullMatrix A = Eigen::cotanLaplacian<typename Cfg::Scalar, typename Cfg::StorageIndex>(V, F);
  SplitGraph<typename Cfg::Scalar> G = graphOf<Cfg>(A);
  const FullMatrix A0 = G.template matrix<FullMatrix>();
  typename Cfg::Solver llt;
  llt.setUpdateCaching(true);
  llt.compute(toInput<Cfg>(A0));
  REQUIRE(llt.info() == Eigen::Success);
  std::mt19937 g(23);
  const std::vector<int> seam = {300, 301, 302, 303, 304};
  const std::vector<int> origin = G.split(seam, g);
  const FullMatrix Acut = G.template matrix<FullMatrix>();
  const Index n = A0.rows(), ns = llt.supernodeCount();
  llt.insertDofs(toInput<Cfg>(Acut), origin);  // the first: a layout anew
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().movedPositions > n / 2);
  checkAgainstFresh<Cfg>(llt, Acut, g);
  for (int cycle = 0; cycle < 3; ++cycle) {
    CAPTURE(cycle);
    llt.mergeDofs(toInput<Cfg>(A0), origin);  // always local
    REQUIRE(llt.info() == Eigen::Success);
    CHECK(llt.lastUpdate().movedPositions < n / 20);
    CHECK(llt.lastUpdate().renumberedSupernodes < ns / 4);
    checkAgainstFresh<Cfg>(llt, A0, g);
    llt.insertDofs(toInput<Cfg>(Acut), origin);  // local: the merge left the room
    REQUIRE(llt.info() == Eigen::Success);
    CHECK(llt.lastUpdate().movedPositions < n / 20);
    CHECK(llt.lastUpdate().renumberedSupernodes < ns / 4);
    checkAgainstFresh<Cfg>(llt, Acut, g);
    for (std::size_t k = 0; k < seam.size(); ++k)  // (each copy right after its origin)
      CHECK(llt.permutationP().indices()[Index(n + k)] > llt.permutationP().indices()[origin[n + k]]);
  }
  // a Dirichlet solve with a copy and an origin fixed: x_B = g, A_II x_I = b_I - A_IB g
  const std::vector<int> fixed = {origin[n], int(n), 0};
  llt.removeDofs(fixed);
  REQUIRE(llt.info() == Eigen::Success);
  const typename Cfg::Dense b = randomDense<Cfg>(Acut.rows(), 2, g), known = randomDense<Cfg>(Acut.rows(), 2, g);
  const typename Cfg::Dense x = llt.solveDirichlet(b, known);
  typename Cfg::Dense r = Acut.template selfadjointView<Eigen::Lower>() * x - b;
  for (int i : fixed) {
    CHECK(x.row(i) == known.row(i));
    r.row(i).setZero();
  }
  CHECK(double(r.norm() / (b.norm() + (Acut.template selfadjointView<Eigen::Lower>() * x).norm())) <=
        100 * exactTolerance<Cfg>());
  llt.restoreDofs(fixed);
  REQUIRE(llt.info() == Eigen::Success);
  // 200 copies of the dof eliminated first: more than any supernode of this grid has room for,
  // a layout anew, which moves every column after it (a local one: only its supernode's)
  int first = 0;
  while (llt.permutationP().indices()[first] != 0) ++first;
  const std::vector<int> many = G.split(std::vector<int>(200, first), g);
  const FullMatrix Amany = G.template matrix<FullMatrix>();
  llt.insertDofs(toInput<Cfg>(Amany), many);
  REQUIRE(llt.info() == Eigen::Success);
  CHECK(llt.lastUpdate().movedPositions > n / 2);
  checkAgainstFresh<Cfg>(llt, Amany, g);
}

TEST_CASE_TEMPLATE("repeated cut/merge cycles reuse their buffers: the same factor, bounded memory", Cfg,
                   UC_CORE_CONFIGS) {
  // the blocks and update matrices a call sets aside become the next call's buffers (stale values
  // that must never be read). Cutting the same seam again gives bitwise the same factor on the
  // partial refactorization route (it recomputes from the caches); on the mixed route each cycle
  // folds into the previous factor, so each cycle is checked against a fresh factorization.
  // The memory held must not grow from cycle to cycle beyond the spare buffers of one call.
  typedef typename Cfg::FullMatrix FullMatrix;
  SplitGraph<typename Cfg::Scalar> G = graphOf<Cfg>(meshLaplacian<Cfg>(false));
  const FullMatrix A0 = G.template matrix<FullMatrix>();
  std::mt19937 g(17);
  const std::vector<int> origin = G.split({100, 101, 102, 122, 0}, g);
  const FullMatrix Acut = G.template matrix<FullMatrix>();
  for (Eigen::UpdateRoute route : {Eigen::UpdateRoute::PartialRefactorization, Eigen::UpdateRoute::Mixed}) {
    CAPTURE(int(route));
    const bool bitwise = route == Eigen::UpdateRoute::PartialRefactorization;
    typename Cfg::Solver llt;
    llt.setUpdateCaching(true);
    llt.compute(toInput<Cfg>(A0));
    REQUIRE(llt.info() == Eigen::Success);
    llt.setUpdateRoute(route);
    FullMatrix firstCut, firstMerged;
    Index heldAfterFirst = -1, mostHeld = 0;
    const int cycles = 8;
    for (int cycle = 0; cycle < cycles; ++cycle) {
      CAPTURE(cycle);
      llt.insertDofs(toInput<Cfg>(Acut), origin);
      REQUIRE(llt.info() == Eigen::Success);
      const FullMatrix cut = llt.matrixL();
      if (!bitwise && cycle % 3 == 0) checkAgainstFresh<Cfg>(llt, Acut, g, lowRankTolerance<Cfg>());
      llt.mergeDofs(toInput<Cfg>(A0), origin);
      REQUIRE(llt.info() == Eigen::Success);
      const FullMatrix merged = llt.matrixL();
      if (!bitwise && cycle % 3 == 0) checkAgainstFresh<Cfg>(llt, A0, g, lowRankTolerance<Cfg>());
      if (cycle == 0) {
        firstCut = cut;
        firstMerged = merged;
        heldAfterFirst = llt.memoryBytes();
        checkAgainstFresh<Cfg>(llt, A0, g, lowRankTolerance<Cfg>());
      } else if (bitwise) {
        REQUIRE(cut.nonZeros() == firstCut.nonZeros());
        CHECK(double((cut - firstCut).norm()) == 0.0);
        CHECK(double((merged - firstMerged).norm()) == 0.0);
      }
      if (cycle > 0) mostHeld = (std::max)(mostHeld, llt.memoryBytes());
    }
    // a leak of a tenth of the memory per cycle would exceed this after the eight cycles
    CHECK(double(mostHeld) <= 1.5 * double(heldAfterFirst));
  }
}

TEST_CASE_TEMPLATE("a supernode block keeps its storage when it changes shape, and a spare serves a larger block",
                   Scalar, double, std::complex<float>) {
  // an update that reshapes a supernode sets its block aside and reuses the blocks of the previous
  // call: a root separator a few rows larger than before must find room in one of them, not
  // allocate (a new block is touched for the first time: page faults) nor copy stale values
  using Eigen::internal::updatable_cholesky::SupernodeBlock;
  typedef Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> Dense;
  SupernodeBlock<Scalar> block;
  block.resize(30, 20);
  CHECK(block.rows() == 30);
  CHECK(block.cols() == 20);
  CHECK(block.size() == 600);
  const Dense M = Dense::Random(30, 20);
  block = M;
  CHECK(block.matrix() == M);
  CHECK(block(7, 3) == M(7, 3));
  CHECK(block.col(4) == M.col(4));
  block.col(4) *= Scalar(2);
  CHECK(block(5, 4) == Scalar(2) * M(5, 4));
  const Scalar* storage = block.data();
  block.resize(25, 24);  // the same or fewer entries, another shape: the same storage
  CHECK(block.data() == storage);
  CHECK(block.capacity() >= 600);
  block.resize(10, 10);
  CHECK(block.data() == storage);
  block.resize(40, 40);  // more than it holds: new storage
  CHECK(block.capacity() >= 1600);
  SupernodeBlock<Scalar> other;
  other.swap(block);
  CHECK(other.rows() == 40);
  CHECK(block.size() == 0);

  Eigen::internal::updatable_cholesky::FactorStructureBackup<Scalar, int> backup;
  SupernodeBlock<Scalar> previous;
  previous.reserve(738 * 738 + 738 * 738 / 8);
  previous.resize(738, 738);
  const Scalar* spare = previous.data();
  backup.spareValues.add(previous.capacity(), previous);
  SupernodeBlock<Scalar> small;
  small.resize(5, 5);
  backup.spareValues.add(small.capacity(), small);
  backup.spareValues.seal();
  SupernodeBlock<Scalar> root;
  backup.takeSpare(740, 740, root);  // a root two columns wider than the spare's: it fits
  CHECK(root.data() == spare);
  CHECK(root.rows() == 740);
  CHECK(root.cols() == 740);
  SupernodeBlock<Scalar> fresh;
  backup.takeSpare(900, 900, fresh);  // nothing large enough is left: new storage, with room to grow
  CHECK(fresh.data() != spare);
  CHECK(fresh.size() == 900 * 900);
  CHECK(fresh.capacity() >= 900 * 900 + 900 * 900 / 8);
  SupernodeBlock<Scalar> tiny;
  backup.takeSpare(2, 2, tiny);  // the 25-entry spare holds more than twice as many: not taken
  CHECK(tiny.size() == 4);
  CHECK(tiny.capacity() < 25);
}

TEST_CASE_TEMPLATE("a cached update matrix moves to new rows without a copy and is laid out when read", Scalar, double,
                   std::complex<float>) {
  // an insertion relabels a folded supernode's update matrix to its new rows (copy rows zero), a
  // merge that drops only rows it does not store relabels it back, and whoever reads it lays it
  // out first: each must give the matrix a dense reference gives
  using Eigen::internal::updatable_cholesky::CachedUpdate;
  typedef Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> Dense;
  const Eigen::Index m0 = 6;
  Dense U0 = Dense::Random(m0, m0);
  U0 = (U0 * U0.adjoint()).eval();
  CachedUpdate<Scalar> U;
  U.resize(std::size_t(m0 * m0));
  std::copy(U0.data(), U0.data() + m0 * m0, U.data());
  CHECK(U.inOwnLayout());
  const Scalar* storage = U.data();
  auto lower = [](const Dense& A) { return Dense(A.template triangularView<Eigen::Lower>()); };
  auto laidOut = [&](CachedUpdate<Scalar>& B, Eigen::Index m) {
    B.layOut();
    REQUIRE(B.inOwnLayout());
    REQUIRE(Eigen::Index(B.size()) == m * m);
    return lower(Eigen::Map<const Dense>(B.data(), m, m));
  };
  // two cuts: rows 0..5 -> 0,1,3,4,5,7 of 8, then 0..7 -> 0,1,2,3,4,6,7,8 of 9
  const std::vector<Eigen::Index> first{0, 1, 3, 4, 5, 7}, second{0, 1, 2, 3, 4, 6, 7, 8};
  Dense expected1 = Dense::Zero(8, 8), expected2 = Dense::Zero(9, 9);
  for (Eigen::Index j = 0; j < m0; ++j)
    for (Eigen::Index i = j; i < m0; ++i) expected1(first[i], first[j]) = U0(i, j);
  for (Eigen::Index j = 0; j < 8; ++j)
    for (Eigen::Index i = j; i < 8; ++i) expected2(second[i], second[j]) = expected1(i, j);
  U.relabelRows(m0, first, 8);
  CHECK_FALSE(U.inOwnLayout());
  CHECK(U.data() == storage);  // (not copied)
  U.relabelRows(8, second, 9);
  CHECK(U.data() == storage);
  CachedUpdate<Scalar> V;
  V.swap(U);  // (the layout goes with the storage)
  CHECK(U.empty());
  CachedUpdate<Scalar> W;
  W.resize(std::size_t(m0 * m0));
  std::copy(V.data(), V.data() + m0 * m0, W.data());
  W.relabelRows(m0, first, 8);
  W.relabelRows(8, second, 9);
  CHECK(laidOut(W, 9) == lower(expected2));
  // a merge back to the first layout's rows: the dropped rows (2 and 5 of 9) are not stored
  const std::vector<Eigen::Index> keep{0, 1, 3, 4, 6, 7, 8};
  Dense expected3 = Dense::Zero(7, 7);
  for (Eigen::Index j = 0; j < 7; ++j)
    for (Eigen::Index i = j; i < 7; ++i) expected3(i, j) = expected2(keep[i], keep[j]);
  REQUIRE(V.keepRows(9, keep.data(), 7));
  CHECK(V.data() == storage);
  CachedUpdate<Scalar> Y = V;
  CHECK(laidOut(Y, 7) == lower(expected3));
  const std::vector<Eigen::Index> undo{0, 1, 2, 3, 4, 6};  // then drop the first cut's other copy (row 5 of 7)
  REQUIRE(V.keepRows(7, undo.data(), 6));
  CHECK(V.inOwnLayout());  // back to the original rows: nothing to lay out
  CHECK(V.data() == storage);
  CHECK(laidOut(V, 6) == lower(U0));
  // a merge that drops a stored row is refused (the caller gathers instead) and changes nothing
  CachedUpdate<Scalar> X;
  X.resize(std::size_t(m0 * m0));
  std::copy(U0.data(), U0.data() + m0 * m0, X.data());
  X.relabelRows(m0, first, 8);
  const std::vector<Eigen::Index> dropsStored{0, 1, 2, 3, 4, 5, 6};  // row 7 of 8 holds U0's last row
  CHECK_FALSE(X.keepRows(8, dropsStored.data(), 7));
  CHECK(laidOut(X, 8) == lower(expected1));
  // resize() starts a matrix in its own layout
  X.relabelRows(8, second, 9);
  X.resize(4);
  CHECK(X.inOwnLayout());
}

TEST_CASE_TEMPLATE("a failed insertDofs keeps the deferred corrections that earlier folds left", Cfg, UC_CORE_CONFIGS) {
  // the folds of a cut and of its merge leave corrections of the folded supernodes' cached update
  // matrices deferred (a grid large enough that they pile up slower than they are applied); the
  // next update sets them aside with those matrices, and a failed one must put them back: the
  // updates after it fold from the same caches
  typedef typename Cfg::FullMatrix FullMatrix;
  typedef typename Cfg::Scalar Scalar;
  std::mt19937 g(21);
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  Eigen::gridMesh(48, 40, V, F);
  SplitGraph<Scalar> G = graphOf<Cfg>(Eigen::cotanLaplacian<Scalar, typename Cfg::StorageIndex>(V, F));
  const FullMatrix A = G.template matrix<FullMatrix>();
  const Index n = A.rows();
  typename Cfg::Solver llt(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  llt.setUpdateRoute(Eigen::UpdateRoute::Mixed);
  std::vector<int> seam[3];  // two next to each other, one far from both
  for (int k = 0; k < 6; ++k)
    seam[0].push_back(20 * 48 + 14 + k), seam[1].push_back(21 * 48 + 15 + k), seam[2].push_back(4 * 48 + 36 + k);
  SplitGraph<Scalar> H[3] = {G, G, G};
  const std::vector<int> origin[3] = {H[0].split(seam[0], g), H[1].split(seam[1], g), H[2].split(seam[2], g)};
  const FullMatrix Acut[3] = {H[0].template matrix<FullMatrix>(), H[1].template matrix<FullMatrix>(),
                              H[2].template matrix<FullMatrix>()};
  for (int round = 0; round < 3; ++round) {
    const int first = round % 2, second = 1 - first;
    llt.insertDofs(toInput<Cfg>(Acut[first]), origin[first]);
    REQUIRE(llt.info() == Eigen::Success);
    llt.mergeDofs(toInput<Cfg>(A), origin[first]);
    REQUIRE(llt.info() == Eigen::Success);
    for (const Scalar diagonal : {Scalar(-1), Scalar(1e-7)}) {  // (1e-7: the copies' pivots pass, the top's fail)
      FullMatrix bad = Acut[second];
      for (Index c = n; c < bad.rows(); ++c) bad.coeffRef(c, c) = diagonal;
      llt.insertDofs(toInput<Cfg>(bad), origin[second]);
      CHECK(llt.info() == Eigen::NumericalIssue);
      CHECK(llt.rows() == n);
      checkAgainstFresh<Cfg>(llt, A, g, lowRankTolerance<Cfg>());
    }
    // a cut far away refactors its path: the top reads the cached update matrices of the
    // supernodes the failed cut left clean again (their deferred corrections included)
    llt.setUpdateRoute(Eigen::UpdateRoute::PartialRefactorization);
    llt.insertDofs(toInput<Cfg>(Acut[2]), origin[2]);
    REQUIRE(llt.info() == Eigen::Success);
    checkAgainstFresh<Cfg>(llt, Acut[2], g, lowRankTolerance<Cfg>());
    llt.mergeDofs(toInput<Cfg>(A), origin[2]);
    REQUIRE(llt.info() == Eigen::Success);
    checkAgainstFresh<Cfg>(llt, A, g, lowRankTolerance<Cfg>());
    llt.setUpdateRoute(Eigen::UpdateRoute::Mixed);
    llt.insertDofs(toInput<Cfg>(Acut[second]), origin[second]);
    REQUIRE(llt.info() == Eigen::Success);
    CHECK(llt.lastUpdate().route == Eigen::UpdateRoute::Mixed);
    checkAgainstFresh<Cfg>(llt, Acut[second], g, lowRankTolerance<Cfg>());
    llt.mergeDofs(toInput<Cfg>(A), origin[second]);
    REQUIRE(llt.info() == Eigen::Success);
    checkAgainstFresh<Cfg>(llt, A, g, lowRankTolerance<Cfg>());
  }
}

TEST_CASE_TEMPLATE("bad insertDofs/mergeDofs input leaves the object as it was", Cfg, UC_CORE_CONFIGS) {
  typedef typename Cfg::FullMatrix FullMatrix;
  typedef typename Cfg::Scalar Scalar;
  std::mt19937 g(9);
  SplitGraph<Scalar> G = graphOf<Cfg>(meshLaplacian<Cfg>(false));
  const FullMatrix A = G.template matrix<FullMatrix>();
  const Index n = A.rows();
  typename Cfg::Solver llt(toInput<Cfg>(A));
  REQUIRE(llt.info() == Eigen::Success);
  auto unchanged = [&]() {
    CHECK(llt.rows() == n);
    checkAgainstFresh<Cfg>(llt, A, g);
  };
  SplitGraph<Scalar> H = G;
  const std::vector<int> origin = H.split({10, 40, 41}, g);
  const FullMatrix Acut = H.template matrix<FullMatrix>();
  SUBCASE("origin of the wrong size, or a matrix of the wrong size") {
    std::vector<int> shortOrigin(origin.begin(), origin.end() - 1);
    llt.insertDofs(toInput<Cfg>(Acut), shortOrigin);
    CHECK(llt.info() == Eigen::InvalidInput);
    llt.insertDofs(toInput<Cfg>(A), origin);
    CHECK(llt.info() == Eigen::InvalidInput);
    unchanged();
  }
  SUBCASE("origin out of range, pointing at a new dof, or renumbering an old dof") {
    for (Index k : {Index(-1), n, n + 1}) {
      std::vector<int> bad = origin;
      bad[n] = int(k);
      llt.insertDofs(toInput<Cfg>(Acut), bad);
      CHECK(llt.info() == Eigen::InvalidInput);
    }
    std::vector<int> bad = origin;
    bad[5] = 6;
    llt.insertDofs(toInput<Cfg>(Acut), bad);
    CHECK(llt.info() == Eigen::InvalidInput);
    unchanged();
  }
  SUBCASE("a changed-dof list out of range or repeated, or an entry outside the pattern with a list") {
    for (const std::vector<int>& bad : {std::vector<int>{10, int(n)}, std::vector<int>{-1}, std::vector<int>{10, 10}}) {
      llt.insertDofs(toInput<Cfg>(Acut), origin, bad);
      CHECK(llt.info() == Eigen::InvalidInput);
    }
    FullMatrix bad = Acut;
    bad.coeffRef(n - 1, n) = Scalar(-0.01);  // (n - 1: not a neighbour of dof 10, the copy n's origin)
    bad.coeffRef(n, n - 1) = Scalar(-0.01);
    bad.makeCompressed();
    // (listed, so read: the list promises that no other old dof's row or column changed, and the
    // outer vectors of the others are not read)
    llt.insertDofs(toInput<Cfg>(bad), origin, std::vector<int>{int(n - 1)});
    CHECK(llt.info() == Eigen::InvalidInput);
    unchanged();
  }
  SUBCASE("an entry outside the duplicated pattern") {
    FullMatrix bad = Acut;
    const Index far = n - 1;  // not a neighbour of dof 10 (the copy n's origin) in the grid
    bad.coeffRef(far, n) = Scalar(-0.01);
    bad.coeffRef(n, far) = Scalar(-0.01);
    bad.makeCompressed();
    llt.insertDofs(toInput<Cfg>(bad), origin);
    CHECK(llt.info() == Eigen::InvalidInput);
    unchanged();
  }
  SUBCASE("a matrix that is not positive definite") {
    FullMatrix bad = Acut;
    bad.coeffRef(n + 1, n + 1) = Scalar(-1);
    llt.insertDofs(toInput<Cfg>(bad), origin);
    CHECK(llt.info() == Eigen::NumericalIssue);
    unchanged();
    llt.insertDofs(toInput<Cfg>(Acut), origin);  // and it still updates
    CHECK(llt.info() == Eigen::Success);
    checkAgainstFresh<Cfg>(llt, Acut, g);
  }
  SUBCASE("not positive definite on the mixed route: in the refactored part, or only in the folded top") {
    llt.setUpdateRoute(Eigen::UpdateRoute::Mixed);
    for (const Scalar diagonal : {Scalar(-1), Scalar(1e-7)}) {  // 1e-7: the copies' pivots pass, the top's fail
      FullMatrix bad = Acut;
      for (Index c = n; c < Acut.rows(); ++c) bad.coeffRef(c, c) = diagonal;
      llt.insertDofs(toInput<Cfg>(bad), origin);
      CHECK(llt.info() == Eigen::NumericalIssue);
      unchanged();
    }
    llt.insertDofs(toInput<Cfg>(Acut), origin);
    CHECK(llt.info() == Eigen::Success);
    checkAgainstFresh<Cfg>(llt, Acut, g, lowRankTolerance<Cfg>());
  }
  SUBCASE("NaN or infinity in the matrix, on every route: NumericalIssue and the object as it was") {
    typedef typename Cfg::RealScalar Real;
    const Scalar badValues[] = {Scalar(std::numeric_limits<Real>::quiet_NaN()), Scalar(std::numeric_limits<Real>::infinity())};
    const Eigen::UpdateRoute routes[] = {Eigen::UpdateRoute::Automatic, Eigen::UpdateRoute::PartialRefactorization,
                                         Eigen::UpdateRoute::Refactorization, Eigen::UpdateRoute::Mixed};
    const Index copy = n, from = origin[n], far = n - 1;  // (far: not a neighbour of the copies' origins)
    Index neighbour = -1;  // an entry of the copy's column off the diagonal
    for (typename FullMatrix::InnerIterator it(Acut, copy); it && neighbour < 0; ++it)
      if (it.row() != copy) neighbour = it.row();
    REQUIRE(neighbour >= 0);
    Index originNeighbour = -1;  // an old dof next to the origin
    for (typename FullMatrix::InnerIterator it(Acut, from); it && originNeighbour < 0; ++it)
      if (it.row() != from && it.row() < n) originNeighbour = it.row();
    REQUIRE(originNeighbour >= 0);
    for (const Eigen::UpdateRoute route : routes)
      for (const Scalar bad : badValues)
        for (int where = 0; where < 5; ++where) {
          CAPTURE(int(route));
          CAPTURE(where);
          llt.setUpdateRoute(route);
          FullMatrix cut = Acut;
          if (where == 0) cut.coeffRef(copy, copy) = bad;             // a copy's pivot
          if (where == 1) {                                            // a copy's entry off the diagonal
            cut.coeffRef(neighbour, copy) = bad;
            cut.coeffRef(copy, neighbour) = bad;
          }
          if (where == 2) cut.coeffRef(from, from) = bad;              // an origin's pivot
          if (where == 3) cut.coeffRef(far, far) = bad;                // an old dof far from the cut
          if (where == 4) {  // between an origin and an old neighbour: a folded supernode may hold it
            cut.coeffRef(from, originNeighbour) = bad;
            cut.coeffRef(originNeighbour, from) = bad;
          }
          cut.makeCompressed();
          llt.insertDofs(toInput<Cfg>(cut), origin);
          CHECK(llt.info() == Eigen::NumericalIssue);
          unchanged();
        }
    llt.setUpdateRoute(Eigen::UpdateRoute::Automatic);
    llt.insertDofs(toInput<Cfg>(Acut), origin);  // and it still cuts, and merges only good values
    REQUIRE(llt.info() == Eigen::Success);
    for (const Scalar bad : badValues) {
      FullMatrix merged = A;
      merged.coeffRef(from, from) = bad;
      llt.mergeDofs(toInput<Cfg>(merged), origin);
      CHECK(llt.info() == Eigen::NumericalIssue);
      CHECK(llt.rows() == Acut.rows());
      checkAgainstFresh<Cfg>(llt, Acut, g);
      merged = A;  // between the origin and an old neighbour
      merged.coeffRef(from, originNeighbour) = bad;
      merged.coeffRef(originNeighbour, from) = bad;
      llt.mergeDofs(toInput<Cfg>(merged), origin);
      CHECK(llt.info() == Eigen::NumericalIssue);
      CHECK(llt.rows() == Acut.rows());
      checkAgainstFresh<Cfg>(llt, Acut, g);
    }
    llt.mergeDofs(toInput<Cfg>(A), origin);
    CHECK(llt.info() == Eigen::Success);
    unchanged();
  }
  SUBCASE("bad merges") {
    llt.insertDofs(toInput<Cfg>(Acut), origin);
    REQUIRE(llt.info() == Eigen::Success);
    std::vector<int> bad = origin;
    bad[n] = int(n + 1);  // merged into a dof that is merged itself
    llt.mergeDofs(toInput<Cfg>(A), bad);
    CHECK(llt.info() == Eigen::InvalidInput);
    llt.mergeDofs(toInput<Cfg>(Acut), origin);  // wrong size
    CHECK(llt.info() == Eigen::InvalidInput);
    llt.mergeDofs(toInput<Cfg>(A), origin, std::vector<int>{int(Acut.rows())});  // a changed dof out of range
    CHECK(llt.info() == Eigen::InvalidInput);
    checkAgainstFresh<Cfg>(llt, Acut, g);
    llt.mergeDofs(toInput<Cfg>(A), origin);
    CHECK(llt.info() == Eigen::Success);
    unchanged();
  }
}

namespace {

/** Cuts, undoes and constrains a triangle mesh step by step, as an interactive session would:
  * seams from seamPath() cut with cutMeshAlongPath(), each cut given to insertDofs() and some
  * undone by mergeDofs(); Dirichlet removals in between. Every step is checked against a fresh
  * factorization and against SimplicialLLT on the cut matrix. */
template <typename Cfg>
void meshCutSession(const Eigen::MatrixXd& V0, const Eigen::MatrixXi& F0, int steps, unsigned seed) {
  seed += seedOffset();
  typedef typename Cfg::FullMatrix FullMatrix;
  typedef typename Cfg::Scalar Scalar;
  std::mt19937 g(seed);
  auto laplacian = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    FullMatrix L = Eigen::cotanLaplacian<Scalar, typename Cfg::StorageIndex>(V, F);
    FullMatrix I(L.rows(), L.cols());
    I.setIdentity();
    FullMatrix A = L + I * Scalar(1e-2);
    A.makeCompressed();
    return A;
  };
  struct State {
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    FullMatrix A;
    std::vector<int> origin;  // the cut that led here
  };
  std::vector<State> history{State{V0, F0, laplacian(V0, F0), {}}};
  typename Cfg::Solver llt;
  llt.setThreadCount(1);
  llt.compute(toInput<Cfg>(history.back().A));
  REQUIRE(llt.info() == Eigen::Success);
  std::vector<char> removed(V0.rows(), 0);
  int cuts = 0, undos = 0;
  for (int step = 0; step < steps; ++step) {
    const State& cur = history.back();
    const int nV = int(cur.V.rows());
    int op = int(g() % 5);
    if (step + 2 == steps && undos == 0 && history.size() == 1) op = 0;  // (something to undo at the end)
    if (step + 1 == steps && undos == 0) op = 2;
    CAPTURE(step);
    CAPTURE(op);
    if (op <= 1 || (op == 2 && history.size() == 1)) {  // a new cut (only on dofs that are not removed)
      std::vector<int> seam;
      int pieces = 0;
      for (unsigned attempt = 0; attempt < 20; ++attempt) {
        seam = Eigen::seamPath(cur.F, nV, 3 + int(g() % 25), unsigned(g()), &pieces);
        if (pieces == 1) break;
      }
      REQUIRE(pieces == 1);
      bool anyRemoved = false;
      for (int v : seam) anyRemoved = anyRemoved || removed[v];
      if (anyRemoved) continue;
      State next;
      Eigen::VectorXi origin;
      std::string error;
      REQUIRE(Eigen::cutMeshAlongPath(cur.V, cur.F, seam, next.V, next.F, origin, &error));
      next.A = laplacian(next.V, next.F);
      next.origin.assign(origin.data(), origin.data() + origin.size());
      llt.insertDofs(toInput<Cfg>(next.A), next.origin);
      REQUIRE(llt.info() == Eigen::Success);
      CHECK(llt.rows() == next.V.rows());
      CHECK(llt.lastUpdate().flopFraction <= 1.0 + 1e-12);
      history.push_back(next);
      removed.resize(next.V.rows(), 0);
      ++cuts;
    } else if (op == 2) {  // undo the latest cut
      const std::vector<int> origin = history.back().origin;
      history.pop_back();
      llt.mergeDofs(toInput<Cfg>(history.back().A), origin);
      REQUIRE(llt.info() == Eigen::Success);
      removed.resize(history.back().V.rows());
      ++undos;
    } else if (op == 3) {  // Dirichlet constraints on a short seam
      std::vector<int> dofs;
      for (int v : Eigen::seamPath(cur.F, nV, 1 + int(g() % 8), unsigned(g())))
        if (!removed[v]) dofs.push_back(v);
      llt.removeDofs(dofs);
      REQUIRE(llt.info() == Eigen::Success);
      for (int v : dofs) removed[v] = 1;
    } else {  // all constraints released
      std::vector<int> dofs;
      for (int v = 0; v < nV; ++v)
        if (removed[v]) dofs.push_back(v);
      llt.restoreDofs(dofs);
      REQUIRE(llt.info() == Eigen::Success);
      std::fill(removed.begin(), removed.end(), 0);
    }
    const FullMatrix current = withIdentityRows<Cfg>(history.back().A, removed);
    checkAgainstFresh<Cfg>(llt, current, g);
    // the same answers as SimplicialLLT on the current (cut) matrix
    typename Cfg::Reference reference(toInput<Cfg>(current));
    REQUIRE(reference.info() == Eigen::Success);
    const typename Cfg::Dense b = randomDense<Cfg>(current.rows(), 1, g);
    const typename Cfg::Dense x = llt.solve(b), xr = reference.solve(b);
    CHECK(double((x - xr).norm() / xr.norm()) <= 1e3 * exactTolerance<Cfg>());
  }
  CHECK(cuts > 0);
  CHECK(undos > 0);
}

}  // namespace

TEST_CASE_TEMPLATE("seam cuts of meshes with and without boundary", Cfg, uctest::d_int_col_lower_amd,
                   uctest::d_long_row_lower_amd) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  SUBCASE("generated grid (boundary)") {
    Eigen::gridMesh(30, 30, V, F);
    meshCutSession<Cfg>(V, F, 30, 1);
  }
  SUBCASE("generated sphere (closed)") {
    Eigen::icosphereMesh(3, V, F);
    meshCutSession<Cfg>(V, F, 30, 2);
  }
  for (const char* name : {"camelhead", "fertility", "bunny"}) {
    SUBCASE(name) {
      const std::string path = std::string(UC_TEST_MESH_DIR) + "/" + name + ".off.gz";
      std::string error;
      if (!Eigen::readOFF(path, V, F, &error)) {
        MESSAGE("skipped (no shared mesh): " << error);
        return;
      }
      meshCutSession<Cfg>(V, F, Cfg::isPrimary ? 12 : 6, 3);
    }
  }
}
