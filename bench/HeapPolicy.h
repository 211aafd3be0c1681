// HeapPolicy: keeps the memory a benchmark frees inside the process, so that no method is timed on
// the page-table work that returning memory to the kernel, and touching it again, costs.
//
// glibc gives freed memory back to the kernel (the top of the heap above M_TRIM_THRESHOLD, 128 KiB
// by default, and every chunk it served by mmap) and the next allocation faults it in again, page by
// page. On the paravirtualised machines these benchmarks run on, a page fault costs about 10 us
// (40 times a bare-metal one; pageFaultMicroseconds() measures it), so a method that allocates
// after another one (or itself, in an earlier call) freed memory was charged tens of milliseconds
// that depend on what ran before it: bunny, 2000-vertex seams, insertDofs took 44-50 ms in the
// interleaved benchmark and 21-23 ms alone. retainFreedMemory() turns trimming off and serves
// allocations up to 32 MiB from the heap (mallopt), for every method in the process alike: a long-
// running application (an interactive editor) reaches the same state once its heap has grown.
//
// With UC_BENCH_HUGE_PAGES=1 the heap is also backed by transparent huge pages where the kernel
// offers them on request (useHugePagesForHeap(): the benchmark re-executes itself once with
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1, so that malloc asks for them with madvise). With 4 KiB
// pages the cost of a pass over a large factor depends on what else the process holds:
// armadillo_loop2, one solve (a pass over L): 33-35 ms with our solver alone in the process, 50-86
// ms with the peers' factors and dense blocks resident, with no page fault in either (nor helper
// threads: OMP/OpenBLAS at one thread change nothing; nor background work: half a second's pause
// before each run changes nothing); with huge pages, 36-42 ms in both. Huge pages are not the
// default: on bunny's 2000-vertex cuts they made insertDofs slower (18.0-19.9 ms against 16.1-17.0
// with 4 KiB pages, removeDofs unchanged), which the comparison of the two must not be charged.
// Set UC_BENCH_MALLOC_DEFAULTS=1 to keep glibc's defaults (neither policy).

#ifndef UPDATABLE_CHOLESKY_BENCH_HEAPPOLICY_H
#define UPDATABLE_CHOLESKY_BENCH_HEAPPOLICY_H

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <sys/mman.h>
#include <unistd.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace bench {

/** \returns the microseconds one first touch of a fresh 4 KiB page costs here (16 MiB mapped anew,
  * touched once per page, unmapped), or a negative value when it cannot be measured. */
inline double pageFaultMicroseconds()
{
  const std::size_t bytes = std::size_t(16) << 20;
  const long page = sysconf(_SC_PAGESIZE);
  if (page <= 0) return -1;
  void* map = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (map == MAP_FAILED) return -1;
  volatile char* p = static_cast<volatile char*>(map);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < bytes; i += std::size_t(page)) p[i] = 1;
  const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  munmap(map, bytes);
  return us / double(bytes / std::size_t(page));
}

/** \returns whether UC_BENCH_MALLOC_DEFAULTS asks for glibc's defaults. */
inline bool mallocDefaultsAsked()
{
  const char* keep = std::getenv("UC_BENCH_MALLOC_DEFAULTS");
  return keep && *keep && std::string(keep) != "0";
}

/** When UC_BENCH_HUGE_PAGES=1, re-executes this program once with glibc.malloc.hugetlb=1 added to
  * GLIBC_TUNABLES (see the top of this file), unless it is there already or UC_BENCH_MALLOC_DEFAULTS
  * is set. Call first thing in main(); returns when nothing is to be done or the re-execution
  * failed. */
inline void useHugePagesForHeap(char** argv)
{
#if defined(__GLIBC__)
  const char* asked = std::getenv("UC_BENCH_HUGE_PAGES");
  if (!asked || std::string(asked) != "1") return;
  if (mallocDefaultsAsked() || std::getenv("UC_BENCH_HUGE_PAGES_REEXEC")) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::string value = tunables ? tunables : "";
  if (value.find("glibc.malloc.hugetlb") != std::string::npos) return;
  value += std::string(value.empty() ? "" : ":") + "glibc.malloc.hugetlb=1";
  setenv("GLIBC_TUNABLES", value.c_str(), 1);
  setenv("UC_BENCH_HUGE_PAGES_REEXEC", "1", 1);  // (once: a glibc without the tunable ignores it)
  std::fflush(nullptr);
  execv("/proc/self/exe", argv);  // (only returns on failure: then run with 4 KiB pages)
  if (tunables) setenv("GLIBC_TUNABLES", tunables, 1); else unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

/** \returns whether malloc was asked for transparent huge pages (GLIBC_TUNABLES) and the kernel
  * grants them on request or always (/sys/kernel/mm/transparent_hugepage/enabled). */
inline bool heapHugePages()
{
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (!tunables || std::string(tunables).find("glibc.malloc.hugetlb=1") == std::string::npos) return false;
  std::FILE* file = std::fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!file) return false;
  char line[128] = {0};
  const bool read = std::fgets(line, sizeof line, file) != nullptr;
  std::fclose(file);
  const std::string mode = read ? line : "";
  return mode.find("[always]") != std::string::npos || mode.find("[madvise]") != std::string::npos;
}

/** Keeps freed memory in the process (see the top of this file). \returns whether the policy is
  * in effect (false without glibc, or when UC_BENCH_MALLOC_DEFAULTS is set). */
inline bool retainFreedMemory()
{
  if (mallocDefaultsAsked()) return false;
#if defined(__GLIBC__)
  const bool trim = mallopt(M_TRIM_THRESHOLD, 1 << 30) == 1;  // (never reached: the heap keeps its top)
  const bool mapped = mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1; // (glibc's largest: bigger blocks are mapped)
  return trim && mapped;
#else
  return false;
#endif
}

/** A line for the benchmark's header: the heap policy in effect and the measured page-fault cost. */
inline std::string heapPolicyNote(bool retained)
{
  char text[320];
  std::snprintf(text, sizeof text,
                "heap: %s, %s; a first touch of a fresh 4 KiB page costs %.2f us here",
                retained ? "freed memory kept in the process (no trim, mmap above 32 MiB only; HeapPolicy.h)"
                         : "glibc's defaults (freed memory returned to the kernel)",
                heapHugePages() ? "transparent huge pages on request (glibc.malloc.hugetlb=1)" : "4 KiB pages",
                pageFaultMicroseconds());
  return text;
}

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_HEAPPOLICY_H
