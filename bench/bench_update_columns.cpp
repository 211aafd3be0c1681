// bench_update_columns: changing the values of k columns of a mesh matrix (UpdatableSupernodalLLT::
// updateColumns, paper §3.3, Algorithm 3, with the signed low-rank folds of LowRankTopUpdate.h).
// The change is the one soft (penalty) constraints at k random vertices make: A + sum_j w_j e_j e_j^T
// with w_j = A_jj / 2, on the cotan Laplacian + 1e-8 I, for k = 1, 5, 20, 100, 500. One METIS
// permutation is shared by every solver. Per step it times, interleaved, the update followed by one
// solve:
//   - ours:       updateColumns(A + C, cols), automatic route;
//   - ours part.: the same with UpdateRoute::PartialRefactorization forced (Algorithm 3 alone);
//   - CHOLMOD:    numeric refactorization (cholmod_factorize, supernodal, analysis reused);
//   - updown:     cholmod_updown of a simplicial LDL^T copy of the factor of A by C C^T (its
//                 conversion and the copy per step are not timed: UpdownPeer.h);
//   - Simplicial: Eigen's SimplicialLLT::factorize (analysis reused).
// Every timed run starts with cold caches (Timing.h: evictCaches()). Every solution is checked by its
// backward error (<= 1e-10). Prints the medians, the ratios of the
// peers to ours (> 1: ours is faster), our route and flop fraction (of a full factorization).
//
// Usage: bench_update_columns [--mesh=PATH] [--counts=1,5,20,100,500] [--repeats=5] [--seed=S]
//                             [--no-simplicial] [--smoke]
// Exit code: 0 if every answer was right, 1 otherwise, 2 on bad usage.

#include <Eigen/UpdatableCholesky>

#include <iostream>  // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <Eigen/SparseCholesky>
#include <unsupported/Eigen/MeshTools>

#include "BenchReport.h"
#include "BlasCore.h"
#include "CholmodPeer.h"
#include "FixedOrdering.h"
#include "Timing.h"
#include "UpdownPeer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

// OpenBLAS's thread control; weak, so the benchmark still links against another BLAS.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

#ifndef UC_BENCH_DEFAULT_MESH
#define UC_BENCH_DEFAULT_MESH "bunny.off.gz"
#endif

namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Ordering = bench::FixedOrdering<int>;
using Ours = Eigen::UpdatableSupernodalLLT<SpMat, Eigen::Lower, Ordering>;
using Simplicial = Eigen::SimplicialLLT<SpMat, Eigen::Lower, Ordering>;

constexpr double kBackwardTolerance = 1e-10;
enum Method { OursAuto, OursPartial, CholmodRefactor, CholmodUpdown, SimplicialRefactor, MethodCount };
const char* const kLabels[MethodCount] = {"ours", "ours part.", "CHOLMOD", "updown", "Simplicial"};

/** ||A x - b||_inf / (||A||_inf ||x||_inf + ||b||_inf). */
double backwardError(const SpMat& A, double normA, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  const double e = (A * x - b).lpNorm<Eigen::Infinity>() / (normA * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>());
  return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

/** Entry point: see the usage text at the top of this file. */
int main(int argc, char** argv) {
  bench::ensureOpenBlasCore(argv);  // (may re-execute with OPENBLAS_CORETYPE: see BlasCore.h)
  if (openblas_set_num_threads) openblas_set_num_threads(1);
  std::string meshPath = UC_BENCH_DEFAULT_MESH, countList = "1,5,20,100,500";
  int repeats = 5;
  unsigned seed = 1;
  bool smoke = false, simplicial = true;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--smoke") smoke = true;
    else if (arg == "--no-simplicial") simplicial = false;
    else if (startsWith(arg, "--mesh=")) meshPath = arg.substr(7);
    else if (startsWith(arg, "--counts=")) countList = arg.substr(9);
    else if (startsWith(arg, "--repeats=") && bench::parseInt(arg.substr(10), repeats) && repeats > 0) {}
    else if (startsWith(arg, "--seed=")) seed = unsigned(std::atoi(arg.c_str() + 7));
    else {
      std::fprintf(stderr,
                   "usage: bench_update_columns [--mesh=PATH] [--counts=1,5,20,100,500] [--repeats=5] [--seed=S]\n"
                   "                            [--no-simplicial] [--smoke]\n");
      return 2;
    }
  }
  std::vector<int> counts;
  if (!bench::forEachListItem(countList, [&](const std::string& item) {
        int k = 0;
        if (!bench::parseInt(item, k) || k < 1) return false;
        counts.push_back(k);
        return true;
      })) {
    std::fprintf(stderr, "bench_update_columns: bad --counts=%s\n", countList.c_str());
    return 2;
  }
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string name = meshPath;
  if (smoke) {
    Eigen::gridMesh(30, 30, V, F);
    name = "grid 30x30 (smoke)";
    counts = {1, 5};
    repeats = 1;
  } else {
    std::string error;
    if (!Eigen::readMesh(meshPath, V, F, &error)) {
      std::fprintf(stderr, "bench_update_columns: %s\n", error.c_str());
      return 2;
    }
  }

  SpMat A = Eigen::cotanLaplacian<double, int>(V, F);
  {
    SpMat I(A.rows(), A.cols());
    I.setIdentity();
    A += 1e-8 * I;
    A.makeCompressed();
  }
  const int n = int(A.rows());
  Ordering::PermutationType perm;
  Eigen::MetisOrdering<int>()(A, perm);
  Ordering::setDefault(&perm);
  std::vector<int> cholmodPerm(perm.indices().data(), perm.indices().data() + n);

  Ours ours, oursPartial;
  for (Ours* o : {&ours, &oursPartial}) {
    o->setThreadCount(1);
    o->setUpdateCaching(true);
    o->compute(A);
    if (o->info() != Eigen::Success) {
      std::printf("FAILED: compute\n");
      return 1;
    }
  }
  oursPartial.setUpdateRoute(Eigen::UpdateRoute::PartialRefactorization);
  bench::CholmodSupernodal cholmod;
  cholmod.analyze(A, cholmodPerm.data());
  if (!cholmod.factorize(A)) {
    std::printf("FAILED: CHOLMOD factorize\n");
    return 1;
  }
  bench::CholmodUpdown updown(cholmod, A);
  Simplicial simplicialLLT;
  if (simplicial) simplicialLLT.analyzePattern(A);

  std::printf("bench_update_columns: %s, n = %d, soft constraints at k random vertices (A + w e_j e_j^T)\n",
              name.c_str(), n);
  std::printf("%6s |", "k");
  for (int m = 0; m < MethodCount; ++m) std::printf(" %11s", kLabels[m]);
  std::printf(" | %9s %9s %9s %9s | %8s %8s %s\n", "/part.", "/CHOLMOD", "/updown", "/Simpl.", "flops", "updown", "route");
  std::mt19937 random(seed);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  bool allOk = true;
  for (int k : counts) {
    std::vector<double> ms[MethodCount];
    double flopFraction = 0, updownFraction = 0;
    std::string route;
    for (int r = 0; r < repeats; ++r) {
      std::vector<int> cols;
      while (int(cols.size()) < std::min(k, n)) {
        const int v = int(random() % unsigned(n));
        if (std::find(cols.begin(), cols.end(), v) == cols.end()) cols.push_back(v);
      }
      std::sort(cols.begin(), cols.end());
      SpMat changed = A;
      std::vector<std::pair<int, double>> terms;
      for (int c : cols) {
        const double w = 0.5 * A.coeff(c, c);
        changed.coeffRef(c, c) += w;
        terms.push_back({c, w});
      }
      const double normChanged = bench::infinityNorm(changed);
      for (int step = 0; step < MethodCount; ++step) {
        const int m = (step + r) % MethodCount;  // (rotated per repeat: no method always goes first)
        if (m == SimplicialRefactor && !simplicial) continue;
        Eigen::VectorXd x;
        if (m == CholmodUpdown) updown.reset();  // (untimed: the factor of A again)
        bench::evictCaches();                    // (every method starts from memory, as the seam benchmarks)
        bench::Stopwatch watch;
        if (m == OursAuto || m == OursPartial) {
          Ours& solver = m == OursAuto ? ours : oursPartial;
          solver.updateColumns(changed, cols);
          if (solver.info() == Eigen::Success) x = solver.solve(b);
          ms[m].push_back(watch.ms());
          if (m == OursAuto) {
            flopFraction = std::max(flopFraction, solver.lastUpdate().flopFraction);
            route = bench::routeName(solver.lastUpdate().route);
          }
          solver.updateColumns(A, cols);  // back to A (untimed)
          if (solver.info() != Eigen::Success) x.resize(0);
        } else if (m == CholmodRefactor) {
          if (cholmod.factorize(changed)) x = cholmod.solve(b);
          ms[m].push_back(watch.ms());
        } else if (m == CholmodUpdown) {
          updown.update(terms);
          x = updown.solve(b);
          ms[m].push_back(watch.ms());
          updownFraction = std::max(updownFraction, updown.updateFlops() / cholmod.flops());
        } else {
          simplicialLLT.factorize(changed);
          if (simplicialLLT.info() == Eigen::Success) x = simplicialLLT.solve(b);
          ms[m].push_back(watch.ms());
        }
        const double error = x.size() == n ? backwardError(changed, normChanged, x, b) : 1.0;
        if (!(error <= kBackwardTolerance)) {
          std::printf("  WRONG: %s at k = %d: backward error %.1e\n", kLabels[m], k, error);
          allOk = false;
        }
      }
    }
    auto median = [](std::vector<double> v) {
      if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    double med[MethodCount];
    for (int m = 0; m < MethodCount; ++m) med[m] = median(ms[m]);
    std::printf("%6d |", k);
    for (int m = 0; m < MethodCount; ++m) std::printf(" %11s", bench::fmtMs(med[m]).c_str());
    std::printf(" | %9s %9s %9s %9s | %8s %8s %s\n", bench::fmtRatio(med[OursPartial], med[OursAuto]).c_str(),
                bench::fmtRatio(med[CholmodRefactor], med[OursAuto]).c_str(),
                bench::fmtRatio(med[CholmodUpdown], med[OursAuto]).c_str(),
                bench::fmtRatio(med[SimplicialRefactor], med[OursAuto]).c_str(), bench::fmtFraction(flopFraction).c_str(),
                bench::fmtFraction(updownFraction).c_str(), route.c_str());
  }
  std::printf("columns: medians [ms] of update + one solve; /X = X's time over ours (> 1: ours is faster); flops =\n"
              "ours lastUpdate().flopFraction, updown = Common.modfl over Common.fl of A (largest of the repeats);\n"
              "route = ours' route in the last repeat\n");
  std::printf("result: %s\n", allOk ? "all answers agree" : "WRONG ANSWERS");
  return allOk ? 0 : 1;
}
