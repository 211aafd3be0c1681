// SeamCutInPlace: cutting a mesh along a seam from its boundary inwards, in place and in time
// proportional to the seam's neighbourhood (plus one scan of the faces), for the interactive seam
// edits of the paper (§5.1): the same result as cutMeshAlongPath() — the same new vertices in the
// same order, the same faces — without rebuilding the mesh's edge tables or copying it, and the
// new boundary loop spliced into the old one instead of traced anew. Anything it does not handle
// (a seam that does not run from the loop into the interior, a non-manifold neighbourhood) is
// left to the general cut.

#ifndef EIGEN_MESHTOOLS_SEAMCUTINPLACE_H
#define EIGEN_MESHTOOLS_SEAMCUTINPLACE_H

namespace Eigen {
namespace internal {
namespace meshtools {

/** \internal One corner of a face rewritten by seamCutInPlace(): F(face, corner) was \a vertex. */
struct CornerEdit
{
  int face, corner, vertex;
};

/** \internal Cuts the mesh (\a V, \a F) along \a path in place, when the path starts on the
  * boundary loop \a loop (a vertex that occurs on it once), is simple, runs through vertices on no
  * boundary (\a onBoundary, by vertex, covers every boundary loop) along edges of F, and the
  * triangles around its vertices form one fan each (no edge on three triangles). The mesh must
  * have no vertex whose triangles form several fans elsewhere (cutMesh() would split those too).
  * Then, as cutMeshAlongPath() would: each path vertex but the last gets one copy, appended to V
  * (and to \a origin, which maps each vertex to the vertex it copies) in the order of its
  * triangles' first corner in F, and the corners on the far side of the seam are rewritten
  * (listed in \a edits, to be undone in reverse order); \a loop becomes the loop that runs up one
  * side of the seam and down the other (same orientation, same start), and \a onBoundary covers
  * the new boundary vertices. \returns false with everything untouched when the path is not of
  * that kind (the caller then cuts the general way). \a mark: scratch by vertex, all -1 between
  * calls (resized as needed). */
inline bool seamCutInPlace(MatrixXd& V, MatrixXi& F, VectorXi& origin, std::vector<int>& loop,
                           std::vector<char>& onBoundary, const std::vector<int>& path, std::vector<CornerEdit>& edits,
                           std::vector<int>& mark)
{
  const Index n = V.rows();
  const std::size_t length = path.size();
  edits.clear();
  if (length < 2 || loop.size() < 3 || origin.size() != n || Index(onBoundary.size()) != n) return false;
  if (Index(mark.size()) < n) mark.resize(std::size_t(n), -1);
  // 1. The path: in range, simple, from the loop (once on it) into the interior.
  std::size_t marked = 0;
  auto unmark = [&]() {
    for (std::size_t i = 0; i < marked; ++i) mark[std::size_t(path[i])] = -1;
    return false;
  };
  for (; marked < length; ++marked)
  {
    const int v = path[marked];
    if (v < 0 || v >= n || mark[std::size_t(v)] >= 0 || (marked > 0 && onBoundary[std::size_t(v)])) return unmark();
    mark[std::size_t(v)] = int(marked);
  }
  if (std::count(loop.begin(), loop.end(), path[0]) != 1) return unmark();
  // 2. The corners at the path's vertices, per vertex in the order of F (one scan of the faces).
  std::vector<std::vector<int>> corners(length);
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
    {
      const int at = mark[std::size_t(F(f, c))];
      if (at >= 0) corners[std::size_t(at)].push_back(int(3 * f + c));
    }
  // 3. Per path vertex, its wedges: corners joined across uncut edges (union-find on positions).
  struct Wedge
  {
    int pathIndex, firstCorner, root;
  };
  std::vector<std::vector<int>> wedgeOf(length);  // per path vertex: its corners' roots
  std::vector<Wedge> copies;
  std::vector<int> parent, roots;
  std::vector<std::pair<int, int>> ends;  // (other end, corner position) of every side at a path vertex
  for (std::size_t i = 0; i < length; ++i)
  {
    const std::vector<int>& list = corners[i];
    const int v = path[i];
    const int before = i > 0 ? path[i - 1] : -1, after = i + 1 < length ? path[i + 1] : -1;
    parent.resize(list.size());
    for (std::size_t a = 0; a < list.size(); ++a) parent[a] = int(a);
    auto find = [&parent](int a) {
      while (parent[std::size_t(a)] != a) a = parent[std::size_t(a)] = parent[std::size_t(parent[std::size_t(a)])];
      return a;
    };
    ends.clear();  // (equal other ends share an edge)
    for (std::size_t a = 0; a < list.size(); ++a)
    {
      const int f = list[a] / 3, c = list[a] % 3;
      ends.emplace_back(F(f, (c + 1) % 3), int(a));
      ends.emplace_back(F(f, (c + 2) % 3), int(a));
    }
    std::sort(ends.begin(), ends.end());
    bool pathEdge[2] = {before < 0, after < 0};
    for (std::size_t b = 0, e = 0; b < ends.size(); b = e)
    {
      e = b + 1;
      while (e < ends.size() && ends[e].first == ends[b].first) ++e;
      const int w = ends[b].first;
      if (e - b > 2 || w == v) return unmark();  // an edge on three triangles, or a degenerate one
      if (w == before || w == after)
      {  // a cut edge: it must be interior (else the seam runs along the boundary) and joins nothing
        if (e - b == 1) return unmark();
        pathEdge[w == before ? 0 : 1] = true;
        continue;
      }
      if (e - b == 2)
      {
        const int x = find(ends[b].second), y = find(ends[b + 1].second);
        if (x != y) parent[std::size_t(std::max(x, y))] = std::min(x, y);
      }
    }
    if (!pathEdge[0] || !pathEdge[1]) return unmark();  // a step of the path is not an edge
    // the roots are the smallest positions of their wedges: positions follow F, so a root is
    // its wedge's first corner; the wedge of the vertex's first corner (position 0) keeps v
    roots.clear();
    for (std::size_t a = 0; a < list.size(); ++a)
    {
      wedgeOf[i].push_back(find(int(a)));
      if (wedgeOf[i].back() == int(a)) roots.push_back(int(a));
    }
    const std::size_t expected = i + 1 < length ? 2 : 1;
    if (roots.size() != expected) return unmark();
    if (expected == 2) copies.push_back(Wedge{int(i), list[std::size_t(roots[1])], roots[1]});
  }
  // 4. The copies, numbered in the order of their first corners; the corners rewritten.
  std::sort(copies.begin(), copies.end(), [](const Wedge& a, const Wedge& b) { return a.firstCorner < b.firstCorner; });
  for (std::size_t q = 0; q < copies.size(); ++q)
  {
    const Wedge& w = copies[q];
    const std::vector<int>& list = corners[std::size_t(w.pathIndex)];
    for (std::size_t a = 0; a < list.size(); ++a)
      if (wedgeOf[std::size_t(w.pathIndex)][a] == w.root)
      {
        const int f = list[a] / 3, c = list[a] % 3;
        edits.push_back(CornerEdit{f, c, F(f, c)});
        F(f, c) = int(n + Index(q));
      }
  }
  // 5. The new loop: from the side arriving at path[0] along the old loop, up one side of the
  //    seam and down the other, to the side leaving towards the old successor. Sides at the
  //    seam's vertices and their copies all lie in the scanned faces.
  const std::size_t at = std::size_t(std::find(loop.begin(), loop.end(), path[0]) - loop.begin());
  const int previous = loop[(at + loop.size() - 1) % loop.size()], next = loop[(at + 1) % loop.size()];
  std::vector<std::uint64_t> sides;            // the directed sides of the scanned faces, sorted
  std::vector<std::pair<int, int>> cornersAt;  // (vertex, corner) at the seam's vertices and copies
  for (const auto& list : corners)
    for (int corner : list)
    {
      const int f = corner / 3;
      cornersAt.emplace_back(F(f, corner % 3), corner);
      for (int c = 0; c < 3; ++c) sides.push_back(directedEdgeKey(F(f, c), F(f, (c + 1) % 3)));
    }
  std::sort(sides.begin(), sides.end());
  std::sort(cornersAt.begin(), cornersAt.end());
  auto hasSide = [&sides](int a, int b) { return std::binary_search(sides.begin(), sides.end(), directedEdgeKey(a, b)); };
  auto forCornersOf = [&cornersAt](int v, auto&& visit) {
    for (auto it = std::lower_bound(cornersAt.begin(), cornersAt.end(), std::make_pair(v, -1));
         it != cornersAt.end() && it->first == v; ++it)
      visit(it->second / 3, it->second % 3);
  };
  int start = path[0];  // the copy of path[0]
  for (std::size_t q = 0; q < copies.size(); ++q)
    if (copies[q].pathIndex == 0) start = int(n + Index(q));
  int arrival = -1, departure = -1;  // the wedges of path[0] the old loop arrives at / leaves from
  for (int x : {path[0], start})
    forCornersOf(x, [&](int f, int c) {
      if (F(f, (c + 2) % 3) == previous && !hasSide(x, previous)) arrival = x;
      if (F(f, (c + 1) % 3) == next && !hasSide(next, x)) departure = x;
    });
  std::vector<int> traced;
  bool ok = arrival >= 0 && departure >= 0;
  for (int current = arrival; ok && current != departure;)
  {
    traced.push_back(current);
    int leaving = -1, count = 0;
    forCornersOf(current, [&](int f, int c) {
      const int w = F(f, (c + 1) % 3);
      if (!hasSide(w, current))
      {
        leaving = w;
        ++count;
      }
    });
    ok = count == 1 && traced.size() <= 2 * length + 2 &&
         (leaving == departure || leaving >= n || mark[std::size_t(leaving)] >= 0);
    current = leaving;
  }
  if (ok) traced.push_back(departure);
  if (!ok || traced.size() != 2 * length - 1)
  {
    for (std::size_t e = edits.size(); e-- > 0;) F(edits[e].face, edits[e].corner) = edits[e].vertex;
    edits.clear();
    return unmark();
  }
  unmark();
  // 6. Commit: the copies' positions and origins, the spliced loop, the boundary flags.
  const Index total = n + Index(copies.size());
  V.conservativeResize(total, V.cols());
  origin.conservativeResize(total);
  for (std::size_t q = 0; q < copies.size(); ++q)
  {
    const int v = path[std::size_t(copies[q].pathIndex)];
    V.row(n + Index(q)) = V.row(v);
    origin[n + Index(q)] = origin[v];
  }
  std::vector<int> spliced(loop.begin(), loop.begin() + std::ptrdiff_t(at));
  spliced.insert(spliced.end(), traced.begin(), traced.end());
  spliced.insert(spliced.end(), loop.begin() + std::ptrdiff_t(at) + 1, loop.end());
  loop.swap(spliced);
  onBoundary.resize(std::size_t(total), 0);
  for (int v : traced) onBoundary[std::size_t(v)] = 1;
  return true;
}

} // namespace meshtools
} // namespace internal
} // namespace Eigen

#endif // EIGEN_MESHTOOLS_SEAMCUTINPLACE_H
