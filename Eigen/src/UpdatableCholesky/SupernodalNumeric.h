// SupernodalNumeric.h — numeric supernodal factorization (paper §3.1 and §3.4, Algorithm 2 on
// supernodes), in multifrontal form: every supernode S assembles its columns of the input
// matrix and the update matrices of its children (extend-add through precomputed relative
// positions), factors its diagonal block (potrf), solves for the rows below (trsm) and forms its
// own update matrix U_S = -L21 L21^H (herk) for its parent. Update matrices live on per-thread
// stacks (postorder makes their lifetimes nested).
//
// Parallelism: the supernodal tree is split into independent subtrees of balanced work
// (SubtreeSchedule), factored at once by worker threads with single-threaded BLAS; the
// supernodes above them (the top separators) follow with multi-threaded BLAS. A
// refactorization of some supernodes only (the updates) splits the forest those supernodes
// form in the same way (ListSchedule).
//
// Failure: the first pivot that is not positive and finite stops the factorization; the
// permuted column is reported. The factor is then incomplete and must not be used to solve.

#ifndef EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_NUMERIC_H
#define EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_NUMERIC_H

#include <algorithm>
#include <atomic>
#include <cstring>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Which supernodes each thread factors: workers take whole subtrees (each subtree
  * of root r is the supernode range [firstDescendant[r], r]); the rest ("top") is factored
  * afterwards in postorder with threaded BLAS. */
struct SubtreeSchedule {
  int threads = 0;
  std::vector<std::vector<Index> > workerRoots;  ///< per worker, subtree roots in increasing order
  std::vector<Index> top;                         ///< remaining supernodes, increasing
};

/** \internal How many entries ahead an assembly map's scattered loads are prefetched. */
constexpr Index AssemblyPrefetchDistance = 16;

/** \internal Below this many flops a factorization runs on one thread. */
constexpr double MinParallelFlops = 2e7;

/** \internal The greedy split of makeSchedule() and makeListSchedule(): the subtrees rooted at
  * \a frontier (work per root in \a work, \a total in all) go, heaviest first, to the least
  * loaded of \a threads bins; while the bins differ by more than 10% (and the frontier still
  * holds half the work), the heaviest root is flagged in \a isTop and replaced by its children
  * (\a expand(root, children) writes them into the empty \a children and returns false for a
  * leaf, which ends the split). \returns the bins (roots per worker). */
template <typename Expand>
std::vector<std::vector<Index> > balanceSubtrees(std::vector<Index> frontier, const std::vector<double>& work,
                                                 double total, int threads, std::vector<char>& isTop, Expand&& expand) {
  std::vector<std::vector<Index> > bins;
  std::vector<Index> children;
  for (int iteration = 0; iteration < 4096; ++iteration) {
    std::sort(frontier.begin(), frontier.end(), [&](Index a, Index b) { return work[a] > work[b]; });
    bins.assign(threads, std::vector<Index>());
    std::vector<double> load(threads, 0.0);
    double frontierWork = 0;
    for (Index s : frontier) {
      const int t = int(std::min_element(load.begin(), load.end()) - load.begin());
      load[t] += work[s];
      bins[t].push_back(s);
      frontierWork += work[s];
    }
    const double maxLoad = *std::max_element(load.begin(), load.end());
    if (maxLoad <= 1.1 * frontierWork / threads || frontierWork < 0.5 * total) break;
    const Index heaviest = frontier.front();
    children.clear();
    if (!expand(heaviest, children)) break;
    isTop[heaviest] = 1;
    frontier.erase(frontier.begin());
    frontier.insert(frontier.end(), children.begin(), children.end());
  }
  return bins;
}

/** \internal Splits the tree for \a threads workers: repeatedly replaces the heaviest subtree
  * by its children until a greedy assignment of subtrees to workers is balanced to 10%. */
template <typename Scalar, typename StorageIndex>
SubtreeSchedule makeSchedule(const SupernodalFactor<Scalar, StorageIndex>& f, int threads) {
  SubtreeSchedule sched;
  sched.threads = threads;
  const Index ns = f.count();
  if (threads <= 1 || ns < 2) {
    for (Index s = 0; s < ns; ++s) sched.top.push_back(s);
    return sched;
  }
  std::vector<double> work(ns);
  for (Index s = 0; s < ns; ++s) work[s] = f.nodes[s].flops() + 1.0;
  for (Index s = 0; s < ns; ++s)
    if (f.parent[s] != -1) work[f.parent[s]] += work[s];
  double total = 0;
  std::vector<Index> frontier;
  for (Index s = 0; s < ns; ++s)
    if (f.parent[s] == -1) {
      frontier.push_back(s);
      total += work[s];
    }
  if (total < MinParallelFlops) {  // starting threads would cost more than they save
    for (Index s = 0; s < ns; ++s) sched.top.push_back(s);
    return sched;
  }
  std::vector<char> isTop(ns, 0);
  std::vector<std::vector<Index> > bins =
      balanceSubtrees(frontier, work, total, threads, isTop, [&](Index s, std::vector<Index>& children) {
        for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) children.push_back(c);
        return !children.empty();
      });
  for (auto& bin : bins) std::sort(bin.begin(), bin.end());
  sched.workerRoots = bins;
  for (Index s = 0; s < ns; ++s)
    if (isTop[s]) sched.top.push_back(s);
  return sched;
}

/** \internal Work of a front counted beside its flops when the threads are balanced: a small
  * front costs a few microseconds of calls and cache misses whatever its flops. */
constexpr double FrontOverheadFlops = 2.5e4;

/** \internal Which entries of a refactorization list (supernodes, increasing, each after the
  * listed ones below it) each thread recomputes. Within the list, a supernode's parent is its
  * parent in the tree when that is listed too; the list is a forest under that relation. Workers
  * take whole subtrees of the forest, balanced by work as makeSchedule() splits the whole tree;
  * the rest ("top") follows in order with threaded BLAS. */
struct ListSchedule {
  Index workers = 0;         ///< 0: the whole list on the calling thread
  std::vector<Index> owner;  ///< per list entry, its worker, or -1 for the top
};

/** \internal Splits \a list for \a threads workers (see ListSchedule); a list of less than
  * MinParallelFlops of work stays on one thread. \a position: scratch by supernode, all zero on
  * entry and on return. */
template <typename Scalar, typename StorageIndex>
ListSchedule makeListSchedule(const SupernodalFactor<Scalar, StorageIndex>& f, const std::vector<Index>& list,
                              int threads, std::vector<Index>& position) {
  ListSchedule sched;
  const Index count = Index(list.size());
  if (threads <= 1 || count < 2) return sched;
  if (Index(position.size()) < f.count()) position.resize(f.count(), 0);
  for (Index k = 0; k < count; ++k) position[list[k]] = k + 1;
  std::vector<Index> up(count);  // the parent's entry in the list, or -1
  std::vector<double> work(count);
  for (Index k = 0; k < count; ++k) {
    const Index p = f.parent[list[k]];
    up[k] = p == -1 ? Index(-1) : position[p] - 1;
    work[k] = f.nodes[list[k]].flops() + FrontOverheadFlops;
  }
  for (Index k = 0; k < count; ++k) position[list[k]] = 0;
  std::vector<Index> childStart(count + 1, 0), children(count);
  for (Index k = 0; k < count; ++k)  // (children come before their parents)
    if (up[k] >= 0) {
      eigen_assert(up[k] > k && "makeListSchedule: a listed parent before its child");
      work[up[k]] += work[k];
      ++childStart[up[k] + 1];
    }
  double total = 0;
  std::vector<Index> frontier;
  for (Index k = 0; k < count; ++k) {
    childStart[k + 1] += childStart[k];
    if (up[k] < 0) {
      frontier.push_back(k);
      total += work[k];
    }
  }
  if (total < MinParallelFlops) return sched;
  {
    std::vector<Index> fill(childStart.begin(), childStart.end() - 1);
    for (Index k = 0; k < count; ++k)
      if (up[k] >= 0) children[fill[up[k]]++] = k;
  }
  std::vector<char> isTop(count, 0);
  const std::vector<std::vector<Index> > bins =
      balanceSubtrees(frontier, work, total, threads, isTop, [&](Index k, std::vector<Index>& below) {
        below.assign(children.begin() + childStart[k], children.begin() + childStart[k + 1]);
        return !below.empty();
      });
  sched.workers = threads;
  sched.owner.assign(count, -1);
  for (int t = 0; t < threads; ++t)
    for (Index k : bins[t]) sched.owner[k] = t;
  for (Index k = count - 1; k >= 0; --k)  // (parents first) below a subtree's root, its worker
    if (!isTop[k] && sched.owner[k] < 0 && up[k] >= 0) sched.owner[k] = sched.owner[up[k]];
  return sched;
}

/** \internal A stack of update matrices (one per thread). Offsets, not pointers, so that it
  * may grow. */
template <typename Scalar>
struct UpdateStack {
  UpdateBuffer<Scalar> buffer;  ///< (not zeroed when it grows: each update matrix is written before it is read)
  Index top = 0;
  std::vector<Scalar> front, update;  ///< scratch of a reduced front (kept rows and columns only)
  std::vector<Index> kept;            ///< its rows in the supernode
  Index push(Index size) {
    const Index offset = top;
    top += size;
    if (top > Index(buffer.size())) buffer.resize((std::max)(top, Index(buffer.size() * 3 / 2)));
    return offset;
  }
};

/** \internal True when a supernode of \a rows rows, \a keptRows of them not removed, is factored on
  * its kept rows and columns alone (a reduced front: a quarter or more of its rows removed). */
inline bool isReducedFront(Index rows, Index keptRows) { return 4 * (rows - keptRows) >= rows; }

/** \internal The rows of \a node whose dofs are not removed go to \a kept; true for a reduced front. */
template <typename Scalar, typename StorageIndex>
bool isReduced(const Supernode<Scalar, StorageIndex>& node, const char* removed, std::vector<Index>& kept) {
  kept.clear();
  const Index nr = node.nrows();
  for (Index k = 0; k < nr; ++k)
    if (!removed[node.rows[k]]) kept.push_back(k);
  return isReducedFront(nr, Index(kept.size()));
}

/** \internal Dense flops of factoring \a node, on its kept rows and columns when it is a reduced
  * front (\a removed: flags by permuted column, or null). */
template <typename Scalar, typename StorageIndex>
double frontFlops(const Supernode<Scalar, StorageIndex>& node, const char* removed) {
  if (!removed) return node.flops();
  const Index nr = node.nrows();
  Index kr = 0, kc = 0;
  for (Index k = 0; k < nr; ++k)
    if (!removed[node.rows[k]]) {
      ++kr;
      kc += k < node.ncols;
    }
  if (!isReducedFront(nr, kr)) return node.flops();
  const double c = double(kc), b = double(kr - kc);
  return c * c * c / 3.0 + b * c * c + b * b * c;
}

/** \internal What a numeric factorization reads: the input's value array, the shift of the
  * diagonal (d_ii -> offset + scale*d_ii, as Eigen's setShift), and optionally the removed (Dirichlet) dofs in the permuted numbering,
  * whose rows and columns are those of the identity. */
template <typename Scalar>
struct NumericInput {
  typedef typename NumTraits<Scalar>::Real RealScalar;
  const Scalar* values = nullptr;
  RealScalar offset = 0, scale = 1;
  const char* removed = nullptr;  ///< removed[j] != 0: permuted column j is a unit column
};

/** \internal Numeric factorization of a SupernodalFactor, in full or of a set of supernodes. */
template <typename Scalar, typename StorageIndex>
class SupernodalNumeric {
 public:
  typedef typename NumTraits<Scalar>::Real RealScalar;
  typedef SupernodalFactor<Scalar, StorageIndex> Factor;
  typedef Supernode<Scalar, StorageIndex> Node;
  typedef NumericInput<Scalar> Input;
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;

  /** Keep every supernode's update matrix after a factorization (the cache that lets
    * refactorize() recompute a supernode from its children without touching clean subtrees).
    * Takes effect at the next factorize(). */
  void setCacheUpdates(bool cache) {
    if (!cache) {
      m_cache.clear();
      m_pending.clear();
    }
    m_cacheUpdates = cache;
  }
  /** True when the update matrices of the last factorization are cached. */
  bool hasCachedUpdates() const { return m_cacheUpdates && m_cacheValid; }

  /** Factors all supernodes. \returns -1 on success or the permuted column of the first bad
    * pivot. */
  Index factorize(Factor& f, const Input& in, int threads) {
    if (m_schedule.threads != threads || Index(m_location.size()) != f.count()) {
      m_schedule = makeSchedule(f, threads);
      m_location.assign(f.count(), Location());
    }
    m_cacheValid = false;
    if (m_cacheUpdates) {
      m_cache.resize(f.count());
      m_pending.resize(f.count());
    }
    // Every block is allocated before the first update matrix, in postorder: the blocks then lie
    // in order in memory rather than between the cached update matrices, and the solve streams
    // through them (6% faster solves on armadillo_loop2 with caching on, in-process A/B).
    for (auto& node : f.nodes)
      if (node.values.rows() != node.nrows() || node.values.cols() != node.ncols)
        node.values.resize(node.nrows(), node.ncols);
    const Index workers = Index(m_schedule.workerRoots.size());
    m_stacks.resize(workers + 1);
    for (auto& stack : m_stacks) stack.top = 0;
    m_failed.store(-1);
    const int previousBlas = setBlasThreads(workers > 0 ? 1 : threads);
    if (workers > 0) {
      std::vector<std::thread> pool;
      for (Index w = 1; w < workers; ++w)
        pool.emplace_back([&, w] { factorSubtrees(f, in, w); });
      factorSubtrees(f, in, 0);
      for (auto& t : pool) t.join();
      setBlasThreads(threads);
    }
    for (Index s : m_schedule.top)
      if (!factorNode(f, s, in, workers)) break;
    if (previousBlas > 0) setBlasThreads(previousBlas);
    m_cacheValid = m_cacheUpdates && m_failed.load() < 0;
    return m_failed.load();
  }

  /** Recomputes the supernodes in \a dirty (increasing, closed under taking parents) from the
    * input and their children's update matrices, the clean ones taken from the cache (which
    * must hold the update matrices of every clean child of a dirty supernode, as after a
    * factorize() or refactorize() with caching on, even a failed refactorize() of the same
    * dirty set). Gives the same values as a full factorize() of the same input. With several
    * \a threads, independent subtrees of the list are recomputed at once (ListSchedule).
    * \returns -1 on success or the permuted column of the first bad pivot; on failure the
    * cache is invalid and the factor incomplete. */
  Index refactorize(Factor& f, const Input& in, const std::vector<Index>& dirty, int threads) {
    eigen_assert(m_cacheUpdates && Index(m_cache.size()) == f.count() && "refactorize() needs cached update matrices");
    m_failed.store(-1);
    m_cacheValid = false;
    const ListSchedule sched = makeListSchedule(f, dirty, threads, m_listPosition);
    const Index workers = sched.workers, count = Index(dirty.size());
    if (Index(m_stacks.size()) < workers + 1) m_stacks.resize(workers + 1);  // (scratch only: the update matrices are cached)
    const int previousBlas = setBlasThreads(workers > 0 ? 1 : threads);
    if (workers > 0) {  // independent subtrees of the list at once, then the rest with threaded BLAS
      auto work = [&](Index w) {
        for (Index k = 0; k < count; ++k)
          if (sched.owner[k] == w && !factorNode(f, dirty[k], in, w)) return;
      };
      std::vector<std::thread> pool;
      for (Index w = 1; w < workers; ++w) pool.emplace_back(work, w);
      work(0);
      for (auto& t : pool) t.join();
      setBlasThreads(threads);
    }
    for (Index k = 0; k < count; ++k)
      if (workers == 0 || sched.owner[k] < 0)
        if (!factorNode(f, dirty[k], in, workers)) break;
    if (previousBlas > 0) setBlasThreads(previousBlas);
    m_cacheValid = m_failed.load() < 0;
    return m_failed.load();
  }

  /** The cached update matrices (supernode s: below() × below(), lower triangle), for updates
    * that change them in place. */
  std::vector<CachedUpdate<Scalar> >& cache() { return m_cache; }

  /** Defers the correction U_s += sign · W W^H (sign +1 or -1) of the cached update matrix of
    * supernode \a s (W: below() × r) until the cache is read; most such corrections are never
    * read, because the supernode is recomputed first (e.g. restoreDofs() after removeDofs()).
    * Applied at once when they pile up. */
  void deferCorrection(const Factor& f, Index s, Dense& W, RealScalar sign = RealScalar(1)) {
    auto& list = m_pending[s];
    list.emplace_back();
    list.back().W.swap(W);
    list.back().sign = sign;
    Index columns = 0;
    for (const Correction& c : list) columns += c.W.cols();
    if (2 * columns >= f.nodes[s].below()) applyCorrections(f, s);
  }
  /** A deferred correction U += sign · W W^H. */
  struct Correction {
    Dense W;
    RealScalar sign;
  };
  /** The deferred corrections of supernode \a s (their rows of removed dofs are zeroed with U's). */
  std::vector<Correction>& pendingCorrections(Index s) { return m_pending[s]; }
  /** Applies the deferred corrections of supernode \a s to its cached update matrix. \returns the flops. */
  double applyCorrections(const Factor& f, Index s) {
    m_cache[s].layOut();
    return applyCorrectionsTo(m_pending[s], f.nodes[s].below(), m_cache[s].data());
  }
  /** Applies the corrections \a list (emptied) to the update matrix \a U (m × m, lower triangle),
    * e.g. a previous update matrix set aside with its corrections by an update. \returns the flops. */
  static double applyCorrectionsTo(std::vector<Correction>& list, Index m, Scalar* U) {
    double flops = 0;
    for (const Correction& c : list) {
      eigen_assert(c.W.rows() == m && "a deferred correction of another shape than its update matrix");
      herkLower(m, c.W.cols(), c.sign, c.W.data(), m, U, m);
      flops += double(m) * double(m) * double(c.W.cols());
    }
    list.clear();
    return flops;
  }
  /** Makes the rows and columns of removed dofs (\a removed: flags by permuted column) in
    * supernode \a s exactly those of the identity: zero rows and unit columns in its block, zero
    * rows and columns in its cached update matrix and in its deferred corrections. The updates'
    * folds keep them so up to rounding only (a rotation or a compression may leave 1e-17 where a
    * zero was), and a solve with Dirichlet values must return them unchanged. \returns true
    * when the block changed (its solves change with it). */
  bool clearRemoved(Factor& f, Index s, const char* removed) {
    Node& node = f.nodes[s];
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    Scalar* L = node.values.data();
    if (Index(m_cache.size()) > s) m_cache[s].layOut();
    const bool cached = m > 0 && Index(m_cache.size()) > s && Index(m_cache[s].size()) == m * m;
    Scalar* U = cached ? m_cache[s].data() : nullptr;
    bool changed = false;
    for (Index p = 0; p < nr; ++p) {
      if (!removed[node.rows[p]]) continue;
      for (Index j = 0; j < (std::min)(p, nc); ++j) {
        changed = changed || L[p + j * nr] != Scalar(0);
        L[p + j * nr] = Scalar(0);
      }
      if (p < nc) {
        for (Index i = p + 1; i < nr && !changed; ++i) changed = L[i + p * nr] != Scalar(0);
        changed = changed || L[p + p * nr] != Scalar(1);
        std::fill(L + p * nr, L + (p + 1) * nr, Scalar(0));
        L[p + p * nr] = Scalar(1);
        continue;
      }
      const Index u = p - nc;
      if (U)
        for (Index i = 0; i < m; ++i) U[u + i * m] = U[i + u * m] = Scalar(0);
      if (Index(m_pending.size()) > s)
        for (Correction& c : m_pending[s]) c.W.row(u).setZero();
    }
    return changed;
  }

  /** Drops the deferred corrections of supernode \a s (its cached matrix is being put back). */
  void discardCorrections(Index s) {
    if (Index(m_pending.size()) > s) m_pending[s].clear();
  }

  /** Bytes of update-matrix workspace currently held. */
  Index workspaceBytes() const {
    Index b = 0;
    for (const auto& s : m_stacks) b += Index(s.buffer.capacity() * sizeof(Scalar));
    for (const auto& u : m_cache) b += Index(u.capacity() * sizeof(Scalar));
    for (const auto& list : m_pending)
      for (const Correction& c : list) b += Index(c.W.size() * sizeof(Scalar));
    return b;
  }

  /** The factor's structure changed (dofs inserted or merged): the thread schedule is rebuilt
    * by the next factorize(). */
  void structureChanged() { m_schedule = SubtreeSchedule(); }

  /** Declares the cache valid again after a failed refactorize() whose dirty supernodes (values
    * and update matrices) were put back by the caller. */
  void cacheRestored() { m_cacheValid = m_cacheUpdates; }

  /** Forgets the schedule and releases the workspace (after a new analysis). */
  void reset() {
    m_schedule = SubtreeSchedule();
    m_location.clear();
    m_stacks.clear();
    m_cache.clear();
    m_pending.clear();
    m_cacheValid = false;
  }

 private:
  struct Location {
    Index stack = -1, offset = 0;
  };

  void factorSubtrees(Factor& f, const Input& in, Index worker) {
    for (Index root : m_schedule.workerRoots[worker])
      for (Index s = f.firstDescendant[root]; s <= root; ++s)
        if (!factorNode(f, s, in, worker)) return;
  }

  /** Scatters the supernode's columns of the input into its zeroed block: diagonal shifted, and
    * with removed dofs' rows and columns replaced by those of the identity. */
  static void assemble(Node& node, const Input& in) {
    const Index nr = node.nrows(), nc = node.ncols;
    Scalar* L = node.values.data();
    std::fill(L, L + nr * nc, Scalar(0));
    const Index na = Index(node.assemblySource.size());
    const Index* target = node.assemblyTarget.data();
    const Index* source = node.assemblySource.data();
    bool anyRemoved = false;
    if (in.removed)
      for (Index k = 0; k < nr && !anyRemoved; ++k) anyRemoved = in.removed[node.rows[k]] != 0;
    if (!anyRemoved) {
      for (Index k = 0; k < na; ++k) {
        // (a supernode's columns are scattered over the input: the loads miss the cache, fetched ahead)
        if (k + AssemblyPrefetchDistance < na) internal::prefetch(in.values + source[k + AssemblyPrefetchDistance]);
        const Index t = target[k];
        const Scalar v = in.values[source[k]];
        if (t >= 0)
          L[t] = v;
        else
          L[~t] = numext::conj(v);
      }
      if (in.offset != RealScalar(0) || in.scale != RealScalar(1))
        for (Index c = 0; c < nc; ++c) L[c * nr + c] = in.offset + in.scale * L[c * nr + c];
      return;
    }
    for (Index k = 0; k < na; ++k) {
      const Index t = target[k] >= 0 ? target[k] : ~target[k];
      const Index c = t / nr, r = t - c * nr;
      if (in.removed[node.rows[r]] || in.removed[node.rows[c]]) continue;
      const Scalar v = in.values[source[k]];
      L[t] = target[k] >= 0 ? v : numext::conj(v);
    }
    for (Index c = 0; c < nc; ++c)
      L[c * nr + c] = in.removed[node.rows[c]] ? Scalar(1) : in.offset + in.scale * L[c * nr + c];
  }

  /** Assembles, factors and forms the update matrix of supernode s, on stack \a stackId or in
    * the cache. */
  bool factorNode(Factor& f, Index s, const Input& in, Index stackId) {
    if (m_failed.load(std::memory_order_relaxed) >= 0) return false;
    Node& node = f.nodes[s];
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    if (node.values.rows() != nr || node.values.cols() != nc) node.values.resize(nr, nc);
    Scalar* L = node.values.data();
    // 1. the input's columns
    assemble(node, in);
    // 2. this supernode's update matrix (its lower triangle is written by the front's rank-k
    //    product, so it is not zeroed here), and the children's update matrices' columns that
    //    fall into this supernode's columns
    Scalar* U = nullptr;
    Index uOffset = 0;
    if (m_cacheUpdates) {
      m_cache[s].resize(m * m);
      m_pending[s].clear();  // recomputed: earlier corrections are part of the new values
      U = m_cache[s].data();
    } else {
      UpdateStack<Scalar>& stack = m_stacks[stackId];
      uOffset = stack.push(m * m);
      U = stack.buffer.data() + uOffset;
    }
#ifndef NDEBUG  // U's previous values are never read: poisoned, so that a test reading them fails
    std::fill(U, U + m * m, Scalar(std::numeric_limits<RealScalar>::quiet_NaN()));
#endif
    auto childUpdate = [&](Index c) -> const Scalar* {
      return m_cacheUpdates ? m_cache[c].data() : m_stacks[m_location[c].stack].buffer.data() + m_location[c].offset;
    };
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) {
      if (m_cacheUpdates) {
        m_cache[c].layOut();  // (a folded child may keep an earlier layout)
        if (!m_pending[c].empty()) applyCorrections(f, c);
      }
      extendAddIntoBlock(f.nodes[c], childUpdate(c), L, nr, nc);
    }
    // 3. dense factorization of the front, then the rest of the children's update matrices
    const Index bad = factorFront(node, L, U, in, stackId);
    if (bad >= 0) {
      Index expected = -1;
      const Index col = node.firstCol + bad;
      while (!m_failed.compare_exchange_weak(expected, col) && (expected < 0 || col < expected)) {
      }
      return false;
    }
    Index lowestChild = -1;
    for (Index c = f.firstChild[s]; c != -1; c = f.nextSibling[c]) {
      extendAddIntoUpdate(f.nodes[c], childUpdate(c), nc, U, m);
      const Location& loc = m_location[c];
      if (!m_cacheUpdates && loc.stack == stackId && (lowestChild < 0 || loc.offset < lowestChild))
        lowestChild = loc.offset;
    }
    if (lowestChild >= 0) {  // pop the children: they sit right below on this stack
      UpdateStack<Scalar>& stack = m_stacks[stackId];
      std::memmove(stack.buffer.data() + lowestChild, U, sizeof(Scalar) * m * m);
      uOffset = lowestChild;
      stack.top = lowestChild + m * m;
    }
    m_location[s].stack = stackId;
    m_location[s].offset = uOffset;
    return true;
  }

  /** Dense factorization of the assembled front (nr × nc block L, update matrix U below):
    * L11 = chol, L21 = L21 L11^{-H}, U -= L21 L21^H. When a quarter or more of its rows belong
    * to removed dofs (zero rows, unit columns: paper §5.3), the kept rows and columns are
    * gathered into a compact front first, so that the work is that of the reduced system A_II
    * (paper §6.5) rather than of the whole supernode. \returns -1 or the local column of a bad
    * pivot. */
  Index factorFront(const Node& node, Scalar* L, Scalar* U, const Input& in, Index stackId) {
    const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
    if (in.removed && isReduced(node, in.removed, m_stacks[stackId].kept)) {
      UpdateStack<Scalar>& ws = m_stacks[stackId];
      const std::vector<Index>& kept = ws.kept;
      const Index kr = Index(kept.size());
      Index kc = 0;
      while (kc < kr && kept[kc] < nc) ++kc;
      const Index km = kr - kc;
      std::fill(U, U + m * m, Scalar(0));  // (the children's updates are added afterwards)
      if (kc == 0) return -1;  // only unit columns: the children's updates pass through U unchanged
      ws.front.assign(kr * kc, Scalar(0));
      Scalar* F = ws.front.data();
      for (Index j = 0; j < kc; ++j) {
        const Scalar* col = L + kept[j] * nr;
        for (Index i = j; i < kr; ++i) F[j * kr + i] = col[kept[i]];
      }
      const Index bad = potrf(kc, F, kr);
      if (bad >= 0) return kept[bad];
      if (km > 0) trsmRightLowerAdjoint(km, kc, F, kr, F + kc, kr);
      for (Index j = 0; j < kc; ++j) {
        Scalar* col = L + kept[j] * nr;
        for (Index i = j; i < kr; ++i) col[kept[i]] = F[j * kr + i];
      }
      if (km > 0) {
        ws.update.assign(km * km, Scalar(0));
        Scalar* T = ws.update.data();
        herkLower(km, kc, RealScalar(-1), F + kc, kr, T, km);
        for (Index j = 0; j < km; ++j) {
          Scalar* dst = U + (kept[kc + j] - nc) * m - nc;
          for (Index i = j; i < km; ++i) dst[kept[kc + i]] += T[j * km + i];
        }
      }
      return -1;
    }
    const Index bad = potrf(nc, L, nr);
    if (bad >= 0) return bad;
    if (m > 0) {
      trsmRightLowerAdjoint(m, nc, L, nr, L + nc, nr);
      herkLower(m, nc, RealScalar(-1), L + nc, nr, U, m, /*overwrite=*/true);
    }
    return -1;
  }

  /** Adds the columns of the child's update matrix (lower triangle, m×m) that fall into the
    * parent's own columns into the parent's block, through the child's precomputed positions in
    * the parent's rows. */
  static void extendAddIntoBlock(const Node& child, const Scalar* U, Scalar* L, Index nr, Index nc) {
    const Index m = child.below();
    const StorageIndex* pos = child.parentPosition.data();
    for (Index k = 0; k < m; ++k) {
      if (pos[k] >= nc) continue;
      const Scalar* src = U + k * m;
      Scalar* dst = L + pos[k] * nr;
      for (Index i = k; i < m; ++i) dst[pos[i]] += src[i];
    }
  }

  /** Adds the rest of the child's update matrix (the columns at the parent's rows below) into
    * the parent's update matrix P (pm × pm). */
  static void extendAddIntoUpdate(const Node& child, const Scalar* U, Index nc, Scalar* P, Index pm) {
    const Index m = child.below();
    const StorageIndex* pos = child.parentPosition.data();
    for (Index k = 0; k < m; ++k) {
      if (pos[k] < nc) continue;
      const Scalar* src = U + k * m;
      Scalar* dst = P + (pos[k] - nc) * pm - nc;
      for (Index i = k; i < m; ++i) dst[pos[i]] += src[i];
    }
  }

  SubtreeSchedule m_schedule;
  std::vector<Location> m_location;
  std::vector<UpdateStack<Scalar> > m_stacks;
  std::vector<Index> m_listPosition;  ///< scratch of makeListSchedule(), all zero between calls
  std::vector<CachedUpdate<Scalar> > m_cache;  ///< per supernode update matrix, when caching
  std::vector<std::vector<Correction> > m_pending;  ///< per supernode deferred corrections U += ±W W^H
  bool m_cacheUpdates = false, m_cacheValid = false;
  std::atomic<Index> m_failed{-1};
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_NUMERIC_H
