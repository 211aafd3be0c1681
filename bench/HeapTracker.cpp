// HeapTracker: replaces malloc, free, calloc, realloc and the aligned allocators of the benchmark
// binary with thin wrappers that forward to glibc (__libc_malloc & co.) and count the usable size of
// every block, to measure peak heap use per phase. The executable's definitions take precedence over
// libc's for every shared library (CHOLMOD, OpenBLAS, libstdc++'s operator new), as glibc documents
// for replacing malloc. glibc only; counters are atomic, so allocations from any thread are seen.

#include "HeapTracker.h"

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <malloc.h>

extern "C" {
void* __libc_malloc(std::size_t size);
void __libc_free(void* ptr);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* ptr, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void* __libc_valloc(std::size_t size);
void* __libc_pvalloc(std::size_t size);
}

namespace {

std::atomic<std::int64_t> g_inUse{0};
std::atomic<std::int64_t> g_peak{0};
std::atomic<std::int64_t> g_base{0};

inline void countAllocation(void* ptr)
{
  if (!ptr) return;
  const std::int64_t size = std::int64_t(malloc_usable_size(ptr));
  const std::int64_t now = g_inUse.fetch_add(size, std::memory_order_relaxed) + size;
  std::int64_t peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
}

inline void countRelease(void* ptr)
{
  if (ptr) g_inUse.fetch_sub(std::int64_t(malloc_usable_size(ptr)), std::memory_order_relaxed);
}

inline bool validAlignment(std::size_t alignment)
{
  return alignment >= sizeof(void*) && (alignment & (alignment - 1)) == 0;
}

} // namespace

extern "C" {

/** malloc, counted. */
void* malloc(std::size_t size)
{
  void* ptr = __libc_malloc(size);
  countAllocation(ptr);
  return ptr;
}

/** free, counted. */
void free(void* ptr)
{
  countRelease(ptr);
  __libc_free(ptr);
}

/** calloc, counted. */
void* calloc(std::size_t count, std::size_t size)
{
  void* ptr = __libc_calloc(count, size);
  countAllocation(ptr);
  return ptr;
}

/** realloc, counted (old block released, new block allocated). */
void* realloc(void* ptr, std::size_t size)
{
  const std::int64_t before = ptr ? std::int64_t(malloc_usable_size(ptr)) : 0;
  void* moved = __libc_realloc(ptr, size);
  if (moved)
  {
    // Account the old block as released and the new one as allocated, so the peak sees the new size.
    g_inUse.fetch_sub(before, std::memory_order_relaxed);
    countAllocation(moved);
  }
  else if (ptr && size == 0)
    g_inUse.fetch_sub(before, std::memory_order_relaxed); // glibc frees the block for realloc(p, 0)
  return moved;
}

/** memalign, counted. */
void* memalign(std::size_t alignment, std::size_t size)
{
  void* ptr = __libc_memalign(alignment, size);
  countAllocation(ptr);
  return ptr;
}

/** aligned_alloc, counted. */
void* aligned_alloc(std::size_t alignment, std::size_t size)
{
  return memalign(alignment, size);
}

/** posix_memalign, counted. */
int posix_memalign(void** out, std::size_t alignment, std::size_t size)
{
  if (!validAlignment(alignment)) return EINVAL;
  void* ptr = __libc_memalign(alignment, size);
  if (!ptr) return ENOMEM;
  countAllocation(ptr);
  *out = ptr;
  return 0;
}

/** valloc, counted. */
void* valloc(std::size_t size)
{
  void* ptr = __libc_valloc(size);
  countAllocation(ptr);
  return ptr;
}

/** pvalloc, counted. */
void* pvalloc(std::size_t size)
{
  void* ptr = __libc_pvalloc(size);
  countAllocation(ptr);
  return ptr;
}

} // extern "C"

namespace bench {

std::int64_t heapBytesInUse() { return g_inUse.load(std::memory_order_relaxed); }

void heapResetPeak()
{
  const std::int64_t now = g_inUse.load(std::memory_order_relaxed);
  g_base.store(now, std::memory_order_relaxed);
  g_peak.store(now, std::memory_order_relaxed);
}

std::int64_t heapPeakSinceReset()
{
  return g_peak.load(std::memory_order_relaxed) - g_base.load(std::memory_order_relaxed);
}

bool heapTrackingActive()
{
  const std::int64_t before = heapBytesInUse();
  void* volatile probe = std::malloc(1000);
  const bool seen = heapBytesInUse() >= before + 1000;
  std::free(probe);
  return seen;
}

} // namespace bench
