// demo: the README's first command. A scripted interactive parameterization session (Herholz &
// Sorkine-Hornung §5.1): Boundary First Flattening (Sawhney & Crane 2017) of a mesh
// (data/camelhead.off.gz unless a path is given), then seam cuts from the boundary inwards, one
// undo and one more cut. Every edit updates the one Cholesky factor in place (removeDofs for a cut,
// restoreDofs for the undo) and lays the mesh out again; the demo prints, for every edit, the
// update time next to the time of a fresh compute() of the same (cut) matrix, and writes a PNG of
// the layout after every edit. At the end the layout is checked against BFF from scratch. A mesh
// with holes or handles is first cut to a disk (cutMeshToDisk), a closed sphere along one path.
//
// Usage: demo [mesh.off[.gz]|.obj|.ply] [output-dir]   (default output dir: demo-out)
// Exit code: 0 on success, 1 on any failure (with a message).

#include <Eigen/UpdatableCholesky>

#include <iostream> // before MetisSupport, which uses std::cerr without including it (Eigen 3.4)
#include <Eigen/MetisSupport>
#include <unsupported/Eigen/MeshParameterization>

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#ifndef UC_DEMO_DEFAULT_MESH
#define UC_DEMO_DEFAULT_MESH "data/camelhead.off.gz"
#endif

namespace {

using Ordering = Eigen::MetisOrdering<int>;
using Flattening = Eigen::BoundaryFirstFlattening<Ordering>;

/** \returns milliseconds elapsed since \a start. */
double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/** \returns the milliseconds of a fresh compute() (ordering, analysis, factorization) of the
  * interior matrix of the current cut mesh: what an edit costs without in-place updates. */
double refactorizationMs(const Flattening& bff)
{
  const Eigen::SparseMatrix<double> A = bff.system().interiorMatrix();
  const auto start = std::chrono::steady_clock::now();
  Eigen::UpdatableSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Ordering> fresh;
  fresh.compute(A);
  return fresh.info() == Eigen::Success ? msSince(start) : -1.0;
}

/** \returns the number of triangles whose uv orientation is not counter-clockwise. */
int flippedTriangles(const Eigen::MatrixXd& UV, const Eigen::MatrixXi& F)
{
  int flipped = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
  {
    const Eigen::Vector2d e1 = (UV.row(F(f, 1)) - UV.row(F(f, 0))).transpose();
    const Eigen::Vector2d e2 = (UV.row(F(f, 2)) - UV.row(F(f, 0))).transpose();
    if (!(e1.x() * e2.y() - e1.y() * e2.x() > 0)) ++flipped;
  }
  return flipped;
}

/** A seam from the boundary to the interior vertex of the cut mesh that lies farthest in
  * direction \a direction (trying the next ones when the farthest is on the boundary). */
std::vector<int> seamTowards(const Flattening& bff, const Eigen::Vector3d& direction)
{
  const Eigen::VectorXd height = bff.cutVertices() * direction;
  std::vector<int> order(std::size_t(height.size()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return height[a] > height[b]; });
  for (std::size_t k = 0; k < order.size() && k < 200; ++k)
  {
    const std::vector<int> seam = Eigen::seamToBoundary(bff.cutVertices(), bff.cutFaces(), order[k]);
    if (seam.size() >= 3) return seam;
  }
  return std::vector<int>();
}

/** Prints one row of the session table and writes the layout as a PNG. */
bool report(const Flattening& bff, const std::string& what, std::size_t seamLength, double cutMs, double updateMs,
            double layoutMs, const std::string& png)
{
  const double fresh = refactorizationMs(bff);
  const Eigen::VectorXd ratio = bff.flatBoundaryLengths().cwiseQuotient(bff.boundaryLengths());
  char speedup[32] = "-";
  if (updateMs > 0) std::snprintf(speedup, sizeof(speedup), "%.1fx", fresh / updateMs);
  std::printf("%-14s %5zu %8.2f %9.2f %9.2f %11.2f %8s %6d %9.5f  %s\n", what.c_str(), seamLength, cutMs, updateMs,
              layoutMs, fresh, speedup, flippedTriangles(bff.uv(), bff.cutFaces()),
              (ratio.array() - 1.0).abs().maxCoeff(), png.c_str());
  std::string error;
  if (!Eigen::renderUVCheckerboard(bff.uv(), bff.cutFaces(), png, 600, 24, &error))
  {
    std::fprintf(stderr, "demo: %s\n", error.c_str());
    return false;
  }
  return true;
}

} // namespace

/** Entry point: see the comment at the top of this file. */
int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : UC_DEMO_DEFAULT_MESH;
  const std::string outputDir = argc > 2 ? argv[2] : "demo-out";
  mkdir(outputDir.c_str(), 0777); // an existing folder is fine; writing the PNGs reports problems

  // 1. Read the mesh.
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::string error;
  if (!Eigen::readMesh(path, V, F, &error))
  {
    std::fprintf(stderr, "demo: %s\n", error.c_str());
    return 1;
  }
  const Eigen::MeshTopology topology = Eigen::meshTopology(F);
  std::printf("mesh      %s: %lld vertices, %lld triangles, %lld boundary loops\n", path.c_str(), (long long)V.rows(),
              (long long)F.rows(), (long long)topology.boundaryLoops);

  // 2. BFF lays out disks. A closed sphere is first cut open along one path; a mesh with holes or
  //    handles is cut to a disk along a cut graph (cutMeshToDisk: paths joining the holes, loops
  //    around the handles), which then is the mesh the session edits.
  std::vector<int> initialSeam;
  if (topology.components != 1)
  {
    std::fprintf(stderr, "demo: the mesh is in %lld pieces; BFF lays out one piece\n", (long long)topology.components);
    return 1;
  }
  if (topology.genus == 0 && topology.boundaryLoops == 0)
  {
    Eigen::Index far = 0;
    (V.rowwise() - V.row(0)).rowwise().squaredNorm().maxCoeff(&far);
    initialSeam = Eigen::shortestEdgePath(V, F, 0, int(far));
    std::printf("closed    cut open along a path of %zu vertices first\n", initialSeam.size());
  }
  else if (!topology.isDisk())
  {
    const Eigen::Index before = V.rows();
    Eigen::VectorXi origin;
    if (!Eigen::cutMeshToDisk(V, F, origin, &error))
    {
      std::fprintf(stderr, "demo: %s\n", error.c_str());
      return 1;
    }
    std::printf("genus %lld, %lld boundary loops: cut to a disk first (%lld vertices copied)\n",
                (long long)topology.genus, (long long)topology.boundaryLoops, (long long)(V.rows() - before));
  }

  // 3. BFF: factor the cotan Laplacian of the whole mesh once (METIS), remove the boundary,
  //    solve for the scale factors, the boundary curve and the interior.
  Flattening bff;
  auto start = std::chrono::steady_clock::now();
  if (!bff.compute(V, F, initialSeam, &error))
  {
    std::fprintf(stderr, "demo: %s\n", error.c_str());
    return 1;
  }
  std::printf("BFF       first layout (factorization of the whole Laplacian included): %.1f ms\n\n", msSince(start));
  std::printf("%-14s %5s %8s %9s %9s %11s %8s %6s %9s  %s\n", "edit", "seam", "cut ms", "update ms", "layout ms",
              "refactor ms", "speedup", "flips", "|l*/l-1|", "picture");
  int step = 0;
  auto png = [&](const std::string& name) {
    char prefix[8];
    std::snprintf(prefix, sizeof(prefix), "%02d_", step++);
    return outputDir + "/" + prefix + name + ".png";
  };
  if (!report(bff, "start", 0, 0, 0, bff.lastLayoutMs(), png("bff")))
    return 1;

  // 4. The scripted session: cuts towards the extremes of the mesh, an undo, one more cut. Each
  //    cut = cutMeshAlongPath + removeDofs(seam) in place + BFF's solves; undo = restoreDofs.
  const Eigen::Vector3d directions[] = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                        Eigen::Vector3d(-1, 0, 0)};
  for (int edit = 0; edit < 4; ++edit)
  {
    const std::vector<int> seam = seamTowards(bff, directions[edit]);
    if (seam.empty() || !bff.addSeam(seam, &error))
    {
      std::fprintf(stderr, "demo: cut %d failed: %s\n", edit + 1, error.c_str());
      return 1;
    }
    if (!report(bff, "cut " + std::to_string(edit + 1), seam.size(), bff.system().lastCutMs(),
                bff.system().lastUpdateMs(), bff.lastLayoutMs(), png("cut" + std::to_string(edit + 1))))
      return 1;
    if (edit == 2)
    {
      if (!bff.undo(&error))
      {
        std::fprintf(stderr, "demo: undo failed: %s\n", error.c_str());
        return 1;
      }
      if (!report(bff, "undo cut 3", 0, 0, bff.system().lastUpdateMs(), bff.lastLayoutMs(), png("undo")))
        return 1;
    }
  }

  // 5. Check: the layout after all edits equals BFF computed from scratch on the cut mesh.
  Flattening scratch;
  if (!scratch.compute(bff.cutVertices(), bff.cutFaces(), {}, &error))
  {
    std::fprintf(stderr, "demo: BFF from scratch failed: %s\n", error.c_str());
    return 1;
  }
  const double difference = (scratch.uv() - bff.uv()).cwiseAbs().maxCoeff();
  std::printf("\ncheck     max |uv(updated) - uv(from scratch)| = %.2e\n", difference);
  std::printf("columns   cut: cutting the mesh; update: removeDofs/restoreDofs on the factor; layout: BFF's\n"
              "          solves; refactor: a fresh compute() (METIS + analysis + factorization) of the same matrix;\n"
              "          speedup = refactor / update; |l*/l-1|: boundary length change (closure correction)\n");
  std::printf("pictures  %s/\n", outputDir.c_str());
  if (!(difference < 1e-8))
  {
    std::fprintf(stderr, "demo: the updated layout differs from the one computed from scratch\n");
    return 1;
  }
  return 0;
}
