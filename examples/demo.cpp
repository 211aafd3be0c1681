// demo: the README's example. Loads a triangle mesh (data/camelhead.off.gz unless a path is given),
// builds its cotan Laplacian + 1e-8 I, factors it with UpdatableSupernodalLLT under a METIS
// ordering, solves, and prints sizes, nnz(L), supernodes, timings and the residual.
//
// Usage: demo [mesh.off[.gz]]     Exit code: 0 on success, 1 on any failure (with a message).

#include <Eigen/UpdatableCholesky>

#include <iostream> // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <unsupported/Eigen/MeshTools>

#include <chrono>
#include <cstdio>
#include <string>

#ifndef UC_DEMO_DEFAULT_MESH
#define UC_DEMO_DEFAULT_MESH "data/camelhead.off.gz"
#endif

namespace {

/** \returns milliseconds elapsed since \a start. */
double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

/** Entry point: see the comment at the top of this file. */
int main(int argc, char** argv)
{
  using Clock = std::chrono::steady_clock;
  const std::string path = argc > 1 ? argv[1] : UC_DEMO_DEFAULT_MESH;

  // 1. Read the mesh: V holds one vertex position per row, F one triangle per row.
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string error;
  if (!Eigen::readOFF(path, V, F, &error))
  {
    std::fprintf(stderr, "demo: %s\n", error.c_str());
    return 1;
  }
  std::printf("mesh      %s\n          %lld vertices, %lld triangles\n", path.c_str(), (long long)V.rows(),
              (long long)F.rows());

  // 2. The matrix: cotan Laplacian (positive semi-definite) plus a tiny shift that makes it definite.
  Eigen::SparseMatrix<double> A = Eigen::cotanLaplacian(V, F);
  Eigen::SparseMatrix<double> identity(A.rows(), A.cols());
  identity.setIdentity();
  A += 1e-8 * identity;
  std::printf("matrix    cotan Laplacian + 1e-8 I: %lld x %lld, %lld non-zeros\n", (long long)A.rows(),
              (long long)A.cols(), (long long)A.nonZeros());

  // 3. Factor: the same API as SimplicialLLT. analyzePattern() orders (METIS) and builds the
  //    supernodal structure; factorize() computes the numbers and may be repeated for new values.
  Eigen::UpdatableSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::MetisOrdering<int>> llt;
  auto start = Clock::now();
  llt.analyzePattern(A);
  const double analysisMs = msSince(start);
  start = Clock::now();
  llt.factorize(A);
  const double factorMs = msSince(start);
  if (llt.info() != Eigen::Success)
  {
    std::fprintf(stderr, "demo: factorization failed (info %d, column %lld)\n", int(llt.info()),
                 (long long)llt.failedColumn());
    return 1;
  }
  std::printf("factor    nnz(L) = %lld stored entries in %lld supernodes, %.1f Mflop\n", (long long)llt.nonZerosL(),
              (long long)llt.supernodeCount(), llt.factorizationFlops() / 1e6);

  // 4. Solve for three right-hand sides at once: the Laplacian coordinates b = A V of the mesh,
  //    from which the solve recovers the vertex positions.
  const Eigen::MatrixXd B = A * V;
  start = Clock::now();
  const Eigen::MatrixXd X = llt.solve(B);
  const double solveMs = msSince(start);
  const double residual = (A * X - B).norm() / B.norm();
  const double positionError = (X - V).cwiseAbs().maxCoeff() / (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();

  std::printf("time      analysis %.2f ms, factorization %.2f ms, solve (3 rhs) %.2f ms\n", analysisMs, factorMs,
              solveMs);
  std::printf("residual  ||A x - b|| / ||b|| = %.2e; max position error / bounding-box diagonal = %.2e\n", residual,
              positionError);
  if (!(residual < 1e-6))
  {
    std::fprintf(stderr, "demo: residual too large\n");
    return 1;
  }
  return 0;
}
