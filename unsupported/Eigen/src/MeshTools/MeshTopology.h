// MeshTopology: the combinatorial topology of a triangle mesh — used vertices, edges, faces,
// connected pieces, boundary loops, Euler characteristic and genus (V − E + F = 2c − 2g − b).
// The disk-based parameterizations (Tutte, BFF; paper §4.1, §5) need a cut mesh that is a
// topological disk; this is how they tell, and how a caller learns how many cuts a handle needs.

#ifndef EIGEN_MESHTOOLS_MESHTOPOLOGY_H
#define EIGEN_MESHTOOLS_MESHTOPOLOGY_H

namespace Eigen {

/** \ingroup MeshTools_Module
  * \brief Counts describing the topology of a triangle mesh (see meshTopology()). */
struct MeshTopology
{
  Index vertices = 0;             ///< vertices used by some face (unused rows of V do not count)
  Index edges = 0;                ///< distinct undirected edges
  Index faces = 0;                ///< triangles
  Index components = 0;           ///< connected pieces (faces sharing a vertex are connected)
  Index boundaryLoops = 0;        ///< closed chains of boundary edges (boundaryLoops())
  Index eulerCharacteristic = 0;  ///< vertices − edges + faces
  /** (2 · components − boundaryLoops − eulerCharacteristic) / 2: the number of handles summed
    * over the pieces (0 for a sphere or a disk, 1 for a torus). -1 when the mesh is not a
    * consistently oriented manifold (an edge on three or more triangles, or two triangles that
    * cross an edge in the same direction: a flipped face or a non-orientable surface such as a
    * Möbius strip), or when that count is odd or negative. */
  Index genus = 0;

  /** \returns true for one piece of genus 0 with one boundary loop: a topological disk, what
    * Tutte embeddings and BFF map to the plane. */
  bool isDisk() const { return components == 1 && boundaryLoops == 1 && genus == 0; }
};

namespace internal {
namespace meshtools {

/** \internal meshTopology() of a valid \a F whose side partners (sidePartners()) and number of
  * boundary loops are known: no sort beyond the one that found the partners. */
inline MeshTopology topologyFromPartners(const MatrixXi& F, const std::vector<int>& partner, Index loopCount)
{
  MatrixXi compact;  // (the sides keep their face*3+corner names: the partners stay valid)
  std::vector<int> used;
  if (compactVertexIndices(F, compact, used)) return topologyFromPartners(compact, partner, loopCount);
  MeshTopology t;
  const Index n = Index(F.maxCoeff()) + 1;
  // connected pieces: union-find over the vertices of each face
  std::vector<int> parent(std::size_t(n), -1); // -1: unused; else a link towards the piece's root
  auto find = [&parent](int v) {
    int root = v;
    while (parent[std::size_t(root)] != root) root = parent[std::size_t(root)];
    while (parent[std::size_t(v)] != root)
    {
      const int up = parent[std::size_t(v)];
      parent[std::size_t(v)] = root;
      v = up;
    }
    return root;
  };
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (parent[std::size_t(F(f, c))] < 0) parent[std::size_t(F(f, c))] = F(f, c);
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 1; c < 3; ++c)
    {
      const int a = find(F(f, 0)), b = find(F(f, c));
      if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
    }
  for (Index v = 0; v < n; ++v)
    if (parent[std::size_t(v)] >= 0)
    {
      ++t.vertices;
      t.components += find(int(v)) == int(v);
    }
  // edges: one per boundary side, one per pair of partner sides, one per key of the sides that
  // share a non-manifold edge (rare: sorted apart)
  std::vector<std::uint64_t> crowded;
  bool orientedManifold = true;  // no edge on three or more faces, none crossed twice the same way
  for (std::size_t side = 0; side < partner.size(); ++side)
  {
    const int other = partner[side];
    if (other == -1 || (other >= 0 && std::size_t(other) > side)) ++t.edges;
    if (other == -2 ||
        (other >= 0 && F(Index(side / 3), Index(side % 3)) != F(Index(other / 3), Index((other % 3 + 1) % 3))))
      orientedManifold = false;
    if (other == -2)
      crowded.push_back(undirectedEdgeKey(F(Index(side / 3), Index(side % 3)), F(Index(side / 3), Index((side % 3 + 1) % 3))));
  }
  std::sort(crowded.begin(), crowded.end());
  t.edges += Index(std::unique(crowded.begin(), crowded.end()) - crowded.begin());
  t.faces = F.rows();
  t.boundaryLoops = loopCount;
  t.eulerCharacteristic = t.vertices - t.edges + t.faces;
  const Index twiceGenus = 2 * t.components - t.boundaryLoops - t.eulerCharacteristic;
  t.genus = orientedManifold && twiceGenus >= 0 && twiceGenus % 2 == 0 ? twiceGenus / 2 : Index(-1);
  return t;
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief The topology of the triangle mesh \a F: counts of used vertices, edges, faces,
  * connected pieces and boundary loops, the Euler characteristic and the genus.
  *
  * \code
  * Eigen::MeshTopology t = Eigen::meshTopology(F);
  * if (!t.isDisk()) std::cerr << "genus " << t.genus << ", " << t.boundaryLoops << " boundary loops\n";
  * \endcode
  *
  * \param F  #F x 3 triangles, 0-based vertex indices (an invalid F gives all counts zero).
  * Cost O(#F log #F).
  * \sa boundaryLoops(), cutMesh()
  */
inline MeshTopology meshTopology(const MatrixXi& F)
{
  if (F.rows() == 0 || F.cols() != 3 || F.minCoeff() < 0 || 3 * F.rows() > Index(std::numeric_limits<int>::max()))
    return MeshTopology();
  const std::vector<int> partner = internal::meshtools::sidePartners(F);
  const Index loops = Index(internal::meshtools::boundaryLoopsFromPartners(F, partner).size());
  return internal::meshtools::topologyFromPartners(F, partner, loops);
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_MESHTOPOLOGY_H
