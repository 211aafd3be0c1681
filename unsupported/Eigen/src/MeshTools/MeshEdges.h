// MeshEdges: internal helpers shared by the topology tools (boundary loops, edge paths, cuts):
// checking that a face matrix is a valid list of triangles over n vertices, and the edges of a
// triangle mesh as half-edge records sorted by their undirected key.

#ifndef EIGEN_MESHTOOLS_MESHEDGES_H
#define EIGEN_MESHTOOLS_MESHEDGES_H

namespace Eigen {
namespace internal {
namespace meshtools {

/** \internal Key of the undirected edge {a, b}: the same for (a, b) and (b, a). */
inline std::uint64_t undirectedEdgeKey(int a, int b)
{
  const int lo = std::min(a, b), hi = std::max(a, b);
  return (std::uint64_t(std::uint32_t(lo)) << 32) | std::uint64_t(std::uint32_t(hi));
}

/** \internal When the vertex indices of \a F span far more values than it has corners (the
  * largest index is above twice the corner count: unused indices dominate), fills \a compact
  * with F's used vertices renumbered 0..k-1 in increasing order and \a used with the index each
  * stood for, and \returns true; otherwise \returns false (F may index arrays by vertex). The
  * tools that allocate per vertex use it so that a stray huge index costs no huge allocation. */
inline bool compactVertexIndices(const MatrixXi& F, MatrixXi& compact, std::vector<int>& used)
{
  if (F.size() == 0 || Index(F.maxCoeff()) < 2 * F.size()) return false;
  used.assign(F.data(), F.data() + F.size());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  compact.resize(F.rows(), F.cols());
  for (Index k = 0; k < F.size(); ++k)
    compact.data()[k] = int(std::lower_bound(used.begin(), used.end(), F.data()[k]) - used.begin());
  return true;
}

/** \internal Key of the directed edge a -> b. */
inline std::uint64_t directedEdgeKey(int a, int b)
{
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint64_t(std::uint32_t(b));
}

/** \internal Checks that \a F is a #F x 3 matrix of indices in [0, \a nVertices).
  * \returns true if so; otherwise false and, if \a error is not null, a message starting with
  * \a who that names the first bad face. */
inline bool checkTriangles(const MatrixXi& F, Index nVertices, const char* who, std::string* error)
{
  if (F.rows() > 0 && F.cols() != 3)
  {
    if (error) *error = std::string(who) + ": F must have 3 columns (triangles), it has " + std::to_string(F.cols());
    return false;
  }
  for (Index f = 0; f < F.rows(); ++f)
    for (Index c = 0; c < F.cols(); ++c)
      if (F(f, c) < 0 || F(f, c) >= nVertices)
      {
        if (error)
          *error = std::string(who) + ": face " + std::to_string(f) + " has vertex index " + std::to_string(F(f, c)) +
                   " outside [0, " + std::to_string(nVertices) + ")";
        return false;
      }
  return true;
}

/** \internal One side of an edge: face \a face holds the edge from its corner \a corner to its
  * corner (corner + 1) % 3. */
struct HalfEdgeRecord
{
  std::uint64_t key; ///< undirected key of the edge
  int face;          ///< face holding this side
  int corner;        ///< local corner (0..2) where this side starts
};

/** \internal Every non-degenerate side (a != b) of every face of \a F, sorted by undirected key
  * (then face, corner), so that the sides of one edge are consecutive. */
inline std::vector<HalfEdgeRecord> sortedHalfEdges(const MatrixXi& F)
{
  std::vector<HalfEdgeRecord> records;
  records.reserve(std::size_t(3 * F.rows()));
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
    {
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      if (a != b) records.push_back({undirectedEdgeKey(a, b), int(f), c});
    }
  std::sort(records.begin(), records.end(), [](const HalfEdgeRecord& x, const HalfEdgeRecord& y) {
    if (x.key != y.key) return x.key < y.key;
    return x.face != y.face ? x.face < y.face : x.corner < y.corner;
  });
  return records;
}

/** \internal For every side face*3+corner of \a F: the other side of the same edge (as
  * face*3+corner) if exactly two sides share the edge, -1 if the side is alone (a boundary edge),
  * -2 if three or more sides share it (a non-manifold edge), -3 if the side is degenerate (a == b). */
inline std::vector<int> sidePartners(const MatrixXi& F)
{
  const std::vector<HalfEdgeRecord> records = sortedHalfEdges(F);
  std::vector<int> partner(std::size_t(3 * F.rows()), -3);
  for (std::size_t begin = 0, end = 0; begin < records.size(); begin = end)
  {
    end = begin + 1;
    while (end < records.size() && records[end].key == records[begin].key) ++end;
    const std::size_t count = end - begin;
    for (std::size_t r = begin; r < end; ++r)
    {
      int& value = partner[std::size_t(records[r].face * 3 + records[r].corner)];
      if (count == 1) value = -1;
      else if (count > 2) value = -2;
      else
      {
        const HalfEdgeRecord& other = records[r == begin ? begin + 1 : begin];
        value = other.face * 3 + other.corner;
      }
    }
  }
  return partner;
}

} // namespace meshtools
} // namespace internal
} // namespace Eigen

#endif // EIGEN_MESHTOOLS_MESHEDGES_H
