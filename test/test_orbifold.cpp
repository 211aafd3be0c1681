// Orbifold Tutte embeddings (unsupported/Eigen/src/MeshParameterization/OrbifoldTutte.h; Aigerman &
// Lipman 2015, Herholz & Sorkine-Hornung §5.2) checked against oracles that do not use the class's
// own constraint bookkeeping: the boundary loop of the cut mesh is split at the cone copies and
// every pair of seam arcs must be related by the exact rotation 2π/k about its cone image (the
// translation for the middle of type IV); the uv area must be the fundamental domain's; no
// triangle may flip; the map must be harmonic inside and across the seam; the answer must match
// SparseLU on the full KKT system (eq. 20); after each edit (cones moved, factor updated) it must
// match a fresh computation. The Schur complement helper is checked against a dense inverse.
#include <doctest/doctest.h>

#include <unsupported/Eigen/MeshParameterization>

#include <Eigen/SparseLU>

#include <cmath>
#include <random>

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;
using Eigen::OrbifoldType;
using Eigen::Vector2d;
using Eigen::VectorXd;
typedef Eigen::OrbifoldTutteEmbedding<> Orbifold;

const double kPi = 3.14159265358979323846;

/** The vertex of V closest to the direction \a d. */
int vertexToward(const MatrixXd& V, const Eigen::Vector3d& d)
{
  Index best = 0;
  (V * d.normalized()).maxCoeff(&best);
  return int(best);
}

/** Well separated cones on a sphere-like mesh, for 3 or 4 cones. */
std::vector<int> spreadCones(const MatrixXd& V, int count)
{
  if (count == 3)
    return {vertexToward(V, {1, 0.1, 0.2}), vertexToward(V, {-0.5, 0.87, -0.1}), vertexToward(V, {-0.5, -0.8, 0.3})};
  return {vertexToward(V, {1, 1, 1}), vertexToward(V, {1, -1, -1}), vertexToward(V, {-1, 1, -1}),
          vertexToward(V, {-1, -1, 1})};
}

Eigen::Matrix2d rotation(double angle)
{
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

double signedArea(const MatrixXd& uv, const MatrixXi& F, Index f)
{
  const Vector2d a = uv.row(F(f, 0)).transpose(), b = uv.row(F(f, 1)).transpose(), c = uv.row(F(f, 2)).transpose();
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

/** The cone orders along the chain, as documented for OrbifoldType (the oracle's own table). */
std::vector<int> ordersOf(OrbifoldType type)
{
  static const int table[4][4] = {{3, 3, 3, 0}, {4, 2, 4, 0}, {6, 2, 3, 0}, {2, 2, 2, 2}};
  const int* row = table[int(type)];
  return std::vector<int>(row, row + (row[3] ? 4 : 3));
}

/** Largest deviation from the orbifold's seam rotations, from the boundary loop of the cut mesh:
  * the loop (counter-clockwise, mesh on the left) is c1, arcs..., and its arcs are paired as the
  * orbifold type says. Also checks the paired vertices copy the same input vertex. */
double seamRotationError(const Orbifold& orbifold)
{
  const MatrixXd& uv = orbifold.uv();
  const Eigen::VectorXi& origin = orbifold.origin();
  const std::vector<std::vector<int>> loops = Eigen::boundaryLoops(orbifold.cutFaces());
  REQUIRE(loops.size() == 1);
  std::vector<int> loop = loops[0];
  const std::vector<int>& cones = orbifold.cones();
  const int k = int(cones.size());
  auto coneOf = [&](int v) {
    for (int i = 0; i < k; ++i)
      if (origin[v] == cones[std::size_t(i)]) return i;
    return -1;
  };
  // start the loop at the single copy of c1
  const auto first = std::find_if(loop.begin(), loop.end(), [&](int v) { return coneOf(v) == 0; });
  REQUIRE(first != loop.end());
  std::rotate(loop.begin(), first, loop.end());
  loop.push_back(loop.front());
  // arcs between consecutive cone copies
  std::vector<std::vector<int>> arcs(1, std::vector<int>(1, loop[0]));
  std::vector<int> arcEndCone;
  for (std::size_t p = 1; p < loop.size(); ++p)
  {
    arcs.back().push_back(loop[p]);
    const int c = coneOf(loop[p]);
    if (c >= 0)
    {
      arcEndCone.push_back(c);
      if (p + 1 < loop.size()) arcs.emplace_back(1, loop[p]);
    }
  }
  // expected cone sequence: 1,2,...,k,...,2,1 (0-based 1..k-1, k-2..0)
  std::vector<int> expected;
  for (int i = 1; i < k; ++i) expected.push_back(i);
  for (int i = k - 2; i >= 0; --i) expected.push_back(i);
  REQUIRE(arcEndCone == expected);
  const std::vector<int> order = ordersOf(orbifold.type());
  const int arcCount = int(arcs.size());  // 2(k-1)
  double worst = 0;
  for (int s = 0; s < k - 1; ++s)
  {
    std::vector<int> left = arcs[std::size_t(s)], right = arcs[std::size_t(arcCount - 1 - s)];
    std::reverse(right.begin(), right.end());  // both now run along the chain direction
    REQUIRE(left.size() == right.size());
    for (std::size_t i = 0; i < left.size(); ++i) CHECK(origin[left[i]] == origin[right[i]]);
    double angle = 0;
    int centerIndex = 0;  // in left/right
    if (s == 0)
      angle = 2 * kPi / order[0];
    else if (s == k - 2)
    {
      angle = -2 * kPi / order[std::size_t(k - 1)];
      centerIndex = int(left.size()) - 1;
    }
    const Eigen::Matrix2d R = rotation(angle);
    const Vector2d cl = uv.row(left[std::size_t(centerIndex)]).transpose();
    const Vector2d cr = uv.row(right[std::size_t(centerIndex)]).transpose();
    if (s == 0 || s == k - 2) worst = std::max(worst, (cl - cr).norm());  // the center is one point
    for (std::size_t i = 0; i < left.size(); ++i)
    {
      const Vector2d l = uv.row(left[i]).transpose(), r = uv.row(right[i]).transpose();
      worst = std::max(worst, (r - (R * (l - cl) + cr)).norm());
      if (i + 1 < left.size())  // equal edge lengths
      {
        const double ll = (uv.row(left[i + 1]) - uv.row(left[i])).norm();
        const double lr = (uv.row(right[i + 1]) - uv.row(right[i])).norm();
        worst = std::max(worst, std::abs(ll - lr));
      }
    }
  }
  return worst;
}

/** The copies of the cones along the boundary loop, starting at c1: c1, c2 (left), ..., ck, ...,
  * c2 (right). */
std::vector<int> coneCopiesAlongLoop(const Orbifold& orbifold)
{
  std::vector<int> loop = Eigen::boundaryLoops(orbifold.cutFaces())[0];
  const auto c1 = std::find_if(loop.begin(), loop.end(), [&](int v) { return orbifold.origin()[v] == orbifold.cones()[0]; });
  std::rotate(loop.begin(), c1, loop.end());
  std::vector<int> copies;
  for (int v : loop)
    for (int c : orbifold.cones())
      if (orbifold.origin()[v] == c) copies.push_back(v);
  return copies;
}

/** Shoelace area of the polygon of the cone copies along the boundary loop. */
double conePolygonArea(const Orbifold& orbifold)
{
  std::vector<Vector2d> corners;
  for (int v : coneCopiesAlongLoop(orbifold)) corners.push_back(orbifold.uv().row(v).transpose());
  double area = 0;
  for (std::size_t i = 0; i < corners.size(); ++i)
  {
    const Vector2d& a = corners[i];
    const Vector2d& b = corners[(i + 1) % corners.size()];
    area += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  return area;
}

/** Harmonicity: (L X)_i = 0 at cut vertices off the boundary; across the seam the rotated sum of
  * both copies' residuals vanishes, (L X)_left + R^T (L X)_right = 0, for seam vertices that are
  * not cones (the copy pairs are read from the boundary loop as in seamRotationError). Returns
  * the largest residual relative to the largest |L X| entry scale (diagonal * |X|). */
double harmonicResidual(const Orbifold& orbifold)
{
  const Orbifold::MatrixType L = Eigen::cotanLaplacian<double, int>(orbifold.cutVertices(), orbifold.cutFaces());
  const MatrixXd LX = L * orbifold.uv();
  const double scale = L.diagonal().maxCoeff() * orbifold.uv().cwiseAbs().maxCoeff();
  std::vector<char> onBoundary(std::size_t(L.rows()), 0);
  const std::vector<int> loop = Eigen::boundaryLoops(orbifold.cutFaces())[0];
  for (int v : loop) onBoundary[std::size_t(v)] = 1;
  double worst = 0;
  for (Index i = 0; i < L.rows(); ++i)
    if (!onBoundary[std::size_t(i)]) worst = std::max(worst, LX.row(i).norm());
  // seam: the two copies of each non-cone seam vertex, related as in seamRotationError
  const std::vector<int>& cones = orbifold.cones();
  const int k = int(cones.size());
  std::vector<int> copies[2];  // per original vertex: first and second copy on the loop
  std::vector<int> firstCopy(std::size_t(orbifold.origin().maxCoeff()) + 1, -1);
  const std::vector<int> order = ordersOf(orbifold.type());
  // identify the segment by walking the loop from c1
  std::vector<int> seq = loop;
  const auto c1 = std::find_if(seq.begin(), seq.end(), [&](int v) { return orbifold.origin()[v] == cones[0]; });
  std::rotate(seq.begin(), c1, seq.end());
  int arc = 0;
  std::vector<int> arcOf(seq.size());
  for (std::size_t p = 0; p < seq.size(); ++p)
  {
    arcOf[p] = arc;
    for (int c : cones)
      if (p > 0 && orbifold.origin()[seq[p]] == c) ++arc;
  }
  for (std::size_t p = 0; p < seq.size(); ++p)
  {
    const int v = seq[p], o = orbifold.origin()[v];
    if (std::find(cones.begin(), cones.end(), o) != cones.end()) continue;
    if (firstCopy[std::size_t(o)] < 0)
    {
      firstCopy[std::size_t(o)] = v;
      continue;
    }
    const int segment = arcOf[p] >= k - 1 ? 2 * (k - 1) - 1 - arcOf[p] : arcOf[p];
    double angle = 0;
    if (segment == 0) angle = 2 * kPi / order[0];
    else if (segment == k - 2) angle = -2 * kPi / order[std::size_t(k - 1)];
    const Eigen::Matrix2d R = rotation(angle);
    const Vector2d left = LX.row(firstCopy[std::size_t(o)]).transpose(), right = LX.row(v).transpose();
    worst = std::max(worst, (left + R.transpose() * right).norm());
  }
  return worst / scale;
}

/** Every property of one embedding. */
void checkEmbedding(const Orbifold& orbifold, bool expectNoFlips = true)
{
  REQUIRE(orbifold.info() == Eigen::Success);
  const MatrixXd& uv = orbifold.uv();
  REQUIRE(uv.rows() == orbifold.cutVertices().rows());
  REQUIRE(uv.allFinite());
  CHECK(seamRotationError(orbifold) < 1e-9);
  // cone images where the type puts them
  const Eigen::MatrixX2d images = orbifold.coneImages();
  const std::vector<int> copies = coneCopiesAlongLoop(orbifold);
  REQUIRE(copies.size() == 2 * orbifold.cones().size() - 2);
  for (std::size_t i = 0; i < orbifold.cones().size(); ++i)
    CHECK((uv.row(copies[i]) - images.row(Index(i))).norm() < 1e-9);
  // area: signed sum = cone polygon = fundamental domain
  double area = 0;
  Index flipped = 0;
  for (Index f = 0; f < orbifold.cutFaces().rows(); ++f)
  {
    const double a = signedArea(uv, orbifold.cutFaces(), f);
    area += a;
    flipped += a <= 0;
  }
  CHECK(std::abs(area - orbifold.domainArea()) < 1e-9);
  CHECK(std::abs(conePolygonArea(orbifold) - orbifold.domainArea()) < 1e-9);
  if (expectNoFlips) CHECK(flipped == 0);
  CHECK(harmonicResidual(orbifold) < 1e-9);
}

/** The KKT system (eq. 20) of the exact cut Laplacian with the class's constraints, by SparseLU. */
MatrixXd kktSolution(const Orbifold& orbifold)
{
  const Orbifold::MatrixType L = Eigen::cotanLaplacian<double, int>(orbifold.cutVertices(), orbifold.cutFaces());
  const Eigen::SparseMatrix<double>& B = orbifold.constraintMatrix();
  const Index N = L.rows(), m = B.rows();
  std::vector<Eigen::Triplet<double>> t;
  for (Index j = 0; j < N; ++j)
    for (Orbifold::MatrixType::InnerIterator it(L, j); it; ++it)
    {
      t.emplace_back(int(it.row()), int(j), it.value());
      t.emplace_back(int(it.row() + N), int(j + N), it.value());
    }
  for (Index j = 0; j < B.cols(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(B, j); it; ++it)
    {
      t.emplace_back(int(2 * N + it.row()), int(j), it.value());
      t.emplace_back(int(j), int(2 * N + it.row()), it.value());
    }
  Eigen::SparseMatrix<double> K(2 * N + m, 2 * N + m);
  K.setFromTriplets(t.begin(), t.end());
  VectorXd rhs = VectorXd::Zero(2 * N + m);
  rhs.tail(m) = orbifold.constraintRhs();
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(K);
  REQUIRE(lu.info() == Eigen::Success);
  const VectorXd x = lu.solve(rhs);
  MatrixXd uv(N, 2);
  uv.col(0) = x.head(N);
  uv.col(1) = x.segment(N, N);
  return uv;
}

} // namespace

TEST_CASE("Schur complement of unit vectors from a sparse factor equals E^T A^-1 E")
{
  // A random sparse SPD matrix, factored; S from the reach-limited forward substitution.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 300;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
  {
    t.emplace_back(i, i, 8.0);
    for (int e = 0; e < 3; ++e)
    {
      const int j = int(rng() % n);
      if (j == i) continue;
      const double w = u(rng);
      t.emplace_back(i, j, w);
      t.emplace_back(j, i, w);
    }
  }
  Orbifold::MatrixType A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  Orbifold::SolverType llt(A);
  REQUIRE(llt.info() == Eigen::Success);
  const std::vector<int> dofs = {17, 3, 250, 99, 100, 101, 5, 299, 0};
  MatrixXd S;
  REQUIRE(Eigen::internal::mesh_parameterization::unitVectorSchurComplement(llt.matrixL().nestedExpression(),
                                                                           llt.permutationP().indices(), dofs, S));
  const MatrixXd Ainv = MatrixXd(A).inverse();
  double worst = 0;
  for (std::size_t a = 0; a < dofs.size(); ++a)
    for (std::size_t b = 0; b < dofs.size(); ++b)
      worst = std::max(worst, std::abs(S(Index(a), Index(b)) - Ainv(dofs[a], dofs[b])));
  CHECK(worst < 1e-12);
}

TEST_CASE("Orbifold Tutte embeddings of types I-IV on an icosphere")
{
  MatrixXd V;
  MatrixXi F;
  Eigen::icosphereMesh(3, V, F);
  for (OrbifoldType type : {OrbifoldType::I, OrbifoldType::II, OrbifoldType::III, OrbifoldType::IV})
  {
    CAPTURE(int(type) + 1);
    Orbifold orbifold;
    const std::vector<int> cones = spreadCones(V, type == OrbifoldType::IV ? 4 : 3);
    REQUIRE(orbifold.setup(V, F, cones, type));
    REQUIRE_MESSAGE(orbifold.compute(), orbifold.error());
    checkEmbedding(orbifold);
    // the Schur complement route solves the KKT system (20) exactly
    const MatrixXd uvKKT = kktSolution(orbifold);
    CHECK((uvKKT - orbifold.uv()).cwiseAbs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("Orbifold Tutte edits update the factor and match a fresh computation")
{
  MatrixXd V;
  MatrixXi F;
  Eigen::icosphereMesh(3, V, F);
  Orbifold edited;
  REQUIRE(edited.setup(V, F, spreadCones(V, 3), OrbifoldType::I));
  REQUIRE(edited.compute());
  struct Edit
  {
    std::vector<int> cones;
    OrbifoldType type;
  };
  std::vector<Edit> edits;
  std::vector<int> cones = edited.cones();
  cones[1] = vertexToward(V, {-0.2, 0.9, 0.5});
  edits.push_back({cones, OrbifoldType::I});
  cones[0] = vertexToward(V, {0.8, -0.3, -0.6});
  edits.push_back({cones, OrbifoldType::II});
  cones[2] = vertexToward(V, {-0.9, -0.2, -0.3});
  edits.push_back({cones, OrbifoldType::III});
  edits.push_back({spreadCones(V, 4), OrbifoldType::IV});
  std::vector<int> four = spreadCones(V, 4);
  four[2] = vertexToward(V, {-1, 0.8, -0.2});
  edits.push_back({four, OrbifoldType::IV});
  edits.push_back({spreadCones(V, 3), OrbifoldType::I});
  for (std::size_t e = 0; e < edits.size(); ++e)
  {
    CAPTURE(e);
    if (e == 0)
      REQUIRE(edited.moveCone(1, edits[e].cones[1]));
    else
      REQUIRE_MESSAGE(edited.setCones(edits[e].cones, edits[e].type), edited.error());
    if (Orbifold::supportsFactorUpdates) CHECK(edited.lastStatistics().factorUpdated);
    checkEmbedding(edited);
    Orbifold fresh;
    REQUIRE(fresh.setup(V, F, edits[e].cones, edits[e].type));
    REQUIRE(fresh.compute());
    REQUIRE(fresh.uv().rows() == edited.uv().rows());
    CHECK((fresh.uv() - edited.uv()).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((fresh.cutFaces() - edited.cutFaces()).cwiseAbs().maxCoeff() == 0);
    // and a solver that shares nothing with ours: SparseLU on the KKT system of the new cut
    CHECK((kktSolution(edited) - edited.uv()).cwiseAbs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("Orbifold Tutte on a finer and a stretched sphere")
{
  MatrixXd V;
  MatrixXi F;
  Eigen::icosphereMesh(4, V, F);  // 2,562 vertices
  for (OrbifoldType type : {OrbifoldType::II, OrbifoldType::IV})
  {
    Orbifold orbifold;
    REQUIRE(orbifold.setup(V, F, spreadCones(V, type == OrbifoldType::IV ? 4 : 3), type));
    REQUIRE(orbifold.compute());
    checkEmbedding(orbifold);
  }
  // an ellipsoid: obtuse triangles, some negative cotan weights; constraints, area and
  // harmonicity still hold exactly (flips are not excluded for non-Delaunay meshes)
  MatrixXd E = V;
  E.col(0) *= 2.5;
  E.col(2) *= 0.6;
  Orbifold ellipsoid;
  REQUIRE(ellipsoid.setup(E, F, spreadCones(E, 3), OrbifoldType::III));
  REQUIRE(ellipsoid.compute());
  checkEmbedding(ellipsoid, false);
}

TEST_CASE("Orbifold Tutte rejects bad input with a message")
{
  MatrixXd V;
  MatrixXi F;
  Eigen::icosphereMesh(2, V, F);
  Orbifold orbifold;
  CHECK_FALSE(orbifold.compute());  // no setup
  CHECK_FALSE(orbifold.error().empty());
  CHECK_FALSE(orbifold.setup(V, F, {0, 1}, OrbifoldType::I));  // too few cones
  CHECK(orbifold.error().find("cones") != std::string::npos);
  CHECK_FALSE(orbifold.setup(V, F, {0, 5, 5}, OrbifoldType::I));  // repeated
  CHECK_FALSE(orbifold.setup(V, F, {0, 5, int(V.rows())}, OrbifoldType::I));  // out of range
  CHECK_FALSE(orbifold.setup(V, F, {0, 5, 9}, OrbifoldType::IV));  // IV needs 4
  MatrixXi badF = F;
  badF(0, 0) = -1;
  CHECK_FALSE(orbifold.setup(V, badF, {0, 5, 9}, OrbifoldType::I));
  CHECK(orbifold.info() == Eigen::InvalidInput);
  // an open mesh (a grid) is not a sphere
  MatrixXd G;
  MatrixXi GF;
  Eigen::gridMesh(6, 6, G, GF);
  CHECK_FALSE(orbifold.setup(G, GF, {7, 14, 28}, OrbifoldType::I));
  CHECK(orbifold.error().find("not closed") != std::string::npos);
  CHECK_FALSE(orbifold.compute());
  // two spheres are not one
  MatrixXi twoF(2 * F.rows(), 3);
  twoF << F, F.array() + int(V.rows());
  MatrixXd twoV(2 * V.rows(), 3);
  twoV << V, V;
  CHECK_FALSE(orbifold.setup(twoV, twoF, {0, 5, 9}, OrbifoldType::I));
  CHECK(orbifold.error().find("not a sphere") != std::string::npos);
  // two spheres touching at two vertices: Euler characteristic 2 and one piece, but no sphere
  MatrixXi touchingF = twoF;
  const int n = int(V.rows());
  for (Index k = 0; k < touchingF.size(); ++k) {
    if (touchingF.data()[k] == n) touchingF.data()[k] = 40;
    if (touchingF.data()[k] == n + 1) touchingF.data()[k] = 120;
  }
  MatrixXd touchingV = twoV;
  touchingV.bottomRows(n).col(0).array() += 2.0;
  CHECK_FALSE(orbifold.setup(touchingV, touchingF, {0, 5, 9}, OrbifoldType::I));
  CHECK(orbifold.error().find("more than one fan") != std::string::npos);
  // a degenerate triangle (0, 0, k) over a new edge keeps every count of a sphere: refused
  {
    std::vector<char> nearZero(std::size_t(n), 0);
    for (Index f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c)
        if (F(f, c) == 0) nearZero[std::size_t(F(f, (c + 1) % 3))] = nearZero[std::size_t(F(f, (c + 2) % 3))] = 1;
    int far = 1;
    while (nearZero[std::size_t(far)]) ++far;
    MatrixXi degenerateF(F.rows() + 1, 3);
    degenerateF << F, Eigen::RowVector3i(0, 0, far);
    CHECK_FALSE(orbifold.setup(V, degenerateF, {5, 9, 20}, OrbifoldType::I));
    INFO(orbifold.error());  // (two fans at vertex 0, or the degenerate side met first)
    CHECK(orbifold.error().find("the mesh is not a") != std::string::npos);
  }
  // a vertex on no triangle would make the Laplacian singular: refused by name
  MatrixXd extraV(n + 1, 3);
  extraV << V, Eigen::RowVector3d(5, 5, 5);
  CHECK_FALSE(orbifold.setup(extraV, F, {0, 5, 9}, OrbifoldType::I));
  CHECK(orbifold.error().find("vertex " + std::to_string(n) + " is on no triangle") != std::string::npos);
  // no cotan weights: a triangle of zero area (up to rounding), a non-finite coordinate
  MatrixXd flatV = V;
  flatV.row(F(0, 2)) = 0.5 * (V.row(F(0, 0)) + V.row(F(0, 1)));
  CHECK_FALSE(orbifold.setup(flatV, F, {0, 5, 9}, OrbifoldType::I));
  CHECK(orbifold.error().find("face 0") != std::string::npos);
  CHECK(orbifold.error().find("zero area") != std::string::npos);
  MatrixXd nanV = V;
  nanV(7, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(orbifold.setup(nanV, F, {0, 5, 9}, OrbifoldType::I));
  CHECK(orbifold.error().find("vertex 7 has a non-finite coordinate") != std::string::npos);
  // a good setup, then a failing edit keeps the object usable
  REQUIRE(orbifold.setup(V, F, spreadCones(V, 3), OrbifoldType::I));
  REQUIRE(orbifold.compute());
  CHECK_FALSE(orbifold.moveCone(3, 0));
  CHECK_FALSE(orbifold.moveCone(1, orbifold.cones()[0]));
  CHECK(orbifold.cones() == spreadCones(V, 3));
}
