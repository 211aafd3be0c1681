// Tutorial 401: as-rigid-as-possible deformation (Sorkine & Alexa 2007) with in-place constraint
// edits (Herholz & Sorkine-Hornung, §5.3). A bar is bent by a handle at its top, then a second
// handle is added in its middle: the cotan Laplacian is factored once, and every change of the
// handles or of the region of interest only removes or restores the dofs that changed.
//
// Usage: tutorial_401_ArapDeformation [output-dir]   (writes 401_ArapDeformation.png, default: .)
#include <unsupported/Eigen/MeshDeformation>

#include <cstdio>
#include <string>
#include <vector>

using namespace Eigen;

int main(int argc, char** argv)
{
  const std::string outputDir = argc > 1 ? argv[1] : ".";

  // 1. The rest shape: an open tube of radius 0.1 along z, from z = 0 to z = 1.
  const int around = 24, rings = 80;
  MatrixXd V;
  MatrixXi F;
  cylinderMesh(around, rings, 0.1, 1.0, V, F);
  auto ring = [&](int j) {
    std::vector<int> r;
    for (int i = 0; i < around; ++i) r.push_back(j * around + i);
    return r;
  };

  // 2. Precompute: cotan Laplacian, factored once.
  ArapDeformation<> arap(V, F);
  if (arap.info() != Success) { std::fprintf(stderr, "%s\n", arap.lastError().c_str()); return 1; }

  // 3. Region of interest: everything above the lowest 5 rings, which stay at rest.
  std::vector<int> region;
  for (int j = 5; j < rings; ++j)
    for (int v : ring(j)) region.push_back(v);
  arap.setRegionOfInterest(region);

  // 4. Handle: the top ring, held at rest for now.
  const std::vector<int> top = ring(rings - 1);
  arap.setHandles(top);

  // 5. Drag the handle as a user would, in 12 small moves, warm-starting each solve from the
  //    last shape: the top ring turns by up to 90 degrees about x, its centre at the end of a
  //    circular arc, a quarter circle of radius r at the end: a bend towards +y. With r = 2/pi + 0.1
  //    the inner side keeps its length and the outer side stretches (a thin tube compressed buckles).
  //    Moving handles changes only the Dirichlet values: the factor is not touched.
  const double pi = 3.14159265358979323846, r = 2.0 / pi + 0.1;
  MatrixXd bent = V;
  std::vector<double> energies;
  const int moves = 12;
  for (int move = 1; move <= moves; ++move)
  {
    const double angle = 0.5 * pi * move / moves;
    const Matrix3d turn = AngleAxisd(-angle, Vector3d::UnitX()).toRotationMatrix();
    const double length = 1 + (r * 0.5 * pi - 1) * move / moves, radius = length / angle;  // the arc
    const Vector3d centre(0, radius * (1 - std::cos(angle)), radius * std::sin(angle));
    MatrixXd targets(around, 3);
    for (int k = 0; k < around; ++k)
      targets.row(k) = (turn * (V.row(top[k]).transpose() - Vector3d(0, 0, 1)) + centre).transpose();
    arap.moveHandles(targets);
    if (!arap.solve(bent, 15, &energies)) { std::fprintf(stderr, "%s\n", arap.lastError().c_str()); return 1; }
  }
  std::printf("bend: ARAP energy %.4g (it never increases within a solve)\n", energies.back());

  // 6. An edit: the middle ring becomes a handle too, pushed outwards, away from the centre of
  //    the bend. Only its 24 dofs are removed from the factor, in place.
  const std::vector<int> middle = ring(rings / 2);
  RowVector3d middleCentre = RowVector3d::Zero();
  for (int v : middle) middleCentre += bent.row(v) / around;
  const RowVector3d outwards = (middleCentre - RowVector3d(0, r, 0)).normalized();
  MatrixXd middleTargets(around, 3);
  for (int k = 0; k < around; ++k) middleTargets.row(k) = bent.row(middle[k]) + 0.12 * outwards;
  arap.addHandles(middle, middleTargets);
  std::printf("edit: %ld dofs removed and %ld restored in place, %.2f ms\n", long(arap.lastEdit().added),
              long(arap.lastEdit().released), 1e3 * arap.lastEdit().seconds);
  MatrixXd pushed = bent;  // warm start from the bent shape
  arap.solve(pushed, 50, &energies);
  std::printf("push: ARAP energy %.4g\n", energies.back());

  // 7. Picture: rest, bent and pushed bars side by side, seen along x, handles as dots.
  const Index n = V.rows();
  MatrixXd all(3 * n, 3);
  all << V, (bent.rowwise() + RowVector3d(0, 0.8, 0)), (pushed.rowwise() + RowVector3d(0, 2.0, 0));
  MatrixXi allF(3 * F.rows(), 3);
  allF << F, (F.array() + int(n)).matrix(), (F.array() + int(2 * n)).matrix();
  std::vector<int> dots;
  for (int v : arap.handles()) dots.push_back(int(2 * n) + v);
  Matrix3d view;  // view x = world y, view y = world z, towards the viewer = world x
  view << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  std::string error;
  const std::string path = outputDir + "/401_ArapDeformation.png";
  if (!renderMeshShaded(all, allF, path, view, 800, dots, &error)) { std::fprintf(stderr, "%s\n", error.c_str()); return 1; }
  std::printf("wrote %s\n", path.c_str());
  return 0;
}
