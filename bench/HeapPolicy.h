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
// Set UC_BENCH_MALLOC_DEFAULTS=1 to keep glibc's defaults.

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

/** Keeps freed memory in the process (see the top of this file). \returns whether the policy is
  * in effect (false without glibc, or when UC_BENCH_MALLOC_DEFAULTS is set). */
inline bool retainFreedMemory()
{
  const char* keep = std::getenv("UC_BENCH_MALLOC_DEFAULTS");
  if (keep && *keep && std::string(keep) != "0") return false;
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
  char text[256];
  std::snprintf(text, sizeof text,
                "heap: %s; a first touch of a fresh 4 KiB page costs %.2f us here",
                retained ? "freed memory kept in the process (no trim, mmap above 32 MiB only; HeapPolicy.h)"
                         : "glibc's defaults (freed memory returned to the kernel)",
                pageFaultMicroseconds());
  return text;
}

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_HEAPPOLICY_H
