// Tutorial 503: orbifold Tutte embeddings (Aigerman & Lipman 2015; Herholz & Sorkine-Hornung
// §5.2). A closed genus-0 mesh is cut into a disk along shortest paths between 3 or 4 cones and
// mapped so that the disk tiles the plane: the two sides of every seam are related by a rotation
// about a cone. The KKT system is solved through its Schur complement on one Cholesky factor of
// the cut Laplacian; moving a cone merges the old seam out of the factor and inserts the new one.
//
// Usage: tutorial_503_OrbifoldTutte [output-dir] [closed mesh]   (default: a bumpy sphere)
// Writes 503_OrbifoldTutte.png (the disk), 503_OrbifoldTutte_tiles.png (copies rotated about c1:
// the seams match), 503_OrbifoldTutte_moved.png (after moving a cone) and
// 503_OrbifoldTutte_mesh.png (the mesh with the cut in red).
#include <unsupported/Eigen/MeshParameterization>

#include <cstdio>
#include <string>
#include <vector>

using namespace Eigen;

int main(int argc, char** argv)
{
  const std::string outputDir = argc > 1 ? argv[1] : ".";
  std::string error;

  // 1. A closed mesh of genus 0: the given file, or an icosphere with bumps (2,562 vertices).
  MatrixXd V;
  MatrixXi F;
  if (argc > 2)
  {
    if (!readMesh(argv[2], V, F, &error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
  }
  else
  {
    icosphereMesh(4, V, F);
    for (Index i = 0; i < V.rows(); ++i)
      V.row(i) *= 1.0 + 0.15 * std::sin(3 * V(i, 0)) * std::cos(2 * V(i, 1)) + 0.3 * V(i, 2) * V(i, 2);
  }

  // 2. Three cones, far apart (the vertices extreme along three directions), type I: (3,3,3).
  auto extreme = [&](const Vector3d& direction) {
    Index best = 0;
    (V * direction).maxCoeff(&best);
    return int(best);
  };
  const std::vector<int> cones = {extreme({1, 0, 0}), extreme({-0.5, 0.87, 0}), extreme({-0.5, -0.87, 0})};

  // 3. Setup + compute: cut along c1 -> c2 -> c3, factor, Schur complement, solve.
  OrbifoldTutteEmbedding<> orbifold;
  if (!orbifold.setup(V, F, cones, OrbifoldType::I) || !orbifold.compute())
  {
    std::fprintf(stderr, "%s\n", orbifold.error().c_str());
    return 1;
  }
  const auto& st = orbifold.lastStatistics();
  std::printf("type I: seam of %ld vertices, %ld constraints; factor %.1f ms, Schur %.1f ms, solve %.1f ms\n",
              long(st.seamVertices), long(st.constraints), 1e3 * st.factorSeconds, 1e3 * st.schurSeconds,
              1e3 * st.solveSeconds);
  const Matrix3d view = (AngleAxisd(0.5, Vector3d::UnitX()) * AngleAxisd(1.3, Vector3d::UnitY())).toRotationMatrix();
  if (!renderUVCheckerboard(orbifold.uv(), orbifold.cutFaces(), outputDir + "/503_OrbifoldTutte.png", 600, 24,
                            &error) ||
      !renderMeshShaded(V, F, outputDir + "/503_OrbifoldTutte_mesh.png", view, 600, orbifold.seam(), &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }

  // 4. Tiling: three copies of the disk rotated by 2π/3 about the image of c1 fit together
  //    along the seam (the right side of each copy meets the left side of the next).
  const Index n = orbifold.uv().rows(), m = orbifold.cutFaces().rows();
  MatrixXd tiles(3 * n, 2);
  MatrixXi tileFaces(3 * m, 3);
  const RowVector2d center = orbifold.uv().row(cones[0]);
  for (int k = 0; k < 3; ++k)
  {
    const Matrix2d R = Rotation2Dd(2 * EIGEN_PI * k / 3).toRotationMatrix();
    tiles.middleRows(k * n, n) = ((orbifold.uv().rowwise() - center) * R.transpose()).rowwise() + center;
    tileFaces.middleRows(k * m, m) = orbifold.cutFaces().array() + int(k * n);
  }
  if (!renderUVCheckerboard(tiles, tileFaces, outputDir + "/503_OrbifoldTutte_tiles.png", 600, 36, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }

  // 5. Edit: move cone c2. The old seam is merged back into the factor, the new one inserted
  //    (mergeDofs/insertDofs): no refactorization.
  if (!orbifold.moveCone(1, extreme({-0.3, 0.5, 0.8})))
  {
    std::fprintf(stderr, "%s\n", orbifold.error().c_str());
    return 1;
  }
  std::printf("moved c2: factor %s in %.1f ms, Schur %.1f ms, solve %.1f ms\n",
              st.factorUpdated ? "updated" : "refactored", 1e3 * st.factorSeconds, 1e3 * st.schurSeconds,
              1e3 * st.solveSeconds);
  if (!renderUVCheckerboard(orbifold.uv(), orbifold.cutFaces(), outputDir + "/503_OrbifoldTutte_moved.png", 600, 24,
                            &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  return 0;
}
