// bench_bff: the cost of one Boundary First Flattening cut edit (Herholz & Sorkine-Hornung §5.1,
// Sawhney & Crane 2017): our in-place update (removeDofs of the seam on the one factor, then BFF's
// solves) against rebuilding the cut mesh's interior system and factoring it from scratch (then
// the same solves), on a mesh (default igea, a closed surface cut open along one path first).
//
// For each of --cuts seams (from the boundary to a seeded random interior vertex, shortest path
// through the interior), independently (each cut is undone before the next):
//   ours      = removeDofs(seam) + BFF layout (3 Dirichlet solves: u, its refinement, the
//               extension with 2 right-hand sides, and the O(#F) geometry between them);
//   scratch   = assembling A_II + eps I of the cut mesh + compute() (METIS ordering, analysis,
//               factorization) + the same 3 solves;
//   scratch-fixed = the same with the ordering fixed to ours restricted to the interior (the
//               factorization without the ordering: "same ordering").
// The cut itself (cutMeshAlongPath, boundary tracing) is the same for both and listed apart.
// Reports medians and the ratios scratch/ours. Exit 0 on success, 1 on failure, 2 on bad usage.
//
// Usage: bench_bff [--mesh=PATH] [--cuts=N] [--seed=S] [--smoke]

#include <Eigen/UpdatableCholesky>

#include <iostream> // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <unsupported/Eigen/MeshParameterization>

#include "BlasCore.h"
#include "FixedOrdering.h"
#include "Timing.h"

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#ifndef UC_BENCH_DEFAULT_MESH
#define UC_BENCH_DEFAULT_MESH "../shared/meshes/igea.off.gz"
#endif

namespace {

using Ordering = Eigen::MetisOrdering<int>;
using Flattening = Eigen::BoundaryFirstFlattening<Ordering>;
using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

/** The three solves of a BFF layout (1, 1 and 2 right-hand sides) with a given factor. */
template <typename Solver>
void bffSolves(const Solver& solver, Eigen::Index n)
{
  Eigen::MatrixXd b = Eigen::MatrixXd::Ones(n, 1);
  Eigen::MatrixXd x = solver.solve(b);
  x = solver.solve(1e-8 * x);
  Eigen::MatrixXd b2 = Eigen::MatrixXd::Ones(n, 2);
  volatile double sink = solver.solve(b2)(0, 0) + x(0, 0);
  (void)sink;
}

/** Our ordering restricted to the rows \a interior (original indices, increasing) of the
  * interior matrix: Pinv for FixedOrdering. */
Permutation restrictedOrdering(const Flattening& bff, const std::vector<int>& interior)
{
  const auto& Pinv = bff.system().solver().permutationPinv();
  std::vector<int> position(std::size_t(Pinv.size()), -1);
  for (std::size_t k = 0; k < interior.size(); ++k) position[std::size_t(interior[k])] = int(k);
  Permutation restricted(Eigen::Index(interior.size()));
  Eigen::Index next = 0;
  for (Eigen::Index k = 0; k < Pinv.size(); ++k)
  {
    const int p = position[std::size_t(Pinv.indices()[k])];
    if (p >= 0) restricted.indices()[next++] = p;
  }
  return restricted;
}

} // namespace

/** Entry point: see the comment at the top of this file. */
int main(int argc, char** argv)
{
  bench::ensureOpenBlasCore(argv);  // (may re-execute with OPENBLAS_CORETYPE: see BlasCore.h)
  std::string meshPath = UC_BENCH_DEFAULT_MESH;
  int cuts = 7;
  unsigned seed = 1;
  bool smoke = false;
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if (arg.rfind("--mesh=", 0) == 0) meshPath = arg.substr(7);
    else if (arg.rfind("--cuts=", 0) == 0) cuts = std::atoi(arg.c_str() + 7);
    else if (arg.rfind("--seed=", 0) == 0) seed = unsigned(std::atoi(arg.c_str() + 7));
    else if (arg == "--smoke") smoke = true;
    else
    {
      std::fprintf(stderr, "usage: bench_bff [--mesh=PATH] [--cuts=N] [--seed=S] [--smoke]\n");
      return 2;
    }
  }
  if (cuts < 1) cuts = 1;

  // 1. The mesh: a generated sphere in smoke mode.
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string error;
  if (smoke)
  {
    Eigen::icosphereMesh(3, V, F);
    cuts = 2;
    meshPath = "icosphere(3)";
  }
  else if (!Eigen::readMesh(meshPath, V, F, &error))
  {
    std::fprintf(stderr, "bench_bff: %s\n", error.c_str());
    return 1;
  }
  std::vector<int> initialSeam;
  if (Eigen::boundaryLoops(F).empty())
  {
    Eigen::Index far = 0;
    (V.rowwise() - V.row(0)).rowwise().squaredNorm().maxCoeff(&far);
    initialSeam = Eigen::shortestEdgePath(V, F, 0, int(far));
  }

  // 2. BFF on the whole (opened) mesh: one factorization.
  Flattening bff;
  bench::Stopwatch watch;
  if (!bff.compute(V, F, initialSeam, &error))
  {
    std::fprintf(stderr, "bench_bff: %s\n", error.c_str());
    return 1;
  }
  std::printf("bench_bff  mesh %s: %lld vertices, %lld triangles; initial cut %zu vertices; first BFF %.0f ms\n",
              meshPath.c_str(), (long long)V.rows(), (long long)F.rows(), initialSeam.size(), watch.ms());

  // 3. The cuts.
  bench::Samples seamLength, cutMs, updateMs, layoutMs, ours, scratch, scratchFixed, scratchFactor;
  std::mt19937 generator(seed);
  bool ok = true;
  for (int c = 0, attempts = 0; c < cuts && attempts < 100 * cuts; ++attempts)
  {
    const int target = int(std::uniform_int_distribution<int>(0, int(bff.cutVertices().rows()) - 1)(generator));
    const std::vector<int> seam = Eigen::seamToBoundary(bff.cutVertices(), bff.cutFaces(), target);
    if (seam.size() < 3) continue;
    if (!bff.addSeam(seam, &error))
    {
      std::fprintf(stderr, "bench_bff: cut failed: %s\n", error.c_str());
      return 1;
    }
    ++c;
    seamLength.add(double(seam.size()));
    cutMs.add(bff.system().lastCutMs());
    updateMs.add(bff.system().lastUpdateMs());
    layoutMs.add(bff.lastLayoutMs());
    ours.add(bff.system().lastUpdateMs() + bff.lastLayoutMs());

    // From scratch: assemble the interior system of the cut mesh, factor it, solve.
    std::vector<int> interior;
    watch.restart();
    Eigen::SparseMatrix<double> A = bff.system().interiorMatrix(&interior);
    Eigen::UpdatableSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Ordering> fresh(A);
    bffSolves(fresh, A.rows());
    scratch.add(watch.ms());
    ok = ok && fresh.info() == Eigen::Success;

    const Permutation fixed = restrictedOrdering(bff, interior);
    watch.restart();
    Eigen::SparseMatrix<double> A2 = bff.system().interiorMatrix();
    Eigen::UpdatableSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower, bench::FixedOrdering<int>> freshFixed;
    freshFixed.ordering().permutation = &fixed;
    freshFixed.analyzePattern(A2);
    bench::Stopwatch factorWatch;
    freshFixed.factorize(A2);
    scratchFactor.add(factorWatch.ms());
    bffSolves(freshFixed, A2.rows());
    scratchFixed.add(watch.ms());
    ok = ok && freshFixed.info() == Eigen::Success;

    if (smoke)
    {
      // The updated layout must equal BFF from scratch on the cut mesh.
      Flattening check;
      ok = ok && check.compute(bff.cutVertices(), bff.cutFaces()) &&
           (check.uv() - bff.uv()).cwiseAbs().maxCoeff() < 1e-8;
    }
    if (!bff.undo(&error))
    {
      std::fprintf(stderr, "bench_bff: undo failed: %s\n", error.c_str());
      return 1;
    }
  }
  if (seamLength.size() == 0)
  {
    std::fprintf(stderr, "bench_bff: found no seam\n");
    return 1;
  }

  std::printf("%zu cuts, seam length median %.0f (min %.0f, max %.0f) vertices; medians in ms:\n", seamLength.size(),
              seamLength.median(), seamLength.min(), seamLength.max());
  std::printf("  cut mesh (same for all)                 %9.2f\n", cutMs.median());
  std::printf("  ours: removeDofs                        %9.2f\n", updateMs.median());
  std::printf("  ours: BFF layout (solves + geometry)    %9.2f\n", layoutMs.median());
  std::printf("  ours: edit = removeDofs + layout        %9.2f\n", ours.median());
  std::printf("  scratch: A_II + compute(METIS) + solves %9.2f   ratio scratch/ours %.1fx\n", scratch.median(),
              scratch.median() / ours.median());
  std::printf("  scratch, our ordering fixed: A_II +\n"
              "    analyze + factorize + solves          %9.2f   ratio %.1fx (factorize alone %.2f)\n",
              scratchFixed.median(), scratchFixed.median() / ours.median(), scratchFactor.median());
  std::printf("  factor update alone: refactorization (same ordering) / removeDofs = %.1fx\n",
              scratchFactor.median() / updateMs.median());
  if (!ok)
  {
    std::fprintf(stderr, "bench_bff: a factorization failed or the updated layout differs from scratch\n");
    return 1;
  }
  return 0;
}
