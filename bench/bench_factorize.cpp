// bench_factorize: full factorization benchmark. For one mesh it builds the cotan Laplacian + 1e-8 I,
// computes one METIS permutation and gives it to three solvers: UpdatableSupernodalLLT (ours),
// CHOLMOD supernodal and Eigen's SimplicialLLT. It reports, as medians over repetitions and for each
// thread count, symbolic analysis, numeric factorization (first and repeated), solves with 1 and 3
// right-hand sides, peak heap, nnz(L), supernodes, GFlop/s and backward errors, with ratios
// ours/CHOLMOD and ours/Simplicial; optionally as CSV. --smoke runs a tiny grid once, for CI.
// This is the comparison behind the paper's remark (§4.2, "Implementation") that storing each
// supernode as its own object costs little in a full factorization.
//
// Usage: bench_factorize [--mesh=PATH | --icosphere=S | --grid=N] [--reps=N] [--threads=1,2]
//                        [--csv=FILE] [--smoke]
// Exit code: 0 if every solver succeeded with a small backward error, 1 otherwise, 2 on bad usage.

#include <Eigen/UpdatableCholesky>

#include <iostream> // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <Eigen/SparseCholesky>
#include <unsupported/Eigen/MeshTools>

#include "BlasCore.h"
#include "CholmodPeer.h"
#include "FixedOrdering.h"
#include "HeapTracker.h"
#include "Timing.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

// OpenBLAS's thread control; weak, so the benchmark still links against another BLAS.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));
extern "C" char* openblas_get_config(void) __attribute__((weak));

#ifndef UC_BENCH_DEFAULT_MESH
#define UC_BENCH_DEFAULT_MESH "bunny.off.gz"
#endif

namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Ordering = bench::FixedOrdering<int>;
using Permutation = Ordering::PermutationType;
using OursLLT = Eigen::UpdatableSupernodalLLT<SpMat, Eigen::Lower, Ordering>;
using SimplicialPeer = Eigen::SimplicialLLT<SpMat, Eigen::Lower, Ordering>;

/** Backward error above which a solve counts as failed: ||Ax-b||_inf / (||A||_inf ||x||_inf + ||b||_inf). */
constexpr double kBackwardErrorTolerance = 1e-10;
/** Diagonal shift that makes the (singular) cotan Laplacian positive definite. */
constexpr double kShift = 1e-8;

enum Solver { Ours, Cholmod, Simplicial, SolverCount };
const char* const kSolverNames[SolverCount] = {"ours", "CHOLMOD", "Simplicial"};

/** Timed and memory quantities, one sample per repetition. */
enum Metric { Analyze, FactorFirst, Refactor, Solve1, Solve3, PeakHeap, FactorHeap, MetricCount };
const char* const kMetricKeys[MetricCount] = {"analyze_ms", "factorize_first_ms", "refactorize_ms", "solve1_ms",
                                              "solve3_ms", "peak_heap_bytes", "factor_heap_bytes"};

/** What one run (analyze, factorize twice, two solves) of one solver produced. */
struct RunResult
{
  std::array<double, MetricCount> value{}; // indexed by Metric; times in ms, heap in bytes
  double storedNnzL = 0, exactNnzL = 0, supernodes = 0, flops = 0, backwardError = 0;
  double selfReportedPeakHeap = std::numeric_limits<double>::quiet_NaN(); // CHOLMOD: Common.memory_usage
  bool ok = false;
  std::string message;
};

/** All repetitions of one solver at one thread count. */
struct SolverSummary
{
  std::array<bench::Samples, MetricCount> samples;
  RunResult last;
  double worstBackwardError = 0;
  bool ok = true;
  std::string message;

  /** Records one repetition. */
  void add(const RunResult& r)
  {
    for (int m = 0; m < MetricCount; ++m) samples[std::size_t(m)].add(r.value[std::size_t(m)]);
    worstBackwardError = std::max(worstBackwardError, r.backwardError);
    if (!r.ok && ok)
    {
      ok = false;
      message = r.message;
    }
    last = r;
  }
};

/** Command-line options (see printUsage()). */
struct Options
{
  std::string mesh = UC_BENCH_DEFAULT_MESH;
  int icosphere = -1, grid = 0, reps = 5;
  std::vector<int> threads{1, 2};
  std::string csv;
  bool smoke = false;
};

/** \returns max over columns of ||A x - b||_inf / (||A||_inf ||x||_inf + ||b||_inf). */
double backwardError(const SpMat& A, double normA, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B)
{
  const Eigen::MatrixXd R = A * X - B;
  double worst = 0;
  for (Eigen::Index j = 0; j < B.cols(); ++j)
  {
    const double denominator = normA * X.col(j).lpNorm<Eigen::Infinity>() + B.col(j).lpNorm<Eigen::Infinity>();
    const double error = R.col(j).lpNorm<Eigen::Infinity>() / denominator;
    worst = std::max(worst, std::isfinite(error) ? error : std::numeric_limits<double>::infinity());
  }
  return worst;
}

/** \returns ||A||_inf (max absolute row sum; A is symmetric, so the column sums serve). */
double infinityNorm(const SpMat& A)
{
  double norm = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
  {
    double sum = 0;
    for (SpMat::InnerIterator it(A, j); it; ++it) sum += std::abs(it.value());
    norm = std::max(norm, sum);
  }
  return norm;
}

/** \returns sum of squared column counts of a simplicial factor (CHOLMOD's flop measure). */
double squaredColumnCounts(const SpMat& L)
{
  double flops = 0;
  for (Eigen::Index j = 0; j < L.outerSize(); ++j)
  {
    const double count = double(L.outerIndexPtr()[j + 1] - L.outerIndexPtr()[j]);
    flops += count * count;
  }
  return flops;
}

/** The common part of a run for the two Eigen-API solvers: time the phases, check, solve. */
template <typename SolverType, typename Configure, typename Statistics>
RunResult runEigenApi(const SpMat& A, double normA, const Eigen::MatrixXd& B1, const Eigen::MatrixXd& B3,
                      Configure&& configure, Statistics&& statistics)
{
  RunResult r;
  SolverType solver;
  configure(solver);
  {
    bench::HeapPhase heap;
    r.value[Analyze] = bench::timeMs([&] { solver.analyzePattern(A); });
    r.value[FactorFirst] = bench::timeMs([&] { solver.factorize(A); });
    r.value[PeakHeap] = double(heap.peak());
    r.value[FactorHeap] = double(heap.retained());
  }
  if (solver.info() != Eigen::Success)
  {
    r.message = "factorize() reported info() = " + std::to_string(int(solver.info()));
    return r;
  }
  r.value[Refactor] = bench::timeMs([&] { solver.factorize(A); });
  if (solver.info() != Eigen::Success)
  {
    r.message = "second factorize() reported info() = " + std::to_string(int(solver.info()));
    return r;
  }
  Eigen::MatrixXd X1, X3;
  r.value[Solve1] = bench::timeMs([&] { X1 = solver.solve(B1); });
  r.value[Solve3] = bench::timeMs([&] { X3 = solver.solve(B3); });
  statistics(solver, r);
  r.backwardError = std::max(backwardError(A, normA, X1, B1), backwardError(A, normA, X3, B3));
  r.ok = r.backwardError <= kBackwardErrorTolerance;
  if (!r.ok) r.message = "backward error " + std::to_string(r.backwardError) + " above tolerance";
  return r;
}

/** One run of UpdatableSupernodalLLT with the fixed permutation and \a threads threads. */
RunResult runOurs(const SpMat& A, double normA, const Permutation& perm, int threads, const Eigen::MatrixXd& B1,
                  const Eigen::MatrixXd& B3)
{
  return runEigenApi<OursLLT>(
      A, normA, B1, B3,
      [&](OursLLT& llt) {
        llt.ordering().permutation = &perm;
        llt.setThreadCount(threads);
      },
      [](const OursLLT& llt, RunResult& r) {
        r.storedNnzL = double(llt.nonZerosL());
        r.exactNnzL = std::numeric_limits<double>::quiet_NaN();
        r.supernodes = double(llt.supernodeCount());
        r.flops = llt.factorizationFlops();
      });
}

/** One run of SimplicialLLT with the fixed permutation (single-threaded). */
RunResult runSimplicial(const SpMat& A, double normA, const Eigen::MatrixXd& B1, const Eigen::MatrixXd& B3)
{
  return runEigenApi<SimplicialPeer>(
      A, normA, B1, B3, [](SimplicialPeer&) {},
      [](const SimplicialPeer& llt, RunResult& r) {
        const SpMat& L = llt.matrixL().nestedExpression();
        r.storedNnzL = r.exactNnzL = double(L.nonZeros());
        r.supernodes = std::numeric_limits<double>::quiet_NaN();
        r.flops = squaredColumnCounts(L);
      });
}

/** One run of CHOLMOD supernodal with the fixed permutation (threads: OpenBLAS's setting). */
RunResult runCholmod(const SpMat& A, double normA, const Permutation& perm, const Eigen::MatrixXd& B1,
                     const Eigen::MatrixXd& B3)
{
  RunResult r;
  try
  {
    bench::CholmodSupernodal chol;
    bool positive = false;
    {
      bench::HeapPhase heap;
      r.value[Analyze] = bench::timeMs([&] { chol.analyze(A, perm.indices().data()); });
      r.value[FactorFirst] = bench::timeMs([&] { positive = chol.factorize(A); });
      r.value[PeakHeap] = double(heap.peak());
      r.value[FactorHeap] = double(heap.retained());
      r.selfReportedPeakHeap = double(chol.reportedPeakMemory());
    }
    if (!positive)
    {
      r.message = "cholmod_factorize: matrix not positive definite";
      return r;
    }
    r.value[Refactor] = bench::timeMs([&] { positive = chol.factorize(A); });
    if (!positive)
    {
      r.message = "second cholmod_factorize: matrix not positive definite";
      return r;
    }
    Eigen::MatrixXd X1, X3;
    r.value[Solve1] = bench::timeMs([&] { X1 = chol.solve(B1); });
    r.value[Solve3] = bench::timeMs([&] { X3 = chol.solve(B3); });
    r.storedNnzL = chol.storedNonZerosL();
    r.exactNnzL = chol.exactNonZerosL();
    r.supernodes = double(chol.supernodeCount());
    r.flops = chol.flops();
    r.backwardError = std::max(backwardError(A, normA, X1, B1), backwardError(A, normA, X3, B3));
    r.ok = r.backwardError <= kBackwardErrorTolerance;
    if (!r.ok) r.message = "backward error " + std::to_string(r.backwardError) + " above tolerance";
  }
  catch (const std::exception& e)
  {
    r.message = e.what();
  }
  return r;
}

/** Runs \a solver once, turning any exception into a failed result. */
RunResult runSolver(Solver solver, const SpMat& A, double normA, const Permutation& perm, int threads,
                    const Eigen::MatrixXd& B1, const Eigen::MatrixXd& B3)
{
  try
  {
    switch (solver)
    {
    case Ours: return runOurs(A, normA, perm, threads, B1, B3);
    case Cholmod: return runCholmod(A, normA, perm, B1, B3);
    default: return runSimplicial(A, normA, B1, B3);
    }
  }
  catch (const std::exception& e)
  {
    RunResult r;
    r.message = std::string("exception: ") + e.what();
    return r;
  }
}

/** Sets OpenBLAS's thread count (CHOLMOD's only parallelism); a no-op with another BLAS. */
void setBlasThreads(int threads)
{
  if (openblas_set_num_threads) openblas_set_num_threads(threads);
}

// ---- output -------------------------------------------------------------------------------------

/** \returns \a v with \a precision decimals, "-" for NaN. */
std::string formatValue(double v, int precision)
{
  if (std::isnan(v)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", precision, v);
  return buffer;
}

/** \returns \a v rounded, with thousands separators, "-" for NaN. */
std::string formatCount(double v)
{
  if (std::isnan(v)) return "-";
  std::string digits = std::to_string(static_cast<long long>(std::llround(v)));
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i)
  {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

/** \returns \a v in scientific notation with two digits, "-" for NaN. */
std::string formatScientific(double v)
{
  if (std::isnan(v)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.1e", v);
  return buffer;
}

/** \returns a/b as "0.00x", "-" if either is NaN or b is 0. */
std::string formatRatio(double a, double b)
{
  if (std::isnan(a) || std::isnan(b) || b == 0) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.2fx", a / b);
  return buffer;
}

/** Prints one table row: label, three solver cells, two ratio cells. */
void printRow(const std::string& label, const std::array<std::string, SolverCount>& cells, const std::string& r1,
              const std::string& r2)
{
  std::printf("  %-40s %13s %13s %13s %14s %16s\n", label.c_str(), cells[0].c_str(), cells[1].c_str(),
              cells[2].c_str(), r1.c_str(), r2.c_str());
}

/** Prints one row whose three values are compared by ratio (ours/CHOLMOD, ours/Simplicial). */
void printComparedRow(const std::string& label, const std::array<double, SolverCount>& v,
                      const std::function<std::string(double)>& format)
{
  printRow(label, {format(v[Ours]), format(v[Cholmod]), format(v[Simplicial])}, formatRatio(v[Ours], v[Cholmod]),
           formatRatio(v[Ours], v[Simplicial]));
}

/** Prints the table of one thread count. */
void printTable(int threads, const std::array<SolverSummary, SolverCount>& s, std::size_t reps)
{
  auto median = [&](Metric m) {
    std::array<double, SolverCount> v;
    for (int k = 0; k < SolverCount; ++k) v[std::size_t(k)] = s[std::size_t(k)].samples[m].median();
    return v;
  };
  auto perSolver = [&](const std::function<double(int)>& f) {
    std::array<double, SolverCount> v;
    for (int k = 0; k < SolverCount; ++k) v[std::size_t(k)] = f(k);
    return v;
  };
  auto last = [&](int k) -> const RunResult& { return s[std::size_t(k)].last; };
  const auto ms = [](double v) { return formatValue(v, 2); };
  const auto mib = [](double v) { return formatValue(v / (1024.0 * 1024.0), 1); };

  std::printf("\n== threads = %d: ours setThreadCount(%d); CHOLMOD openblas_set_num_threads(%d); "
              "SimplicialLLT is single-threaded at every thread count\n",
              threads, threads, threads);
  std::printf("   medians over %zu repetitions; ratios < 1 mean ours is faster/smaller\n", reps);
  printRow("", {"ours", "CHOLMOD", "Simplicial"}, "ours/CHOLMOD", "ours/Simplicial");
  printComparedRow("symbolic analysis [ms]", median(Analyze), ms);
  printComparedRow("numeric factorization, first [ms]", median(FactorFirst), ms);
  printComparedRow("numeric factorization, repeated [ms]", median(Refactor), ms);
  printComparedRow("solve, 1 rhs [ms]", median(Solve1), ms);
  printComparedRow("solve, 3 rhs [ms]", median(Solve3), ms);
  printComparedRow("peak heap, analyze+factorize [MiB]", median(PeakHeap), mib);
  printComparedRow("heap held after factorize [MiB]", median(FactorHeap), mib);
  printComparedRow("nnz(L) stored, relaxed zeros incl.", perSolver([&](int k) { return last(k).storedNnzL; }),
                   formatCount);
  printComparedRow("nnz(L) exact (no amalgamation)", perSolver([&](int k) { return last(k).exactNnzL; }), formatCount);
  printComparedRow("supernodes", perSolver([&](int k) { return last(k).supernodes; }), formatCount);
  const auto flopFormat = [](double v) { return formatValue(v, 1); };
  printComparedRow("factorization flops, own count [Mflop]", perSolver([&](int k) { return last(k).flops / 1e6; }),
                   flopFormat);
  const std::array<double, SolverCount> refactor = median(Refactor);
  const auto rateFormat = [](double v) { return formatValue(v, 2); };
  printComparedRow("GFlop/s: own flops / repeated factor.",
                   perSolver([&](int k) { return last(k).flops / (refactor[std::size_t(k)] * 1e6); }), rateFormat);
  printComparedRow("GFlop/s: CHOLMOD Common.fl / same time",
                   perSolver([&](int k) { return last(Cholmod).flops / (refactor[std::size_t(k)] * 1e6); }), rateFormat);
  printRow("backward error (worst rhs, worst rep)",
           {formatScientific(s[Ours].worstBackwardError), formatScientific(s[Cholmod].worstBackwardError),
            formatScientific(s[Simplicial].worstBackwardError)},
           "", "");
  std::printf("  (cross-check: CHOLMOD's own peak count, Common.memory_usage: %s MiB)\n",
              mib(s[Cholmod].last.selfReportedPeakHeap).c_str());
  for (int k = 0; k < SolverCount; ++k)
    if (!s[std::size_t(k)].ok) std::printf("  FAILED %s: %s\n", kSolverNames[k], s[std::size_t(k)].message.c_str());
}

/** Appends the rows of one thread count to the CSV (one per solver and metric). */
void writeCsvRows(std::ostream& csv, const std::string& mesh, Eigen::Index n, Eigen::Index faces, Eigen::Index nnzA,
                  int threads, const std::array<SolverSummary, SolverCount>& s)
{
  for (int k = 0; k < SolverCount; ++k)
  {
    const SolverSummary& x = s[std::size_t(k)];
    auto row = [&](const char* metric, double median, double lo, double hi, std::size_t count) {
      csv << mesh << ',' << n << ',' << faces << ',' << nnzA << ',' << threads << ',' << kSolverNames[k] << ','
          << metric << ',' << median << ',' << lo << ',' << hi << ',' << count << '\n';
    };
    for (int m = 0; m < MetricCount; ++m)
    {
      const bench::Samples& samples = x.samples[std::size_t(m)];
      row(kMetricKeys[m], samples.median(), samples.min(), samples.max(), samples.size());
    }
    row("nnz_L_stored", x.last.storedNnzL, x.last.storedNnzL, x.last.storedNnzL, 1);
    row("nnz_L_exact", x.last.exactNnzL, x.last.exactNnzL, x.last.exactNnzL, 1);
    row("supernodes", x.last.supernodes, x.last.supernodes, x.last.supernodes, 1);
    row("flops", x.last.flops, x.last.flops, x.last.flops, 1);
    row("backward_error_worst", x.worstBackwardError, x.worstBackwardError, x.worstBackwardError, 1);
    row("ok", x.ok ? 1 : 0, x.ok ? 1 : 0, x.ok ? 1 : 0, 1);
  }
}

// ---- command line -------------------------------------------------------------------------------

/** Prints the command-line help. */
void printUsage()
{
  std::cout << "usage: bench_factorize [--mesh=PATH | --icosphere=S | --grid=N] [--reps=N] [--threads=1,2]\n"
               "                       [--csv=FILE] [--smoke]\n"
               "  --mesh=PATH     OFF mesh, plain or gzip (default: " UC_BENCH_DEFAULT_MESH ")\n"
               "  --icosphere=S   generated icosphere with S subdivisions (S=7: 163,842 vertices)\n"
               "  --grid=N        generated N x N planar grid\n"
               "  --reps=N        timed repetitions per solver and thread count, after one warm-up (default 5)\n"
               "  --threads=LIST  comma-separated thread counts (default 1,2)\n"
               "  --csv=FILE      also write the results as CSV (one row per mesh/threads/solver/metric)\n"
               "  --smoke         tiny generated grid, 1 repetition: a quick correctness run for CI\n";
}

/** Parses a whole string as an int. \returns false if it is not one. */
bool parseInt(const std::string& text, int& value)
{
  try
  {
    std::size_t used = 0;
    value = std::stoi(text, &used);
    return used == text.size();
  }
  catch (const std::exception&)
  {
    return false;
  }
}

/** \returns false on a malformed command line (after printing why). */
bool parseOptions(int argc, char** argv, Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const std::string::size_type eq = arg.find('=');
    const std::string key = arg.substr(0, eq), value = eq == std::string::npos ? std::string() : arg.substr(eq + 1);
    bool good = true;
    if (key == "--mesh" && !value.empty()) options.mesh = value;
    else if (key == "--icosphere") good = parseInt(value, options.icosphere) && options.icosphere >= 0 && options.icosphere <= 10;
    else if (key == "--grid") good = parseInt(value, options.grid) && options.grid >= 2;
    else if (key == "--reps") good = parseInt(value, options.reps) && options.reps >= 1;
    else if (key == "--csv" && !value.empty()) options.csv = value;
    else if (key == "--smoke" && eq == std::string::npos) options.smoke = true;
    else if (key == "--threads")
    {
      options.threads.clear();
      std::stringstream list(value);
      std::string item;
      while (good && std::getline(list, item, ','))
      {
        int t = 0;
        good = parseInt(item, t) && t >= 1;
        options.threads.push_back(t);
      }
      good = good && !options.threads.empty();
    }
    else if (key == "--help" || key == "-h")
    {
      printUsage();
      std::exit(0);
    }
    else good = false;
    if (!good)
    {
      std::cerr << "bench_factorize: bad argument '" << arg << "'\n";
      printUsage();
      return false;
    }
  }
  if (options.smoke)
  {
    options.grid = 40;
    options.reps = 1;
  }
  return true;
}

/** \returns the CPU model name from /proc/cpuinfo. */
std::string cpuModel()
{
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

} // namespace

/** Entry point: see the usage text at the top of this file. */
int main(int argc, char** argv)
{
  bench::ensureOpenBlasCore(argv);  // (may re-execute with OPENBLAS_CORETYPE: see BlasCore.h)
  Options options;
  if (!parseOptions(argc, argv, options)) return 2;

  // ---- mesh and matrix ----------------------------------------------------------------------
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string meshName;
  if (options.grid > 0)
  {
    Eigen::gridMesh(options.grid, options.grid, V, F);
    meshName = "grid" + std::to_string(options.grid) + "x" + std::to_string(options.grid);
  }
  else if (options.icosphere >= 0)
  {
    Eigen::icosphereMesh(options.icosphere, V, F);
    meshName = "icosphere" + std::to_string(options.icosphere);
  }
  else
  {
    std::string error;
    if (!Eigen::readOFF(options.mesh, V, F, &error))
    {
      std::cerr << "bench_factorize: " << error << "\n";
      return 1;
    }
    meshName = options.mesh.substr(options.mesh.find_last_of('/') + 1);
  }
  SpMat A = Eigen::cotanLaplacian<double, int>(V, F);
  SpMat shift(A.rows(), A.cols());
  shift.setIdentity();
  A += kShift * shift;
  A.makeCompressed();
  const double normA = infinityNorm(A);

  // ---- one METIS permutation for everybody -------------------------------------------------
  Permutation perm;
  const double orderingMs = bench::timeMs([&] { Eigen::MetisOrdering<int>()(A, perm); });
  Ordering::setDefault(&perm);

  // Right-hand sides: fixed seed, uniform in [-1, 1].
  std::mt19937 generator(20240611u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd B1(A.rows(), 1), B3(A.rows(), 3);
  for (Eigen::Index i = 0; i < B1.size(); ++i) B1.data()[i] = uniform(generator);
  for (Eigen::Index i = 0; i < B3.size(); ++i) B3.data()[i] = uniform(generator);

  std::printf("bench_factorize: %s\n", options.smoke ? "SMOKE run (tiny grid, 1 repetition)" : "factorization benchmark");
  std::printf("  mesh     %s: %s vertices, %s triangles\n", meshName.c_str(), formatCount(double(V.rows())).c_str(),
              formatCount(double(F.rows())).c_str());
  std::printf("  matrix   cotan Laplacian + %.0e I, n = %s, nnz = %s (both triangles stored; solvers read Lower)\n", kShift,
              formatCount(double(A.rows())).c_str(), formatCount(double(A.nonZeros())).c_str());
  std::printf("  ordering METIS via Eigen::MetisOrdering<int> on the full matrix, %.1f ms, computed once and given to "
              "all three solvers\n",
              orderingMs);
  std::printf("  machine  %s, %u hardware threads; BLAS %s\n", cpuModel().c_str(), std::thread::hardware_concurrency(),
              openblas_get_config ? openblas_get_config() : "(not OpenBLAS: thread count not controlled)");
  std::printf("           %s\n", bench::openBlasCoreNote().c_str());
  std::printf("  heap     %s\n", bench::heapTrackingActive() ? "tracked by malloc interposition (usable sizes, all threads)"
                                                            : "NOT tracked (allocator interposition inactive)");
  std::printf("  runs     per thread count: one untimed warm-up run of each solver, then %d timed repetitions,\n"
              "           solvers interleaved (each repetition starts with a different solver)\n",
              options.reps);

  std::ofstream csv;
  if (!options.csv.empty())
  {
    csv.open(options.csv);
    if (!csv)
    {
      std::cerr << "bench_factorize: cannot write " << options.csv << "\n";
      return 1;
    }
    csv << "mesh,vertices,faces,nnz_A,threads,solver,metric,median,min,max,count\n";
    csv.precision(10);
    csv << meshName << ',' << V.rows() << ',' << F.rows() << ',' << A.nonZeros() << ",1,METIS,ordering_ms,"
        << orderingMs << ',' << orderingMs << ',' << orderingMs << ",1\n";
  }

  bool allOk = true;
  for (int threads : options.threads)
  {
    setBlasThreads(threads);
    std::array<SolverSummary, SolverCount> summary;
    // Warm-up: first-touch costs (BLAS buffers, page faults) must not land on whichever solver runs first.
    for (int k = 0; k < SolverCount; ++k)
    {
      const RunResult warm = runSolver(Solver(k), A, normA, perm, threads, B1, B3);
      if (!warm.ok && summary[std::size_t(k)].ok)
      {
        summary[std::size_t(k)].ok = false;
        summary[std::size_t(k)].message = "warm-up: " + warm.message;
      }
    }
    for (int rep = 0; rep < options.reps; ++rep)
      for (int i = 0; i < SolverCount; ++i)
      {
        const int k = (rep + i) % SolverCount;
        summary[std::size_t(k)].add(runSolver(Solver(k), A, normA, perm, threads, B1, B3));
      }
    printTable(threads, summary, std::size_t(options.reps));
    if (csv.is_open()) writeCsvRows(csv, meshName, V.rows(), F.rows(), A.nonZeros(), threads, summary);
    for (const SolverSummary& s : summary) allOk = allOk && s.ok;
  }

  std::printf("\nnotes: nnz(L) stored = entries on and below the diagonal including relaxed-supernode zeros "
              "(CHOLMOD: per supernode nrows*ncols - ncols*(ncols-1)/2, i.e. L->xsize without the upper triangles "
              "of the diagonal blocks; ours: nonZerosL()). nnz(L) exact = CHOLMOD Common.lnz / SimplicialLLT's L.\n"
              "       flops: ours factorizationFlops(); CHOLMOD Common.fl and Simplicial = sum of squared column "
              "counts of the exact factor.\n");
  if (csv.is_open()) std::printf("CSV written to %s\n", options.csv.c_str());
  std::printf("%s\n", allOk ? "result: all solvers OK" : "result: FAILURE (see FAILED lines above)");
  return allOk ? 0 : 1;
}
