// GenerateMeshes: synthetic triangle meshes of any size for tests and benchmarks: a planar grid
// (a disk with one boundary loop), a subdivided icosahedron on the unit sphere (closed, genus 0)
// and a torus (closed, genus 1).

#ifndef EIGEN_MESHTOOLS_GENERATEMESHES_H
#define EIGEN_MESHTOOLS_GENERATEMESHES_H

namespace Eigen {

/** \ingroup MeshTools_Module
  * \brief Regular triangulated grid on the unit square [0,1]^2 in the plane z = 0.
  *
  * Vertex (i, j), 0 <= i < nx, 0 <= j < ny, has index j*nx + i and position
  * (i/(nx-1), j/(ny-1), 0). Each grid cell is split along the same diagonal into two triangles,
  * counter-clockwise seen from +z, so F has 2*(nx-1)*(ny-1) rows. The mesh is a topological disk.
  * If nx < 2 or ny < 2 there are no triangles (and a single row or column is placed at 0).
  *
  * \param nx  vertices along x.
  * \param ny  vertices along y.
  * \param V   output: (nx*ny) x 3 vertex positions.
  * \param F   output: 2*(nx-1)*(ny-1) x 3 triangles, 0-based.
  */
inline void gridMesh(int nx, int ny, MatrixXd& V, MatrixXi& F)
{
  nx = std::max(nx, 0);
  ny = std::max(ny, 0);
  V.resize(Index(nx) * ny, 3);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      V.row(Index(j) * nx + i) << (nx > 1 ? double(i) / (nx - 1) : 0.0), (ny > 1 ? double(j) / (ny - 1) : 0.0), 0.0;

  const Index cells = (nx > 1 && ny > 1) ? Index(nx - 1) * (ny - 1) : 0;
  F.resize(2 * cells, 3);
  Index f = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
    {
      const int v00 = j * nx + i, v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
      F.row(f++) << v00, v10, v11;
      F.row(f++) << v00, v11, v01;
    }
}

/** \ingroup MeshTools_Module
  * \brief Icosphere: a regular icosahedron subdivided \a subdivisions times, projected onto the unit sphere.
  *
  * Each subdivision splits every triangle into four through its edge midpoints (shared between
  * neighbouring triangles) and pushes the new vertices onto the sphere. The result has
  * 10*4^s + 2 vertices and 20*4^s triangles (s = 0: 12 / 20, s = 6: 40,962 / 81,920,
  * s = 7: 163,842 / 327,680), is closed and of genus 0, and its faces are counter-clockwise
  * seen from outside. The old vertices keep their indices; new ones are appended.
  *
  * \param subdivisions  number of 1-to-4 refinements (s >= 0; negative values are treated as 0).
  * \param V             output: #V x 3 unit-length vertex positions.
  * \param F             output: #F x 3 triangles, 0-based.
  */
inline void icosphereMesh(int subdivisions, MatrixXd& V, MatrixXi& F)
{
  // The 12 icosahedron vertices are the cyclic permutations of (0, +-1, +-phi); they all have the
  // same norm, and two of them share an edge exactly when their distance is the shortest one (2
  // before normalisation).
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  std::vector<Vector3d> points;
  for (int axis = 0; axis < 3; ++axis)
    for (int s1 = -1; s1 <= 1; s1 += 2)
      for (int s2 = -1; s2 <= 1; s2 += 2)
      {
        Vector3d p;
        p[axis] = 0.0;
        p[(axis + 1) % 3] = s1 * 1.0;
        p[(axis + 2) % 3] = s2 * phi;
        points.push_back(p.normalized());
      }
  double edgeLength = std::numeric_limits<double>::infinity(); // the shortest vertex distance
  for (int a = 0; a < 12; ++a)
    for (int b = a + 1; b < 12; ++b) edgeLength = std::min(edgeLength, (points[a] - points[b]).norm());
  auto adjacent = [&](int a, int b) { return std::abs((points[a] - points[b]).norm() - edgeLength) < 1e-9; };

  // Faces: the 20 triples of mutually adjacent vertices, oriented so the normal points outwards.
  std::vector<std::array<int, 3>> faces;
  for (int a = 0; a < 12; ++a)
    for (int b = a + 1; b < 12; ++b)
      for (int c = b + 1; c < 12; ++c)
        if (adjacent(a, b) && adjacent(b, c) && adjacent(a, c))
        {
          const Vector3d normal = (points[b] - points[a]).cross(points[c] - points[a]);
          if (normal.dot(points[a] + points[b] + points[c]) > 0) faces.push_back({a, b, c});
          else faces.push_back({a, c, b});
        }
  eigen_internal_assert(faces.size() == 20);

  for (int level = 0; level < subdivisions; ++level)
  {
    // One new vertex per edge, keyed by its sorted endpoint pair.
    std::unordered_map<std::uint64_t, int> midpoint;
    midpoint.reserve(faces.size() * 3 / 2);
    auto edgeVertex = [&](int a, int b) {
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
      const auto found = midpoint.find(key);
      if (found != midpoint.end()) return found->second;
      const int index = int(points.size());
      points.push_back((points[a] + points[b]).normalized());
      midpoint.emplace(key, index);
      return index;
    };
    std::vector<std::array<int, 3>> refined;
    refined.reserve(4 * faces.size());
    for (const auto& t : faces)
    {
      const int ab = edgeVertex(t[0], t[1]), bc = edgeVertex(t[1], t[2]), ca = edgeVertex(t[2], t[0]);
      refined.push_back({t[0], ab, ca});
      refined.push_back({t[1], bc, ab});
      refined.push_back({t[2], ca, bc});
      refined.push_back({ab, bc, ca});
    }
    faces.swap(refined);
  }

  V.resize(Index(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) V.row(Index(i)) = points[i].transpose();
  F.resize(Index(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) F.row(Index(f)) << faces[f][0], faces[f][1], faces[f][2];
}

/** \ingroup MeshTools_Module
  * \brief Torus: a closed mesh of genus 1 around the z axis, \a rings x \a segments vertices.
  *
  * Vertex (i, j), 0 <= i < rings (around the z axis), 0 <= j < segments (around the tube), has
  * index i*segments + j and position ((R + r cos v) cos u, (R + r cos v) sin u, r sin v) with
  * u = 2 pi i / rings, v = 2 pi j / segments. Each cell is split into two triangles facing
  * outwards, so F has 2*rings*segments rows, and every edge lies on two of them. A mesh with a
  * handle: a disk-based parameterization needs it cut along a loop around the tube and one
  * around the axis. Needs rings, segments >= 3 (otherwise V and F are empty).
  *
  * \param rings     vertices around the z axis.
  * \param segments  vertices around the tube.
  * \param V         output: (rings*segments) x 3 vertex positions.
  * \param F         output: (2*rings*segments) x 3 triangles, 0-based.
  * \param R         distance from the axis to the centre of the tube.
  * \param r         radius of the tube.
  */
inline void torusMesh(int rings, int segments, MatrixXd& V, MatrixXi& F, double R = 2.0, double r = 1.0)
{
  if (rings < 3 || segments < 3)
  {
    V.resize(0, 3);
    F.resize(0, 3);
    return;
  }
  V.resize(Index(rings) * segments, 3);
  F.resize(2 * Index(rings) * segments, 3);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j)
    {
      const double u = 2 * EIGEN_PI * i / rings, v = 2 * EIGEN_PI * j / segments;
      const int a = i * segments + j, b = ((i + 1) % rings) * segments + j,
                c = ((i + 1) % rings) * segments + (j + 1) % segments, d = i * segments + (j + 1) % segments;
      V.row(a) << (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v);
      F.row(2 * Index(a)) << a, b, c;
      F.row(2 * Index(a) + 1) << a, c, d;
    }
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_GENERATEMESHES_H
