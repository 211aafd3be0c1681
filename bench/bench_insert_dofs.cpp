// bench_insert_dofs: adding dofs by cutting a mesh along a seam, the paper's Fig. 6 for insertion.
// For each mesh it builds the cotan Laplacian + 1e-8 I (--diagonal-shift: + 1e-8 diag(L), with which a
// cut glues back exactly) and one METIS permutation shared by every
// solver; for seams of l vertices (seamPath(), DESIGN §5) it cuts the mesh along every piece of the
// seam (cutMesh: interior seam vertices get a copy), builds the cut Laplacian Acut ((n+m)^2) and
// times, in the same run and interleaved per seam, an update followed by one solve with Acut:
//   - ours insert: UpdatableSupernodalLLT::insertDofs(Acut, origin, K) + solve, with K the changed
//     old dofs that rowadd and Woodbury get too (mergeDofs(A, origin, K), timed apart, brings the
//     factor back so that every seam starts from the same one);
//   - ours remove: removeDofs(seam) + solveDirichlet on the uncut factor, the same seam (then
//     restoreDofs): the issue asks for insertDofs <= 1.5x removeDofs;
//   - CHOLMOD analysis + factorization of Acut (permutation: the uncut one with each copy right after
//     its origin, as ours) + solve;
//   - cholmod_rowdel/cholmod_rowadd on a simplicial LDL^T factor of the uncut matrix with identity
//     placeholders for the new dofs (built per seam, untimed; RowaddPeer.h) + solve;
//   - Sherman-Morrison-Woodbury on blkdiag(A, I_m) with the factor of A (Yeung et al.; paper §3.5;
//     WoodburyPeer.h) + solve.
// Ours insert is checked by its backward error, ours remove by that of its Dirichlet system, every
// other solution against ours insert (relative difference <= 1e-8, or else its own backward error
// <= 1e-10: the cut system is ill-conditioned, so two right answers may differ). Prints medians per l with
// ratios and flop fractions; optionally writes CSV (plot it with plot_insert_dofs.sh). --smoke runs
// a tiny grid once, for CI.
//
// Usage: bench_insert_dofs [--mesh=PATH[,PATH...]]... [--grid=N] [--lengths=1,5,20,100,500,2000]
//                          [--seams=5] [--repeats=1] [--threads=1] [--seed=S] [--csv-dir=DIR] [--ours-only]
//                          [--diagonal-shift] [--smoke]
// (--ours-only: insertDofs and removeDofs alone, for many repeats of their ratio on a large mesh.)
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
#include "RowaddPeer.h"
#include "SchurPeer.h"
#include "Timing.h"
#include "WoodburyPeer.h"

#include <algorithm>
#include <array>
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
using bench::csvNumber;
using bench::routeName;
using bench::fmt;
using bench::fmtCount;
using bench::fmtFraction;
using bench::fmtMs;
using bench::fmtRatio;
using bench::meshStem;
using bench::parseInt;

/** Diagonal shift that makes the (singular) cotan Laplacian positive definite. */
constexpr double kShift = 1e-8;
/** Largest accepted relative difference ||x - x_ours||_inf / ||x_ours||_inf of a peer's solution. */
constexpr double kRelativeTolerance = 1e-8;
/** Largest accepted backward error of our solves (the references). */
constexpr double kBackwardTolerance = 1e-10;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/** \returns Laplacian + kShift I of a mesh (with \a byDiagonal: + kShift diag(Laplacian), which a
  * cut shares out between an origin and its copies as it does the Laplacian), both triangles
  * stored, compressed. */
SpMat shiftedLaplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, bool byDiagonal)
{
  SpMat A = Eigen::cotanLaplacian<double, int>(V, F);
  SpMat shift(A.rows(), A.cols());
  shift.setIdentity();
  if (byDiagonal)
    for (int i = 0; i < A.rows(); ++i) shift.coeffRef(i, i) = A.coeff(i, i);
  A += kShift * shift;
  A.makeCompressed();
  return A;
}

// ---- methods ------------------------------------------------------------------------------------

enum class Kind { OursInsert, OursRemove, CholmodCut, Rowadd, Woodbury };

/** One timed way of getting the solution of a cut (or, for ours remove, of the seam's removal). */
struct Method
{
  std::string key;    ///< CSV name
  std::string label;  ///< table heading
  Kind kind;
};

std::vector<Method> allMethods()
{
  return {{"ours_insert", "ours ins", Kind::OursInsert},
          {"ours_remove", "ours rem", Kind::OursRemove},
          {"cholmod_cut", "CHM cut", Kind::CholmodCut},
          {"cholmod_rowadd", "rowadd", Kind::Rowadd},
          {"woodbury", "SMW", Kind::Woodbury}};
}

/** What one method did on one seam. */
struct Sample
{
  double ms = kNaN;            ///< update + solve
  double callMs = kNaN;        ///< the update alone, wall time (ours: the insertDofs/removeDofs call)
  double updateMs = kNaN;      ///< ours: lastUpdate().seconds
  /** ours: lastUpdate()'s phases (compare, structure, plan, numeric) and the rest of its seconds */
  double phaseMs[5] = {kNaN, kNaN, kNaN, kNaN, kNaN};
  double extraMs = kNaN;       ///< ours: mergeDofs/restoreDofs afterwards; rowadd: its per-seam setup
  double flopFraction = kNaN;  ///< update flops / full factorization flops (each method's own count)
  double error = kNaN;         ///< relative difference to ours insert (ours: backward error)
  std::string route;           ///< ours: the route taken
  long dirty = -1;             ///< ours: dirty supernodes; SMW: size of the capacity matrix
  bool ok = true;
  bool skipped = false;        ///< not run (--ours-only): no time, no answer
  std::string message;
  Eigen::VectorXd x;
};

/** The medians of one method at one l. */
struct Summary
{
  bench::Samples ms, call, update, extra, flops, dirty;
  bench::Samples phase[5];  ///< ours: lastUpdate()'s phases and the rest
  std::map<std::string, int> routes;
  double worstError = 0;

  void add(const Sample& s)
  {
    if (s.skipped) return;
    ms.add(s.ms);
    if (!std::isnan(s.callMs)) call.add(s.callMs);
    if (!std::isnan(s.updateMs)) update.add(s.updateMs);
    for (int k = 0; k < 5; ++k)
      if (!std::isnan(s.phaseMs[k])) phase[k].add(s.phaseMs[k]);
    if (!std::isnan(s.extraMs)) extra.add(s.extraMs);
    if (!std::isnan(s.flopFraction)) flops.add(s.flopFraction);
    if (s.dirty >= 0) dirty.add(double(s.dirty));
    if (!s.route.empty()) ++routes[s.route];
    if (!std::isnan(s.error)) worstError = std::max(worstError, s.error);
  }
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

/** One seam and its cut: everything the methods need, built before any of them runs. */
struct Cut
{
  std::vector<int> seam;       ///< the seam's vertices (pieces one after the other)
  int pieces = 0;
  SpMat Acut;                  ///< Laplacian + shift of the cut mesh, (n+m)^2, both triangles
  Eigen::VectorXi origin;      ///< cutMesh's map: origin[i] == i for i < n, the copied vertex for i >= n
  int m = 0;                   ///< new dofs
  std::vector<int> changed;    ///< old dofs whose column of Acut differs from that of blkdiag(A, I)
  std::vector<int> added;      ///< the new dofs n..n+m-1
  std::vector<int> perm;       ///< extended permutation: each copy right after its origin
  Eigen::VectorXd b;           ///< right-hand side of the cut system
};

// ---- command line -------------------------------------------------------------------------------

using Options = bench::SeamBenchOptions;

/** This benchmark's names on the shared command line (SeamBenchOptions.h). */
const bench::SeamBenchNames kNames{"bench_insert_dofs", "insert_dofs", "bench/plot_insert_dofs.sh", UC_BENCH_DEFAULT_MESHES};

// ---- one mesh -----------------------------------------------------------------------------------

/** Everything of one mesh that the seams share: matrix, ordering, the factored solvers. */
class MeshBench
{
public:
  MeshBench(const Options& options, const std::string& name, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F)
      : m_options(options), m_name(name), m_V(V), m_F(F), m_methods(allMethods())
  {
    m_n = int(V.rows());
    m_A = shiftedLaplacian(V, F, options.diagonalShift);
    m_normA = bench::infinityNorm(m_A);
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
    m_setup["ours_supernodes"] = double(m_ours.supernodeCount());

    m_setup["cholmod_analyze_factorize_ms"] = m_setup["cholmod_fl"] = m_setup["schur_layout_factorization_flops"] = kNaN;
    if (!options.oursOnly) // (the peers' factor of A and Woodbury's layout: not needed by ours alone)
    {
      m_setup["cholmod_analyze_factorize_ms"] = bench::timeMs([&] {
        m_base.analyze(m_A, m_perm.indices().data());
        if (!m_base.factorize(m_A)) throw std::runtime_error("CHOLMOD: factorize failed");
      });
      m_setup["cholmod_fl"] = m_base.flops();
      m_schur.reset(new bench::SchurComplementDirichlet(m_base));
      m_woodbury.reset(new bench::WoodburyCutSolve(*m_schur, m_A));
      m_setup["schur_layout_factorization_flops"] = m_schur->factorizationFlops();
    }

    std::mt19937 generator(options.seed ^ 0x5eedu);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    m_b.resize(2 * m_n); // the cut system's right-hand sides are prefixes (n + m <= 2n here)
    m_g.resize(m_n);
    for (Eigen::Index i = 0; i < m_b.size(); ++i) m_b[i] = uniform(generator);
    for (int i = 0; i < m_n; ++i) m_g[i] = uniform(generator);

    bench::Samples oursSolve, oursRepeat, cholmodSolve;
    const Eigen::VectorXd b = m_b.head(m_n);
    for (int rep = 0; rep < 5; ++rep)
    {
      Eigen::VectorXd x;
      bench::timeFullAndRepeatedSolve(m_ours, b, oursSolve, oursRepeat);
      if (options.oursOnly) continue;
      bench::evictCaches();
      cholmodSolve.add(bench::timeMs([&] { x = m_base.solve(b); }));
    }
    m_setup["ours_solve_ms"] = oursSolve.median();
    m_setup["ours_repeated_solve_ms"] = oursRepeat.median();
    m_setup["cholmod_solve_ms"] = cholmodSolve.median();
  }

  /** Runs every length and prints the tables. \returns false if some answer was wrong. */
  bool run()
  {
    printHeader();
    openCsv();
    bool ok = true;
    { // warm-up: one untimed seam of every method (first-touch costs, BLAS buffers, caches)
      const int l = std::min(m_n, std::max(5, m_options.lengths.front()));
      Cut cut;
      if (makeCut(l, m_options.seed + 7u, cut))
      {
        std::vector<Sample> samples = runSeam(cut, 0);
        ok = check(cut, samples) && ok;
      }
    }
    for (int l : m_options.lengths)
    {
      std::vector<Summary> summary(m_methods.size());
      bench::Samples copies, changed, cutMs;
      double pieces = 0;
      int done = 0;
      for (int s = 0; s < m_options.seams; ++s)
      {
        Cut cut;
        bench::Stopwatch watch;
        if (!makeCut(l, m_options.seed + 1000003u * unsigned(l) + 7919u * unsigned(s), cut)) break;
        cutMs.add(watch.ms());
        std::vector<Sample> samples = runSeam(cut, 131 * l + s);
        ok = check(cut, samples) && ok;
        for (std::size_t k = 0; k < m_methods.size(); ++k) summary[k].add(samples[k]);
        copies.add(double(cut.m));
        changed.add(double(cut.changed.size() + cut.added.size()));
        pieces = std::max(pieces, double(cut.pieces));
        writeSamples(l, s, cut, samples);
        ++done;
      }
      if (done == 0)
      {
        std::printf("  l = %d: no seam of that many vertices on this mesh, skipped\n", l);
        continue;
      }
      m_rows.push_back({l, done, pieces, copies.median(), changed.median(), cutMs.median(), summary});
      writeSummary(m_rows.back());
    }
    printTables();
    return ok;
  }

private:
  struct Row
  {
    int l, seams;
    double pieces, copies, changed, cutMs;
    std::vector<Summary> summary;
  };

  /** Draws the seam of \a l vertices with \a seed and cuts the mesh along each of its pieces. */
  bool makeCut(int l, unsigned seed, Cut& cut)
  {
    cut.seam = Eigen::seamPath(m_F, m_n, l, seed, &cut.pieces);
    if (cut.seam.empty()) return false;
    // seamPath's pieces follow one another: k pieces of l/k vertices, the first l mod k one longer.
    std::vector<std::array<int, 2>> edges;
    const int k = std::max(cut.pieces, 1), size = int(cut.seam.size());
    for (int piece = 0, begin = 0; piece < k; ++piece)
    {
      const int length = size / k + (piece < size % k ? 1 : 0);
      for (int i = begin; i + 1 < begin + length; ++i) edges.push_back({cut.seam[std::size_t(i)], cut.seam[std::size_t(i) + 1]});
      begin += length;
    }
    Eigen::MatrixXd Vcut;
    Eigen::MatrixXi Fcut;
    std::string error;
    if (!Eigen::cutMesh(m_V, m_F, edges, Vcut, Fcut, cut.origin, &error)) throw std::runtime_error(error);
    cut.m = int(Vcut.rows()) - m_n;
    if (cut.m > m_n) throw std::runtime_error("the cut more than doubles the vertices");
    cut.Acut = shiftedLaplacian(Vcut, Fcut, m_options.diagonalShift);
    cut.b = m_b.head(m_n + cut.m);

    // Old dofs whose column changed (values, or entries at new dofs); every new dof.
    const SpMat& C = cut.Acut;
    for (int j = 0; j < m_n; ++j)
    {
      const int a0 = m_A.outerIndexPtr()[j], a1 = m_A.outerIndexPtr()[j + 1];
      const int c0 = C.outerIndexPtr()[j], c1 = C.outerIndexPtr()[j + 1];
      bool same = a1 - a0 == c1 - c0;
      for (int p = 0; same && p < a1 - a0; ++p)
        same = m_A.innerIndexPtr()[a0 + p] == C.innerIndexPtr()[c0 + p] && m_A.valuePtr()[a0 + p] == C.valuePtr()[c0 + p];
      if (!same) cut.changed.push_back(j);
    }
    for (int j = m_n; j < m_n + cut.m; ++j) cut.added.push_back(j);

    // The uncut permutation with each copy right after its origin (copies of one origin in order).
    std::vector<std::vector<int>> copiesOf;
    std::vector<int> firstCopy(std::size_t(m_n), -1);
    for (int j = m_n; j < m_n + cut.m; ++j)
    {
      int& slot = firstCopy[std::size_t(cut.origin[j])];
      if (slot < 0)
      {
        slot = int(copiesOf.size());
        copiesOf.emplace_back();
      }
      copiesOf[std::size_t(slot)].push_back(j);
    }
    cut.perm.clear();
    cut.perm.reserve(std::size_t(m_n + cut.m));
    for (int k2 = 0; k2 < m_n; ++k2)
    {
      const int v = m_perm.indices()[k2];
      cut.perm.push_back(v);
      if (firstCopy[std::size_t(v)] >= 0)
        for (int c : copiesOf[std::size_t(firstCopy[std::size_t(v)])]) cut.perm.push_back(c);
    }
    return true;
  }

  /** Runs every method on one cut, in random orders drawn from \a seed (see interleavedMedianRuns). */
  std::vector<Sample> runSeam(const Cut& cut, int seed)
  {
    std::vector<Sample> samples = bench::interleavedMedianRuns<Sample>(
        m_methods.size(), m_options.repeats, seed, [&](std::size_t k) { return runMethod(m_methods[k], cut); });
    return samples;
  }

  /** Fills the statistics of our last update into \a s. */
  void oursStatistics(Sample& s) const
  {
    const Eigen::UpdateStatistics& st = m_ours.lastUpdate();
    s.flopFraction = st.flopFraction;
    s.updateMs = st.seconds * 1e3;
    const double phases[4] = {st.compareSeconds, st.structureSeconds, st.planSeconds, st.numericSeconds};
    s.phaseMs[4] = s.updateMs;  // (the rest, at least 0: the phases are parts of seconds, up to rounding)
    for (int k = 0; k < 4; ++k)
    {
      s.phaseMs[k] = phases[k] * 1e3;
      s.phaseMs[4] -= s.phaseMs[k];
    }
    s.phaseMs[4] = std::max(0.0, s.phaseMs[4]);
    s.route = routeName(st.route);
    s.dirty = long(st.dirtySupernodes);
  }

  Sample runMethod(const Method& method, const Cut& cut)
  {
    Sample s;
    if (m_options.oursOnly && method.kind != Kind::OursInsert && method.kind != Kind::OursRemove)
    {
      s.skipped = true;
      return s;
    }
    switch (method.kind)
    {
    case Kind::OursInsert:
    {
      bench::Stopwatch watch;
      m_ours.insertDofs(cut.Acut, cut.origin, cut.changed);
      s.callMs = watch.ms();
      const bool inserted = m_ours.info() == Eigen::Success;
      if (inserted) s.x = m_ours.solve(cut.b);
      s.ms = watch.ms();
      if (!inserted) throw std::runtime_error("insertDofs: info() = " + std::to_string(int(m_ours.info())));
      oursStatistics(s);
      s.extraMs = bench::timeMs([&] { m_ours.mergeDofs(m_A, cut.origin, cut.changed); });
      if (m_ours.info() != Eigen::Success) throw std::runtime_error("mergeDofs: info() = " + std::to_string(int(m_ours.info())));
      if (m_ours.rows() != m_n) throw std::runtime_error("mergeDofs left the wrong size");
      break;
    }
    case Kind::OursRemove:
    {
      Eigen::MatrixXd x;
      const Eigen::VectorXd b = m_b.head(m_n);
      bench::Stopwatch watch;
      m_ours.removeDofs(cut.seam);
      s.callMs = watch.ms();
      const bool removed = m_ours.info() == Eigen::Success;
      if (removed) x = m_ours.solveDirichlet(b, m_g);
      s.ms = watch.ms();
      if (!removed) throw std::runtime_error("removeDofs: info() = " + std::to_string(int(m_ours.info())));
      oursStatistics(s);
      s.x = x.col(0);
      s.extraMs = bench::timeMs([&] { m_ours.restoreDofs(cut.seam); });
      if (m_ours.info() != Eigen::Success) throw std::runtime_error("restoreDofs: info() = " + std::to_string(int(m_ours.info())));
      break;
    }
    case Kind::CholmodCut:
    {
      bench::CholmodSupernodal chol;
      bench::Stopwatch watch;
      chol.analyze(cut.Acut, cut.perm.data());
      const bool positive = chol.factorize(cut.Acut);
      s.callMs = watch.ms();
      if (positive) s.x = chol.solve(cut.b);
      s.ms = watch.ms();
      if (!positive) throw std::runtime_error("cholmod_factorize of the cut matrix failed");
      s.flopFraction = chol.flops() / m_base.flops();
      break;
    }
    case Kind::Rowadd:
    {
      // Setup, untimed: factor of blkdiag(A, I_m) with the new dofs at their places in the order.
      bench::Stopwatch setup;
      SpMat placeholders(m_n + cut.m, m_n + cut.m);
      {
        std::vector<Eigen::Triplet<double, int>> entries;
        entries.reserve(std::size_t(m_A.nonZeros()) + std::size_t(cut.m));
        for (int j = 0; j < m_n; ++j)
          for (SpMat::InnerIterator it(m_A, j); it; ++it) entries.emplace_back(int(it.row()), j, it.value());
        for (int j = m_n; j < m_n + cut.m; ++j) entries.emplace_back(j, j, 1.0);
        placeholders.setFromTriplets(entries.begin(), entries.end());
        placeholders.makeCompressed();
      }
      bench::CholmodRowadd rowadd(placeholders, cut.perm);
      s.extraMs = setup.ms();
      bench::Stopwatch watch;
      rowadd.replaceRows(cut.Acut, cut.changed, cut.added);
      s.callMs = watch.ms();
      s.x = rowadd.solve(cut.b);
      s.ms = watch.ms();
      s.flopFraction = rowadd.updateFlops() / m_base.flops();
      break;
    }
    case Kind::Woodbury:
    {
      bench::Stopwatch watch;
      s.x = m_woodbury->solve(cut.Acut, cut.changed, cut.b);
      s.ms = watch.ms();
      s.flopFraction = m_woodbury->updateFlops() / m_schur->factorizationFlops();
      s.dirty = m_woodbury->rank();
      break;
    }
    }
    return s;
  }

  /** Checks every solution: ours by backward errors, the other cut solutions against ours insert. */
  bool check(const Cut& cut, std::vector<Sample>& samples)
  {
    bool ok = true;
    Sample& ref = samples[0];
    if (ref.ok)
    {
      const Eigen::VectorXd r = cut.Acut * ref.x - cut.b;
      ref.error = r.lpNorm<Eigen::Infinity>() /
                  (bench::infinityNorm(cut.Acut) * ref.x.lpNorm<Eigen::Infinity>() + cut.b.lpNorm<Eigen::Infinity>());
      if (!(ref.error <= kBackwardTolerance))
      {
        ref.ok = false;
        ref.message = "backward error of the cut solve " + std::to_string(ref.error);
      }
    }
    Sample& removal = samples[1];
    if (removal.ok)
    {
      for (int j : cut.seam) m_inB[std::size_t(j)] = 1;
      removal.error = bench::dirichletBackwardError(m_A, m_normA, m_inB, cut.seam, removal.x, m_b.head(m_n), m_g);
      for (int j : cut.seam) m_inB[std::size_t(j)] = 0;
      if (!(removal.error <= kBackwardTolerance))
      {
        removal.ok = false;
        removal.message = "backward error of the Dirichlet solve " + std::to_string(removal.error);
      }
    }
    const double refNorm = ref.ok ? ref.x.lpNorm<Eigen::Infinity>() : kNaN;
    for (std::size_t k = 2; k < samples.size(); ++k)
    {
      Sample& s = samples[k];
      if (!s.ok || !ref.ok || s.skipped) continue;
      s.error = s.x.size() == ref.x.size() ? (s.x - ref.x).lpNorm<Eigen::Infinity>() / refNorm : kNaN;
      if (!(s.error <= kRelativeTolerance))
      {
        // The cut Laplacian + 1e-8 I is ill-conditioned, so two right answers may differ by more
        // than the tolerance (Woodbury's capacity matrix of a long seam loses digits): a peer
        // that differs is still right when its own backward error on the cut system is small.
        const double backward = s.x.size() == ref.x.size()
                                    ? (cut.Acut * s.x - cut.b).lpNorm<Eigen::Infinity>() /
                                          (bench::infinityNorm(cut.Acut) * s.x.lpNorm<Eigen::Infinity>() +
                                           cut.b.lpNorm<Eigen::Infinity>())
                                    : kNaN;
        char buffer[200];
        if (backward <= kBackwardTolerance)
        {
          std::printf("  note: %s (seam of %zu, %d copies) differs from ours by %.2e, its backward error %.1e is "
                      "within %.0e\n",
                      m_methods[k].key.c_str(), cut.seam.size(), cut.m, s.error, backward, kBackwardTolerance);
          continue;
        }
        s.ok = false;
        std::snprintf(buffer, sizeof(buffer), "relative difference to ours %.2e > %.0e, backward error %.2e > %.0e",
                      s.error, kRelativeTolerance, backward, kBackwardTolerance);
        s.message = buffer;
      }
    }
    for (std::size_t k = 0; k < samples.size(); ++k)
    {
      if (!samples[k].ok)
      {
        std::printf("  FAILED %s (seam of %zu, %d copies): %s\n", m_methods[k].key.c_str(), cut.seam.size(), cut.m,
                    samples[k].message.c_str());
        ok = false;
      }
      samples[k].x.resize(0);
    }
    return ok;
  }

  void printHeader() const
  {
    auto get = [&](const char* key) { return m_setup.at(key); };
    std::printf("\n=== %s: %s vertices, %s triangles, nnz(A) = %s; threads = %d\n", m_name.c_str(),
                fmtCount(get("vertices")).c_str(), fmtCount(get("faces")).c_str(), fmtCount(get("nnz_A")).c_str(),
                m_options.threads);
    std::printf("  setup: METIS %s ms; ours compute (analyze+factorize, update caching on) %s ms, %s supernodes;\n"
                "         CHOLMOD analyze+factorize %s ms; one solve, 1 rhs (median of 5, cold caches): ours %s ms (the same b\n"
                "         again, forward substitution kept: %s ms), CHOLMOD %s ms\n",
                fmtMs(get("metis_ms")).c_str(), fmtMs(get("ours_compute_ms")).c_str(),
                fmtCount(get("ours_supernodes")).c_str(), fmtMs(get("cholmod_analyze_factorize_ms")).c_str(),
                fmtMs(get("ours_solve_ms")).c_str(), fmtMs(get("ours_repeated_solve_ms")).c_str(),
                fmtMs(get("cholmod_solve_ms")).c_str());
  }

  void printTables() const
  {
    const std::size_t count = m_methods.size();
    const std::size_t insert = 0, remove = 1;
    std::printf("\n  %s, update + solve [ms], medians over the seams of each l (seeds fixed)\n", m_name.c_str());
    std::printf("  %5s %3s %3s %5s %6s |", "l", "#", "pcs", "m", "|K|");
    for (std::size_t k = 0; k < count; ++k) std::printf(" %9s", m_methods[k].label.c_str());
    std::printf(" | %9s %9s %9s %9s\n", "merge", "restore", "rowadd su", "cut mesh");
    for (const Row& row : m_rows)
    {
      std::printf("  %5d %3d %3s %5s %6s |", row.l, row.seams, fmt(row.pieces, 0).c_str(), fmtCount(row.copies).c_str(),
                  fmtCount(row.changed).c_str());
      for (std::size_t k = 0; k < count; ++k) std::printf(" %9s", fmtMs(row.summary[k].ms.median()).c_str());
      std::printf(" | %9s %9s %9s %9s\n", fmtMs(row.summary[insert].extra.median()).c_str(),
                  fmtMs(row.summary[remove].extra.median()).c_str(), fmtMs(row.summary[3].extra.median()).c_str(),
                  fmtMs(row.cutMs).c_str());
    }

    std::printf("\n  %s, ratios of medians (ours insert / other, update + solve; < 1: ours is faster), insert/remove, "
                "flop fractions\n", m_name.c_str());
    std::printf("  %5s |", "l");
    for (std::size_t k = 2; k < count; ++k) std::printf(" %9s", ("/" + m_methods[k].label).c_str());
    std::printf(" | %8s %8s | flops:", "ins/rem", "ins/rem");
    for (std::size_t k = 0; k < count; ++k) std::printf(" %8s", m_methods[k].label.c_str());
    std::printf(" | %6s %6s %-8s\n", "dirty", "dirty", "route");
    std::printf("  %5s |", "");
    for (std::size_t k = 2; k < count; ++k) std::printf(" %9s", "");
    std::printf(" | %8s %8s |       ", "update", "+solve");
    for (std::size_t k = 0; k < count; ++k) std::printf(" %8s", "");
    std::printf(" | %6s %6s %-8s\n", "ins", "rem", "ins");
    for (const Row& row : m_rows)
    {
      const Summary& in = row.summary[insert];
      const Summary& rm = row.summary[remove];
      std::printf("  %5d |", row.l);
      for (std::size_t k = 2; k < count; ++k) std::printf(" %9s", fmtRatio(in.ms.median(), row.summary[k].ms.median()).c_str());
      std::printf(" | %8s %8s |       ", fmtRatio(in.call.median(), rm.call.median()).c_str(),
                  fmtRatio(in.ms.median(), rm.ms.median()).c_str());
      for (std::size_t k = 0; k < count; ++k) std::printf(" %8s", fmtFraction(row.summary[k].flops.median()).c_str());
      std::printf(" | %6s %6s %-8s\n", fmtCount(in.dirty.median()).c_str(), fmtCount(rm.dirty.median()).c_str(),
                  in.routeText().c_str());
    }

    std::printf("\n  %s, where ours spends its update time [ms, medians]: the call's wall time vs lastUpdate().seconds\n",
                m_name.c_str());
    std::printf("  %5s | %10s %10s %10s | %10s %10s %10s | %10s %10s\n", "l", "insertDofs", "lastUpd", "outside",
                "removeDofs", "lastUpd", "outside", "ins solve", "rem solve");
    for (const Row& row : m_rows)
    {
      const Summary& in = row.summary[insert];
      const Summary& rm = row.summary[remove];
      std::printf("  %5d | %10s %10s %10s | %10s %10s %10s | %10s %10s\n", row.l, fmtMs(in.call.median()).c_str(),
                  fmtMs(in.update.median()).c_str(), fmtMs(in.call.median() - in.update.median()).c_str(),
                  fmtMs(rm.call.median()).c_str(), fmtMs(rm.update.median()).c_str(),
                  fmtMs(rm.call.median() - rm.update.median()).c_str(),
                  fmtMs(in.ms.median() - in.call.median()).c_str(), fmtMs(rm.ms.median() - rm.call.median()).c_str());
    }

    std::printf("\n  %s, the phases of insertDofs [ms, medians of each]: before = the call's wall time outside\n"
                "  lastUpdate().seconds, then lastUpdate()'s compareSeconds (checks and compare), structureSeconds (layout\n"
                "  and relabeling), planSeconds, numericSeconds, and the rest (commit)\n",
                m_name.c_str());
    std::printf("  %5s | %9s %9s %9s %9s %9s %9s | %10s\n", "l", "before", "compare", "structure", "plan", "numeric", "rest",
                "removeDofs");
    for (const Row& row : m_rows)
    {
      const Summary& in = row.summary[insert];
      const Summary& rm = row.summary[remove];
      std::printf("  %5d | %9s %9s %9s %9s %9s %9s | %10s\n", row.l, fmtMs(in.call.median() - in.update.median()).c_str(),
                  fmtMs(in.phase[0].median()).c_str(), fmtMs(in.phase[1].median()).c_str(),
                  fmtMs(in.phase[2].median()).c_str(), fmtMs(in.phase[3].median()).c_str(),
                  fmtMs(in.phase[4].median()).c_str(), fmtMs(rm.call.median()).c_str());
    }

    double worst = 0;
    std::string worstName;
    for (const Row& row : m_rows)
      for (std::size_t k = 2; k < count; ++k)
        if (row.summary[k].worstError > worst)
        {
          worst = row.summary[k].worstError;
          worstName = m_methods[k].key;
        }
    std::printf("  largest relative difference to ours insert: %.1e (%s); tolerance %.0e\n", worst,
                worstName.empty() ? "-" : worstName.c_str(), kRelativeTolerance);
    std::printf(
        "  columns: # seams, pcs = most pieces a seam was split into, m = new dofs (copies), |K| = changed old + new dofs;\n"
        "  ours ins = insertDofs(Acut, origin, K_old) + solve (K_old: the changed old dofs, as rowadd and SMW get them);\n"
        "  ours rem = removeDofs(seam) + solveDirichlet on the uncut factor;\n"
        "  CHM cut = cholmod_analyze_p + cholmod_factorize of Acut + solve; rowadd = cholmod_rowdel of the changed old dofs +\n"
        "  cholmod_rowadd of changed and new dofs on a simplicial LDL' factor with identity placeholders + solve; SMW = Woodbury\n"
        "  on blkdiag(A, I_m) with CHOLMOD's factor of A (capacity matrix |K| x |K|) + solve. Not in the times: merge =\n"
        "  mergeDofs(A, origin, K_old) after ours ins, restore = restoreDofs after ours rem, rowadd su = rowadd's per-seam setup (factor +\n"
        "  conversion), cut mesh = seamPath + cutMesh + Laplacian + the changed set. ins/rem update = insertDofs / removeDofs\n"
        "  call (wall time), +solve = with the solves; flops = update flops / full factorization flops, each by its own count\n"
        "  (ours lastUpdate().flopFraction; CHM cut Common.fl of Acut / of A; rowadd Common.modfl / Common.fl of A; SMW dense\n"
        "  flops of W, S, capacity matrix and its LU over a full factorization on CHOLMOD's layout); dirty = lastUpdate().dirtySupernodes.\n");
  }

  void openCsv()
  {
    if (m_options.csvDir.empty()) return;
    std::filesystem::create_directories(m_options.csvDir);
    const std::string base = m_options.csvDir + "/insert_dofs_" + meshStem(m_name);
    std::ofstream setup(base + "_setup.csv");
    setup.precision(10);
    setup << "mesh,key,value\n";
    for (const auto& kv : m_setup) setup << m_name << ',' << kv.first << ',' << kv.second << '\n';
    m_samplesCsv.open(base + "_samples.csv");
    m_samplesCsv << "mesh,vertices,l,seam,seam_vertices,pieces,copies,changed_old,method,ms,call_ms,update_ms,extra_ms,"
                    "flop_fraction,route,dirty,error,ok\n";
    m_summaryCsv.open(base + ".csv");
    m_summaryCsv << "l,seams,pieces,copies,changed";
    for (const Method& m : m_methods)
      m_summaryCsv << ',' << m.key << "_ms," << m.key << "_min_ms," << m.key << "_max_ms," << m.key << "_call_ms,"
                   << m.key << "_flop_fraction";
    m_summaryCsv << ",ours_insert_update_ms,ours_remove_update_ms,ours_merge_ms,ours_restore_ms,rowadd_setup_ms,"
                    "insert_remove_update_ratio,insert_remove_total_ratio"
                 << std::endl;
    if (!m_samplesCsv || !m_summaryCsv || !setup) throw std::runtime_error("cannot write CSV files in " + m_options.csvDir);
  }

  void writeSamples(int l, int seam, const Cut& cut, const std::vector<Sample>& samples)
  {
    if (!m_samplesCsv.is_open()) return;
    for (std::size_t k = 0; k < samples.size(); ++k)
    {
      const Sample& s = samples[k];
      m_samplesCsv << m_name << ',' << m_n << ',' << l << ',' << seam << ',' << cut.seam.size() << ',' << cut.pieces << ','
                   << cut.m << ',' << cut.changed.size() << ',' << m_methods[k].key << ',' << csvNumber(s.ms) << ','
                   << csvNumber(s.callMs) << ',' << csvNumber(s.updateMs) << ',' << csvNumber(s.extraMs) << ','
                   << csvNumber(s.flopFraction) << ',' << s.route << ',' << s.dirty << ',' << csvNumber(s.error) << ','
                   << (s.ok ? 1 : 0) << '\n';
    }
    m_samplesCsv.flush();
  }

  void writeSummary(const Row& row)
  {
    if (!m_summaryCsv.is_open()) return;
    m_summaryCsv << row.l << ',' << row.seams << ',' << csvNumber(row.pieces) << ',' << csvNumber(row.copies) << ','
                 << csvNumber(row.changed);
    for (const Summary& s : row.summary)
      m_summaryCsv << ',' << csvNumber(s.ms.median()) << ',' << csvNumber(s.ms.min()) << ',' << csvNumber(s.ms.max()) << ','
                   << csvNumber(s.call.median()) << ',' << csvNumber(s.flops.median());
    const Summary& in = row.summary[0];
    const Summary& rm = row.summary[1];
    m_summaryCsv << ',' << csvNumber(in.update.median()) << ',' << csvNumber(rm.update.median()) << ','
                 << csvNumber(in.extra.median()) << ',' << csvNumber(rm.extra.median()) << ','
                 << csvNumber(row.summary[3].extra.median()) << ',' << csvNumber(in.call.median() / rm.call.median())
                 << ',' << csvNumber(in.ms.median() / rm.ms.median()) << '\n';
    m_summaryCsv.flush();
  }

  const Options& m_options;
  std::string m_name;
  const Eigen::MatrixXd& m_V;
  const Eigen::MatrixXi& m_F;
  std::vector<Method> m_methods;
  int m_n = 0;
  SpMat m_A;
  double m_normA = 0;
  Permutation m_perm;
  OursLLT m_ours;
  bench::CholmodSupernodal m_base;
  std::unique_ptr<bench::SchurComplementDirichlet> m_schur;
  std::unique_ptr<bench::WoodburyCutSolve> m_woodbury;
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
  if (openblas_set_num_threads) openblas_set_num_threads(options.threads);

  std::printf("bench_insert_dofs: %s\n", options.smoke ? "SMOKE run (tiny grid, l = 1,5, one seam)"
                                                      : "adding dofs by cutting seams (paper Fig. 6, insertion)");
  std::printf("  matrix cotan Laplacian + %.0e %s; one METIS ordering per mesh given to every solver; seams: "
              "Eigen::seamPath, %d per l, base seed %u, cut with Eigen::cutMesh along every piece; %d run(s) of every "
              "method per seam, their median counts\n",
              kShift, options.diagonalShift ? "diag(L)" : "I", options.seams, options.seed, options.repeats);
  std::printf("  every time is update + one solve (b uniform in [-1,1]), methods interleaved per seam (a random order each round) after one "
              "warm-up seam\n");
  std::printf("  compiled for %s (ours, Eigen); %s\n", bench::compiledInstructionSet(),
              bench::openBlasCoreNote().c_str());
  std::printf("  %s\n", bench::heapPolicyNote(heapRetained).c_str());

  const bool allOk = bench::forEachMesh("bench_insert_dofs", options.grid, options.meshes,
                                         [&](const std::string& name, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
                                           MeshBench bench(options, name, V, F);
                                           return bench.run();
                                         });
  if (!options.csvDir.empty())
    std::printf("\nCSV written to %s (plot: bench/plot_insert_dofs.sh %s)\n", options.csvDir.c_str(), options.csvDir.c_str());
  std::printf("%s\n", allOk ? "result: all answers agree" : "result: FAILURE (see FAILED lines above)");
  return allOk ? 0 : 1;
}
