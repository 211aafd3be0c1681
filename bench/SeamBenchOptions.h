// SeamBenchOptions: the command line the seam benchmarks (bench_remove_dofs, bench_insert_dofs)
// share: meshes or a generated grid, seam lengths, seams per length, threads, seed, CSV folder and
// the smoke run of CI. Each benchmark names itself, its CSV files, plot script and default meshes.

#ifndef UPDATABLE_CHOLESKY_BENCH_SEAMBENCHOPTIONS_H
#define UPDATABLE_CHOLESKY_BENCH_SEAMBENCHOPTIONS_H

#include "BenchReport.h"

#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace bench {

/** What a seam benchmark runs on and how. */
struct SeamBenchOptions
{
  std::vector<std::string> meshes;
  int grid = 0;
  std::vector<int> lengths{1, 5, 20, 100, 500, 2000};
  int seams = 5, threads = 1;
  int repeats = 1;  ///< runs of every method per seam; the seam's sample is their median
  unsigned seed = 20240611u;
  std::string csvDir;
  bool smoke = false;
  bool oursOnly = false;  ///< run only this library's methods (the peers' columns stay empty)
  bool diagonalShift = false;  ///< regularize by 1e-8 diag(L) instead of 1e-8 I (bench_insert_dofs)
};

/** How one seam benchmark names itself: program, CSV stem (<stem>_<mesh>.csv), plot script, and
  * its default meshes (comma-separated). */
struct SeamBenchNames
{
  const char* program;
  const char* csvStem;
  const char* plotScript;
  const char* defaultMeshes;
};

/** Prints the usage text of the benchmark \a names. */
inline void printSeamBenchUsage(const SeamBenchNames& names)
{
  const std::string pad(std::string(names.program).size(), ' ');
  std::cout << "usage: " << names.program << " [--mesh=PATH[,PATH...]]... [--grid=N] [--lengths=1,5,20,100,500,2000]\n"
            << "       " << pad << " [--seams=5] [--repeats=1] [--threads=1] [--seed=S] [--csv-dir=DIR] [--ours-only]\n"
            << "       " << pad << " [--diagonal-shift] [--smoke]\n"
            << "  --mesh=PATH     OFF mesh, plain or gzip; repeatable or comma-separated\n"
            << "                  (default: " << names.defaultMeshes << ")\n"
            << "  --grid=N        a generated N x N planar grid instead\n"
            << "  --lengths=LIST  seam lengths in vertices (default 1,5,20,100,500,2000)\n"
            << "  --seams=N       seams per length; medians are over them (default 5)\n"
            << "  --repeats=R     runs of every method per seam, interleaved; the seam counts their median (default 1)\n"
            << "  --threads=N     threads of every solver: ours setThreadCount, OpenBLAS for CHOLMOD (default 1)\n"
            << "  --seed=S        base seed of the seams (default 20240611)\n"
            << "  --csv-dir=DIR   write " << names.csvStem << "_<mesh>.csv (medians), _samples.csv and _setup.csv there;\n"
            << "                  plot with " << names.plotScript << " DIR\n"
            << "  --ours-only     (bench_insert_dofs) only this library's methods: many repeats of the insert/remove\n"
            << "                  ratio on a large mesh without the peers' seconds per seam (their columns print '-')\n"
            << "  --diagonal-shift (bench_insert_dofs) Laplacian + 1e-8 diag(Laplacian) instead of + 1e-8 I: a cut then\n"
            << "                  glues back exactly (its copies' rows and columns added onto their origins give the\n"
            << "                  uncut matrix), so the change of a cut is one-signed; with I each origin's diagonal differs\n"
            << "  --smoke         tiny grid, l = 1,5, one seam: a quick correctness run for CI\n";
}

/** Parses the command line into \a o; prints the usage and returns false on a bad argument
  * (--help prints it and exits). */
inline bool parseSeamBenchOptions(int argc, char** argv, const SeamBenchNames& names, SeamBenchOptions& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const std::string::size_type eq = arg.find('=');
    const std::string key = arg.substr(0, eq), value = eq == std::string::npos ? std::string() : arg.substr(eq + 1);
    bool good = true;
    auto splitList = [&](const std::function<bool(const std::string&)>& take) { good = forEachListItem(value, take); };
    if (key == "--mesh") splitList([&](const std::string& s) { o.meshes.push_back(s); return true; });
    else if (key == "--grid") good = parseInt(value, o.grid) && o.grid >= 2;
    else if (key == "--lengths")
    {
      o.lengths.clear();
      splitList([&](const std::string& s) {
        o.lengths.push_back(0);
        return parseInt(s, o.lengths.back()) && o.lengths.back() >= 1;
      });
    }
    else if (key == "--seams") good = parseInt(value, o.seams) && o.seams >= 1;
    else if (key == "--repeats") good = parseInt(value, o.repeats) && o.repeats >= 1;
    else if (key == "--threads") good = parseInt(value, o.threads) && o.threads >= 1;
    else if (key == "--seed")
    {
      int s = 0;
      good = parseInt(value, s);
      o.seed = unsigned(s);
    }
    else if (key == "--csv-dir" && !value.empty()) o.csvDir = value;
    else if (key == "--smoke" && eq == std::string::npos) o.smoke = true;
    else if (key == "--ours-only" && eq == std::string::npos) o.oursOnly = true;
    else if (key == "--diagonal-shift" && eq == std::string::npos) o.diagonalShift = true;
    else if (key == "--help" || key == "-h")
    {
      printSeamBenchUsage(names);
      std::exit(0);
    }
    else good = false;
    if (!good)
    {
      std::cerr << names.program << ": bad argument '" << arg << "'\n";
      printSeamBenchUsage(names);
      return false;
    }
  }
  if (o.smoke)
  {
    o.meshes.clear();
    o.grid = 24;
    o.lengths = {1, 5};
    o.seams = 1;
    o.repeats = 1;
  }
  if (o.meshes.empty() && o.grid == 0)
    forEachListItem(names.defaultMeshes, [&](const std::string& s) { o.meshes.push_back(s); return true; });
  return true;
}

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_SEAMBENCHOPTIONS_H
