// ARAP deformation (unsupported/Eigen/MeshDeformation; Sorkine & Alexa 2007, and Herholz &
// Sorkine-Hornung §5.3) against oracles: the energy never increases over the iterations, handles
// hold exactly, a rigid motion of all handles gives the rigidly moved mesh, every iteration equals
// an independent reference (per-face cotan weights, the reduced system A_II factored from scratch
// by SimplicialLDLT), after every handle / region-of-interest edit the in-place updated object
// gives what a fresh object with the same constraints gives, and bad input is a clear error.
// Meshes: generated bars (open cylinders) and grids, and data/camelhead.off.gz.
#include <doctest/doctest.h>

#include <Eigen/SparseCholesky>
#include <unsupported/Eigen/MeshDeformation>

#include <fstream>
#include <map>

#ifndef UC_TEST_DATA_DIR
#error "UC_TEST_DATA_DIR must name the data folder of the project"
#endif

using namespace Eigen;

namespace {

/** A bar of `rings` rings of `around` vertices, radius 0.1, length 1 along z. */
void bar(int around, int rings, MatrixXd& V, MatrixXi& F) { cylinderMesh(around, rings, 0.1, 1.0, V, F); }

/** The vertices of ring j of a cylinderMesh. */
std::vector<int> ring(int around, int j) {
  std::vector<int> r;
  for (int i = 0; i < around; ++i) r.push_back(j * around + i);
  return r;
}

/** Concatenation of two vertex lists. */
std::vector<int> join(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

/** Rows \a vertices of \a V. */
MatrixXd rows(const MatrixXd& V, const std::vector<int>& vertices) {
  MatrixXd P(Index(vertices.size()), 3);
  for (std::size_t k = 0; k < vertices.size(); ++k) P.row(Index(k)) = V.row(vertices[k]);
  return P;
}

/** Rotation by \a degrees about \a axis, applied to the rows of \a P about \a center. */
MatrixXd rotateRows(const MatrixXd& P, double degrees, const Vector3d& axis, const Vector3d& center) {
  const Matrix3d R = AngleAxisd(degrees * 3.14159265358979323846 / 180.0, axis.normalized()).toRotationMatrix();
  MatrixXd Q = P;
  for (Index k = 0; k < P.rows(); ++k) Q.row(k) = (R * (P.row(k).transpose() - center) + center).transpose();
  return Q;
}

/** Vertices within Euclidean distance \a radius of vertex \a center. */
std::vector<int> ball(const MatrixXd& V, int center, double radius) {
  std::vector<int> inside;
  for (Index v = 0; v < V.rows(); ++v)
    if ((V.row(v) - V.row(center)).norm() <= radius) inside.push_back(int(v));
  return inside;
}

/** An independent ARAP: cotan weights summed per face into adjacency lists, the reduced system
  * L_II of the free vertices assembled and factored from scratch by SimplicialLDLT, right-hand
  * side b_I - L_IB g_B. Same iteration as the class (local step, then global step). */
class ReferenceArap {
 public:
  ReferenceArap(const MatrixXd& V, const MatrixXi& F) : m_rest(V), m_neighbours(std::size_t(V.rows())) {
    std::vector<std::map<int, double>> weight(std::size_t(V.rows()));
    for (Index f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int a = F(f, (c + 1) % 3), b = F(f, (c + 2) % 3), o = F(f, c);
        const Vector3d u = (V.row(a) - V.row(o)).transpose(), w = (V.row(b) - V.row(o)).transpose();
        const double cross = u.cross(w).norm();
        if (cross <= 0) continue;
        const double halfCot = 0.5 * u.dot(w) / cross;
        weight[std::size_t(a)][b] += halfCot;
        weight[std::size_t(b)][a] += halfCot;
      }
    for (std::size_t i = 0; i < weight.size(); ++i)
      for (const auto& [j, w] : weight[i]) m_neighbours[i].push_back({j, w});
  }

  /** \a iterations ARAP iterations from the rest mesh; \a fixed flags the constrained vertices,
    * held at the rows of \a values. */
  MatrixXd solve(const std::vector<char>& fixed, const MatrixXd& values, int iterations) const {
    const Index n = m_rest.rows();
    std::vector<int> freeIndex(std::size_t(n), -1);
    int freeCount = 0;
    for (Index v = 0; v < n; ++v)
      if (!fixed[std::size_t(v)]) freeIndex[std::size_t(v)] = freeCount++;
    std::vector<Triplet<double>> t;
    for (Index i = 0; i < n; ++i) {
      if (freeIndex[std::size_t(i)] < 0) continue;
      double diagonal = 0;
      for (const auto& [j, w] : m_neighbours[std::size_t(i)]) {
        diagonal += w;
        if (freeIndex[std::size_t(j)] >= 0) t.emplace_back(freeIndex[std::size_t(i)], freeIndex[std::size_t(j)], -w);
      }
      t.emplace_back(freeIndex[std::size_t(i)], freeIndex[std::size_t(i)], diagonal);
    }
    SparseMatrix<double> Lii(freeCount, freeCount);
    Lii.setFromTriplets(t.begin(), t.end());
    SimplicialLDLT<SparseMatrix<double>> ldlt(Lii);
    REQUIRE(ldlt.info() == Success);

    MatrixXd U = m_rest;
    for (Index v = 0; v < n; ++v)
      if (fixed[std::size_t(v)]) U.row(v) = values.row(v);
    for (int iteration = 0; iteration < iterations; ++iteration) {
      // rotations of the current positions (the first from the rest mesh, as the class does)
      const MatrixXd& current = iteration == 0 ? m_rest : U;
      std::vector<Matrix3d> R{std::size_t(n)};
      for (Index i = 0; i < n; ++i) {
        Matrix3d S = Matrix3d::Zero();
        for (const auto& [j, w] : m_neighbours[std::size_t(i)])
          S += w * (m_rest.row(i) - m_rest.row(j)).transpose() * (current.row(i) - current.row(j));
        JacobiSVD<Matrix3d> svd(S, ComputeFullU | ComputeFullV);
        Matrix3d svdU = svd.matrixU();
        if ((svd.matrixV() * svdU.transpose()).determinant() < 0) svdU.col(2) *= -1;
        R[std::size_t(i)] = svd.matrixV() * svdU.transpose();
      }
      MatrixXd b = MatrixXd::Zero(freeCount, 3);
      for (Index i = 0; i < n; ++i) {
        const int fi = freeIndex[std::size_t(i)];
        if (fi < 0) continue;
        for (const auto& [j, w] : m_neighbours[std::size_t(i)]) {
          const Vector3d e = (m_rest.row(i) - m_rest.row(j)).transpose();
          b.row(fi) += (0.5 * w * (R[std::size_t(i)] + R[std::size_t(j)]) * e).transpose();
          if (freeIndex[std::size_t(j)] < 0) b.row(fi) += w * values.row(j);
        }
      }
      const MatrixXd x = ldlt.solve(b);
      for (Index v = 0; v < n; ++v)
        if (freeIndex[std::size_t(v)] >= 0) U.row(v) = x.row(freeIndex[std::size_t(v)]);
    }
    return U;
  }

 private:
  MatrixXd m_rest;
  std::vector<std::vector<std::pair<int, double>>> m_neighbours;
};

/** The constrained flags and Dirichlet values an ArapDeformation should use: handles at their
  * positions, vertices outside \a region (empty = everything inside) at rest. */
void constraintsFor(const MatrixXd& V, const std::vector<int>& handles, const MatrixXd& positions,
                    const std::vector<int>* region, std::vector<char>& fixed, MatrixXd& values) {
  fixed.assign(std::size_t(V.rows()), region ? 1 : 0);
  if (region)
    for (int v : *region) fixed[std::size_t(v)] = 0;
  values = V;
  for (std::size_t k = 0; k < handles.size(); ++k) {
    fixed[std::size_t(handles[k])] = 1;
    values.row(handles[k]) = positions.row(Index(k));
  }
}

/** Checks the energy sequence never increases (up to round-off). */
void checkMonotone(const std::vector<double>& energies) {
  for (std::size_t k = 1; k < energies.size(); ++k) {
    INFO("iteration " << k << ": " << energies[k - 1] << " -> " << energies[k]);
    CHECK(energies[k] <= energies[k - 1] * (1 + 1e-12) + 1e-15);
  }
}

/** Checks that every handle sits exactly at its position. */
void checkHandlesHold(const MatrixXd& U, const std::vector<int>& handles, const MatrixXd& positions) {
  for (std::size_t k = 0; k < handles.size(); ++k) {
    INFO("handle " << k << " (vertex " << handles[k] << ")");
    CHECK(U.row(handles[k]) == positions.row(Index(k)));
  }
}

/** A fresh object with the given constraints, solved from the rest mesh. */
MatrixXd solveFresh(const MatrixXd& V, const MatrixXi& F, const std::vector<int>& handles, const MatrixXd& positions,
                    const std::vector<int>* region, int iterations) {
  ArapDeformation<> fresh(V, F);
  REQUIRE(fresh.info() == Success);
  if (region) REQUIRE(fresh.setRegionOfInterest(*region));
  REQUIRE(fresh.setHandles(handles, positions));
  MatrixXd U;
  REQUIRE(fresh.solve(U, iterations));
  return U;
}

}  // namespace

TEST_CASE("bending a bar: the energy never increases, handles hold, the reference agrees") {
  const int around = 12, rings = 25;
  MatrixXd V;
  MatrixXi F;
  bar(around, rings, V, F);
  ArapDeformation<> arap(V, F);
  REQUIRE(arap.info() == Success);

  // bottom ring fixed, top ring turned by 60 degrees about the x axis through the bar's middle
  const std::vector<int> bottom = ring(around, 0), top = ring(around, rings - 1);
  const std::vector<int> handles = join(bottom, top);
  MatrixXd positions = rows(V, handles);
  positions.bottomRows(around) = rotateRows(positions.bottomRows(around), 60, Vector3d::UnitX(), Vector3d(0, 0, 0.5));
  REQUIRE(arap.setHandles(handles, positions));

  MatrixXd U;
  std::vector<double> energies;
  REQUIRE(arap.solve(U, 30, &energies));
  REQUIRE(energies.size() == 30);
  checkMonotone(energies);
  CHECK(energies.back() < 0.5 * energies.front());  // it really optimises
  checkHandlesHold(U, handles, positions);
  CHECK(arap.energy(U) == doctest::Approx(energies.back()).epsilon(1e-12));

  // the same iterations by the independent reference
  std::vector<char> fixed;
  MatrixXd values;
  constraintsFor(V, handles, positions, nullptr, fixed, values);
  const ReferenceArap reference(V, F);
  for (int iterations : {1, 5, 30}) {
    MatrixXd ours;
    REQUIRE(arap.solve(ours, iterations));
    const MatrixXd theirs = reference.solve(fixed, values, iterations);
    INFO("iterations " << iterations);
    CHECK((ours - theirs).cwiseAbs().maxCoeff() < 1e-9);
  }

  // warm start: continuing from U keeps decreasing the energy
  std::vector<double> more;
  REQUIRE(arap.solve(U, 5, &more));
  CHECK(more.front() <= energies.back() * (1 + 1e-12));
  checkMonotone(more);
}

TEST_CASE("grid pulled out of its plane and a shared mesh: monotone energy, handles hold") {
  SUBCASE("grid") {
    MatrixXd V;
    MatrixXi F;
    gridMesh(15, 15, V, F);
    ArapDeformation<> arap(V, F);
    const std::vector<int> handles = {0, 14, 210, 224, 112};  // corners and the centre
    MatrixXd positions = rows(V, handles);
    positions(4, 2) = 0.4;
    REQUIRE(arap.setHandles(handles, positions));
    MatrixXd U;
    std::vector<double> energies;
    REQUIRE(arap.solve(U, 20, &energies));
    checkMonotone(energies);
    checkHandlesHold(U, handles, positions);
    CHECK(U(113, 2) > 0.1);  // the neighbourhood follows the centre
  }
  SUBCASE("camelhead") {
    const std::string path = std::string(UC_TEST_DATA_DIR) + "/camelhead.off.gz";
    MatrixXd V;
    MatrixXi F;
    std::string error;
    REQUIRE_MESSAGE(readOFF(path, V, F, &error), error);
    ArapDeformation<> arap(V, F);
    REQUIRE(arap.info() == Success);
    // region: a ball around vertex 0; handles: a smaller ball around it, lifted along the normal-ish direction
    const double extent = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
    const std::vector<int> region = ball(V, 0, 0.3 * extent), handles = ball(V, 0, 0.05 * extent);
    REQUIRE(handles.size() > 0);
    REQUIRE(region.size() > handles.size());
    REQUIRE(arap.setRegionOfInterest(region));
    MatrixXd positions = rows(V, handles);
    positions.rowwise() += RowVector3d(0.1, 0.05, 0.08) * extent;
    REQUIRE(arap.setHandles(handles, positions));
    MatrixXd U;
    std::vector<double> energies;
    REQUIRE(arap.solve(U, 8, &energies));
    checkMonotone(energies);
    checkHandlesHold(U, handles, positions);
    std::vector<char> inRegion(std::size_t(V.rows()), 0);
    for (int v : region) inRegion[std::size_t(v)] = 1;
    Index outsideMoved = 0;
    for (Index v = 0; v < V.rows(); ++v)
      if (!inRegion[std::size_t(v)] && U.row(v) != V.row(v)) ++outsideMoved;
    CHECK(outsideMoved == 0);
  }
}

TEST_CASE("a rigid motion of all handles gives the rigidly moved mesh") {
  const int around = 10, rings = 15;
  MatrixXd V;
  MatrixXi F;
  bar(around, rings, V, F);
  const Matrix3d R = AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const RowVector3d t(0.3, -0.2, 0.5);
  const MatrixXd moved = (V * R.transpose()).rowwise() + t;

  ArapDeformation<> arap(V, F);
  const std::vector<int> handles = join(ring(around, 0), ring(around, rings - 1));
  REQUIRE(arap.setHandles(handles, rows(moved, handles)));

  SUBCASE("from the moved mesh: it is a fixed point of the iteration") {
    MatrixXd U = moved;
    std::vector<double> energies;
    REQUIRE(arap.solve(U, 3, &energies));
    CHECK((U - moved).cwiseAbs().maxCoeff() < 1e-10);
    for (double e : energies) CHECK(e < 1e-18);
  }
  SUBCASE("from the rest mesh: the iteration converges to it") {
    MatrixXd U;
    std::vector<double> energies;
    REQUIRE(arap.solve(U, 200, &energies));
    checkMonotone(energies);
    CHECK(energies.back() < 1e-8 * energies.front());
    CHECK((U - moved).cwiseAbs().maxCoeff() < 1e-4);
  }
  SUBCASE("a single handle vertex translated: a pure translation") {
    REQUIRE(arap.setHandles({7}, RowVector3d(V.row(7) + t)));
    MatrixXd U;
    REQUIRE(arap.solve(U, 2));
    CHECK(((V.rowwise() + t) - U).cwiseAbs().maxCoeff() < 1e-10);
  }
}

TEST_CASE("after every edit of handles and region the result equals a fresh solver's") {
  const int around = 12, rings = 30, iterations = 6;
  MatrixXd V;
  MatrixXi F;
  bar(around, rings, V, F);
  ArapDeformation<> arap(V, F);
  REQUIRE(arap.info() == Success);
  const ReferenceArap reference(V, F);

  std::vector<int> handles;
  MatrixXd positions(0, 3);
  std::vector<int> region;
  bool hasRegion = false;
  std::vector<char> constrainedBefore(std::size_t(V.rows()), 0);

  auto check = [&](const std::string& step) {
    INFO("after: " << step);
    MatrixXd ours;
    REQUIRE(arap.solve(ours, iterations));
    const MatrixXd fresh = solveFresh(V, F, handles, positions, hasRegion ? &region : nullptr, iterations);
    CHECK((ours - fresh).cwiseAbs().maxCoeff() < 1e-9);
    std::vector<char> fixed;
    MatrixXd values;
    constraintsFor(V, handles, positions, hasRegion ? &region : nullptr, fixed, values);
    CHECK((ours - reference.solve(fixed, values, iterations)).cwiseAbs().maxCoeff() < 1e-9);
    // the edit touched exactly the vertices whose status changed
    Index added = 0, released = 0;
    for (Index v = 0; v < V.rows(); ++v) {
      CHECK(arap.isConstrained(v) == bool(fixed[std::size_t(v)]));
      added += fixed[std::size_t(v)] && !constrainedBefore[std::size_t(v)];
      released += !fixed[std::size_t(v)] && constrainedBefore[std::size_t(v)];
    }
    CHECK(arap.lastEdit().added == added);
    CHECK(arap.lastEdit().released == released);
    constrainedBefore = fixed;
    checkHandlesHold(ours, handles, positions);
  };

  // 1. handles: the bottom ring, held at rest, and the top ring, moved
  handles = join(ring(around, 0), ring(around, rings - 1));
  positions = rows(V, handles);
  positions.bottomRows(around).rowwise() += RowVector3d(0.4, 0, -0.1);
  REQUIRE(arap.setHandles(handles, positions));
  check("setHandles");

  // 2. add a handle ring in the middle, pushed sideways
  const std::vector<int> middle = ring(around, rings / 2);
  MatrixXd middlePositions = rows(V, middle);
  middlePositions.rowwise() += RowVector3d(0, 0.2, 0);
  REQUIRE(arap.addHandles(middle, middlePositions));
  handles = join(handles, middle);
  positions.conservativeResize(Index(handles.size()), 3);
  positions.bottomRows(around) = middlePositions;
  check("addHandles");

  // 3. region of interest: the upper two thirds (the lower third is held at rest)
  for (int j = rings / 3; j < rings; ++j) region = join(region, ring(around, j));
  hasRegion = true;
  REQUIRE(arap.setRegionOfInterest(region));
  check("setRegionOfInterest (shrink)");

  // 4. move the handles only: no dofs change
  positions.rowwise() += RowVector3d(0.05, 0.05, 0);
  REQUIRE(arap.moveHandles(positions));
  {
    MatrixXd ours;
    REQUIRE(arap.solve(ours, iterations));
    CHECK((ours - solveFresh(V, F, handles, positions, &region, iterations)).cwiseAbs().maxCoeff() < 1e-9);
  }

  // 5. remove the bottom ring handles (outside the region: they stay constrained, at rest now)
  const std::vector<int> bottom = ring(around, 0);
  REQUIRE(arap.removeHandles(bottom));
  handles.erase(handles.begin(), handles.begin() + around);
  positions = positions.bottomRows(positions.rows() - around).eval();
  check("removeHandles (outside the region)");

  // 6. remove the middle ring handles (inside the region: they become free)
  REQUIRE(arap.removeHandles(middle));
  handles.resize(handles.size() - middle.size());
  positions.conservativeResize(Index(handles.size()), 3);
  check("removeHandles (inside the region)");

  // 7. grow the region to all but the two lowest rings, then to the whole mesh plus new handles
  region.clear();
  for (int j = 2; j < rings; ++j) region = join(region, ring(around, j));
  REQUIRE(arap.setRegionOfInterest(region));
  check("setRegionOfInterest (grow)");
  REQUIRE(arap.clearRegionOfInterest());
  hasRegion = false;
  check("clearRegionOfInterest");
  REQUIRE(arap.addHandles(bottom));
  handles = join(handles, bottom);
  positions.conservativeResize(Index(handles.size()), 3);
  positions.bottomRows(around) = rows(V, bottom);
  check("addHandles at rest");

  // 8. replace everything at once
  handles = join(ring(around, 3), ring(around, rings - 4));
  positions = rows(V, handles);
  positions.bottomRows(around) = rotateRows(positions.bottomRows(around), 45, Vector3d::UnitY(), Vector3d(0, 0, 0.5));
  REQUIRE(arap.setHandles(handles, positions));
  check("setHandles (replace)");
}

TEST_CASE("bad input gives a clear error and changes nothing") {
  MatrixXd V;
  MatrixXi F;
  bar(8, 6, V, F);
  const Index n = V.rows();

  SUBCASE("before compute") {
    ArapDeformation<> arap;
    MatrixXd U;
    CHECK_FALSE(arap.solve(U, 1));
    CHECK(arap.info() == InvalidInput);
    CHECK(arap.lastError().find("compute()") != std::string::npos);
    CHECK_FALSE(arap.setHandles({0}));
  }
  SUBCASE("bad meshes") {
    ArapDeformation<> arap;
    MatrixXi badF = F;
    badF(3, 1) = int(n);
    CHECK_FALSE(arap.compute(V, badF));
    CHECK(arap.info() == InvalidInput);
    CHECK(arap.lastError().find("out of range") != std::string::npos);
    CHECK_FALSE(arap.compute(V.leftCols(2), F));
    MatrixXd nanV = V;
    nanV(2, 2) = std::nan("");
    CHECK_FALSE(arap.compute(nanV, F));
    CHECK(arap.lastError().find("NaN") != std::string::npos);
    // a triangle of zero area is no error: it has no energy and its weights are left out
    MatrixXd flatV = V;
    flatV.row(F(0, 2)) = 0.5 * (V.row(F(0, 0)) + V.row(F(0, 1)));
    REQUIRE(arap.compute(flatV, F));
    REQUIRE(arap.setHandles({0, 1, int(n) - 1}));
    MatrixXd U;
    REQUIRE(arap.solve(U, 2));
    CHECK(U.allFinite());
  }

  ArapDeformation<> arap(V, F);
  REQUIRE(arap.info() == Success);
  const std::vector<int> handles = {0, 1, int(n) - 1};
  REQUIRE(arap.setHandles(handles));
  MatrixXd before;
  REQUIRE(arap.solve(before, 3));
  auto unchanged = [&]() {
    CHECK(arap.handles() == handles);
    MatrixXd after;
    REQUIRE(arap.solve(after, 3));
    CHECK(after == before);
  };

  SUBCASE("handle out of range") {
    CHECK_FALSE(arap.setHandles({0, int(n)}));
    CHECK(arap.info() == InvalidInput);
    CHECK(arap.lastError().find("out of range") != std::string::npos);
    CHECK_FALSE(arap.addHandles({-1}));
    CHECK(arap.lastError().find("out of range") != std::string::npos);
    unchanged();
  }
  SUBCASE("repeated handle") {
    CHECK_FALSE(arap.setHandles({3, 4, 3}));
    CHECK(arap.lastError().find("repeated") != std::string::npos);
    CHECK_FALSE(arap.addHandles({1}));  // already a handle
    CHECK(arap.lastError().find("repeated") != std::string::npos);
    unchanged();
  }
  SUBCASE("wrong sizes and values") {
    CHECK_FALSE(arap.setHandles({3, 4}, MatrixXd::Zero(3, 3)));
    CHECK(arap.lastError().find("2 x 3") != std::string::npos);
    CHECK_FALSE(arap.moveHandles(MatrixXd::Zero(2, 3)));
    MatrixXd inf = MatrixXd::Zero(3, 3);
    inf(1, 1) = std::numeric_limits<double>::infinity();
    CHECK_FALSE(arap.moveHandles(inf));
    CHECK(arap.lastError().find("NaN or Inf") != std::string::npos);
    MatrixXd U;
    CHECK_FALSE(arap.solve(U, -1));
    unchanged();
  }
  SUBCASE("removing a vertex that is not a handle") {
    CHECK_FALSE(arap.removeHandles({5}));
    CHECK(arap.lastError().find("not a handle") != std::string::npos);
    unchanged();
  }
  SUBCASE("bad region of interest") {
    CHECK_FALSE(arap.setRegionOfInterest({2, int(n) + 5}));
    CHECK(arap.lastError().find("out of range") != std::string::npos);
    CHECK_FALSE(arap.setRegionOfInterest({2, 2}));
    CHECK(arap.lastError().find("repeated") != std::string::npos);
    unchanged();
  }
  SUBCASE("no constraint: not unique") {
    REQUIRE(arap.setHandles({}));
    MatrixXd U;
    CHECK_FALSE(arap.solve(U, 1));
    CHECK(arap.info() == InvalidInput);
    CHECK(arap.lastError().find("no constrained vertex") != std::string::npos);
  }
}

TEST_CASE("two pieces and an unused vertex") {
  MatrixXd V1, V2;
  MatrixXi F1, F2;
  bar(8, 6, V1, F1);
  bar(8, 6, V2, F2);
  const Index n1 = V1.rows();
  MatrixXd V(2 * n1 + 1, 3);
  V << V1, (V2.rowwise() + RowVector3d(1, 0, 0)), RowVector3d(5, 5, 5);  // the last vertex is in no face
  MatrixXi F(F1.rows() + F2.rows(), 3);
  F << F1, (F2.array() + int(n1)).matrix();

  ArapDeformation<> arap(V, F);
  REQUIRE(arap.info() == Success);
  CHECK(arap.isConstrained(2 * n1));  // unused: held at rest
  REQUIRE(arap.setHandles({0, 47}));   // both in the first bar
  MatrixXd U;
  CHECK_FALSE(arap.solve(U, 1));
  CHECK(arap.lastError().find("vertex " + std::to_string(n1)) != std::string::npos);

  REQUIRE(arap.addHandles({int(n1) + 3}, RowVector3d(V.row(n1 + 3) + RowVector3d(0, 0, 1))));
  std::vector<double> energies;
  REQUIRE(arap.solve(U, 3, &energies));
  CHECK(U.row(2 * n1) == V.row(2 * n1));
  // the second bar only has one handle: it translates rigidly
  CHECK((U.middleRows(n1, n1) - (V.middleRows(n1, n1).rowwise() + RowVector3d(0, 0, 1))).cwiseAbs().maxCoeff() < 1e-10);
}
