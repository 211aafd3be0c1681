// BenchReport: the small helpers the seam benchmarks (bench_remove_dofs, bench_insert_dofs) share
// for their command lines, tables and CSV files: number formatting, mesh names, integer parsing,
// the infinity norm of a sparse matrix, comma-separated option values, the loop over the meshes.

#ifndef UPDATABLE_CHOLESKY_BENCH_BENCHREPORT_H
#define UPDATABLE_CHOLESKY_BENCH_BENCHREPORT_H

#include <Eigen/SparseCore>
#include <Eigen/UpdatableCholesky>
#include <unsupported/Eigen/MeshTools>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <sstream>
#include <limits>
#include <string>
#include <vector>

namespace bench {

/** \returns \a v with \a precision decimals, "-" for NaN. */
/** The vector instruction set this benchmark was compiled for (our code and Eigen's; CHOLMOD's
  * dense work runs in OpenBLAS, which picks its kernels at run time). */
inline const char* compiledInstructionSet() {
#if defined(__AVX512F__)
  return "AVX-512";
#elif defined(__AVX2__) && defined(__FMA__)
  return "AVX2 + FMA";
#elif defined(__AVX__)
  return "AVX";
#else
  return "generic x86-64 (SSE2)";
#endif
}

inline std::string fmt(double v, int precision = 2)
{
  if (std::isnan(v)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", precision, v);
  return buffer;
}

/** \returns a time in ms with about three significant digits. */
inline std::string fmtMs(double v)
{
  if (std::isnan(v)) return "-";
  return fmt(v, v < 1 ? 3 : v < 10 ? 2 : v < 100 ? 1 : 0);
}

/** \returns a / b as "0.42x", "-" when either is missing or b is 0. */
inline std::string fmtRatio(double a, double b)
{
  if (std::isnan(a) || std::isnan(b) || b == 0) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.2fx", a / b);
  return buffer;
}

/** \returns a fraction with three decimals, or in exponent form below 0.001. */
inline std::string fmtFraction(double v)
{
  if (std::isnan(v)) return "-";
  char buffer[64];
  if (v < 0.001) std::snprintf(buffer, sizeof(buffer), "%.1e", v);
  else std::snprintf(buffer, sizeof(buffer), "%.3f", v);
  return buffer;
}

/** \returns a count with thousands separators ("692,138"). */
inline std::string fmtCount(double v)
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

/** \returns \a v for a CSV cell: 10 significant digits, "NaN" when missing. */
inline std::string csvNumber(double v)
{
  if (std::isnan(v)) return "NaN";
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

/** \returns "bunny" for ".../bunny.off.gz". */
inline std::string meshStem(const std::string& path)
{
  std::string name = path.substr(path.find_last_of('/') + 1);
  for (const char* suffix : {".gz", ".off", ".OFF"})
  {
    const std::string s = suffix;
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) name.resize(name.size() - s.size());
  }
  return name;
}

/** Parses a whole string as an int. \returns false (value unspecified) if it is not one. */
inline bool parseInt(const std::string& text, int& value)
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

/** \returns a short name of an update route of UpdatableSupernodalLLT. */
inline std::string routeName(Eigen::UpdateRoute route)
{
  switch (route)
  {
  case Eigen::UpdateRoute::Automatic: return "Automatic";
  case Eigen::UpdateRoute::PartialRefactorization: return "Partial";
  case Eigen::UpdateRoute::LowRank: return "LowRank";
  case Eigen::UpdateRoute::Refactorization: return "Refactor";
  case Eigen::UpdateRoute::Mixed: return "Mixed";
  default: return "route" + std::to_string(int(route));
  }
}

/** \returns ||A||_inf (max absolute column sum of a symmetric A stored in full). */
template <typename SparseMatrixType>
double infinityNorm(const SparseMatrixType& A)
{
  double norm = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
  {
    double sum = 0;
    for (typename SparseMatrixType::InnerIterator it(A, j); it; ++it) sum += std::abs(it.value());
    norm = std::max(norm, sum);
  }
  return norm;
}

/** \returns ||A x - b||_inf on the rows outside B (inB[i] != 0 on B) over ||A||_inf ||x||_inf +
  * ||b||_inf: the backward error of the Dirichlet system A_II x_I = b_I - A_IB g_B; infinity when x
  * differs from g on the dofs \a seam of B. */
template <typename SparseMatrixType>
double dirichletBackwardError(const SparseMatrixType& A, double normA, const std::vector<char>& inB,
                              const std::vector<int>& seam, const Eigen::VectorXd& x, const Eigen::VectorXd& b,
                              const Eigen::VectorXd& g)
{
  for (int j : seam)
    if (!(std::abs(x[j] - g[j]) <= 1e-14 * std::max(1.0, std::abs(g[j])))) return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd r = A * x - b;
  double worst = 0;
  for (Eigen::Index i = 0; i < r.size(); ++i)
    if (!inB[std::size_t(i)]) worst = std::max(worst, std::abs(r[i]));
  const double e = worst / (normA * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>());
  return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
}

/** Calls \a take on every item of the comma-separated \a value. \returns false when an item is
  * empty, \a take returns false, or there is no item. */
inline bool forEachListItem(const std::string& value, const std::function<bool(const std::string&)>& take)
{
  std::stringstream list(value);
  std::string item;
  int count = 0;
  while (std::getline(list, item, ','))
  {
    if (item.empty() || !take(item)) return false;
    ++count;
  }
  return count > 0;
}

/** Runs \a run(name, V, F) on a generated grid x grid mesh (if grid > 0) and on every mesh file of
  * \a paths (readMesh: OFF, OBJ, PLY, plain or gzip). A file that cannot be read or a run that
  * throws is reported (\a program names the benchmark) and counts as a failure.
  * \returns true when every mesh was read and every run returned true. */
inline bool forEachMesh(const char* program, int grid, const std::vector<std::string>& paths,
                        const std::function<bool(const std::string&, const Eigen::MatrixXd&, const Eigen::MatrixXi&)>& run)
{
  std::vector<std::pair<std::string, std::string>> inputs; // name, path ("" = grid)
  if (grid > 0) inputs.push_back({"grid" + std::to_string(grid) + "x" + std::to_string(grid), ""});
  for (const std::string& m : paths) inputs.push_back({m.substr(m.find_last_of('/') + 1), m});
  bool allOk = true;
  for (const auto& input : inputs)
  {
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    std::string error;
    if (input.second.empty()) Eigen::gridMesh(grid, grid, V, F);
    else if (!Eigen::readMesh(input.second, V, F, &error))
    {
      std::fprintf(stderr, "%s: %s\n", program, error.c_str());
      allOk = false;
      continue;
    }
    try
    {
      allOk = run(input.first, V, F) && allOk;
    }
    catch (const std::exception& e)
    {
      std::printf("  FAILED %s: %s\n", input.first.c_str(), e.what());
      allOk = false;
    }
  }
  return allOk;
}

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_BENCHREPORT_H
