// CutToDisk: the edges along which a connected triangle mesh of any genus and any number of
// boundary loops must be cut to become a topological disk (a cut graph), for the disk-based
// parameterizations (Tutte, BFF; paper §5: a closed or holed surface is cut before it is laid
// out). A spanning tree of the faces across interior edges glues the faces into a disk; the
// interior edges it does not cross are cut; cut edges that end inside the surface (dangling) are
// glued back one by one, which keeps the disk, until only the loops around the handles and the
// paths that join the boundary loops remain (on a closed sphere, a path of two edges).

#ifndef EIGEN_MESHTOOLS_CUTTODISK_H
#define EIGEN_MESHTOOLS_CUTTODISK_H

namespace Eigen {

/** \ingroup MeshTools_Module
  * \brief A cut graph: edges of \a F that cutMesh() cuts to turn the mesh into a topological disk.
  *
  * \code
  * std::vector<std::array<int, 2>> cuts;
  * if (Eigen::cutToDisk(F, cuts, &error) && Eigen::cutMesh(V, F, cuts, Vdisk, Fdisk, origin, &error))
  *   bff.compute(Vdisk, Fdisk);   // Eigen::meshTopology(Fdisk).isDisk() holds
  * \endcode
  *
  * The mesh must be one piece through its edges, with every edge on one or two consistently
  * oriented triangles (an orientable manifold surface, possibly with boundary). The cut of a
  * surface of genus g with b boundary loops is made of 2g loops around and through the handles
  * and b − 1 paths joining the boundary loops, with no dangling ends; a disk gives no edge; a
  * closed surface of genus 0 gives a path of two edges (one edge alone would open nothing). The
  * edges come as (a, b) vertex pairs, each once, in the order of their first side in F.
  *
  * \param F         #F x 3 triangles, 0-based vertex indices.
  * \param cutEdges  output: the edges to cut (untouched on failure).
  * \param error     if not null, a message on failure, cleared on success.
  * \returns false when F is empty or not #F x 3 with non-negative indices, has an edge on three
  *          or more triangles or on two triangles that are not consistently oriented, or is not one piece.
  *          Cost O(#F log #F).
  * \sa cutMesh(), meshTopology(), boundaryLoops()
  */
inline bool cutToDisk(const MatrixXi& F, std::vector<std::array<int, 2>>& cutEdges, std::string* error = nullptr)
{
  auto fail = [error](const std::string& message) {
    if (error) *error = "cutToDisk: " + message;
    return false;
  };
  if (F.rows() == 0 || F.cols() != 3 || F.minCoeff() < 0) return fail("F must be a non-empty #F x 3 index matrix");
  {
    MatrixXi compact;  // (a stray huge index: work on the used vertices, name the cuts by F's indices)
    std::vector<int> used;
    if (internal::meshtools::compactVertexIndices(F, compact, used))
    {
      if (!cutToDisk(compact, cutEdges, error)) return false;
      for (auto& edge : cutEdges)
        for (int& v : edge) v = used[std::size_t(v)];
      return true;
    }
  }
  const std::vector<int> partner = internal::meshtools::sidePartners(F);
  const Index n = Index(F.maxCoeff()) + 1, sides = 3 * F.rows();
  for (Index side = 0; side < sides; ++side)
  {
    const int other = partner[std::size_t(side)];
    if (other == -2)
      return fail("edge (" + std::to_string(F(side / 3, side % 3)) + ", " + std::to_string(F(side / 3, (side % 3 + 1) % 3)) +
                  ") lies on three or more triangles (not a manifold surface)");
    if (other >= 0 && F(side / 3, side % 3) != F(other / 3, (other % 3 + 1) % 3))
      return fail("the triangles on edge (" + std::to_string(F(side / 3, side % 3)) + ", " +
                  std::to_string(F(side / 3, (side % 3 + 1) % 3)) + ") are not consistently oriented");
  }
  // 1. A spanning tree of the faces across interior edges (breadth first): the sides it crosses
  //    stay glued, every other interior edge is cut.
  std::vector<char> reached(std::size_t(F.rows()), 0), crossed(std::size_t(sides), 0);
  std::vector<int> queue{0};
  reached[0] = 1;
  for (std::size_t head = 0; head < queue.size(); ++head)
    for (int c = 0; c < 3; ++c)
    {
      const int side = queue[head] * 3 + c, other = partner[std::size_t(side)];
      if (other < 0 || reached[std::size_t(other / 3)]) continue;
      reached[std::size_t(other / 3)] = 1;
      crossed[std::size_t(side)] = crossed[std::size_t(other)] = 1;
      queue.push_back(other / 3);
    }
  if (Index(queue.size()) != F.rows()) return fail("the mesh is not one piece through its edges");
  // 2. The cut edges (one side each) and, per vertex, how many cut or boundary edges meet there.
  std::vector<int> cutSide;             // a side of each cut edge
  std::vector<int> degree(std::size_t(n), 0);
  std::vector<std::vector<int>> cutsAt{std::size_t(n)};  // per vertex: positions in cutSide
  bool boundary = false;
  for (Index side = 0; side < sides; ++side)
  {
    const int other = partner[std::size_t(side)];
    const int a = F(side / 3, side % 3), b = F(side / 3, (side % 3 + 1) % 3);
    if (other == -1)
    {  // a boundary edge: it keeps its ends in the graph
      boundary = true;
      ++degree[std::size_t(a)];
      ++degree[std::size_t(b)];
    }
    else if (other > side && !crossed[std::size_t(side)])
    {
      cutsAt[std::size_t(a)].push_back(int(cutSide.size()));
      cutsAt[std::size_t(b)].push_back(int(cutSide.size()));
      cutSide.push_back(int(side));
      ++degree[std::size_t(a)];
      ++degree[std::size_t(b)];
    }
  }
  // 3. Glue back the dangling cut edges: one whose end has no other cut or boundary edge. A
  //    closed mesh keeps two edges, which open it.
  std::vector<char> glued(cutSide.size(), 0);
  Index remaining = Index(cutSide.size());
  std::vector<int> leaves;
  for (Index v = 0; v < n; ++v)
    if (degree[std::size_t(v)] == 1) leaves.push_back(int(v));
  while (!leaves.empty() && (boundary || remaining > 2))
  {
    const int v = leaves.back();
    leaves.pop_back();
    if (degree[std::size_t(v)] != 1) continue;
    int edge = -1;
    for (int e : cutsAt[std::size_t(v)])
      if (!glued[std::size_t(e)]) edge = e;
    if (edge < 0) continue;  // (its one edge is a boundary edge: cannot happen on a closed chain)
    glued[std::size_t(edge)] = 1;
    --remaining;
    const int side = cutSide[std::size_t(edge)];
    for (int end : {F(side / 3, side % 3), F(side / 3, (side % 3 + 1) % 3)})
      if (--degree[std::size_t(end)] == 1) leaves.push_back(end);
  }
  cutEdges.clear();
  for (std::size_t e = 0; e < cutSide.size(); ++e)
    if (!glued[e]) cutEdges.push_back({F(cutSide[e] / 3, cutSide[e] % 3), F(cutSide[e] / 3, (cutSide[e] % 3 + 1) % 3)});
  if (error) error->clear();
  return true;
}

/** \ingroup MeshTools_Module
  * \brief Cuts the mesh (\a V, \a F) to a topological disk: cutToDisk() followed by cutMesh().
  *
  * \param V, F      the mesh (one orientable piece; any genus, any number of boundary loops).
  * \param Vdisk     output: the vertices of the disk (copies appended, see cutMesh()).
  * \param Fdisk     output: its triangles, in the order of F.
  * \param origin    output: for every vertex of the disk, the vertex of V it copies.
  * \param error     if not null, a message on failure, cleared on success.
  * \returns false (outputs untouched) when cutToDisk() or cutMesh() refuses the mesh. A disk comes
  *          back as it is; meshTopology(Fdisk).isDisk() holds on success.
  */
inline bool cutMeshToDisk(const MatrixXd& V, const MatrixXi& F, MatrixXd& Vdisk, MatrixXi& Fdisk, VectorXi& origin,
                          std::string* error = nullptr)
{
  std::vector<std::array<int, 2>> cuts;
  return internal::meshtools::checkTriangles(F, V.rows(), "cutMeshToDisk", error) && cutToDisk(F, cuts, error) &&
         cutMesh(V, F, cuts, Vdisk, Fdisk, origin, error);
}

/** \ingroup MeshTools_Module
  * \brief cutMeshToDisk() in place: \a V and \a F become the disk's vertices and triangles, and
  * \a origin maps each of its vertices to the vertex it copies. A disk stays as it is.
  * \returns false (\a V, \a F untouched, \a error says why) when the mesh is refused.
  *
  * \code
  * if (!Eigen::meshTopology(F).isDisk() && !Eigen::cutMeshToDisk(V, F, origin, &error)) return 1;
  * \endcode
  */
inline bool cutMeshToDisk(MatrixXd& V, MatrixXi& F, VectorXi& origin, std::string* error = nullptr)
{
  MatrixXd Vdisk;
  MatrixXi Fdisk;
  if (!cutMeshToDisk(V, F, Vdisk, Fdisk, origin, error)) return false;
  V.swap(Vdisk);
  F.swap(Fdisk);
  return true;
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_CUTTODISK_H
