// ShortestEdgePath: the shortest path between two vertices along the edges of a triangle mesh
// (Dijkstra by Euclidean edge length, or by hop count), used to lay out the seams that the
// paper's applications cut and glue (§5: cone-to-cone cuts of orbifold and BFF parameterizations).

#ifndef EIGEN_MESHTOOLS_SHORTESTEDGEPATH_H
#define EIGEN_MESHTOOLS_SHORTESTEDGEPATH_H

#include <functional>
#include <queue>

namespace Eigen {

/** \ingroup MeshTools_Module
  * \brief Shortest path from \a source to \a target along the edges of a triangle mesh.
  *
  * The graph is the set of edges of \a F on the V.rows() vertices. With \a byLength (the
  * default) an edge weighs its Euclidean length |V.row(a) - V.row(b)|, otherwise 1 (fewest hops).
  * Dijkstra's algorithm; among paths of equal length the one found first is returned (the search
  * settles vertices in order of distance, then of index), so the result is deterministic.
  *
  * \param V         #V x d vertex positions (any d >= 1; only used when \a byLength).
  * \param F         #F x 3 triangles, 0-based indices into the rows of V.
  * \param source    first vertex of the path.
  * \param target    last vertex of the path.
  * \param byLength  weigh edges by length (true) or count hops (false).
  * \returns the vertices from \a source to \a target, consecutive ones joined by an edge of F;
  *          {source} if source == target; empty if \a target cannot be reached, an index is out
  *          of range or F is not a valid #F x 3 index matrix.
  *
  * \sa cutMeshAlongPath(), seamPath()
  */
inline std::vector<int> shortestEdgePath(const MatrixXd& V, const MatrixXi& F, int source, int target,
                                         bool byLength = true)
{
  const int n = int(std::min<Index>(V.rows(), std::numeric_limits<int>::max()));
  if (source < 0 || source >= n || target < 0 || target >= n) return std::vector<int>();
  if (!internal::meshtools::checkTriangles(F, n, "shortestEdgePath", nullptr)) return std::vector<int>();
  if (source == target) return std::vector<int>(1, source);

  const internal::meshtools::SeamGraph graph(F, n);
  std::vector<double> distance(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  std::vector<int> parent(static_cast<std::size_t>(n), -1);
  std::vector<char> settled(static_cast<std::size_t>(n), 0);
  typedef std::pair<double, int> Entry; // (distance, vertex)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  distance[std::size_t(source)] = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty())
  {
    const int v = queue.top().second;
    queue.pop();
    if (settled[std::size_t(v)]) continue;
    settled[std::size_t(v)] = 1;
    if (v == target) break;
    for (int p = graph.offsets[std::size_t(v)]; p < graph.offsets[std::size_t(v) + 1]; ++p)
    {
      const int w = graph.adjacency[std::size_t(p)];
      if (settled[std::size_t(w)]) continue;
      const double weight = byLength ? (V.row(v) - V.row(w)).norm() : 1.0;
      const double candidate = distance[std::size_t(v)] + weight;
      if (candidate < distance[std::size_t(w)])
      {
        distance[std::size_t(w)] = candidate;
        parent[std::size_t(w)] = v;
        queue.emplace(candidate, w);
      }
    }
  }
  if (!settled[std::size_t(target)]) return std::vector<int>();
  std::vector<int> path;
  for (int v = target; v != -1; v = parent[std::size_t(v)]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_SHORTESTEDGEPATH_H
