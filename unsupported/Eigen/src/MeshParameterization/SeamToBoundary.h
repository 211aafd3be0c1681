// SeamToBoundary: the seam an interactive session adds to a disk-like (cut) mesh (Herholz &
// Sorkine-Hornung §5.1): the shortest edge path from a picked vertex to the nearest boundary
// vertex through interior vertices only, so that it starts on the boundary, runs inside the
// surface and never touches the boundary again (Dijkstra by edge length, stopped at the boundary).

#ifndef EIGEN_MESHPARAMETERIZATION_SEAMTOBOUNDARY_H
#define EIGEN_MESHPARAMETERIZATION_SEAMTOBOUNDARY_H

namespace Eigen {

/** \ingroup MeshParameterization_Module
  * \brief The seam from the boundary to vertex \a target: the shortest edge path (by 3-D length)
  * from \a target to its nearest boundary vertex whose other vertices are all interior, returned
  * boundary vertex first (ready for TutteEmbedding::addSeam() / BoundaryFirstFlattening::addSeam()).
  *
  * \param V       #V x 3 vertex positions (of the current cut mesh).
  * \param F       #F x 3 triangles.
  * \param target  the vertex the seam runs to; it must be interior.
  * \returns the path (at least two vertices), or an empty vector if \a target is out of range, on
  *          the boundary, or no boundary is reachable (closed component).
  *
  * \sa shortestEdgePath(), cutMeshAlongPath()
  */
inline std::vector<int> seamToBoundary(const MatrixXd& V, const MatrixXi& F, int target)
{
  const int n = int(V.rows());
  if (target < 0 || target >= n || !internal::meshtools::checkTriangles(F, n, "seamToBoundary", nullptr))
    return std::vector<int>();
  std::vector<char> onBoundary(std::size_t(n), 0);
  for (const std::vector<int>& loop : boundaryLoops(F))
    for (int v : loop) onBoundary[std::size_t(v)] = 1;
  if (onBoundary[std::size_t(target)]) return std::vector<int>();

  const internal::meshtools::SeamGraph graph(F, n);
  std::vector<double> distance(std::size_t(n), std::numeric_limits<double>::infinity());
  std::vector<int> parent(std::size_t(n), -1);
  typedef std::pair<double, int> Entry; // (distance, vertex)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  distance[std::size_t(target)] = 0;
  queue.emplace(0.0, target);
  while (!queue.empty())
  {
    const Entry top = queue.top();
    queue.pop();
    const int v = top.second;
    if (top.first > distance[std::size_t(v)]) continue; // stale entry
    if (onBoundary[std::size_t(v)])
    {
      std::vector<int> path;
      for (int w = v; w != -1; w = parent[std::size_t(w)]) path.push_back(w);
      return path; // boundary vertex first, target last
    }
    for (int p = graph.offsets[std::size_t(v)]; p < graph.offsets[std::size_t(v) + 1]; ++p)
    {
      const int w = graph.adjacency[std::size_t(p)];
      const double candidate = distance[std::size_t(v)] + (V.row(v) - V.row(w)).norm();
      if (candidate < distance[std::size_t(w)])
      {
        distance[std::size_t(w)] = candidate;
        parent[std::size_t(w)] = v;
        queue.emplace(candidate, w);
      }
    }
  }
  return std::vector<int>();
}

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_SEAMTOBOUNDARY_H
