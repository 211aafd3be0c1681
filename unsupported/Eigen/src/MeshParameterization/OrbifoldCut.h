// OrbifoldCut: the cut of a sphere-type mesh for an Euclidean orbifold Tutte embedding
// (Aigerman & Lipman 2015, "Orbifold Tutte Embeddings", §4-5; Herholz & Sorkine-Hornung, "Sparse
// Cholesky Updates for Interactive Mesh Parameterization", §5.2): the four sphere orbifolds with
// 3 or 4 cones, the cone images of their fundamental domains, the chain of shortest edge paths
// c1 -> c2 -> ... -> ck that cuts the closed surface into a disk, and the pairs of seam copies
// (left and right of the chain) with the rotation that relates them.

#ifndef EIGEN_MESHPARAMETERIZATION_ORBIFOLDCUT_H
#define EIGEN_MESHPARAMETERIZATION_ORBIFOLDCUT_H

namespace Eigen {

/** \ingroup MeshParameterization_Module
  * \brief The four Euclidean orbifolds of the sphere (Aigerman & Lipman 2015, Fig. 3).
  *
  * The cones are given in the order of the cut chain c1 -> c2 -> ... -> ck; cone i then has the
  * order k_i listed here (its total angle is 2π/k_i):
  * - I:   (3,3,3)   — the disk is a rhombus of two equilateral triangles;
  * - II:  (4,2,4)   — the disk is a square (the (2,4,4) orbifold, the order-2 cone in the middle);
  * - III: (6,2,3)   — the disk is a kite with right angles at c2 (the (2,3,6) orbifold);
  * - IV:  (2,2,2,2) — the disk is a 2 x 1 rectangle (the pillowcase).
  */
enum class OrbifoldType { I, II, III, IV };

namespace internal {
namespace mesh_parameterization {

/** \internal \returns the cone orders of \a type in chain order (see OrbifoldType). */
inline std::vector<int> orbifoldConeOrders(OrbifoldType type)
{
  switch (type)
  {
    case OrbifoldType::I: return {3, 3, 3};
    case OrbifoldType::II: return {4, 2, 4};
    case OrbifoldType::III: return {6, 2, 3};
    case OrbifoldType::IV: return {2, 2, 2, 2};
  }
  return {};
}

/** \internal The rotation by \a angle (counter-clockwise) of the plane. */
inline Matrix2d planeRotation(double angle)
{
  Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

/** \internal The images of the cones' left copies in the plane (one row per cone, chain order).
  * The disk's boundary, counter-clockwise, runs c1 -> c2 (left) -> ... -> ck -> ... -> c2 (right)
  * -> c1; the right copies follow from the rotations. For three cones c1 = (0,0), c3 = (1,0) and
  * c2 below the axis where the angles 2π/k1 at c1 and 2π/k3 at c3 put it (the disk is a kite,
  * symmetric about c1c3). For four cones c1..c4 = (0,0), (1,0), (1,1), (0,1). */
inline MatrixX2d orbifoldConePositions(OrbifoldType type)
{
  const std::vector<int> order = orbifoldConeOrders(type);
  MatrixX2d P(Index(order.size()), 2);
  if (order.size() == 4)
  {
    P << 0, 0, 1, 0, 1, 1, 0, 1;
    return P;
  }
  const double pi = 3.14159265358979323846;
  const double a1 = 2 * pi / order[0], a2 = 2 * pi / order[1], a3 = 2 * pi / order[2];
  // Triangle c1 c2 c3: angles a1/2 at c1, a3/2 at c3, a2/2 at c2; |c1 c3| = 1 (law of sines).
  const double c1c2 = std::sin(a3 / 2) / std::sin(a2 / 2);
  P << 0, 0, c1c2 * std::cos(a1 / 2), -c1c2 * std::sin(a1 / 2), 1, 0;
  return P;
}

/** \internal Area of the fundamental domain (the disk) with the cone images of
  * orbifoldConePositions(): the kite for three cones, the rectangle for four. */
inline double orbifoldDomainArea(OrbifoldType type)
{
  const MatrixX2d P = orbifoldConePositions(type);
  if (P.rows() == 4) return 2.0;
  return -P(1, 1);  // two triangles of base |c1c3| = 1 and height |y(c2)|
}

/** \internal One seam constraint: the right copy equals the rotation of the left copy,
  * X(right) = R(angle) (X(left) - X(center)) + X(centerImage); for a rotation about a cone the
  * center is the cone's (fixed) image on both sides, for the translation of the middle segment of
  * type IV (angle 0) the center is the left copy of c2 and centerImage its right copy. */
struct OrbifoldSeamPair
{
  int left = -1, right = -1;    ///< the two copies (indices of the cut mesh)
  double angle = 0;             ///< rotation angle (radians, counter-clockwise)
  int centerCone = -1;          ///< cone (chain position 0..k-1) whose image is the center
  int centerLeft = -1, centerRight = -1;  ///< the center's copies in the cut mesh
};

/** \internal The cut of a closed mesh along the cone chain, with everything the constraints need. */
struct OrbifoldCutResult
{
  std::vector<int> chain;        ///< vertices of the chain c1 -> ... -> ck (original indices)
  std::vector<int> conePosition; ///< position of each cone in \a chain
  std::vector<int> left, right;  ///< per chain vertex: its copy left / right of the chain
  MatrixXd Vcut;                 ///< cut mesh vertices
  MatrixXi Fcut;                 ///< cut mesh faces (same rows as F)
  VectorXi origin;               ///< cut vertex -> original vertex
  std::vector<OrbifoldSeamPair> pairs;  ///< one per right copy that is not a fixed cone image
};

/** \internal Checks that F is a closed, consistently oriented, connected surface of genus 0 (every
  * directed edge once, with its reverse; Euler characteristic 2 over the used vertices; one fan of
  * triangles around each vertex).
  * \returns false with \a error set otherwise. */
inline bool checkSphereTopology(const MatrixXi& F, std::string& error)
{
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(std::size_t(3 * F.rows()));
  auto key = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (++directed[key(F(f, c), F(f, (c + 1) % 3))] > 1)
      {
        error = "the mesh is not consistently oriented or not manifold at edge " + std::to_string(F(f, c)) + "-" +
                std::to_string(F(f, (c + 1) % 3));
        return false;
      }
  for (const auto& e : directed)
    if (directed.find((e.first << 32) | (e.first >> 32)) == directed.end())
    {
      error = "the mesh is not closed: edge " + std::to_string(int(e.first >> 32)) + "-" +
              std::to_string(int(e.first & 0xffffffffu)) + " is on the boundary (a sphere-type mesh is needed)";
      return false;
    }
  // one sort of the sides for the counts and the fans below (closed here: no boundary loops)
  const std::vector<int> partner = internal::meshtools::sidePartners(F);
  const MeshTopology topology = internal::meshtools::topologyFromPartners(F, partner, 0);
  const Index components = topology.components, euler = topology.eulerCharacteristic;
  if (components != 1 || euler != 2)
  {
    error = "the mesh is not a sphere: " + std::to_string(components) + " component(s), Euler characteristic " +
            std::to_string(euler) + " (genus 0 and one piece are needed)";
    return false;
  }
  // every vertex on one fan of triangles: two spheres touching at two vertices pass the counts
  // above (Euler characteristic 2, one piece) but are no sphere
  std::vector<char> walked(std::size_t(3 * F.rows()), 0);
  std::vector<char> hasFan(std::size_t(F.maxCoeff()) + 1, 0);
  for (Index corner = 0; corner < 3 * F.rows(); ++corner)
  {
    if (walked[std::size_t(corner)]) continue;
    const int v = F(corner / 3, corner % 3);
    if (hasFan[std::size_t(v)])
    {
      error = "the mesh is not a sphere: the triangles around vertex " + std::to_string(v) +
              " form more than one fan (surfaces touching at a vertex)";
      return false;
    }
    hasFan[std::size_t(v)] = 1;
    for (Index c = corner; !walked[std::size_t(c)];)
    {  // to the next triangle around v, across the side that enters v
      walked[std::size_t(c)] = 1;
      const int across = partner[std::size_t(3 * (c / 3) + (c % 3 + 2) % 3)];
      if (across < 0)
      {  // (a degenerate side, with a repeated vertex, has no partner)
        error = "the mesh is not a manifold surface at vertex " + std::to_string(v) + " (a degenerate triangle)";
        return false;
      }
      c = Index(across);  // (that side leaves v in the neighbour: its corner is at v)
    }
  }
  return true;
}

/** \internal Shortest edge path from \a source to \a target that avoids the vertices flagged in
  * \a blocked (the endpoints excepted): shortestEdgePath() on the faces free of blocked vertices. */
inline std::vector<int> pathAvoiding(const MatrixXd& V, const MatrixXi& F, int source, int target,
                                     const std::vector<char>& blocked)
{
  std::vector<int> keep;
  keep.reserve(std::size_t(F.rows()));
  for (Index f = 0; f < F.rows(); ++f)
  {
    bool free = true;
    for (int c = 0; c < 3 && free; ++c)
    {
      const int v = F(f, c);
      free = !blocked[std::size_t(v)] || v == source || v == target;
    }
    if (free) keep.push_back(int(f));
  }
  MatrixXi Ffree(Index(keep.size()), 3);
  for (std::size_t k = 0; k < keep.size(); ++k) Ffree.row(Index(k)) = F.row(keep[k]);
  return shortestEdgePath(V, Ffree, source, target);
}

/** \internal Cuts the closed mesh (V, F) along the chain of shortest paths through \a cones (each
  * path avoiding the earlier ones and the other cones) and pairs the seam copies.
  * \returns false with \a error set when the cones are invalid or a path does not exist. */
inline bool orbifoldCut(const MatrixXd& V, const MatrixXi& F, const std::vector<int>& cones, OrbifoldType type,
                        OrbifoldCutResult& cut, std::string& error)
{
  const std::vector<int> order = orbifoldConeOrders(type);
  const int n = int(V.rows()), k = int(cones.size());
  if (k != int(order.size()))
  {
    error = "orbifold type " + std::to_string(int(type) + 1) + " needs " + std::to_string(order.size()) +
            " cones, got " + std::to_string(k);
    return false;
  }
  for (int i = 0; i < k; ++i)
  {
    if (cones[std::size_t(i)] < 0 || cones[std::size_t(i)] >= n)
    {
      error = "cone " + std::to_string(i) + " is not a vertex index: " + std::to_string(cones[std::size_t(i)]);
      return false;
    }
    for (int j = 0; j < i; ++j)
      if (cones[std::size_t(i)] == cones[std::size_t(j)])
      {
        error = "cones " + std::to_string(j) + " and " + std::to_string(i) + " are the same vertex";
        return false;
      }
  }

  // The chain c1 -> c2 -> ... -> ck, each path avoiding the chain so far and the later cones.
  std::vector<char> blocked(std::size_t(n), 0);
  for (int c : cones) blocked[std::size_t(c)] = 1;
  cut.chain.assign(1, cones[0]);
  cut.conePosition.assign(1, 0);
  for (int s = 0; s + 1 < k; ++s)
  {
    const std::vector<int> path = pathAvoiding(V, F, cones[std::size_t(s)], cones[std::size_t(s) + 1], blocked);
    if (path.size() < 2)
    {
      error = "no edge path from cone " + std::to_string(s) + " (vertex " + std::to_string(cones[std::size_t(s)]) +
              ") to cone " + std::to_string(s + 1) + " (vertex " + std::to_string(cones[std::size_t(s) + 1]) +
              ") that avoids the cut so far";
      return false;
    }
    for (std::size_t p = 1; p < path.size(); ++p)
    {
      cut.chain.push_back(path[p]);
      blocked[std::size_t(path[p])] = 1;
    }
    cut.conePosition.push_back(int(cut.chain.size()) - 1);
  }

  std::vector<std::array<int, 2>> edges;
  for (std::size_t p = 0; p + 1 < cut.chain.size(); ++p) edges.push_back({cut.chain[p], cut.chain[p + 1]});
  std::string cutError;
  if (!cutMesh(V, F, edges, cut.Vcut, cut.Fcut, cut.origin, &cutError))
  {
    error = "cutting along the cone chain failed: " + cutError;
    return false;
  }

  // Left/right copies: the face on the left of the directed chain edge a -> b holds a -> b in its
  // own (counter-clockwise) order; the face on the right holds b -> a.
  std::unordered_map<std::uint64_t, int> faceOfDirectedEdge;
  faceOfDirectedEdge.reserve(std::size_t(3 * F.rows()));
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      faceOfDirectedEdge[(std::uint64_t(std::uint32_t(F(f, c))) << 32) | std::uint32_t(F(f, (c + 1) % 3))] = int(f);
  auto faceOf = [&](int a, int b) {
    const auto it = faceOfDirectedEdge.find((std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b));
    return it == faceOfDirectedEdge.end() ? -1 : it->second;
  };
  auto copyIn = [&](int face, int v) {
    for (int c = 0; c < 3; ++c)
      if (F(face, c) == v) return cut.Fcut(face, c);
    return -1;
  };
  const std::size_t m = cut.chain.size();
  cut.left.assign(m, -1);
  cut.right.assign(m, -1);
  for (std::size_t p = 0; p + 1 < m; ++p)
  {
    const int a = cut.chain[p], b = cut.chain[p + 1];
    const int fl = faceOf(a, b), fr = faceOf(b, a);
    if (fl < 0 || fr < 0)
    {
      error = "the mesh is not closed and consistently oriented along the cut (edge " + std::to_string(a) + "-" +
              std::to_string(b) + ")";
      return false;
    }
    const int copies[4] = {copyIn(fl, a), copyIn(fl, b), copyIn(fr, a), copyIn(fr, b)};
    const int* sides[2] = {copies, copies + 2};
    std::vector<int>* lists[2] = {&cut.left, &cut.right};
    for (int side = 0; side < 2; ++side)
      for (int e = 0; e < 2; ++e)
      {
        int& slot = (*lists[side])[p + std::size_t(e)];
        if (slot >= 0 && slot != sides[side][e])
        {
          error = "the cut along the cone chain is not a disk (vertex " + std::to_string(cut.chain[p + std::size_t(e)]) +
                  " has more than two sides)";
          return false;
        }
        slot = sides[side][e];
      }
  }
  if (cut.left.front() != cut.right.front() || cut.left.back() != cut.right.back())
  {
    error = "the ends of the cone chain were split: the mesh is not a closed surface of genus 0 around them";
    return false;
  }
  for (std::size_t p = 1; p + 1 < m; ++p)
    if (cut.left[p] == cut.right[p])
    {
      error = "chain vertex " + std::to_string(cut.chain[p]) + " was not split by the cut";
      return false;
    }

  // One pair per right copy. Vertices up to c2 turn about c1 by 2π/k1, those after c_{k-1}
  // about ck by -2π/k_k; the middle segment of type IV (after c2, up to c3) is the translation
  // taking c2's left copy to its right one (angle 2π/k1 + 2π/k2 = 2π).
  const double pi = 3.14159265358979323846;
  cut.pairs.clear();
  for (std::size_t p = 1; p + 1 < m; ++p)
  {
    OrbifoldSeamPair pair;
    pair.left = cut.left[p];
    pair.right = cut.right[p];
    const int pos = int(p);
    if (pos <= cut.conePosition[1])
    {
      pair.centerCone = 0;
      pair.angle = 2 * pi / order[0];
    }
    else if (pos > cut.conePosition[std::size_t(k) - 2])
    {
      pair.centerCone = k - 1;
      pair.angle = -2 * pi / order[std::size_t(k) - 1];
    }
    else
    {
      pair.centerCone = 1;
      pair.angle = 0;
    }
    const std::size_t centerPos = std::size_t(cut.conePosition[std::size_t(pair.centerCone)]);
    pair.centerLeft = cut.left[centerPos];
    pair.centerRight = cut.right[centerPos];
    cut.pairs.push_back(pair);
  }
  return true;
}

} // namespace mesh_parameterization
} // namespace internal

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_ORBIFOLDCUT_H
