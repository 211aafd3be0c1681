// BoundaryLoops: the boundary loops of a triangle mesh as ordered vertex lists, oriented like the
// faces (the mesh lies to the left of each loop), longest first. The boundary of a parameterized
// patch is what BFF and the Dirichlet-boundary Tutte embedding of the paper (§5) constrain.

#ifndef EIGEN_MESHTOOLS_BOUNDARYLOOPS_H
#define EIGEN_MESHTOOLS_BOUNDARYLOOPS_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal Starting at the boundary side that ends at vertex \a b in face \a face (corner
  * \a corner starts it), turns around b through the faces across interior edges until it meets a
  * boundary side leaving b. This picks the continuation of a loop inside one fan when several
  * fans touch at b. \returns that side as face*3+corner, or -1 if the turn hits a non-manifold or
  * inconsistently oriented edge, or takes more than \a maxSteps steps. */
inline int nextBoundarySideAround(const MatrixXi& F, const std::vector<int>& partner, int face, int corner, int b,
                                  int maxSteps)
{
  int side = face * 3 + (corner + 1) % 3; // the side of `face` that leaves b
  for (int step = 0; step <= maxSteps; ++step)
  {
    const int across = partner[std::size_t(side)];
    if (across == -1) return side; // a boundary side leaving b
    if (across < 0) return -1;     // non-manifold edge
    const int g = across / 3, d = across % 3;
    if (F(g, (d + 1) % 3) != b) return -1; // neighbour oriented the other way
    side = g * 3 + (d + 1) % 3;
  }
  return -1;
}

} // namespace meshtools
} // namespace internal

namespace internal {
namespace meshtools {

/** \internal boundaryLoops() of a valid \a F whose side partners (sidePartners()) are known. */
inline std::vector<std::vector<int>> boundaryLoopsFromPartners(const MatrixXi& F, const std::vector<int>& partner)
{
  std::vector<std::vector<int>> loops;

  // The boundary sides (as face*3+corner) in face order, and as (start vertex, side) pairs sorted
  // by vertex: the sides leaving a vertex are one range (no array over the index range of F).
  std::vector<int> boundarySides;
  std::vector<std::pair<int, int>> leaving;
  for (int side = 0; side < int(partner.size()); ++side)
    if (partner[std::size_t(side)] == -1)
    {
      boundarySides.push_back(side);
      leaving.emplace_back(F(side / 3, side % 3), side);
    }
  std::sort(leaving.begin(), leaving.end());

  std::vector<char> used(partner.size(), 0);
  std::vector<int> candidates;
  for (int first : boundarySides)
  {
    if (used[std::size_t(first)]) continue;
    const int start = F(first / 3, first % 3);
    std::vector<int> loop;
    for (int side = first; side >= 0;)
    {
      used[std::size_t(side)] = 1;
      const int face = side / 3, corner = side % 3;
      loop.push_back(F(face, corner));
      const int b = F(face, (corner + 1) % 3);
      if (b == start) break;
      // The unused boundary sides leaving b; with several (fans touching at b), turn around b.
      candidates.clear();
      for (auto it = std::lower_bound(leaving.begin(), leaving.end(), std::make_pair(b, -1));
           it != leaving.end() && it->first == b; ++it)
        if (!used[std::size_t(it->second)]) candidates.push_back(it->second);
      if (candidates.empty()) side = -1;
      else if (candidates.size() == 1) side = candidates.front();
      else
      {
        const int turned = nextBoundarySideAround(F, partner, face, corner, b, int(F.rows()));
        side = (turned >= 0 && !used[std::size_t(turned)]) ? turned : candidates.front();
      }
    }
    loops.push_back(std::move(loop));
  }
  std::stable_sort(loops.begin(), loops.end(),
                   [](const std::vector<int>& x, const std::vector<int>& y) { return x.size() > y.size(); });
  return loops;
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief The boundary loops of a triangle mesh.
  *
  * A boundary edge is an edge used by exactly one triangle. Each loop is the ordered list of the
  * vertices along a closed chain of boundary edges, in the direction of the triangle's side (so
  * for counter-clockwise faces the mesh lies to the left of the loop, and a planar disk's outer
  * loop runs counter-clockwise). Each vertex of a loop appears once in it; the edge from the last
  * vertex back to the first closes it. Where several fans of triangles touch at one vertex, each
  * loop stays inside its own fan, so such a vertex is listed once in each loop through it.
  *
  * Loops are sorted by decreasing length (ties: the loop whose first boundary side comes first
  * in F comes first); each starts at the start vertex of its first boundary side in face order.
  * A closed mesh has no loops. On non-manifold or inconsistently oriented meshes the chains are
  * traced as far as they go and returned as they are.
  *
  * \param F  #F x 3 triangles, 0-based vertex indices.
  * \returns the loops; empty if there is no boundary or F is not a valid #F x 3 index matrix
  *          (negative indices, other than 3 columns). Cost O(#F log #F).
  *
  * \sa cutMesh(), shortestEdgePath()
  */
inline std::vector<std::vector<int>> boundaryLoops(const MatrixXi& F)
{
  if (F.rows() == 0 || F.cols() != 3 || F.minCoeff() < 0 || 3 * F.rows() > Index(std::numeric_limits<int>::max()))
    return std::vector<std::vector<int>>();
  return internal::meshtools::boundaryLoopsFromPartners(F, internal::meshtools::sidePartners(F));
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_BOUNDARYLOOPS_H
