// bench_remove_dofs: removing dofs (Dirichlet constraints along a seam), the paper's Fig. 6 (left).
// For each mesh it builds the cotan Laplacian + 1e-8 I, one METIS permutation shared by every
// solver, and for seams of l vertices (seamPath(), DESIGN §5) times, in the same run, an update
// followed by the Dirichlet solve A_II x_I = b_I - A_IB g, x_B = g, by
//   - ours: UpdatableSupernodalLLT::removeDofs + solveDirichlet, with the automatic route and with
//     every route forced (restoreDofs, timed apart, brings the factor back between seams);
//   - CHOLMOD numeric refactorization of A^B reusing the symbolic analysis of A, + solve;
//   - CHOLMOD analysis + factorization of the reduced A_II (same permutation restricted), + solve;
//   - cholmod_rowdel per dof on a simplicial LDL^T factor with the row patterns from
//     cholmod_row_lsubtree (conversion from the supernodal factor reported apart), + solve;
//   - the Schur complement of the factor of A (Yeung et al.; paper §3.5), computing only the rows of
//     L^{-1} P H_B on the etree reach of B (SchurPeer.h).
// Every solution is checked against ours (relative error <= 1e-8); ours is checked by its residual.
// Prints medians per l with ratios and flop fractions, one table per mesh; optionally writes CSV
// (plot it with plot_remove_dofs.sh). --smoke runs a tiny grid once, for CI.
//
// Usage: bench_remove_dofs [--mesh=PATH[,PATH...]]... [--grid=N] [--lengths=1,5,20,100,500,2000]
//                          [--seams=5] [--repeats=1] [--threads=1] [--seed=S] [--csv-dir=DIR] [--smoke]
// Exit code: 0 if every answer was right, 1 otherwise, 2 on bad usage.

#include <Eigen/UpdatableCholesky>

#include <iostream> // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <unsupported/Eigen/MeshTools>

#include "BlasCore.h"
#include "HeapPolicy.h"
#include "BenchReport.h"
#include "SeamBenchOptions.h"
#include "CholmodPeer.h"
#include "FixedOrdering.h"
#include "RowdelPeer.h"
#include "SchurPeer.h"
#include "Timing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

// OpenBLAS's thread control; weak, so the benchmark still links against another BLAS.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

#ifndef UC_BENCH_DEFAULT_MESHES
#define UC_BENCH_DEFAULT_MESHES "bunny.off.gz"
#endif

namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Ordering = bench::FixedOrdering<int>;
using Permutation = Ordering::PermutationType;
using OursLLT = Eigen::UpdatableSupernodalLLT<SpMat, Eigen::Lower, Ordering>;
using Eigen::UpdateRoute;
using bench::csvNumber;
using bench::dirichletBackwardError;
using bench::fmt;
using bench::fmtCount;
using bench::fmtFraction;
using bench::fmtMs;
using bench::fmtRatio;
using bench::infinityNorm;
using bench::meshStem;
using bench::parseInt;

/** Diagonal shift that makes the (singular) cotan Laplacian positive definite. */
constexpr double kShift = 1e-8;
/** Largest accepted relative difference ||x - x_ours||_inf / ||x_ours||_inf of a peer's solution. */
constexpr double kRelativeTolerance = 1e-8;
/** Largest accepted backward error of our Dirichlet solve (the reference). */
constexpr double kBackwardTolerance = 1e-10;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/** UpdateRoute::LowRank when the library has it (it is being added), detected at compile time. */
template <typename E, typename = void>
struct LowRankRoute
{
  static constexpr bool available = false;
  static E value() { return E::Automatic; }
};
template <typename E>
struct LowRankRoute<E, std::void_t<decltype(E::LowRank)>>
{
  static constexpr bool available = true;
  static E value() { return E::LowRank; }
};
using LowRank = LowRankRoute<UpdateRoute>;

/** \returns a short name of an update route. */
std::string routeName(UpdateRoute route)
{
  if (LowRank::available && route == LowRank::value()) return "LowRank";
  switch (route)
  {
  case UpdateRoute::Automatic: return "Automatic";
  case UpdateRoute::PartialRefactorization: return "Partial";
  case UpdateRoute::Refactorization: return "Refactor";
  case UpdateRoute::Mixed: return "Mixed";
  default: return "route" + std::to_string(int(route));
  }
}

// ---- methods ------------------------------------------------------------------------------------

enum class Kind { Ours, CholmodRefactor, CholmodReduced, Rowdel, Schur };

/** One timed way of removing the dofs of a seam and solving the Dirichlet system. */
struct Method
{
  std::string key;    ///< CSV name
  std::string label;  ///< table heading
  Kind kind;
  UpdateRoute route;  ///< ours only
};

/** \returns the methods of this build: ours with every route (LowRank if the library has it), then the peers. */
std::vector<Method> allMethods()
{
  std::vector<Method> m;
  m.push_back({"ours_auto", "ours auto", Kind::Ours, UpdateRoute::Automatic});
  m.push_back({"ours_partial", "partial", Kind::Ours, UpdateRoute::PartialRefactorization});
  m.push_back({"ours_refactor", "refactor", Kind::Ours, UpdateRoute::Refactorization});
  if (LowRank::available) m.push_back({"ours_lowrank", "lowrank", Kind::Ours, LowRank::value()});
  m.push_back({"ours_mixed", "mixed", Kind::Ours, UpdateRoute::Mixed});
  m.push_back({"cholmod_refactor", "CHM refac", Kind::CholmodRefactor, UpdateRoute::Automatic});
  m.push_back({"cholmod_reduced", "CHM A_II", Kind::CholmodReduced, UpdateRoute::Automatic});
  m.push_back({"cholmod_rowdel", "rowdel", Kind::Rowdel, UpdateRoute::Automatic});
  m.push_back({"schur", "Schur", Kind::Schur, UpdateRoute::Automatic});
  return m;
}

/** What one method did on one seam. */
struct Sample
{
  double ms = kNaN;            ///< update + Dirichlet solve
  double flopFraction = kNaN;  ///< update flops / full factorization flops (each method's own count)
  double extraMs = kNaN;       ///< ours: restoreDofs afterwards; A_II: extracting A_II; others: -
  double updateMs = kNaN;      ///< ours: the update alone (lastUpdate().seconds), the rest is the solve
  double error = kNaN;         ///< relative difference to ours (ours auto: backward error)
  std::string route;           ///< ours: the route taken
  long dirty = -1;             ///< ours: dirty supernodes; Schur: supernodes on the reach
  double forwardFraction = kNaN;  ///< ours: columns its solve substituted forward / n (setSolveCaching())
  bool ok = true;
  std::string message;
  Eigen::VectorXd x;
};

/** The medians of one method at one l. */
struct Summary
{
  bench::Samples ms, flops, extra, dirty, update, forward;
  std::map<std::string, int> routes;
  double worstError = 0;
  bool ok = true;
  std::string message;

  void add(const Sample& s)
  {
    ms.add(s.ms);
    if (!std::isnan(s.flopFraction)) flops.add(s.flopFraction);
    if (!std::isnan(s.extraMs)) extra.add(s.extraMs);
    if (!std::isnan(s.updateMs)) update.add(s.updateMs);
    if (s.dirty >= 0) dirty.add(double(s.dirty));
    if (!std::isnan(s.forwardFraction)) forward.add(s.forwardFraction);
    if (!s.route.empty()) ++routes[s.route];
    if (!std::isnan(s.error)) worstError = std::max(worstError, s.error);
    if (!s.ok && ok)
    {
      ok = false;
      message = s.message;
    }
  }
  /** \returns the routes taken, e.g. "LowRank" or "Partial 2/LowRank 1". */
  std::string routeText() const
  {
    std::string text;
    for (const auto& r : routes)
    {
      if (!text.empty()) text += '/';
      text += r.first;
      if (routes.size() > 1) text += ' ' + std::to_string(r.second);
    }
    return text;
  }
};

// ---- the Dirichlet system -----------------------------------------------------------------------

/** \returns b_I - A_IB g_B on I and g_B on B, in the original numbering (A stores both triangles).
  * Touches only the columns of B besides copying b. */
Eigen::VectorXd dirichletRhs(const SpMat& A, const std::vector<char>& inB, const std::vector<int>& seam,
                             const Eigen::VectorXd& b, const Eigen::VectorXd& g)
{
  Eigen::VectorXd rhs = b;
  for (int j : seam)
    for (SpMat::InnerIterator it(A, j); it; ++it)
      if (!inB[std::size_t(it.row())]) rhs[it.row()] -= it.value() * g[j];
  for (int j : seam) rhs[j] = g[j];
  return rhs;
}

/** Turns the values of \a AB (same pattern as A, both triangles stored) into those of A^B: rows
  * and columns of B zero, unit diagonal. Touches only the entries of the rows and columns of B. */
void makeDirichletMatrix(SpMat& AB, const std::vector<int>& seam)
{
  const int* outer = AB.outerIndexPtr();
  const int* inner = AB.innerIndexPtr();
  double* values = AB.valuePtr();
  for (int j : seam)
    for (int p = outer[j]; p < outer[j + 1]; ++p)
    {
      const int i = inner[p];
      if (i == j)
      {
        values[p] = 1.0;
        continue;
      }
      values[p] = 0.0; // A(i, j)
      const int* first = inner + outer[i];
      const int* last = inner + outer[i + 1];
      values[std::lower_bound(first, last, j) - inner] = 0.0; // A(j, i), in column i
    }
}

/** The reduced matrix A_II (lower triangle) with the permutation restricted to I. */
struct ReducedSystem
{
  SpMat lower;
  std::vector<int> perm;      ///< perm[k] = reduced index at position k (Eigen's Pinv convention)
  std::vector<int> reduced;   ///< original -> reduced index, -1 on B
  std::vector<int> original;  ///< reduced -> original index
};

/** Extracts A_II (lower triangle) and the restricted permutation; O(nnz(A) + n). */
void extractReduced(const SpMat& A, const Permutation& perm, const std::vector<char>& inB, ReducedSystem& r)
{
  const int n = int(A.rows());
  r.reduced.assign(std::size_t(n), -1);
  r.original.clear();
  for (int i = 0; i < n; ++i)
    if (!inB[std::size_t(i)])
    {
      r.reduced[std::size_t(i)] = int(r.original.size());
      r.original.push_back(i);
    }
  const int m = int(r.original.size());
  std::vector<int> outer(std::size_t(m) + 1, 0), inner;
  std::vector<double> values;
  inner.reserve(std::size_t(A.nonZeros() / 2 + n));
  values.reserve(inner.capacity());
  for (int jr = 0; jr < m; ++jr)
  {
    const int j = r.original[std::size_t(jr)];
    for (SpMat::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j && !inB[std::size_t(it.row())])
      {
        inner.push_back(r.reduced[std::size_t(it.row())]);
        values.push_back(it.value());
      }
    outer[std::size_t(jr) + 1] = int(inner.size());
  }
  r.lower = Eigen::Map<const SpMat>(m, m, Eigen::Index(inner.size()), outer.data(), inner.data(), values.data());
  r.perm.clear();
  r.perm.reserve(std::size_t(m));
  for (Eigen::Index k = 0; k < perm.size(); ++k)
  {
    const int i = perm.indices()[k];
    if (!inB[std::size_t(i)]) r.perm.push_back(r.reduced[std::size_t(i)]);
  }
}

// ---- command line -------------------------------------------------------------------------------

using Options = bench::SeamBenchOptions;

/** This benchmark's names on the shared command line (SeamBenchOptions.h). */
const bench::SeamBenchNames kNames{"bench_remove_dofs", "remove_dofs", "bench/plot_remove_dofs.sh", UC_BENCH_DEFAULT_MESHES};

// ---- one mesh -----------------------------------------------------------------------------------

/** Everything of one mesh that the seams share: matrix, ordering, the factored solvers. */
class MeshBench
{
public:
  MeshBench(const Options& options, const std::string& name, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F)
      : m_options(options), m_name(name), m_F(F), m_methods(allMethods())
  {
    m_n = int(V.rows());
    m_A = Eigen::cotanLaplacian<double, int>(V, F);
    SpMat shift(m_A.rows(), m_A.cols());
    shift.setIdentity();
    m_A += kShift * shift;
    m_A.makeCompressed();
    m_AB = m_A;
    m_normA = infinityNorm(m_A);
    m_inB.assign(std::size_t(m_n), 0);
    m_setup["vertices"] = double(m_n);
    m_setup["faces"] = double(F.rows());
    m_setup["nnz_A"] = double(m_A.nonZeros());
    m_setup["threads"] = double(options.threads);

    m_setup["metis_ms"] = bench::timeMs([&] { Eigen::MetisOrdering<int>()(m_A, m_perm); });

    m_ours.ordering().permutation = &m_perm;
    m_ours.setThreadCount(options.threads);
    m_ours.setUpdateCaching(true);
    m_setup["ours_compute_ms"] = bench::timeMs([&] { m_ours.compute(m_A); });
    if (m_ours.info() != Eigen::Success) throw std::runtime_error("ours: compute() failed");
    m_setup["ours_factorization_flops"] = m_ours.factorizationFlops();
    m_setup["ours_nnz_L"] = double(m_ours.nonZerosL());
    m_setup["ours_supernodes"] = double(m_ours.supernodeCount());

    m_setup["cholmod_analyze_ms"] = bench::timeMs([&] { m_refactor.analyze(m_A, m_perm.indices().data()); });
    bool positive = false;
    m_setup["cholmod_factorize_ms"] = bench::timeMs([&] { positive = m_refactor.factorize(m_A); });
    if (!positive) throw std::runtime_error("CHOLMOD: factorize failed");
    m_setup["cholmod_fl"] = m_refactor.flops();
    m_base.analyze(m_A, m_perm.indices().data());
    if (!m_base.factorize(m_A)) throw std::runtime_error("CHOLMOD: factorize failed");
    m_schur.reset(new bench::SchurComplementDirichlet(m_base));
    m_setup["schur_layout_factorization_flops"] = m_schur->factorizationFlops();
    m_rowdel.reset(new bench::CholmodRowdel(m_base, m_A));
    m_setup["rowdel_conversion_ms"] = m_rowdel->conversionMs();

    std::mt19937 generator(options.seed ^ 0x5eedu);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    m_b.resize(m_n);
    m_g.resize(m_n);
    for (int i = 0; i < m_n; ++i) m_b[i] = uniform(generator);
    for (int i = 0; i < m_n; ++i) m_g[i] = uniform(generator);

    // Plain solves with one right-hand side, the floor of every method's time (median of 5).
    bench::Samples oursSolve, oursRepeat, cholmodSolve, simplicialSolve;
    m_rowdel->reset();
    for (int rep = 0; rep < 5; ++rep)
    {
      Eigen::VectorXd x;
      bench::timeFullAndRepeatedSolve(m_ours, m_b, oursSolve, oursRepeat);
      bench::evictCaches();
      cholmodSolve.add(bench::timeMs([&] { x = m_base.solve(m_b); }));
      bench::evictCaches();
      simplicialSolve.add(bench::timeMs([&] { x = m_rowdel->solve(m_b); }));
    }
    m_setup["ours_solve_ms"] = oursSolve.median();
    m_setup["ours_repeated_solve_ms"] = oursRepeat.median();
    m_setup["cholmod_solve_ms"] = cholmodSolve.median();
    m_setup["cholmod_simplicial_ldlt_solve_ms"] = simplicialSolve.median();
  }

  /** Runs every length and prints the tables. \returns false if some answer was wrong. */
  bool run()
  {
    printHeader();
    openCsv();
    bool ok = true;
    // Warm-up: one untimed run of every method (first-touch costs, BLAS buffers, caches).
    {
      const std::vector<int> seam = Eigen::seamPath(m_F, m_n, m_options.lengths.front(), m_options.seed + 7u);
      if (!seam.empty())
      {
        std::vector<Sample> samples = runSeam(seam, 0);
        ok = check(seam, samples) && ok;
      }
    }
    for (int l : m_options.lengths)
    {
      std::vector<Summary> summary(m_methods.size());
      bench::Samples seamVertices, pieceCounts;
      int done = 0;
      for (int s = 0; s < m_options.seams; ++s)
      {
        int pieces = 0;
        const unsigned seed = m_options.seed + 1000003u * unsigned(l) + 7919u * unsigned(s);
        const std::vector<int> seam = Eigen::seamPath(m_F, m_n, l, seed, &pieces);
        if (seam.empty()) break;
        std::vector<Sample> samples = runSeam(seam, 131 * l + s);
        ok = check(seam, samples) && ok;
        for (std::size_t k = 0; k < m_methods.size(); ++k) summary[k].add(samples[k]);
        seamVertices.add(double(seam.size()));
        pieceCounts.add(double(pieces));
        writeSamples(l, s, seam, pieces, samples);
        ++done;
      }
      if (done == 0)
      {
        std::printf("  l = %d: no seam of that many vertices on this mesh, skipped\n", l);
        continue;
      }
      m_rows.push_back({l, done, pieceCounts.max(), summary});
      writeSummary(l, done, seamVertices.median(), pieceCounts.max(), summary);
    }
    printTables();
    return ok;
  }

private:
  struct Row
  {
    int l, seams;
    double pieces;
    std::vector<Summary> summary;
  };

  /** Runs every method on one seam, in random orders drawn from \a seed (see interleavedMedianRuns). */
  std::vector<Sample> runSeam(const std::vector<int>& seam, int seed)
  {
    for (int j : seam) m_inB[std::size_t(j)] = 1;
    std::vector<Sample> samples = bench::interleavedMedianRuns<Sample>(
        m_methods.size(), m_options.repeats, seed, [&](std::size_t k) { return runMethod(m_methods[k], seam); });
    for (int j : seam) m_inB[std::size_t(j)] = 0;
    return samples;
  }

  Sample runMethod(const Method& method, const std::vector<int>& seam)
  {
    Sample s;
    switch (method.kind)
    {
    case Kind::Ours:
    {
      m_ours.setUpdateRoute(method.route);
      Eigen::MatrixXd x;
      bench::Stopwatch watch;
      m_ours.removeDofs(seam);
      const bool removed = m_ours.info() == Eigen::Success;
      if (removed) x = m_ours.solveDirichlet(m_b, m_g);
      s.ms = watch.ms();
      if (!removed) throw std::runtime_error("removeDofs: info() = " + std::to_string(int(m_ours.info())));
      const Eigen::UpdateStatistics st = m_ours.lastUpdate();
      s.flopFraction = st.flopFraction;
      s.updateMs = st.seconds * 1e3;
      s.route = routeName(st.route);
      s.dirty = long(st.dirtySupernodes);
      s.forwardFraction = double(m_ours.lastSolveForwardColumns()) / double(m_n);
      s.x = x.col(0);
      m_ours.setUpdateRoute(UpdateRoute::Automatic);
      s.extraMs = bench::timeMs([&] { m_ours.restoreDofs(seam); });
      if (m_ours.info() != Eigen::Success) throw std::runtime_error("restoreDofs: info() = " + std::to_string(int(m_ours.info())));
      if (!m_ours.removedDofs().empty()) throw std::runtime_error("restoreDofs left removed dofs behind");
      break;
    }
    case Kind::CholmodRefactor:
    {
      bool positive = false;
      bench::Stopwatch watch;
      makeDirichletMatrix(m_AB, seam);
      positive = m_refactor.factorize(m_AB);
      if (positive) s.x = m_refactor.solve(dirichletRhs(m_A, m_inB, seam, m_b, m_g));
      s.ms = watch.ms();
      std::copy(m_A.valuePtr(), m_A.valuePtr() + m_A.nonZeros(), m_AB.valuePtr());
      if (!positive) throw std::runtime_error("cholmod_factorize of A^B failed");
      s.flopFraction = 1.0;
      break;
    }
    case Kind::CholmodReduced:
    {
      ReducedSystem r;
      s.extraMs = bench::timeMs([&] { extractReduced(m_A, m_perm, m_inB, r); });
      bench::CholmodSupernodal chol;
      Eigen::VectorXd xr;
      bench::Stopwatch watch;
      chol.analyze(r.lower, r.perm.data());
      const bool positive = chol.factorize(r.lower);
      if (positive)
      {
        const Eigen::VectorXd rhs = dirichletRhs(m_A, m_inB, seam, m_b, m_g);
        Eigen::VectorXd rhsReduced(Eigen::Index(r.original.size()));
        for (std::size_t i = 0; i < r.original.size(); ++i) rhsReduced[Eigen::Index(i)] = rhs[r.original[i]];
        xr = chol.solve(rhsReduced);
      }
      s.ms = watch.ms();
      if (!positive) throw std::runtime_error("cholmod_factorize of A_II failed");
      s.x = m_g;
      for (std::size_t i = 0; i < r.original.size(); ++i) s.x[r.original[i]] = xr[Eigen::Index(i)];
      s.flopFraction = chol.flops() / m_refactor.flops();
      break;
    }
    case Kind::Rowdel:
    {
      m_rowdel->reset();
      bench::Stopwatch watch;
      m_rowdel->removeDofs(seam);
      s.x = m_rowdel->solve(dirichletRhs(m_A, m_inB, seam, m_b, m_g));
      s.ms = watch.ms();
      s.flopFraction = m_rowdel->updateFlops() / m_refactor.flops();
      break;
    }
    case Kind::Schur:
    {
      bench::Stopwatch watch;
      s.x = m_schur->solve(seam, m_b, m_g);
      s.ms = watch.ms();
      s.flopFraction = m_schur->updateFlops() / m_schur->factorizationFlops();
      s.dirty = m_schur->reachSupernodes();
      break;
    }
    }
    return s;
  }

  /** Checks every solution: ours auto by its backward error, the others against ours auto. */
  bool check(const std::vector<int>& seam, std::vector<Sample>& samples)
  {
    for (int j : seam) m_inB[std::size_t(j)] = 1;
    bool ok = true;
    Sample& ref = samples[0];
    if (ref.ok)
    {
      ref.error = dirichletBackwardError(m_A, m_normA, m_inB, seam, ref.x, m_b, m_g);
      if (!(ref.error <= kBackwardTolerance))
      {
        ref.ok = false;
        ref.message = "backward error of the Dirichlet solve " + std::to_string(ref.error) + " (seam of " +
                      std::to_string(seam.size()) + ")";
      }
    }
    const double refNorm = ref.ok ? ref.x.lpNorm<Eigen::Infinity>() : kNaN;
    for (std::size_t k = 1; k < samples.size(); ++k)
    {
      Sample& s = samples[k];
      if (!s.ok || !ref.ok) continue;
      s.error = (s.x - ref.x).lpNorm<Eigen::Infinity>() / refNorm;
      if (!(s.error <= kRelativeTolerance))
      {
        s.ok = false;
        char buffer[160];
        std::snprintf(buffer, sizeof(buffer), "relative difference to ours %.2e > %.0e (seam of %zu)", s.error,
                      kRelativeTolerance, seam.size());
        s.message = buffer;
      }
    }
    for (std::size_t k = 0; k < samples.size(); ++k)
    {
      if (!samples[k].ok)
      {
        std::printf("  FAILED %s: %s\n", m_methods[k].key.c_str(), samples[k].message.c_str());
        ok = false;
      }
      samples[k].x.resize(0);
    }
    for (int j : seam) m_inB[std::size_t(j)] = 0;
    return ok;
  }

  void printHeader() const
  {
    auto get = [&](const char* key) { return m_setup.at(key); };
    std::printf("\n=== %s: %s vertices, %s triangles, nnz(A) = %s; threads = %d\n", m_name.c_str(),
                fmtCount(get("vertices")).c_str(), fmtCount(get("faces")).c_str(), fmtCount(get("nnz_A")).c_str(),
                m_options.threads);
    std::printf("  setup: METIS %s ms; ours compute (analyze+factorize, update caching on) %s ms, %s supernodes;\n"
                "         CHOLMOD analyze %s ms + factorize %s ms; rowdel: supernodal LL' -> simplicial LDL' "
                "conversion (with copy) %s ms\n"
                "         one solve, 1 rhs (median of 5, cold caches): ours %s ms (the same b again, forward substitution kept: %s ms),\n"
                "         CHOLMOD supernodal %s ms, CHOLMOD simplicial "
                "LDL' (rowdel's) %s ms\n",
                fmtMs(get("metis_ms")).c_str(), fmtMs(get("ours_compute_ms")).c_str(),
                fmtCount(get("ours_supernodes")).c_str(), fmtMs(get("cholmod_analyze_ms")).c_str(),
                fmtMs(get("cholmod_factorize_ms")).c_str(), fmtMs(get("rowdel_conversion_ms")).c_str(),
                fmtMs(get("ours_solve_ms")).c_str(), fmtMs(get("ours_repeated_solve_ms")).c_str(),
                fmtMs(get("cholmod_solve_ms")).c_str(),
                fmtMs(get("cholmod_simplicial_ldlt_solve_ms")).c_str());
    std::printf("  low-rank route: %s\n", LowRank::available ? "in this build (UpdateRoute::LowRank)"
                                                             : "not in this build's UpdateRoute");
  }

  void printTables() const
  {
    const std::size_t count = m_methods.size();
    std::printf("\n  %s, update + Dirichlet solve [ms], medians over the seams of each l (seeds fixed)\n", m_name.c_str());
    std::printf("  %5s %4s %3s |", "l", "#", "pcs");
    for (std::size_t k = 0; k < count; ++k)
    {
      std::printf(" %10s", m_methods[k].label.c_str());
      if (k == 0) std::printf(" %8s %-14s", "(update)", "route");
    }
    std::printf(" | %8s\n", "restore");
    for (const Row& row : m_rows)
    {
      std::printf("  %5d %4d %3s |", row.l, row.seams, fmt(row.pieces, 0).c_str());
      for (std::size_t k = 0; k < count; ++k)
      {
        std::printf(" %10s", fmtMs(row.summary[k].ms.median()).c_str());
        if (k == 0)
          std::printf(" %8s %-14s", ("(" + fmtMs(row.summary[0].update.median()) + ")").c_str(),
                      row.summary[0].routeText().c_str());
      }
      std::printf(" | %8s\n", fmtMs(row.summary[0].extra.median()).c_str());
    }

    // ratios and flop fractions
    std::vector<std::size_t> forced, peers;
    for (std::size_t k = 1; k < count; ++k) (m_methods[k].kind == Kind::Ours ? forced : peers).push_back(k);
    std::printf("\n  %s, ratios of medians (ours auto / other; < 1: ours is faster) and flop fractions\n", m_name.c_str());
    std::printf("  %5s | %10s %9s |", "l", "best forced", "auto/best");
    for (std::size_t k : peers) std::printf(" %10s", ("/" + m_methods[k].label).c_str());
    std::printf(" | flops:");
    for (std::size_t k = 0; k < count; ++k) std::printf(" %9s", m_methods[k].label.c_str());
    std::printf(" | %6s %6s\n", "dirty", "fwd");
    for (const Row& row : m_rows)
    {
      const double ours = row.summary[0].ms.median();
      double best = kNaN;
      std::string bestName = "-";
      for (std::size_t k : forced)
      {
        const double v = row.summary[k].ms.median();
        if (!std::isnan(v) && (std::isnan(best) || v < best))
        {
          best = v;
          bestName = m_methods[k].label;
        }
      }
      std::printf("  %5d | %10s %9s |", row.l, bestName.c_str(), fmtRatio(ours, best).c_str());
      for (std::size_t k : peers) std::printf(" %10s", fmtRatio(ours, row.summary[k].ms.median()).c_str());
      std::printf(" |       ");
      for (std::size_t k = 0; k < count; ++k) std::printf(" %9s", fmtFraction(row.summary[k].flops.median()).c_str());
      std::printf(" | %6s %6s\n", fmtCount(row.summary[0].dirty.median()).c_str(),
                  fmtFraction(row.summary[0].forward.median()).c_str());
    }
    double worst = 0;
    std::string worstName;
    for (const Row& row : m_rows)
      for (std::size_t k = 1; k < count; ++k)
        if (row.summary[k].worstError > worst)
        {
          worst = row.summary[k].worstError;
          worstName = m_methods[k].key;
        }
    std::printf("  largest relative difference to ours: %.1e (%s); tolerance %.0e\n", worst,
                worstName.empty() ? "-" : worstName.c_str(), kRelativeTolerance);
    std::printf("  columns: # seams, pcs = most pieces a seam was split into (1: one shortest path); restore = "
                "restoreDofs after ours auto (not in the update time);\n"
                "  (update) = ours auto's update alone (lastUpdate().seconds), the rest of its time is solveDirichlet;\n"
                "  flops = update flops / full factorization flops, each by its own count (ours lastUpdate().flopFraction; "
                "CHOLMOD refactorization 1; A_II and rowdel: Common.fl of A_II / Common.modfl over Common.fl of A;\n"
                "  Schur: dense flops of W, S and its factorization over a full factorization on CHOLMOD's layout); "
                "dirty = ours auto lastUpdate().dirtySupernodes;\n"
                "  fwd = columns of L ours auto's solve substituted forward / n: the solve keeps its forward substitution "
                "(setSolveCaching()) and redoes it only above what changed; its backward pass is always whole.\n");
  }

  void openCsv()
  {
    if (m_options.csvDir.empty()) return;
    std::filesystem::create_directories(m_options.csvDir);
    const std::string base = m_options.csvDir + "/remove_dofs_" + meshStem(m_name);
    std::ofstream setup(base + "_setup.csv");
    setup.precision(10);
    setup << "mesh,key,value\n";
    for (const auto& kv : m_setup) setup << m_name << ',' << kv.first << ',' << kv.second << '\n';
    setup << m_name << ",lowrank_available," << (LowRank::available ? 1 : 0) << '\n';
    m_samplesCsv.open(base + "_samples.csv");
    m_samplesCsv.precision(10);
    m_samplesCsv << "mesh,vertices,l,seam,seam_vertices,pieces,method,ms,flop_fraction,route,dirty_supernodes,"
                    "extra_ms,update_ms,error,forward_fraction,ok\n";
    m_summaryCsv.open(base + ".csv");
    m_summaryCsv.precision(10);
    m_summaryCsv << "l,seams,seam_vertices,pieces";
    for (const Method& m : m_methods)
      m_summaryCsv << ',' << m.key << "_ms," << m.key << "_min_ms," << m.key << "_max_ms," << m.key << "_flop_fraction";
    m_summaryCsv << ",ours_auto_route,ours_restore_ms,ours_auto_update_ms" << std::endl;
    if (!m_samplesCsv || !m_summaryCsv || !setup) throw std::runtime_error("cannot write CSV files in " + m_options.csvDir);
  }

  void writeSamples(int l, int seam, const std::vector<int>& vertices, int pieces, const std::vector<Sample>& samples)
  {
    if (!m_samplesCsv.is_open()) return;
    for (std::size_t k = 0; k < samples.size(); ++k)
    {
      const Sample& s = samples[k];
      m_samplesCsv << m_name << ',' << m_n << ',' << l << ',' << seam << ',' << vertices.size() << ',' << pieces << ','
                   << m_methods[k].key << ',' << csvNumber(s.ms) << ',' << csvNumber(s.flopFraction) << ',' << s.route
                   << ',' << s.dirty << ',' << csvNumber(s.extraMs) << ',' << csvNumber(s.updateMs) << ','
                   << csvNumber(s.error) << ',' << csvNumber(s.forwardFraction) << ','
                   << (s.ok ? 1 : 0) << '\n';
    }
  }

  void writeSummary(int l, int seams, double seamVertices, double pieces, const std::vector<Summary>& summary)
  {
    if (!m_summaryCsv.is_open()) return;
    m_summaryCsv << l << ',' << seams << ',' << csvNumber(seamVertices) << ',' << csvNumber(pieces);
    for (const Summary& s : summary)
      m_summaryCsv << ',' << csvNumber(s.ms.median()) << ',' << csvNumber(s.ms.min()) << ',' << csvNumber(s.ms.max()) << ','
                   << csvNumber(s.flops.median());
    std::string route = summary[0].routeText();
    std::replace(route.begin(), route.end(), ' ', ':');
    m_summaryCsv << ',' << route << ',' << csvNumber(summary[0].extra.median()) << ','
                 << csvNumber(summary[0].update.median()) << '\n';
    m_summaryCsv.flush();
  }

  const Options& m_options;
  std::string m_name;
  Eigen::MatrixXi m_F;
  std::vector<Method> m_methods;
  int m_n = 0;
  SpMat m_A, m_AB;
  double m_normA = 0;
  Permutation m_perm;
  OursLLT m_ours;
  bench::CholmodSupernodal m_refactor, m_base;
  std::unique_ptr<bench::SchurComplementDirichlet> m_schur;
  std::unique_ptr<bench::CholmodRowdel> m_rowdel;
  Eigen::VectorXd m_b, m_g;
  std::vector<char> m_inB;
  std::map<std::string, double> m_setup;
  std::vector<Row> m_rows;
  std::ofstream m_samplesCsv, m_summaryCsv;
};

} // namespace

/** Entry point: see the usage text at the top of this file. */
int main(int argc, char** argv)
{
  bench::useHugePagesForHeap(argv);  // (may re-execute with GLIBC_TUNABLES: see HeapPolicy.h)
  bench::ensureOpenBlasCore(argv);  // (may re-execute with OPENBLAS_CORETYPE: see BlasCore.h)
  const bool heapRetained = bench::retainFreedMemory();  // (every method alike: see HeapPolicy.h)
  Options options;
  if (!bench::parseSeamBenchOptions(argc, argv, kNames, options)) return 2;
  if (options.oursOnly || options.diagonalShift)
  {
    std::fprintf(stderr, "bench_remove_dofs: --%s is an option of bench_insert_dofs only\n",
                 options.oursOnly ? "ours-only" : "diagonal-shift");
    return 2;
  }
  if (openblas_set_num_threads) openblas_set_num_threads(options.threads);

  std::printf("bench_remove_dofs: %s\n", options.smoke ? "SMOKE run (tiny grid, l = 1,5, one seam)"
                                                      : "removing dofs along seams (paper Fig. 6)");
  std::printf("  matrix cotan Laplacian + %.0e I; one METIS ordering per mesh given to every solver; seams: "
              "Eigen::seamPath, %d per l, base seed %u; %d run(s) of every method per seam, their median counts\n",
              kShift, options.seams, options.seed, options.repeats);
  std::printf("  every time is update + Dirichlet solve (A_II x_I = b_I - A_IB g, x_B = g; b, g uniform in [-1,1]), "
              "methods interleaved per seam (a random order each round) after one warm-up seam\n");
  std::printf("  compiled for %s (ours, Eigen); %s\n", bench::compiledInstructionSet(),
              bench::openBlasCoreNote().c_str());
  std::printf("  %s\n", bench::heapPolicyNote(heapRetained).c_str());

  const bool allOk = bench::forEachMesh("bench_remove_dofs", options.grid, options.meshes,
                                         [&](const std::string& name, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
                                           MeshBench bench(options, name, V, F);
                                           return bench.run();
                                         });
  if (!options.csvDir.empty()) std::printf("\nCSV written to %s (plot: bench/plot_remove_dofs.sh %s)\n", options.csvDir.c_str(), options.csvDir.c_str());
  std::printf("%s\n", allOk ? "result: all answers agree" : "result: FAILURE (see FAILED lines above)");
  return allOk ? 0 : 1;
}
