// SeamPath: random seams of a given number of vertices along shortest edge paths of a triangle
// mesh, following the evaluation protocol of the paper (§6): seeded random start, hop distances
// by breadth-first search, a vertex at the wanted distance, the shortest path to it; other starts
// when the mesh is too small around the first one; several shorter disjoint paths as a last resort.

#ifndef EIGEN_MESHTOOLS_SEAMPATH_H
#define EIGEN_MESHTOOLS_SEAMPATH_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal Uniform integer in [0, n) from a 32-bit Mersenne twister draw, by a multiply-shift
  * (unlike std::uniform_int_distribution, the same on every standard library). */
inline int seamUniformIndex(std::mt19937& generator, int n)
{
  return int((std::uint64_t(generator()) * std::uint64_t(n)) >> 32);
}

/** \internal The vertex graph of a triangle mesh: sorted, duplicate-free neighbour lists in
  * compressed form (neighbours of v are adjacency[offsets[v] .. offsets[v+1]-1]). */
struct SeamGraph
{
  std::vector<int> offsets, adjacency;

  /** Builds the graph of the edges of \a F on \a n vertices (indices already checked). */
  SeamGraph(const MatrixXi& F, int n) : offsets(std::size_t(n) + 1, 0)
  {
    for (Index f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c)
      {
        const int a = F(f, c), b = F(f, (c + 1) % 3);
        if (a == b) continue;
        ++offsets[std::size_t(a) + 1];
        ++offsets[std::size_t(b) + 1];
      }
    for (int v = 0; v < n; ++v) offsets[std::size_t(v) + 1] += offsets[std::size_t(v)];
    adjacency.resize(std::size_t(offsets[std::size_t(n)]));
    std::vector<int> fill(offsets.begin(), offsets.end() - 1);
    for (Index f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c)
      {
        const int a = F(f, c), b = F(f, (c + 1) % 3);
        if (a == b) continue;
        adjacency[std::size_t(fill[std::size_t(a)]++)] = b;
        adjacency[std::size_t(fill[std::size_t(b)]++)] = a;
      }
    // Sort and deduplicate each list (every interior edge appears twice), then compact.
    int write = 0;
    for (int v = 0; v < n; ++v)
    {
      const auto first = adjacency.begin() + offsets[std::size_t(v)];
      const auto last = adjacency.begin() + offsets[std::size_t(v) + 1];
      std::sort(first, last);
      const int count = int(std::unique(first, last) - first);
      offsets[std::size_t(v)] = write;
      std::copy(first, first + count, adjacency.begin() + write);
      write += count;
    }
    offsets[std::size_t(n)] = write;
    adjacency.resize(std::size_t(write));
  }
};

/** \internal Draws start vertices among those not \a blocked and looks for a shortest path of
  * exactly \a length vertices that avoids the blocked vertices, up to \a attempts starts.
  * \returns the path (start first), or an empty vector. \a distance and \a parent are n-sized
  * workspaces; \a freeVertices lists the vertices not blocked (the caller keeps it in sync). */
inline std::vector<int> seamTryPath(const SeamGraph& graph, const std::vector<char>& blocked,
                                    const std::vector<int>& freeVertices, int length, int attempts,
                                    std::mt19937& generator, std::vector<int>& distance,
                                    std::vector<int>& parent)
{
  std::vector<int> queue, visited, candidates;
  for (int attempt = 0; attempt < attempts && !freeVertices.empty(); ++attempt)
  {
    const int start = freeVertices[std::size_t(seamUniformIndex(generator, int(freeVertices.size())))];
    // Breadth-first search from start, stopped once every vertex at distance length-1 is known
    // (they are all discovered before the first of them leaves the queue).
    queue.assign(1, start);
    visited.assign(1, start);
    distance[std::size_t(start)] = 0;
    parent[std::size_t(start)] = -1;
    candidates.clear();
    for (std::size_t head = 0; head < queue.size(); ++head)
    {
      const int v = queue[head];
      const int d = distance[std::size_t(v)];
      if (d == length - 1) break;
      for (int p = graph.offsets[std::size_t(v)]; p < graph.offsets[std::size_t(v) + 1]; ++p)
      {
        const int w = graph.adjacency[std::size_t(p)];
        if (blocked[std::size_t(w)] || distance[std::size_t(w)] >= 0) continue;
        distance[std::size_t(w)] = d + 1;
        parent[std::size_t(w)] = v;
        queue.push_back(w);
        visited.push_back(w);
      }
    }
    for (int v : queue)
      if (distance[std::size_t(v)] == length - 1) candidates.push_back(v);
    std::vector<int> path;
    if (!candidates.empty())
    {
      int v = candidates[std::size_t(seamUniformIndex(generator, int(candidates.size())))];
      for (; v != -1; v = parent[std::size_t(v)]) path.push_back(v);
      std::reverse(path.begin(), path.end());
    }
    for (int v : visited) distance[std::size_t(v)] = -1;
    if (!path.empty()) return path;
  }
  return std::vector<int>();
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief A random seam of exactly \a length distinct vertices along shortest edge paths of a
  * triangle mesh (the seams of the paper's evaluation, §6).
  *
  * The vertex graph is the set of edges of \a F. The procedure, all of it driven by one
  * std::mt19937 seeded with \a seed (so the result depends only on F, nVertices, length and seed,
  * on every platform):
  *
  * 1. Draw a start vertex uniformly at random, compute hop distances by breadth-first search, and
  *    if some vertex lies exactly length-1 hops away, pick one of them uniformly at random and
  *    return the shortest path from the start to it (the breadth-first tree path, neighbours
  *    visited in increasing index order): \a length vertices, start first, consecutive vertices
  *    joined by an edge. A length of 1 returns the start vertex alone.
  * 2. If no vertex is that far, try again from another random start, 16 starts in all.
  * 3. If all of them fail (the mesh is too small or too thin for one path), split the seam into
  *    k pieces of length/k vertices (the first length mod k pieces one longer), for
  *    k = 2, 3, 4, 6, 9, 13, ... (each about 1.5 times the previous, so that a hopeless length
  *    costs O(log length) rounds), the last round being k = length. Each piece is found as in
  *    steps 1-2 in the graph without the vertices already taken (starts are drawn among the
  *    vertices not taken), so the pieces are vertex-disjoint shortest paths of what is left. The
  *    first k for which every piece is found is used; the pieces follow one another in the
  *    result, and two consecutive pieces may happen to be joined by an edge.
  *
  * Every vertex appears at most once. Vertices used by no triangle are isolated: they can only be
  * a whole piece of length 1.
  *
  * \param F          #F x 3 triangles, 0-based indices in [0, nVertices).
  * \param nVertices  number of vertices of the mesh (rows of V).
  * \param length     number of vertices of the seam.
  * \param seed       seed of the random choices.
  * \param pieces     optional output: number of paths the seam is made of (1 unless step 3 was
  *                   needed, 0 when the result is empty).
  * \returns the seam's vertex indices; an empty vector exactly when length <= 0,
  *          length > nVertices, or F holds an index outside [0, nVertices) or has other than 3
  *          columns (otherwise the last round, pieces of one vertex, always succeeds).
  *
  * \sa cotanLaplacian(), readOFF()
  */
inline std::vector<int> seamPath(const MatrixXi& F, int nVertices, int length, unsigned seed, int* pieces = nullptr)
{
  if (pieces) *pieces = 0;
  if (length <= 0 || nVertices <= 0 || length > nVertices) return std::vector<int>();
  if (F.rows() > 0 && (F.cols() != 3 || F.minCoeff() < 0 || F.maxCoeff() >= nVertices)) return std::vector<int>();

  const internal::meshtools::SeamGraph graph(F, nVertices);
  std::mt19937 generator(seed);
  std::vector<int> distance(std::size_t(nVertices), -1), parent(std::size_t(nVertices), -1);
  const int attempts = 16;

  for (int k = 1;; k = std::min(length, std::max(k + 1, k * 3 / 2)))
  {
    // Fresh state for this number of pieces: nothing blocked, every vertex free.
    std::vector<char> blocked(std::size_t(nVertices), 0);
    std::vector<int> freeVertices(static_cast<std::size_t>(nVertices)), position(static_cast<std::size_t>(nVertices));
    for (int v = 0; v < nVertices; ++v) freeVertices[std::size_t(v)] = position[std::size_t(v)] = v;
    std::vector<int> seam;
    bool ok = true;
    for (int piece = 0; piece < k && ok; ++piece)
    {
      const int pieceLength = length / k + (piece < length % k ? 1 : 0);
      const std::vector<int> path = internal::meshtools::seamTryPath(graph, blocked, freeVertices, pieceLength, attempts,
                                                                      generator, distance, parent);
      ok = !path.empty();
      for (int v : path)
      {
        blocked[std::size_t(v)] = 1;
        // Remove v from the free list in O(1): move the last entry into its slot.
        const int slot = position[std::size_t(v)], last = freeVertices.back();
        freeVertices[std::size_t(slot)] = last;
        position[std::size_t(last)] = slot;
        freeVertices.pop_back();
        seam.push_back(v);
      }
    }
    if (ok)
    {
      if (pieces) *pieces = k;
      return seam;
    }
    if (k == length) return std::vector<int>(); // not reached: pieces of one vertex always succeed
  }
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_SEAMPATH_H
