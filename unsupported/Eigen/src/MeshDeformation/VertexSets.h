// VertexSets: checking user-given vertex lists (handles, regions of interest) and turning the
// change between two sets of constrained vertices into the dofs to remove and to restore, the
// edits that UpdatableSupernodalLLT applies in place (Herholz & Sorkine-Hornung, §4.1 and §5.3).

#ifndef EIGEN_MESHDEFORMATION_VERTEXSETS_H
#define EIGEN_MESHDEFORMATION_VERTEXSETS_H

namespace Eigen {
namespace internal {
namespace mesh_deformation {

/** Checks that every entry of \a vertices is a vertex index in [0, \a vertexCount) and that none
  * repeats. \returns true if so; otherwise false and, in \a error, a message that starts with
  * \a what (e.g. "handle") and names the offending position and index. */
inline bool checkVertexList(const std::vector<int>& vertices, Index vertexCount, const char* what,
                            std::string& error)
{
  std::vector<char> seen(std::size_t(vertexCount), 0);
  for (std::size_t k = 0; k < vertices.size(); ++k)
  {
    const int v = vertices[k];
    if (v < 0 || Index(v) >= vertexCount)
    {
      error = std::string(what) + " " + std::to_string(k) + " is vertex " + std::to_string(v) +
              ", out of range [0, " + std::to_string(vertexCount) + ")";
      return false;
    }
    if (seen[std::size_t(v)])
    {
      error = std::string(what) + " " + std::to_string(k) + ": vertex " + std::to_string(v) + " is repeated";
      return false;
    }
    seen[std::size_t(v)] = 1;
  }
  return true;
}

/** The edit that turns the constrained set \a before into \a after (both flags per vertex):
  * \a added receives the vertices constrained only in \a after (dofs to remove from the system),
  * \a released those constrained only in \a before (dofs to restore), both in increasing order. */
inline void constraintChange(const std::vector<char>& before, const std::vector<char>& after, std::vector<int>& added,
                             std::vector<int>& released)
{
  eigen_assert(before.size() == after.size());
  added.clear();
  released.clear();
  for (std::size_t v = 0; v < after.size(); ++v)
  {
    if (after[v] && !before[v]) added.push_back(int(v));
    if (before[v] && !after[v]) released.push_back(int(v));
  }
}

} // namespace mesh_deformation
} // namespace internal
} // namespace Eigen

#endif // EIGEN_MESHDEFORMATION_VERTEXSETS_H
