// CutMesh: cuts a triangle mesh open along a set of its edges (or along a vertex path), giving
// the cut vertices one copy per wedge of triangles, with the map from new to old vertices. This is
// the seam cut of the paper's applications (§5: Tutte/orbifold/BFF parameterizations cut a closed
// surface to a disk; the solver's insertDofs/mergeDofs then follow the new vertices). Same output
// convention as libigl's cut_mesh (the `I` map).

#ifndef EIGEN_MESHTOOLS_CUTMESH_H
#define EIGEN_MESHTOOLS_CUTMESH_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal Union-find over the 3*#F face corners, with path halving. */
class CornerUnion
{
public:
  explicit CornerUnion(std::size_t count) : m_parent(count)
  {
    for (std::size_t i = 0; i < count; ++i) m_parent[i] = int(i);
  }
  /** \returns the representative of corner \a c. */
  int find(int c)
  {
    while (m_parent[std::size_t(c)] != c)
    {
      m_parent[std::size_t(c)] = m_parent[std::size_t(m_parent[std::size_t(c)])];
      c = m_parent[std::size_t(c)];
    }
    return c;
  }
  /** Joins the sets of corners \a a and \a b (the smaller representative wins). */
  void join(int a, int b)
  {
    a = find(a);
    b = find(b);
    if (a < b) m_parent[std::size_t(b)] = a;
    else if (b < a) m_parent[std::size_t(a)] = b;
  }

private:
  std::vector<int> m_parent;
};

/** \internal \returns the corner face*3+k of face \a face at vertex \a v (the first one if v
  * appears twice), or -1. */
inline int cornerOfVertex(const MatrixXi& F, int face, int v)
{
  for (int k = 0; k < 3; ++k)
    if (F(face, k) == v) return face * 3 + k;
  return -1;
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Cuts a triangle mesh open along some of its edges.
  *
  * At each vertex v, the triangles around v form fans; two triangles at v belong to the same
  * wedge when they are joined, around v, across edges at v that are not cut (a boundary edge, used
  * by one triangle, joins nothing; an uncut edge joins all triangles on it). The wedge holding the
  * first corner of v in F (lowest face, then corner) keeps the index v; every other wedge gets a
  * new vertex, appended after the old ones in the order of their first corner in F: n, n+1, ...
  * (n = V.rows()). So a vertex inside a cut path (two cut edges) gets one copy, the end of a cut
  * inside the surface (one cut edge) none, and a boundary vertex where a cut starts one: a cut
  * from the boundary opens the mesh. A cut edge becomes two boundary edges as soon as one of its
  * ends is split, which holds for every edge of a path of two or more edges and for every edge
  * touching the boundary; a lone interior cut edge (no other cut edge at either end) opens
  * nothing. Vertices whose fans were already separate (two fans touching only at the vertex) are
  * split as well.
  *
  * Faces keep their order and orientation; Fcut(f, k) is v or a copy of v where F(f, k) == v.
  * Cut edges that are boundary edges already, or listed twice, change nothing more.
  *
  * \param V        #V x d vertex positions (any d).
  * \param F        #F x 3 triangles, 0-based indices into the rows of V.
  * \param cutEdges the edges to cut, as vertex pairs (either order); each must be an edge of F.
  * \param Vcut     output: (#V + copies) x d positions, Vcut.row(i) == V.row(origin[i]).
  * \param Fcut     output: #F x 3 triangles on the new vertices.
  * \param origin   output: for every new vertex, the old vertex it copies (origin[i] == i for
  *                 i < n), like libigl's cut_mesh `I`.
  * \param error    if not null, receives a message on failure and is cleared on success.
  * \returns true on success; false (outputs untouched) if F is not a #F x 3 matrix of indices into
  *          V, or a cut edge has an index out of range, equal ends, or is not an edge of F.
  *
  * \sa cutMeshAlongPath(), boundaryLoops()
  */
inline bool cutMesh(const MatrixXd& V, const MatrixXi& F, const std::vector<std::array<int, 2>>& cutEdges,
                    MatrixXd& Vcut, MatrixXi& Fcut, VectorXi& origin, std::string* error = nullptr)
{
  using namespace internal::meshtools;
  if (V.rows() > Index(std::numeric_limits<int>::max() / 2) || 3 * F.rows() > Index(std::numeric_limits<int>::max()))
  {
    if (error) *error = "cutMesh: mesh too large for int indices";
    return false;
  }
  const int n = int(V.rows());
  if (!checkTriangles(F, n, "cutMesh", error)) return false;

  // The mesh's edges (sorted keys) and the cut ones among them.
  const std::vector<HalfEdgeRecord> records = sortedHalfEdges(F);
  std::vector<std::uint64_t> edgeKeys(records.size());
  for (std::size_t r = 0; r < records.size(); ++r) edgeKeys[r] = records[r].key;
  std::vector<std::uint64_t> cutKeys;
  cutKeys.reserve(cutEdges.size());
  for (std::size_t e = 0; e < cutEdges.size(); ++e)
  {
    const int a = cutEdges[e][0], b = cutEdges[e][1];
    const std::string which = "cut edge " + std::to_string(e) + " (" + std::to_string(a) + ", " + std::to_string(b) + ")";
    if (a < 0 || a >= n || b < 0 || b >= n)
    {
      if (error) *error = "cutMesh: " + which + " has a vertex index outside [0, " + std::to_string(n) + ")";
      return false;
    }
    const std::uint64_t key = undirectedEdgeKey(a, b);
    if (a == b || !std::binary_search(edgeKeys.begin(), edgeKeys.end(), key))
    {
      if (error) *error = "cutMesh: " + which + " is not an edge of the mesh";
      return false;
    }
    cutKeys.push_back(key);
  }
  std::sort(cutKeys.begin(), cutKeys.end());

  // Join the corners at both ends of every uncut edge across all the triangles on it.
  CornerUnion wedges(std::size_t(3 * F.rows()));
  for (std::size_t begin = 0, end = 0; begin < records.size(); begin = end)
  {
    end = begin + 1;
    while (end < records.size() && records[end].key == records[begin].key) ++end;
    if (std::binary_search(cutKeys.begin(), cutKeys.end(), records[begin].key)) continue;
    const HalfEdgeRecord& first = records[begin];
    const int a = F(first.face, first.corner), b = F(first.face, (first.corner + 1) % 3);
    for (std::size_t r = begin + 1; r < end; ++r)
    {
      wedges.join(cornerOfVertex(F, first.face, a), cornerOfVertex(F, records[r].face, a));
      wedges.join(cornerOfVertex(F, first.face, b), cornerOfVertex(F, records[r].face, b));
    }
  }

  // A degenerate face's corners at one vertex are one point: one wedge (its sides are skipped
  // above, and cornerOfVertex() names only the first of them).
  for (int face = 0; face < int(F.rows()); ++face)
    for (int k = 0; k < 3; ++k)
      for (int l = k + 1; l < 3; ++l)
        if (F(face, k) == F(face, l)) wedges.join(face * 3 + k, face * 3 + l);

  // Number the wedges: the first wedge of each vertex keeps its index, the others are appended.
  std::vector<int> wedgeVertex(std::size_t(3 * F.rows()), -1);
  std::vector<char> vertexTaken(static_cast<std::size_t>(n), 0);
  std::vector<int> copies;
  MatrixXi newF(F.rows(), 3);
  for (int corner = 0; corner < int(3 * F.rows()); ++corner)
  {
    const int v = F(corner / 3, corner % 3);
    int& target = wedgeVertex[std::size_t(wedges.find(corner))];
    if (target < 0)
    {
      if (!vertexTaken[std::size_t(v)])
      {
        vertexTaken[std::size_t(v)] = 1;
        target = v;
      }
      else
      {
        target = n + int(copies.size());
        copies.push_back(v);
      }
    }
    newF(corner / 3, corner % 3) = target;
  }

  const Index total = Index(n) + Index(copies.size());
  origin.resize(total);
  for (int i = 0; i < n; ++i) origin[i] = i;
  for (std::size_t j = 0; j < copies.size(); ++j) origin[Index(n) + Index(j)] = copies[j];
  MatrixXd newV(total, V.cols());
  for (Index i = 0; i < total; ++i) newV.row(i) = V.row(origin[i]);
  Vcut.swap(newV);
  Fcut.swap(newF);
  if (error) error->clear();
  return true;
}

/** \ingroup MeshTools_Module
  * \brief Cuts a triangle mesh open along a path of vertices: cutMesh() with the edges
  * (path[i], path[i+1]).
  *
  * \param path  vertex indices, consecutive ones joined by an edge of F (e.g. from
  *              shortestEdgePath()). A path of fewer than two vertices cuts nothing (the outputs
  *              are then V, F and the identity).
  * \returns true on success; false with a message naming the offending path position (outputs
  *          untouched) if a step of the path is not an edge of F or an index is out of range.
  *
  * \sa cutMesh(), shortestEdgePath()
  */
inline bool cutMeshAlongPath(const MatrixXd& V, const MatrixXi& F, const std::vector<int>& path, MatrixXd& Vcut,
                             MatrixXi& Fcut, VectorXi& origin, std::string* error = nullptr)
{
  std::vector<std::array<int, 2>> edges;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) edges.push_back({path[i], path[i + 1]});
  if (path.size() == 1 && (path[0] < 0 || path[0] >= V.rows()))
  {
    if (error) *error = "cutMeshAlongPath: path vertex 0 (" + std::to_string(path[0]) + ") is out of range";
    return false;
  }
  std::string cutError;
  if (cutMesh(V, F, edges, Vcut, Fcut, origin, &cutError))
  {
    if (error) error->clear();
    return true;
  }
  if (error)
  {
    // Name the path step for cut edge errors ("cut edge i" is the step from path[i] to path[i+1]).
    const std::string prefix = "cutMesh: cut edge ";
    *error = "cutMeshAlongPath: " +
             (cutError.compare(0, prefix.size(), prefix) == 0 ? "path step " + cutError.substr(prefix.size())
                                                               : cutError.substr(std::string("cutMesh: ").size()));
  }
  return false;
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_CUTMESH_H
