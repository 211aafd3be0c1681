// bench_orbifold: orbifold Tutte embeddings after each new cut, the paper's Fig. 7 (Herholz &
// Sorkine-Hornung, §6.3; Aigerman & Lipman 2015). For a closed genus-0 mesh and a sequence of
// random cone sets (types I-IV in turn, seeded), each new cut is solved, in the same run, by
//   - ours: OrbifoldTutteEmbedding::setCones — the factor of the cut Laplacian is updated in
//     place (previous seam merged back, new seam inserted: mergeDofs/insertDofs, paper §4.2) and
//     the KKT system is solved through the Schur complement C = B blkdiag(A^-1, A^-1) B^T
//     (eq. 21-23), one factor shared by x and y;
//   - SparseLU: Eigen's SparseLU (COLAMD) on the full KKT matrix (eq. 20) of the cut Laplacian,
//     the way CGAL's Orbifold_Tutte_parameterizer_3 solves it: analyze + factorize + solve;
//   - fresh: our solver on the cut Laplacian from scratch (METIS ordering, analysis,
//     factorization), for reference: what an edit would cost without the update.
// Not timed, as in the paper: the cone paths, the cut, the Laplacian and KKT assembly. The
// answers are compared (max |uv_ours - uv_LU| / max |uv_LU| <= 1e-8). Prints per cut and the
// medians with the ratio SparseLU / ours. --smoke runs a small icosphere for CI.
//
// Usage: bench_orbifold [--mesh=PATH] [--icosphere=S] [--cuts=6] [--types=I,II,III,IV] [--seed=S]
//                       [--threads=1] [--no-lu] [--smoke]
// Exit code: 0 if every answer agreed, 1 otherwise, 2 on bad usage or unreadable mesh.

#include <Eigen/UpdatableCholesky>

#include <iostream> // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <Eigen/SparseLU>
#include <unsupported/Eigen/MeshParameterization>

#include "BlasCore.h"
#include "Timing.h"

#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#ifndef UC_BENCH_DEFAULT_MESH
#define UC_BENCH_DEFAULT_MESH "igea.off.gz"
#endif

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;
using Eigen::OrbifoldType;
typedef Eigen::OrbifoldTutteEmbedding<Eigen::MetisOrdering<int>> Orbifold;
typedef Eigen::SparseMatrix<double> SpMat;

struct Options
{
  std::string mesh = UC_BENCH_DEFAULT_MESH;
  int icosphere = -1;
  int cuts = 6;
  std::vector<OrbifoldType> types = {OrbifoldType::I, OrbifoldType::II, OrbifoldType::III, OrbifoldType::IV};
  unsigned seed = 1;
  int threads = 1;
  bool lu = true;
  bool smoke = false;
};

const char* typeName(OrbifoldType t)
{
  static const char* names[] = {"I", "II", "III", "IV"};
  return names[int(t)];
}

bool parseTypes(const std::string& list, std::vector<OrbifoldType>& types)
{
  types.clear();
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ','))
  {
    if (item == "I") types.push_back(OrbifoldType::I);
    else if (item == "II") types.push_back(OrbifoldType::II);
    else if (item == "III") types.push_back(OrbifoldType::III);
    else if (item == "IV") types.push_back(OrbifoldType::IV);
    else return false;
  }
  return !types.empty();
}

bool parse(int argc, char** argv, Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&](const char* key) { return a.compare(0, std::strlen(key), key) == 0 ? a.substr(std::strlen(key)) : std::string(); };
    if (a == "--smoke")
    {
      o.smoke = true;
      o.icosphere = 3;
      o.cuts = 4;
    }
    else if (a == "--no-lu") o.lu = false;
    else if (!value("--mesh=").empty()) o.mesh = value("--mesh=");
    else if (!value("--icosphere=").empty()) o.icosphere = std::atoi(value("--icosphere=").c_str());
    else if (!value("--cuts=").empty()) o.cuts = std::atoi(value("--cuts=").c_str());
    else if (!value("--seed=").empty()) o.seed = unsigned(std::atoi(value("--seed=").c_str()));
    else if (!value("--threads=").empty()) o.threads = std::atoi(value("--threads=").c_str());
    else if (!value("--types=").empty())
    {
      if (!parseTypes(value("--types="), o.types)) return false;
    }
    else return false;
  }
  return o.cuts >= 1 && o.threads >= 1;
}

/** Random distinct cones, at least a few hops apart is not needed: the paths handle any choice. */
std::vector<int> randomCones(std::mt19937& rng, int n, int count)
{
  std::vector<int> cones;
  std::uniform_int_distribution<int> pick(0, n - 1);
  while (int(cones.size()) < count)
  {
    const int v = pick(rng);
    if (std::find(cones.begin(), cones.end(), v) == cones.end()) cones.push_back(v);
  }
  return cones;
}

/** The KKT matrix (eq. 20) of the exact cut Laplacian and the constraints B. */
SpMat kktMatrix(const Orbifold& orbifold)
{
  const SpMat L = Eigen::cotanLaplacian<double, int>(orbifold.cutVertices(), orbifold.cutFaces());
  const SpMat& B = orbifold.constraintMatrix();
  const Index N = L.rows(), m = B.rows();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(2 * L.nonZeros() + 2 * B.nonZeros()));
  for (Index j = 0; j < N; ++j)
    for (SpMat::InnerIterator it(L, j); it; ++it)
    {
      t.emplace_back(int(it.row()), int(j), it.value());
      t.emplace_back(int(it.row() + N), int(j + N), it.value());
    }
  for (Index j = 0; j < B.cols(); ++j)
    for (SpMat::InnerIterator it(B, j); it; ++it)
    {
      t.emplace_back(int(2 * N + it.row()), int(j), it.value());
      t.emplace_back(int(j), int(2 * N + it.row()), it.value());
    }
  SpMat K(2 * N + m, 2 * N + m);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  return K;
}

} // namespace

int main(int argc, char** argv)
{
  bench::ensureOpenBlasCore(argv);  // (may re-execute with OPENBLAS_CORETYPE: see BlasCore.h)
  Options o;
  if (!parse(argc, argv, o))
  {
    std::fprintf(stderr,
                 "usage: bench_orbifold [--mesh=PATH] [--icosphere=S] [--cuts=N] [--types=I,II,III,IV] [--seed=S] "
                 "[--threads=N] [--no-lu] [--smoke]\n");
    return 2;
  }
  Eigen::setNbThreads(o.threads);
  MatrixXd V;
  MatrixXi F;
  std::string meshName;
  if (o.icosphere >= 0)
  {
    Eigen::icosphereMesh(o.icosphere, V, F);
    meshName = "icosphere " + std::to_string(o.icosphere);
  }
  else
  {
    std::string error;
    if (!Eigen::readOFF(o.mesh, V, F, &error))
    {
      std::fprintf(stderr, "bench_orbifold: %s\n", error.c_str());
      return 2;
    }
    meshName = o.mesh.substr(o.mesh.find_last_of('/') + 1);
  }
  std::printf("bench_orbifold: %s, %ld vertices, %ld faces, %d cuts, threads %d, seed %u, factor updates %s\n",
              meshName.c_str(), long(V.rows()), long(F.rows()), o.cuts, o.threads, o.seed,
              Orbifold::supportsFactorUpdates ? "insertDofs/mergeDofs" : "unavailable (refactorization)");

  std::mt19937 rng(o.seed);
  Orbifold orbifold;
  orbifold.solver().setThreadCount(o.threads);
  auto conesFor = [&](OrbifoldType t) { return randomCones(rng, int(V.rows()), t == OrbifoldType::IV ? 4 : 3); };
  if (!orbifold.setup(V, F, conesFor(o.types[0]), o.types[0]) || !orbifold.compute())
  {
    std::fprintf(stderr, "bench_orbifold: %s\n", orbifold.error().c_str());
    return 2;
  }
  std::printf("initial cut and factorization (not timed below): %.1f ms\n\n",
              1e3 * (orbifold.lastStatistics().cutSeconds + orbifold.lastStatistics().editSeconds()));

  std::printf("%4s %4s %6s %6s | %9s %9s %9s %9s %7s | %9s %9s | %8s %9s\n", "cut", "type", "seam", "rows",
              "ours ms", "factor", "Schur", "solve", "updated", "LU ms", "fresh ms", "LU/ours", "error");
  bench::Samples ours, factor, schur, solve, lu, fresh, ratio;
  bool allGood = true;
  for (int c = 0; c < o.cuts; ++c)
  {
    const OrbifoldType type = o.types[std::size_t(c) % o.types.size()];
    if (!orbifold.setCones(conesFor(type), type))
    {
      std::printf("%4d %4s: %s\n", c, typeName(type), orbifold.error().c_str());
      allGood = false;
      continue;
    }
    const Orbifold::Statistics st = orbifold.lastStatistics();
    ours.add(1e3 * st.editSeconds());
    factor.add(1e3 * st.factorSeconds);
    schur.add(1e3 * st.schurSeconds);
    solve.add(1e3 * st.solveSeconds);

    // fresh: our solver from scratch on the same cut Laplacian (+ the same anchor weight)
    const SpMat L = Eigen::cotanLaplacian<double, int>(orbifold.cutVertices(), orbifold.cutFaces());
    SpMat K = L;
    K.coeffRef(orbifold.cones()[0], orbifold.cones()[0]) += L.diagonal().mean();
    double freshMs;
    {
      Orbifold::SolverType llt;
      llt.setThreadCount(o.threads);
      freshMs = bench::timeMs([&] { llt.compute(K); });
      if (llt.info() != Eigen::Success) allGood = false;
    }
    fresh.add(freshMs);

    double luMs = std::numeric_limits<double>::quiet_NaN(), error = std::numeric_limits<double>::quiet_NaN();
    if (o.lu)
    {
      const SpMat KKT = kktMatrix(orbifold);
      const Index N = L.rows(), m = orbifold.constraintMatrix().rows();
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * N + m), x;
      rhs.tail(m) = orbifold.constraintRhs();
      Eigen::SparseLU<SpMat> sparseLU;
      luMs = bench::timeMs([&] {
        sparseLU.analyzePattern(KKT);
        sparseLU.factorize(KKT);
        x = sparseLU.solve(rhs);
      });
      if (sparseLU.info() != Eigen::Success)
      {
        std::printf("SparseLU failed: %s\n", sparseLU.lastErrorMessage().c_str());
        allGood = false;
      }
      else
      {
        MatrixXd uvLU(N, 2);
        uvLU.col(0) = x.head(N);
        uvLU.col(1) = x.segment(N, N);
        error = (uvLU - orbifold.uv()).cwiseAbs().maxCoeff() / uvLU.cwiseAbs().maxCoeff();
        if (!(error <= 1e-8)) allGood = false;
      }
      lu.add(luMs);
      ratio.add(luMs / (1e3 * st.editSeconds()));
    }
    std::printf("%4d %4s %6ld %6ld | %9.1f %9.1f %9.1f %9.1f %7s | %9.1f %9.1f | %8.1f %9.1e\n", c, typeName(type),
                long(st.seamVertices), long(st.constraints), 1e3 * st.editSeconds(), 1e3 * st.factorSeconds,
                1e3 * st.schurSeconds, 1e3 * st.solveSeconds, st.factorUpdated ? "yes" : "no", luMs, freshMs,
                luMs / (1e3 * st.editSeconds()), error);
    std::fflush(stdout);
  }
  std::printf("\nmedians over %zu cuts: ours %.1f ms (factor update %.1f, Schur %.1f, solve %.1f), SparseLU on the KKT "
              "%.1f ms, fresh factorization %.1f ms\n",
              ours.size(), ours.median(), factor.median(), schur.median(), solve.median(), lu.median(), fresh.median());
  if (o.lu)
    std::printf("SparseLU / ours: %.1fx (ratio of medians), %.1fx (median of per-cut ratios, min %.1fx)\n",
                lu.median() / ours.median(), ratio.median(), ratio.min());
  std::printf("%s\n", allGood ? "all answers agree" : "FAILED: some answer disagreed or a solver failed");
  return allGood ? 0 : 1;
}
