// HeapTracker: how many heap bytes the process holds and their peak, so a benchmark can report the
// peak memory of one phase (e.g. a solver's analyze + factorize). The counting itself is done by
// HeapTracker.cpp, which replaces malloc and its relatives in the binary it is linked into (glibc).

#ifndef UPDATABLE_CHOLESKY_BENCH_HEAPTRACKER_H
#define UPDATABLE_CHOLESKY_BENCH_HEAPTRACKER_H

#include <cstdint>

namespace bench {

/** \returns the bytes currently allocated through malloc, calloc, realloc, the aligned allocators
  * and operator new (usable sizes as reported by malloc_usable_size, all threads). */
std::int64_t heapBytesInUse();

/** Starts a measurement: the peak is reset to the bytes in use now. */
void heapResetPeak();

/** \returns the highest number of bytes in use since the last heapResetPeak(), minus the bytes
  * that were in use at that call; i.e. the extra heap the measured phase needed at its worst. */
std::int64_t heapPeakSinceReset();

/** \returns whether allocations really go through the counting functions (false when another
  * allocator, e.g. a sanitizer's, took precedence); the numbers above are meaningless then. */
bool heapTrackingActive();

/** RAII helper: resets the peak at construction; peak() and retained() read the phase's numbers. */
class HeapPhase
{
public:
  /** Starts the phase (resets the peak counter). */
  HeapPhase() : m_start(heapBytesInUse()) { heapResetPeak(); }
  /** \returns the extra bytes the phase held at its peak. */
  std::int64_t peak() const { return heapPeakSinceReset(); }
  /** \returns the extra bytes still held now compared with the start of the phase. */
  std::int64_t retained() const { return heapBytesInUse() - m_start; }

private:
  std::int64_t m_start;
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_HEAPTRACKER_H
