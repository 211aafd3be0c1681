// Tutorial 502: Boundary First Flattening (Sawhney & Crane 2017) with zero boundary scale factors
// -- the conformal flattening with least area distortion -- and interactive cuts (Herholz &
// Sorkine-Hornung §5.1): the scale factors, the boundary curve and its harmonic extension all come
// from Dirichlet solves with one factor of the Laplacian; a cut is one removeDofs() on it.
//
// Usage: tutorial_502_BoundaryFirstFlattening [output-dir] [mesh]   (default: data/camelhead.off.gz)
// Writes 502_BoundaryFirstFlattening.png (layout), 502_BoundaryFirstFlattening_textured.png (the
// mesh textured with it: squares stay square) and 502_BoundaryFirstFlattening_cuts.png.
#include <unsupported/Eigen/MeshParameterization>

#include <cstdio>
#include <string>
#include <vector>

using namespace Eigen;

int main(int argc, char** argv)
{
  const std::string outputDir = argc > 1 ? argv[1] : ".";
  const std::string meshPath = argc > 2 ? argv[2] : UC_TUTORIAL_DATA_DIR "/camelhead.off.gz";

  // 1. A disk-like mesh. Any other (closed, with holes or handles) is first cut to a disk.
  MatrixXd V;
  MatrixXi F;
  std::string error;
  if (!readMesh(meshPath, V, F, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  VectorXi origin;  // (each vertex of the disk -> the vertex of the mesh it copies)
  if (!meshTopology(F).isDisk() && !cutMeshToDisk(V, F, origin, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }

  // 2. BFF: factor the cotan Laplacian once, remove the boundary, then
  //    (a) scale factors u with u = 0 on the boundary (a Poisson problem),
  //    (b) their normal derivative bends the boundary: new turning angles,
  //    (c) a closed curve with the original boundary edge lengths (closure corrected),
  //    (d) the interior filled in harmonically.
  BoundaryFirstFlattening<> bff;
  if (!bff.compute(V, F, {}, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const VectorXd ratio = bff.flatBoundaryLengths().cwiseQuotient(bff.boundaryLengths());
  std::printf("BFF: boundary edge length ratio uv/3-D in [%.5f, %.5f], scale factors in [%.2f, %.2f]\n",
              ratio.minCoeff(), ratio.maxCoeff(), bff.scaleFactors().minCoeff(), bff.scaleFactors().maxCoeff());
  const Matrix3d view = AngleAxisd(0.5 * EIGEN_PI, Vector3d::UnitY()).toRotationMatrix();
  if (!renderUVCheckerboard(bff.uv(), bff.cutFaces(), outputDir + "/502_BoundaryFirstFlattening.png", 600, 24, &error) ||
      !renderMeshCheckerboard(bff.cutVertices(), bff.cutFaces(), bff.uv(),
                              outputDir + "/502_BoundaryFirstFlattening_textured.png", view, 600, 40, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }

  // 3. Two cuts from the boundary, to the two vertices farthest apart along the mesh's longest
  //    axis. Each cut opens the boundary: one removeDofs() of the seam, then BFF's solves again.
  Index tip[2];
  V.col(1).maxCoeff(&tip[0]);
  V.col(2).maxCoeff(&tip[1]);
  for (Index target : tip)
  {
    const std::vector<int> seam = seamToBoundary(bff.cutVertices(), bff.cutFaces(), int(target));
    if (seam.empty() || !bff.addSeam(seam, &error))
    {
      std::fprintf(stderr, "cut to vertex %lld failed: %s\n", (long long)target, error.c_str());
      return 1;
    }
    std::printf("cut of %zu vertices: factor update %.2f ms, BFF solves %.2f ms\n", seam.size(),
                bff.system().lastUpdateMs(), bff.lastLayoutMs());
  }
  if (!renderUVCheckerboard(bff.uv(), bff.cutFaces(), outputDir + "/502_BoundaryFirstFlattening_cuts.png", 600, 24,
                            &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  return 0;
}
