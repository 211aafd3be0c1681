// Timing: a monotonic stopwatch, a sample set with median/min/max, and interleaved repeated runs of
// several methods with the median run of each, for benchmarks that report medians over repetitions
// (the machines are noisy; a median ignores the odd slow run). Every run starts with cold caches
// (evictCaches()): the last-level cache here holds a whole factor, so without it a method would be
// timed on whatever the method before it left in the cache. Cold caches are not enough: each round
// runs the methods in a fresh random order, because what the method before left behind still
// shows through them. With the fixed cyclic order of stops up to 47, our insertDofs always ran
// right after the Woodbury peer and our removeDofs right after the insertion; on igea (`--seams=3
// --repeats=3 --lengths=5,100`) swapping the two in that order moved both the update and the solve
// times by 10-60%: the insertion 2.05 -> 1.55 ms at l = 5 and 19.9 -> 18.0 ms at l = 100, its solve
// 11.1 -> 6.9 and 9.7 -> 7.6 ms, and the removal's solve the other way (7.8 -> 9.0 ms at l = 100).

#ifndef UPDATABLE_CHOLESKY_BENCH_TIMING_H
#define UPDATABLE_CHOLESKY_BENCH_TIMING_H

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <string>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <unistd.h>

namespace bench {

/** Writes and reads a buffer of twice the last-level cache (at least 64 MiB, at most 1 GiB), so
    that whatever a method timed next touches comes from memory, as after any other work. */
inline void evictCaches()
{
  static std::vector<long> buffer;
  if (buffer.empty())
  {
    long bytes = 0;
#ifdef _SC_LEVEL3_CACHE_SIZE
    bytes = sysconf(_SC_LEVEL3_CACHE_SIZE);
#endif
    bytes = std::min(std::max(2 * bytes, 64L << 20), 1L << 30);
    buffer.assign(std::size_t(bytes) / sizeof(long), 0);
  }
  static volatile long sink = 0;
  long sum = 0;
  for (std::size_t i = 0; i < buffer.size(); i += 8)  // one write and one read per cache line
  {
    buffer[i] += 1;
    sum += buffer[i];
  }
  sink = sink + sum;
}

/** Measures wall-clock time with std::chrono::steady_clock. */
class Stopwatch
{
public:
  /** Starts the stopwatch. */
  Stopwatch() : m_start(std::chrono::steady_clock::now()) {}
  /** Restarts the stopwatch. */
  void restart() { m_start = std::chrono::steady_clock::now(); }
  /** \returns milliseconds since construction or the last restart(). */
  double ms() const { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_start).count(); }

private:
  std::chrono::steady_clock::time_point m_start;
};

/** \returns the milliseconds that one call of \a f takes. */
template <typename F>
double timeMs(F&& f)
{
  Stopwatch watch;
  f();
  return watch.ms();
}

/** A set of measurements of one quantity, summarised by median, minimum and maximum. */
class Samples
{
public:
  /** Adds one measurement. */
  void add(double value) { m_values.push_back(value); }
  /** \returns the number of measurements. */
  std::size_t size() const { return m_values.size(); }
  /** \returns the median (mean of the two middle values for an even count), NaN if empty. */
  double median() const
  {
    if (m_values.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::vector<double> sorted = m_values;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t mid = sorted.size() / 2;
    return sorted.size() % 2 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
  }
  /** \returns the smallest measurement, NaN if empty. */
  double min() const
  {
    return m_values.empty() ? std::numeric_limits<double>::quiet_NaN() : *std::min_element(m_values.begin(), m_values.end());
  }
  /** \returns the largest measurement, NaN if empty. */
  double max() const
  {
    return m_values.empty() ? std::numeric_limits<double>::quiet_NaN() : *std::max_element(m_values.begin(), m_values.end());
  }

private:
  std::vector<double> m_values;
};

/** Times, with cold caches, one solve of \a b by an UpdatableSupernodalLLT \a solver with its
    forward substitution not kept (setSolveCaching(false): a whole solve) into \a full, and with
    it kept, the same b solved a second time (the backward pass and the copies only) into
    \a repeated. Solve caching is on afterwards. */
template <typename Solver, typename Rhs>
void timeFullAndRepeatedSolve(Solver& solver, const Rhs& b, Samples& full, Samples& repeated)
{
  Rhs x;
  solver.setSolveCaching(false);
  evictCaches();
  full.add(timeMs([&] { x = solver.solve(b); }));
  solver.setSolveCaching(true);
  x = solver.solve(b);
  evictCaches();
  repeated.add(timeMs([&] { x = solver.solve(b); }));
}

/** Runs \a count methods on one input \a repeats times, interleaved (each round runs every method
    once, in an order drawn at random from \a seed and the round, each after evictCaches()), through
    runOne(k), which returns a Sample (with `ok`, `message` and `ms`) or throws. \returns per method
    the run of median time among those that succeeded (the upper median for an even count), or its
    first run when none did. */
template <typename Sample, typename RunOne>
std::vector<Sample> interleavedMedianRuns(std::size_t count, int repeats, int seed, RunOne&& runOne)
{
  std::vector<std::vector<Sample> > runs(count);
  std::vector<std::size_t> order(count);
  for (int repeat = 0; repeat < repeats; ++repeat)
  {
    for (std::size_t i = 0; i < count; ++i) order[i] = i;
    std::mt19937 generator(0x9e3779b9u * unsigned(seed) + 7919u * unsigned(repeat) + 1u);
    for (std::size_t i = count; i > 1; --i)  // (Fisher-Yates by hand: std::shuffle's draws differ by library)
      std::swap(order[i - 1], order[std::size_t(generator() % i)]);
    for (std::size_t k : order)
    {
      runs[k].emplace_back();
      evictCaches();
      try
      {
        runs[k].back() = runOne(k);
      }
      catch (const std::exception& e)
      {
        runs[k].back().ok = false;
        runs[k].back().message = std::string("exception: ") + e.what();
      }
    }
  }
  std::vector<Sample> samples(count);
  for (std::size_t k = 0; k < count; ++k)
  {
    std::vector<Sample*> good;
    for (Sample& r : runs[k])
      if (r.ok) good.push_back(&r);
    std::sort(good.begin(), good.end(), [](const Sample* a, const Sample* b) { return a->ms < b->ms; });
    samples[k] = std::move(good.empty() ? runs[k].front() : *good[good.size() / 2]);
  }
  return samples;
}

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_TIMING_H
