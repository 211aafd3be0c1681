// Timing: a monotonic stopwatch and a sample set with median/min/max, for benchmarks that report
// medians over repetitions (the machines are noisy; a median ignores the odd slow run).

#ifndef UPDATABLE_CHOLESKY_BENCH_TIMING_H
#define UPDATABLE_CHOLESKY_BENCH_TIMING_H

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace bench {

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

/** Of several runs of one method on one input (each with `ok` and `ms`), the run of median time
    among those that succeeded (the upper median for an even count); the first run when none did. */
template <typename Sample>
Sample medianRun(std::vector<Sample> runs)
{
  std::vector<Sample> good;
  for (Sample& r : runs)
    if (r.ok) good.push_back(std::move(r));
  if (good.empty()) return std::move(runs.front());
  std::sort(good.begin(), good.end(), [](const Sample& a, const Sample& b) { return a.ms < b.ms; });
  return std::move(good[good.size() / 2]);
}

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_TIMING_H
