// bench_arap: handle and region-of-interest edits of ARAP deformation (Sorkine & Alexa 2007), the
// paper's §5.3 / Fig. 9: when the constraint set of an editing session changes, ours updates the
// one factor of the cotan Laplacian in place (restoreDofs of the released vertices + removeDofs of
// the newly constrained ones), where an ARAP implementation without updates refactors. For each
// edit of a scripted session it times, in the same run, the edit followed by one global step
// (solveDirichlet with the 3 coordinates as right-hand sides):
//   - ours:       UpdatableSupernodalLLT::restoreDofs + removeDofs, automatic route;
//   - refactor:   the same calls with UpdateRoute::Refactorization forced (numeric refactorization
//                 of the whole Dirichlet matrix, symbolic analysis reused);
//   - scratch:    analyzePattern + factorize of the reduced matrix A_II of the free vertices (METIS),
//                 as an ARAP precomputation without updates does, + solve of b_I - A_IB g_B;
// and an ARAP iteration (local step + global step) of ArapDeformation for scale. The matrix is the
// cotan Laplacian + 1e-10 (mean diagonal) I, the one ArapDeformation factors. Every peer's solution
// is checked against ours (relative error <= 1e-8). Prints medians and the ratios of the peers to
// ours (> 1: ours is faster).
//
// Usage: bench_arap [--mesh=PATH] [--bar=AROUND,RINGS] [--reps=N] [--seed=S] [--smoke]
// Exit code: 0 if every answer was right, 1 otherwise, 2 on bad usage.

#include <iostream>  // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <unsupported/Eigen/MeshDeformation>

#include "BlasCore.h"
#include "Timing.h"

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#ifndef UC_BENCH_DEFAULT_MESH
#define UC_BENCH_DEFAULT_MESH "bunny.off.gz"
#endif

namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Solver = Eigen::UpdatableSupernodalLLT<SpMat, Eigen::Lower, Eigen::MetisOrdering<int>>;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;

constexpr double kRelativeTolerance = 1e-8;

/** One constraint set of the session: constrained flags and a name. */
struct Step {
  std::string name;
  std::vector<char> constrained;
};

/** Constrained flags: everything outside the ball (center, roiRadius), plus the handle ball. */
std::vector<char> constraints(const MatrixXd& V, int roiCenter, double roiRadius, int handleCenter,
                              double handleRadius) {
  std::vector<char> c(std::size_t(V.rows()), 0);
  for (Index v = 0; v < V.rows(); ++v)
    c[std::size_t(v)] = (V.row(v) - V.row(roiCenter)).norm() > roiRadius ||
                        (V.row(v) - V.row(handleCenter)).norm() <= handleRadius;
  return c;
}

/** The vertices constrained in \a to but not in \a from. */
std::vector<int> newlyConstrained(const std::vector<char>& from, const std::vector<char>& to) {
  std::vector<int> added, released;
  Eigen::internal::mesh_deformation::constraintChange(from, to, added, released);
  return added;
}

/** Applies the edit from -> to to \a solver in place: restore the released, remove the added. */
bool applyEdit(Solver& solver, const std::vector<char>& from, const std::vector<char>& to) {
  const std::vector<int> added = newlyConstrained(from, to), released = newlyConstrained(to, from);
  if (!released.empty() && solver.restoreDofs(released).info() != Eigen::Success) return false;
  if (!added.empty() && solver.removeDofs(added).info() != Eigen::Success) return false;
  return true;
}

/** The from-scratch global step: factor A_II of the free vertices and solve b_I - A_IB g_B. */
MatrixXd solveReduced(const SpMat& A, const std::vector<char>& constrained, const MatrixXd& b, const MatrixXd& g) {
  const Index n = A.rows();
  std::vector<int> freeIndex(std::size_t(n), -1);
  int freeCount = 0;
  for (Index v = 0; v < n; ++v)
    if (!constrained[std::size_t(v)]) freeIndex[std::size_t(v)] = freeCount++;
  std::vector<Eigen::Triplet<double>> t;
  MatrixXd rhs(freeCount, 3);
  for (Index v = 0; v < n; ++v)
    if (freeIndex[std::size_t(v)] >= 0) rhs.row(freeIndex[std::size_t(v)]) = b.row(v);
  for (Index j = 0; j < n; ++j)
    for (SpMat::InnerIterator it(A, j); it; ++it) {
      const int fi = freeIndex[std::size_t(it.row())], fj = freeIndex[std::size_t(j)];
      if (fi >= 0 && fj >= 0) t.emplace_back(fi, fj, it.value());
      else if (fi >= 0) rhs.row(fi) -= it.value() * g.row(j);
    }
  SpMat Aii(freeCount, freeCount);
  Aii.setFromTriplets(t.begin(), t.end());
  Solver fresh(Aii);
  const MatrixXd xI = fresh.solve(rhs);
  MatrixXd x = g;
  for (Index v = 0; v < n; ++v)
    if (freeIndex[std::size_t(v)] >= 0) x.row(v) = xI.row(freeIndex[std::size_t(v)]);
  return x;
}

double relativeError(const MatrixXd& x, const MatrixXd& reference) {
  return (x - reference).cwiseAbs().maxCoeff() / std::max(reference.cwiseAbs().maxCoeff(), 1e-300);
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

int main(int argc, char** argv) {
  bench::ensureOpenBlasCore(argv);  // (may re-execute with OPENBLAS_CORETYPE: see BlasCore.h)
  std::string meshPath = UC_BENCH_DEFAULT_MESH;
  int barAround = 0, barRings = 0, reps = 5;
  unsigned seed = 1;
  bool smoke = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--smoke") smoke = true;
    else if (startsWith(arg, "--mesh=")) meshPath = arg.substr(7);
    else if (startsWith(arg, "--bar=") && std::sscanf(arg.c_str() + 6, "%d,%d", &barAround, &barRings) == 2) {}
    else if (startsWith(arg, "--reps=")) reps = std::max(1, std::atoi(arg.c_str() + 7));
    else if (startsWith(arg, "--seed=")) seed = unsigned(std::atoi(arg.c_str() + 7));
    else {
      std::fprintf(stderr, "usage: bench_arap [--mesh=PATH] [--bar=AROUND,RINGS] [--reps=N] [--seed=S] [--smoke]\n");
      return 2;
    }
  }
  if (smoke) {
    barAround = 16;
    barRings = 60;
    reps = 1;
  }

  MatrixXd V;
  MatrixXi F;
  std::string name;
  if (barAround > 0) {
    Eigen::cylinderMesh(barAround, barRings, 0.1, 1.0, V, F);
    name = "bar " + std::to_string(barAround) + "x" + std::to_string(barRings);
  } else {
    std::string error;
    if (!Eigen::readOFF(meshPath, V, F, &error)) {
      std::fprintf(stderr, "bench_arap: %s\n", error.c_str());
      return 2;
    }
    name = meshPath;
  }

  // The matrix ArapDeformation factors.
  const SpMat L = Eigen::cotanLaplacian<double, int>(V, F);
  SpMat I(L.rows(), L.cols());
  I.setIdentity();
  const SpMat A = L + 1e-10 * (L.diagonal().sum() / double(L.rows())) * I;

  // The session (Fig. 9): a region of interest around a random vertex with a handle ball inside,
  // then the handle moves, the region grows, the region moves, the handle grows.
  std::mt19937 random(seed);
  const int c0 = int(std::uniform_int_distribution<Index>(0, V.rows() - 1)(random));
  const double extent = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const double r = 0.25 * extent, h = 0.04 * extent;
  auto nearest = [&](const Eigen::RowVector3d& p) {
    Index best = 0;
    (V.rowwise() - p).rowwise().squaredNorm().minCoeff(&best);
    return int(best);
  };
  const Eigen::RowVector3d towards = (V.colwise().mean() - V.row(c0)).normalized();
  const int c1 = nearest(V.row(c0) + 0.1 * extent * towards), c2 = nearest(V.row(c0) + 0.15 * extent * towards);
  std::vector<Step> session = {
      {"set region + handle", constraints(V, c0, r, c0, h)},
      {"move handle", constraints(V, c0, r, c1, h)},
      {"grow region", constraints(V, c0, 1.3 * r, c1, h)},
      {"move region", constraints(V, c2, 1.3 * r, c1, h)},
      {"grow handle", constraints(V, c2, 1.3 * r, c1, 2 * h)},
  };

  std::printf("bench_arap: %s, %lld vertices, %d reps, ARAP edits (region radius %.2f, handle %.2f of the extent)\n",
              name.c_str(), (long long)V.rows(), reps, 0.25, 0.04);
  bench::Stopwatch setup;
  Solver ours, forced;
  ours.setUpdateCaching(true);
  forced.setUpdateCaching(true);
  ours.compute(A);
  forced.compute(A);
  forced.setUpdateRoute(Eigen::UpdateRoute::Refactorization);
  if (ours.info() != Eigen::Success || forced.info() != Eigen::Success) {
    std::fprintf(stderr, "bench_arap: factorization failed\n");
    return 1;
  }
  std::printf("initial analysis + factorization (x2): %.1f ms\n\n", setup.ms());

  // Right-hand side of a global step and Dirichlet values: rest positions moved a little.
  const MatrixXd b = L * V;
  MatrixXd g = V;
  g.col(2).array() += 0.05 * extent;

  std::printf("%-20s %8s %8s | %10s %10s %10s | %8s %8s | %s\n", "edit", "+dofs", "-dofs", "ours ms", "refact ms",
              "scratch ms", "refact/o", "scratch/o", "route (ours)    flops: ours refact (fraction of a full factorization, last call)");
  bool allRight = true;
  std::vector<char> current(std::size_t(V.rows()), 0);
  for (const Step& step : session) {
    const std::vector<int> added = newlyConstrained(current, step.constrained),
                           released = newlyConstrained(step.constrained, current);
    bench::Samples oursMs, forcedMs, scratchMs;
    MatrixXd xOurs, xForced, xScratch;
    for (int rep = 0; rep < reps; ++rep) {
      // each repetition: edit (timed) + global step, then the inverse edit (untimed)
      bench::Stopwatch w;
      bool ok = applyEdit(ours, current, step.constrained);
      xOurs = ours.solveDirichlet(b, g);
      oursMs.add(w.ms());
      w.restart();
      ok = applyEdit(forced, current, step.constrained) && ok;
      xForced = forced.solveDirichlet(b, g);
      forcedMs.add(w.ms());
      w.restart();
      xScratch = solveReduced(A, step.constrained, b, g);
      scratchMs.add(w.ms());
      allRight = allRight && ok;
      if (rep + 1 < reps) {
        allRight = applyEdit(ours, step.constrained, current) && allRight;
        allRight = applyEdit(forced, step.constrained, current) && allRight;
      }
    }
    const double errForced = relativeError(xForced, xOurs), errScratch = relativeError(xScratch, xOurs);
    const bool right = errForced <= kRelativeTolerance && errScratch <= kRelativeTolerance;
    allRight = allRight && right;
    const char* route = "-";
    switch (ours.lastUpdate().route) {
      case Eigen::UpdateRoute::PartialRefactorization: route = "partial"; break;
      case Eigen::UpdateRoute::Refactorization: route = "refactorization"; break;
      case Eigen::UpdateRoute::LowRank: route = "low-rank"; break;
      case Eigen::UpdateRoute::Mixed: route = "mixed"; break;
      default: break;
    }
    std::printf("%-20s %8zu %8zu | %10.2f %10.2f %10.2f | %8.2f %8.2f | %-15s %7.3f %7.3f%s\n", step.name.c_str(),
                added.size(), released.size(), oursMs.median(), forcedMs.median(), scratchMs.median(),
                forcedMs.median() / oursMs.median(), scratchMs.median() / oursMs.median(), route,
                ours.lastUpdate().flopFraction, forced.lastUpdate().flopFraction, right ? "" : "  WRONG");
    current = step.constrained;
  }

  // One ARAP iteration (local step + global step) for scale, in the last configuration.
  Eigen::ArapDeformation<Eigen::MetisOrdering<int>> arap(V, F);
  std::vector<int> region, handles;
  for (Index v = 0; v < V.rows(); ++v) {
    if ((V.row(v) - V.row(c2)).norm() <= 1.3 * r) region.push_back(int(v));
    if ((V.row(v) - V.row(c1)).norm() <= 2 * h) handles.push_back(int(v));
  }
  MatrixXd targets(Index(handles.size()), 3);
  for (std::size_t k = 0; k < handles.size(); ++k) targets.row(Index(k)) = g.row(handles[k]);
  MatrixXd U;
  bench::Samples iterationMs;
  if (arap.setRegionOfInterest(region) && arap.setHandles(handles, targets) && arap.solve(U, 1)) {
    for (int rep = 0; rep < reps; ++rep) iterationMs.add(bench::timeMs([&]() { arap.solve(U, 1); }));
    std::printf("\none ARAP iteration (local SVDs + global step with refinement): %.2f ms (median)\n",
                iterationMs.median());
  } else {
    std::printf("\nARAP iteration: %s\n", arap.lastError().c_str());
    allRight = false;
  }
  std::printf("%s\n", allRight ? "all solutions agree (relative error <= 1e-8)" : "SOME SOLUTIONS ARE WRONG");
  return allRight ? 0 : 1;
}
