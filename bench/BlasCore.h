// BlasCore: makes OpenBLAS run the kernels of the CPU it runs on, for every method of a benchmark.
//
// OpenBLAS picks its kernels at run time from the CPU model. On a model it does not know (the
// virtualised Xeons these benchmarks run on report a generic "Intel Xeon Processor" with AVX-512)
// Debian's build falls back to its oldest x86-64 kernels, "Prescott" (SSE3, no FMA), and every
// BLAS call, CHOLMOD's and ours, runs two to four times slower than the hardware allows. The
// peers must each get their best form, so ensureOpenBlasCore() re-executes the benchmark once with
// OPENBLAS_CORETYPE set to the newest kernel family that the CPU supports (SkylakeX with AVX-512,
// Haswell with AVX2 and FMA) when OpenBLAS detected an older one and the user did not choose.
// openBlasCore() says which kernels run; the benchmarks print it.

#ifndef UPDATABLE_CHOLESKY_BENCH_BLASCORE_H
#define UPDATABLE_CHOLESKY_BENCH_BLASCORE_H

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

extern "C" char* openblas_get_corename(void) __attribute__((weak));

namespace bench {

/** \returns the name of the kernels OpenBLAS runs, or "not OpenBLAS". */
inline std::string openBlasCore()
{
  return openblas_get_corename ? std::string(openblas_get_corename()) : std::string("not OpenBLAS");
}

/** \returns the OpenBLAS kernel family for this CPU's vector units, or null if it has no AVX2. */
inline const char* bestOpenBlasCore()
{
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return nullptr;
}

/** Re-executes this program with OPENBLAS_CORETYPE set (see the file comment) when OpenBLAS fell
    back to kernels without AVX2 on a CPU that has it. Call first thing in main(); returns when
    nothing is to be done or the re-execution failed. */
inline void ensureOpenBlasCore(char** argv)
{
  if (std::getenv("OPENBLAS_CORETYPE") || !openblas_get_corename) return;
  const char* best = bestOpenBlasCore();
  if (!best) return;
  std::string detected = openBlasCore();
  for (char& c : detected) c = char(std::tolower(static_cast<unsigned char>(c)));
  const char* const old[] = {"prescott", "core2", "penryn", "dunnington", "nehalem", "atom", "sandybridge", "katmai",
                             "coppermine", "northwood", "banias", "unknown"};
  bool fallback = false;
  for (const char* name : old) fallback = fallback || detected == name;
  if (!fallback) return;
  setenv("OPENBLAS_CORETYPE", best, 1);
  setenv("UPDATABLE_CHOLESKY_BENCH_DETECTED_CORE", openBlasCore().c_str(), 1);
  std::fflush(nullptr);
  execv("/proc/self/exe", argv);  // (only returns on failure: then run with the detected kernels)
  unsetenv("OPENBLAS_CORETYPE");
}

/** One line for the benchmark's header: which OpenBLAS kernels run, and why. */
inline std::string openBlasCoreNote()
{
  std::string note = "OpenBLAS kernels: " + openBlasCore();
  if (const char* detected = std::getenv("UPDATABLE_CHOLESKY_BENCH_DETECTED_CORE"))
    note += std::string(" (OPENBLAS_CORETYPE set by the benchmark: OpenBLAS detected ") + detected +
            " on this CPU, which has " + (bestOpenBlasCore() ? bestOpenBlasCore() : "?") + "-class vector units)";
  else if (std::getenv("OPENBLAS_CORETYPE"))
    note += " (OPENBLAS_CORETYPE set by the user)";
  return note;
}

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_BLASCORE_H
