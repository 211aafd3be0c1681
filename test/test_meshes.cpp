// Cotan Laplacians + 1e-8 I of meshes, the matrices the library is made for: generated grids and
// icospheres (unsupported/Eigen/MeshTools) and the small real meshes of the shared mesh folder
// (fertility, rocker-arm, camelhead; skipped with a message if the folder is missing), each
// compared with SimplicialLLT. Complex configurations also factor a magnetic (Hermitian) Laplacian
// on the same mesh. Single precision cannot resolve a 1e-8 shift against a diagonal of order one,
// so float configurations use a shift of 1e-3 times the mean diagonal instead.
#include "test_checks.h"

#include <unsupported/Eigen/MeshTools>

#include <fstream>

#ifndef UC_TEST_MESH_DIR
#error "UC_TEST_MESH_DIR must name the folder of the shared test meshes"
#endif

using namespace uctest;

namespace {

struct Mesh {
  std::string name;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

bool fileExists(const std::string& path) { return std::ifstream(path).good(); }

/** The meshes of the shared folder that exist; a MESSAGE for each one that does not. */
std::vector<Mesh> sharedMeshes(const std::vector<std::string>& names) {
  std::vector<Mesh> meshes;
  for (const std::string& name : names) {
    const std::string path = std::string(UC_TEST_MESH_DIR) + "/" + name + ".off.gz";
    if (!fileExists(path)) {
      MESSAGE("skipping mesh " << name << ": " << path << " not found");
      continue;
    }
    Mesh m;
    m.name = name;
    std::string error;
    const bool ok = Eigen::readOFF(path, m.V, m.F, &error);
    INFO(error);
    REQUIRE(ok);
    meshes.push_back(m);
  }
  return meshes;
}

Mesh generatedGrid(int nx, int ny) {
  Mesh m;
  m.name = "grid " + std::to_string(nx) + "x" + std::to_string(ny);
  Eigen::gridMesh(nx, ny, m.V, m.F);
  return m;
}

Mesh generatedIcosphere(int subdivisions) {
  Mesh m;
  m.name = "icosphere " + std::to_string(subdivisions);
  Eigen::icosphereMesh(subdivisions, m.V, m.F);
  return m;
}

/** cotan Laplacian + shift*I, the shift 1e-8 (or 1e-3 of the mean diagonal in single precision). */
template <typename Cfg>
typename Cfg::FullMatrix laplacianPlusShift(const Mesh& mesh) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::RealScalar Real;
  typename Cfg::FullMatrix L = Eigen::cotanLaplacian<Scalar, typename Cfg::StorageIndex>(mesh.V, mesh.F);
  double meanDiagonal = 0;
  for (Index i = 0; i < L.rows(); ++i) meanDiagonal += double(Eigen::numext::real(L.coeff(i, i)));
  meanDiagonal /= double(std::max<Index>(L.rows(), 1));
  const double shift = std::numeric_limits<Real>::epsilon() > 1e-10 ? 1e-3 * meanDiagonal : 1e-8;
  typename Cfg::FullMatrix I(L.rows(), L.cols());
  I.setIdentity();
  typename Cfg::FullMatrix A = L + Scalar(Real(shift)) * I;
  A.makeCompressed();
  return A;
}

/** Magnetic Laplacian: off-diagonal w_ij e^{i theta_ij} (theta random per edge, Hermitian), diagonal
  * sum_j |w_ij| + 1e-8. Hermitian positive definite, with a complex factor. */
template <typename Cfg>
typename Cfg::FullMatrix magneticLaplacian(const Mesh& mesh, unsigned seed) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::RealScalar Real;
  const Eigen::SparseMatrix<double> L = Eigen::cotanLaplacian<double, int>(mesh.V, mesh.F);
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586);
  std::vector<Eigen::Triplet<Scalar, typename Cfg::StorageIndex>> t;
  std::vector<double> diag(L.rows(), 1e-8);
  for (Index j = 0; j < L.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
      if (it.row() > j) {
        const double w = it.value(), a = angle(g);
        const Scalar v = Scalar(Real(w * std::cos(a)), Real(w * std::sin(a)));
        t.emplace_back(it.row(), j, v);
        t.emplace_back(j, it.row(), Eigen::numext::conj(v));
        diag[it.row()] += std::abs(w);
        diag[j] += std::abs(w);
      }
  for (Index i = 0; i < L.rows(); ++i) t.emplace_back(i, i, Scalar(Real(diag[i])));
  typename Cfg::FullMatrix A(L.rows(), L.cols());
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

template <typename Cfg>
void checkMesh(const Mesh& mesh) {
  INFO("mesh: " << mesh.name << " (" << mesh.V.rows() << " vertices)");
  computeAndCheck<Cfg>(laplacianPlusShift<Cfg>(mesh));
  if constexpr (Cfg::isComplex) {
    INFO("magnetic Laplacian");
    computeAndCheck<Cfg>(magneticLaplacian<Cfg>(mesh, 5));
  }
}

}  // namespace

TEST_CASE_TEMPLATE("cotan Laplacians of generated meshes", Cfg, UC_CONFIGS) {
  if (Cfg::fillReducing) {
    checkMesh<Cfg>(generatedGrid(Cfg::isPrimary ? 90 : 40, Cfg::isPrimary ? 70 : 30));
    checkMesh<Cfg>(generatedIcosphere(Cfg::isPrimary ? 5 : 3));
  } else {
    // natural / reverse order of a mesh: keep the (banded) factor small
    checkMesh<Cfg>(generatedGrid(40, 12));
    checkMesh<Cfg>(generatedIcosphere(2));
  }
  // degenerate meshes: a single triangle, a strip
  checkMesh<Cfg>(generatedGrid(2, 2));
  checkMesh<Cfg>(generatedGrid(2, 30));
}

TEST_CASE_TEMPLATE("cotan Laplacians of real meshes", Cfg, UC_CORE_CONFIGS) {
  if (!Cfg::fillReducing) return;  // a natural order of a real mesh has too much fill for a test
  const std::vector<Mesh> meshes =
      Cfg::isPrimary ? sharedMeshes({"fertility", "rocker-arm", "camelhead"}) : sharedMeshes({"fertility"});
  for (const Mesh& mesh : meshes) checkMesh<Cfg>(mesh);
}

TEST_CASE("updates with 2 threads recompute independent dirty subtrees at once (bunny)") {
  // bunny: large enough that the dirty supernodes of these updates hold more than
  // MinParallelFlops of work, so the partial refactorization splits them among the threads
  typedef d_int_col_lower_amd Cfg;
  const std::vector<Mesh> meshes = sharedMeshes({"bunny"});
  for (const Mesh& mesh : meshes) {
    const Cfg::FullMatrix A = laplacianPlusShift<Cfg>(mesh);
    const Index n = A.rows();
    Cfg::Solver one, two;
    one.setThreadCount(1);
    two.setThreadCount(2);
    for (Cfg::Solver* s : {&one, &two}) {
      s->setUpdateCaching(true);
      s->setUpdateRoute(Eigen::UpdateRoute::PartialRefactorization);
      s->compute(A);
      REQUIRE(s->info() == Eigen::Success);
    }
    // B = D A D with D = 1.5 on the first half of the vertices, 1 on the others (positive
    // definite): the columns of the first half and of their neighbours change, most of the tree
    // is dirty
    Cfg::FullMatrix B = A;
    std::vector<int> columns;
    for (Index j = 0; j < B.outerSize(); ++j) {
      bool changed = false;
      for (Cfg::FullMatrix::InnerIterator it(B, j); it; ++it) {
        const double scale = (it.row() < n / 2 ? 1.5 : 1.0) * (it.col() < n / 2 ? 1.5 : 1.0);
        it.valueRef() *= scale;
        changed = changed || scale != 1.0;
      }
      if (changed) columns.push_back(int(j));
    }
    for (Cfg::Solver* s : {&one, &two}) {
      s->updateColumns(B, columns);
      REQUIRE(s->info() == Eigen::Success);
      CHECK(s->lastUpdate().route == Eigen::UpdateRoute::PartialRefactorization);
    }
    REQUIRE(two.lastUpdate().flops > 2 * Eigen::internal::updatable_cholesky::MinParallelFlops);
    Cfg::Reference refB(B);
    checkAgainstReference<Cfg>(two, B, refB);
    CHECK(factorDifference<Cfg>(two, one) <= 1e3 * std::numeric_limits<double>::epsilon());
    Cfg::Solver fresh;
    fresh.setThreadCount(2);
    fresh.compute(B);
    CHECK(factorDifference<Cfg>(two, fresh) <= 1e3 * std::numeric_limits<double>::epsilon());
    // a Dirichlet removal of a third of the dofs, refactored in part
    std::vector<int> removed;
    for (Index j = n / 3; j < 2 * n / 3; ++j) removed.push_back(int(j));
    for (Cfg::Solver* s : {&one, &two}) {
      s->removeDofs(removed);
      REQUIRE(s->info() == Eigen::Success);
    }
    CHECK(factorDifference<Cfg>(two, one) <= 1e3 * std::numeric_limits<double>::epsilon());
    const Cfg::Dense b = Cfg::Dense::Ones(n, 1);
    const Cfg::Dense x1 = one.solveDirichlet(b, b), x2 = two.solveDirichlet(b, b);
    CHECK(double((x1 - x2).norm() / x1.norm()) <= 1e-8);
    // and a failed update on 2 threads leaves the previous factor
    Cfg::FullMatrix bad = B;
    bad.coeffRef(0, 0) = -1.0;
    two.restoreDofs(removed);
    REQUIRE(two.info() == Eigen::Success);
    two.updateColumns(bad, columns);
    CHECK(two.info() == Eigen::NumericalIssue);
    const Cfg::Dense xr = refB.solve(b), xt = two.solve(b);
    CHECK(double((xt - xr).norm() / xr.norm()) <= 1e-6);
  }
}

TEST_CASE("a real mesh with 2 threads, refactorized with new values") {
  typedef d_int_col_lower_amd Cfg;
  const std::vector<Mesh> meshes = sharedMeshes({"camelhead"});
  for (const Mesh& mesh : meshes) {
    const Cfg::FullMatrix A = laplacianPlusShift<Cfg>(mesh);
    Cfg::Reference ref(A);
    Cfg::Solver one, two, twoAgain;
    one.setThreadCount(1);
    two.setThreadCount(2);
    twoAgain.setThreadCount(2);
    one.compute(A);
    two.compute(A);
    twoAgain.compute(A);
    checkAgainstReference<Cfg>(two, A, ref);
    MESSAGE(mesh.name << ": 1 and 2 threads give "
                      << std::string(sameFactorBitwise<Cfg>(one, two) ? "bitwise identical" : "different") << " factors");
    CHECK(factorDifference<Cfg>(one, two) <= 1e3 * std::numeric_limits<double>::epsilon());
    CHECK(sameFactorBitwise<Cfg>(two, twoAgain));
    // new values on the same pattern (a different positive diagonal scaling)
    Cfg::FullMatrix B = A;
    for (Index j = 0; j < B.outerSize(); ++j)
      for (Cfg::FullMatrix::InnerIterator it(B, j); it; ++it)
        it.valueRef() *= (1.0 + 0.25 * double(it.row() % 5)) * (1.0 + 0.25 * double(it.col() % 5));
    two.factorize(B);
    Cfg::Reference refB(B);
    checkAgainstReference<Cfg>(two, B, refB);
    Cfg::Solver fresh;
    fresh.setThreadCount(2);
    fresh.compute(B);
    CHECK(sameFactorBitwise<Cfg>(two, fresh));
  }
}
