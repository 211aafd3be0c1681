// Tutorial 501: Tutte embedding with interactive seams (Tutte 1963; Herholz & Sorkine-Hornung
// §4.1 and §5.1). The boundary of a disk-like mesh goes onto the unit circle and every other vertex
// becomes the average of its neighbours. The Laplacian is factored once; cutting a seam from the
// boundary makes the seam part of the boundary, which is one removeDofs() on the same factor.
//
// Usage: tutorial_501_TutteEmbedding [output-dir] [mesh]   (default mesh: data/camelhead.off.gz)
// Writes 501_TutteEmbedding.png (layout), 501_TutteEmbedding_seam.png (layout after the cut)
// 501_TutteEmbedding_mesh.png (the mesh with the seam in red) and 501_TutteEmbedding_textured.png
// (the cut mesh textured with the layout's checkerboard).
#include <unsupported/Eigen/MeshParameterization>

#include <cstdio>
#include <string>
#include <vector>

using namespace Eigen;

int main(int argc, char** argv)
{
  const std::string outputDir = argc > 1 ? argv[1] : ".";
  const std::string meshPath = argc > 2 ? argv[2] : UC_TUTORIAL_DATA_DIR "/camelhead.off.gz";

  // 1. A mesh with one boundary loop (camelhead: open at the neck). A closed mesh, or one with
  //    handles, is first cut to a disk (holes may stay: Tutte leaves them free).
  MatrixXd V;
  MatrixXi F;
  std::string error;
  if (!readMesh(meshPath, V, F, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const MeshTopology topology = meshTopology(F);
  VectorXi origin;  // (each vertex of the disk -> the vertex of the mesh it copies)
  if ((topology.genus != 0 || topology.boundaryLoops == 0) && !cutMeshToDisk(V, F, origin, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }

  // 2. Tutte embedding: uniform weights, boundary spaced by arc length on the unit circle.
  //    compute() factors L + 1e-8 I of the whole mesh, removes the boundary dofs, solves.
  TutteEmbedding<> tutte;
  tutte.setWeights(LaplacianWeights::Uniform).setBoundarySpacing(BoundarySpacing::ArcLength);
  if (!tutte.compute(V, F, {}, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  if (!renderUVCheckerboard(tutte.uv(), tutte.cutFaces(), outputDir + "/501_TutteEmbedding.png", 600, 24, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }

  // 3. A seam from the boundary to the vertex farthest from the boundary's centre (the snout of
  //    the camel): seamToBoundary() gives the shortest path through interior vertices.
  Vector3d boundaryCentre = Vector3d::Zero();
  for (int v : tutte.system().boundaryLoop()) boundaryCentre += V.row(v).transpose();
  boundaryCentre /= double(tutte.system().boundaryLoop().size());
  Index farthest = 0;
  (V.rowwise() - boundaryCentre.transpose()).rowwise().squaredNorm().maxCoeff(&farthest);
  const std::vector<int> seam = seamToBoundary(tutte.cutVertices(), tutte.cutFaces(), int(farthest));

  // 4. Cut: the seam's vertices join the boundary, removeDofs() updates the factor in place, the
  //    new (longer) boundary goes onto the circle and the interior is solved again.
  if (!tutte.addSeam(seam, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("seam of %zu vertices: factor update %.2f ms, solve %.2f ms\n", seam.size(),
              tutte.system().lastUpdateMs(), tutte.lastLayoutMs());
  if (!renderUVCheckerboard(tutte.uv(), tutte.cutFaces(), outputDir + "/501_TutteEmbedding_seam.png", 600, 24,
                            &error) ||
      !renderMeshShaded(V, F, outputDir + "/501_TutteEmbedding_mesh.png",
                        AngleAxisd(0.5 * EIGEN_PI, Vector3d::UnitY()).toRotationMatrix(), 600, seam, &error) ||
      !renderMeshCheckerboard(tutte.cutVertices(), tutte.cutFaces(), tutte.uv(),
                              outputDir + "/501_TutteEmbedding_textured.png",
                              AngleAxisd(0.5 * EIGEN_PI, Vector3d::UnitY()).toRotationMatrix(), 600, 24, &error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }

  // 5. Undo: restoreDofs() gives the seam's rows back, the first layout returns.
  tutte.undo();
  std::printf("undo: factor update %.2f ms; %lld vertices again\n", tutte.system().lastUpdateMs(),
              (long long)tutte.uv().rows());
  return 0;
}
