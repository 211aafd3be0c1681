// Mesh topology tools of unsupported/Eigen/MeshTools against independent oracles: boundaryLoops
// (loop count, length, orientation by signed area), shortestEdgePath (breadth-first search and
// Floyd-Warshall on small grids), cutMesh / cutMeshAlongPath (vertex copies, Euler
// characteristic, face correspondence through origin, boundary edges, disks from trees),
// meshTopology (counts against independent ones on disks, spheres, tori, holes, pieces),
// cutToDisk (the cut meshes are disks, no dangling cuts), massMatrix (total area, positive diagonal, hand-computed triangles, non-finite corners refused)
// and the triangles cotanLaplacian skips (zero area), refuses (non-finite corners) or keeps (thin ones).
#include <doctest/doctest.h>

#include <unsupported/Eigen/MeshTools>

#include <map>
#include <set>

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;
using Eigen::VectorXi;

/** Undirected edges of F with the number of faces on each. */
std::map<std::pair<int, int>, int> edgeUse(const MatrixXi& F) {
  std::map<std::pair<int, int>, int> use;
  for (Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      ++use[{std::min(a, b), std::max(a, b)}];
    }
  return use;
}

/** V - E + F counting only the vertices used by faces. */
int eulerCharacteristic(const MatrixXi& F) {
  std::set<int> used(F.data(), F.data() + F.size());
  return int(used.size()) - int(edgeUse(F).size()) + int(F.rows());
}

/** Signed area of a loop of vertices in the xy-plane (positive: counter-clockwise). */
double signedArea(const MatrixXd& V, const std::vector<int>& loop) {
  double area = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const int a = loop[i], b = loop[(i + 1) % loop.size()];
    area += V(a, 0) * V(b, 1) - V(b, 0) * V(a, 1);
  }
  return 0.5 * area;
}

/** Each consecutive pair of the loop is a boundary side a -> b of some face (in that direction). */
void checkLoopIsBoundary(const MatrixXi& F, const std::vector<int>& loop) {
  const auto use = edgeUse(F);
  std::set<std::pair<int, int>> sides;
  for (Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) sides.insert({F(f, k), F(f, (k + 1) % 3)});
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const int a = loop[i], b = loop[(i + 1) % loop.size()];
    INFO("loop edge " << a << " -> " << b);
    CHECK(use.at({std::min(a, b), std::max(a, b)}) == 1);
    CHECK(sides.count({a, b}) == 1);
  }
}

/** Number of boundary edges (used by one face). */
int boundaryEdgeCount(const MatrixXi& F) {
  int count = 0;
  for (const auto& e : edgeUse(F)) count += e.second == 1;
  return count;
}

/** Hop distances from source by breadth-first search over an explicit edge set. */
std::vector<int> bfsDistances(const MatrixXi& F, int n, int source) {
  std::vector<std::vector<int>> adjacent(n);
  for (const auto& e : edgeUse(F)) {
    adjacent[e.first.first].push_back(e.first.second);
    adjacent[e.first.second].push_back(e.first.first);
  }
  std::vector<int> distance(n, -1), queue{source};
  distance[source] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head)
    for (int w : adjacent[queue[head]])
      if (distance[w] < 0) {
        distance[w] = distance[queue[head]] + 1;
        queue.push_back(w);
      }
  return distance;
}

/** Checks that path runs from s to t along edges of F and returns its Euclidean length. */
double checkedPathLength(const MatrixXd& V, const MatrixXi& F, const std::vector<int>& path, int s, int t) {
  REQUIRE(!path.empty());
  CHECK(path.front() == s);
  CHECK(path.back() == t);
  const auto use = edgeUse(F);
  double length = 0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const int a = path[i], b = path[i + 1];
    CHECK(use.count({std::min(a, b), std::max(a, b)}) == 1);
    length += (V.row(a) - V.row(b)).norm();
  }
  return length;
}

/** The invariants of every cut: face count, faces map back through origin, positions copied. */
void checkCutCorrespondence(const MatrixXd& V, const MatrixXi& F, const MatrixXd& Vcut, const MatrixXi& Fcut,
                            const VectorXi& origin) {
  REQUIRE(Fcut.rows() == F.rows());
  REQUIRE(origin.size() == Vcut.rows());
  REQUIRE(Vcut.rows() >= V.rows());
  for (Index i = 0; i < V.rows(); ++i) CHECK(origin[i] == i);
  for (Index i = 0; i < Vcut.rows(); ++i) {
    REQUIRE(origin[i] >= 0);
    REQUIRE(origin[i] < V.rows());
    CHECK(Vcut.row(i) == V.row(origin[i]));
  }
  for (Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) CHECK(origin[Fcut(f, k)] == F(f, k));
}

/** Each cut edge {a, b} of F that was interior has become two distinct boundary edges of Fcut. */
void checkCutEdgesOpened(const MatrixXi& F, const MatrixXi& Fcut, const VectorXi& origin,
                         const std::vector<std::array<int, 2>>& cut) {
  const auto before = edgeUse(F);
  const auto after = edgeUse(Fcut);
  for (const auto& e : cut) {
    const std::pair<int, int> key{std::min(e[0], e[1]), std::max(e[0], e[1])};
    if (before.at(key) != 2) continue;
    int copies = 0;
    for (const auto& edge : after) {
      const int a = origin[edge.first.first], b = origin[edge.first.second];
      if (std::make_pair(std::min(a, b), std::max(a, b)) != key) continue;
      ++copies;
      CHECK(edge.second == 1);
    }
    INFO("cut edge " << e[0] << " " << e[1]);
    CHECK(copies == 2);
  }
}

std::vector<std::array<int, 2>> pathEdges(const std::vector<int>& path) {
  std::vector<std::array<int, 2>> edges;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) edges.push_back({path[i], path[i + 1]});
  return edges;
}

} // namespace

TEST_CASE("boundaryLoops: grid, icosphere, hole, separate pieces, bowtie") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(6, 4, V, F);
  auto loops = Eigen::boundaryLoops(F);
  REQUIRE(loops.size() == 1);
  CHECK(loops[0].size() == 2 * 5 + 2 * 3);
  CHECK(signedArea(V, loops[0]) == doctest::Approx(1.0)); // counter-clockwise around the unit square
  checkLoopIsBoundary(F, loops[0]);
  CHECK(std::set<int>(loops[0].begin(), loops[0].end()).size() == loops[0].size());

  MatrixXd S;
  MatrixXi G;
  Eigen::icosphereMesh(2, S, G);
  CHECK(Eigen::boundaryLoops(G).empty());

  // A hole: drop the two triangles of the cell (2, 1) of a 6 x 5 grid; its loop runs clockwise.
  Eigen::gridMesh(6, 5, V, F);
  const int cell = 1 * 5 + 2;
  MatrixXi H(F.rows() - 2, 3);
  for (Index f = 0, g = 0; f < F.rows(); ++f)
    if (f / 2 != cell) H.row(g++) = F.row(f);
  loops = Eigen::boundaryLoops(H);
  REQUIRE(loops.size() == 2);
  CHECK(loops[0].size() == 18);
  CHECK(loops[1].size() == 4);
  CHECK(signedArea(V, loops[0]) == doctest::Approx(1.0));
  CHECK(signedArea(V, loops[1]) == doctest::Approx(-1.0 / 20));
  checkLoopIsBoundary(H, loops[0]);
  checkLoopIsBoundary(H, loops[1]);

  // Two separate grids, the smaller first in F: the longer loop comes first.
  MatrixXd V1, V2;
  MatrixXi F1, F2;
  Eigen::gridMesh(2, 2, V1, F1);
  Eigen::gridMesh(4, 3, V2, F2);
  MatrixXi both(F1.rows() + F2.rows(), 3);
  both << F1, (F2.array() + int(V1.rows())).matrix();
  loops = Eigen::boundaryLoops(both);
  REQUIRE(loops.size() == 2);
  CHECK(loops[0].size() == 10);
  CHECK(loops[1].size() == 4);

  // Two triangles touching at vertex 0: one loop per triangle, each through vertex 0.
  MatrixXi bowtie(2, 3);
  bowtie << 0, 1, 2, 0, 3, 4;
  loops = Eigen::boundaryLoops(bowtie);
  REQUIRE(loops.size() == 2);
  for (const auto& loop : loops) {
    CHECK(loop.size() == 3);
    CHECK(std::count(loop.begin(), loop.end(), 0) == 1);
    checkLoopIsBoundary(bowtie, loop);
  }

  // Two grids of 2 x 2 cells touching at one corner (vertex 8 of the first is vertex 0 of the
  // second): each loop stays in its own fan at the shared vertex.
  Eigen::gridMesh(3, 3, V1, F1);
  MatrixXi corner(2 * F1.rows(), 3);
  corner << F1, (F1.array() + 8).matrix();
  loops = Eigen::boundaryLoops(corner);
  REQUIRE(loops.size() == 2);
  for (const auto& loop : loops) {
    CHECK(loop.size() == 8);
    checkLoopIsBoundary(corner, loop);
  }

  // Sparse huge indices cost nothing more than small ones.
  MatrixXi far(1, 3);
  far << 0, 1, 2000000000;
  loops = Eigen::boundaryLoops(far);
  REQUIRE(loops.size() == 1);
  CHECK(loops[0] == std::vector<int>{0, 1, 2000000000});

  CHECK(Eigen::boundaryLoops(MatrixXi(0, 3)).empty());
  MatrixXi negative(1, 3);
  negative << 0, -1, 2;
  CHECK(Eigen::boundaryLoops(negative).empty());
}

TEST_CASE("shortestEdgePath: hop counts against BFS, lengths against Floyd-Warshall") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(7, 5, V, F);
  const int n = int(V.rows());
  // Jitter the vertices so that edge lengths differ and shortest paths are unique.
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  for (Index i = 0; i < V.rows(); ++i) {
    V(i, 0) += jitter(generator);
    V(i, 1) += jitter(generator);
  }

  // Floyd-Warshall over the edges.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> d(n, std::vector<double>(n, inf));
  for (int i = 0; i < n; ++i) d[i][i] = 0;
  for (const auto& e : edgeUse(F)) {
    const double w = (V.row(e.first.first) - V.row(e.first.second)).norm();
    d[e.first.first][e.first.second] = d[e.first.second][e.first.first] = w;
  }
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) d[i][j] = std::min(d[i][j], d[i][k] + d[k][j]);

  for (int s = 0; s < n; s += 3) {
    const std::vector<int> hops = bfsDistances(F, n, s);
    for (int t = 0; t < n; t += 2) {
      INFO("source " << s << " target " << t);
      const std::vector<int> byHops = Eigen::shortestEdgePath(V, F, s, t, false);
      checkedPathLength(V, F, byHops, s, t);
      CHECK(int(byHops.size()) - 1 == hops[t]);

      const std::vector<int> forward = Eigen::shortestEdgePath(V, F, s, t);
      const std::vector<int> backward = Eigen::shortestEdgePath(V, F, t, s);
      const double lengthForward = checkedPathLength(V, F, forward, s, t);
      const double lengthBackward = checkedPathLength(V, F, backward, t, s);
      CHECK(lengthForward == doctest::Approx(d[s][t]).epsilon(1e-12));
      CHECK(lengthBackward == doctest::Approx(lengthForward).epsilon(1e-12));
    }
  }

  CHECK(Eigen::shortestEdgePath(V, F, 4, 4) == std::vector<int>{4});
  CHECK(Eigen::shortestEdgePath(V, F, -1, 4).empty());
  CHECK(Eigen::shortestEdgePath(V, F, 0, n).empty());

  // Two components: no path between them; an isolated vertex reaches nothing.
  MatrixXd V2(7, 3);
  V2.setRandom();
  MatrixXi F2(2, 3);
  F2 << 0, 1, 2, 3, 4, 5;
  CHECK(Eigen::shortestEdgePath(V2, F2, 0, 4).empty());
  CHECK(Eigen::shortestEdgePath(V2, F2, 6, 0, false).empty());
  CHECK(Eigen::shortestEdgePath(V2, F2, 0, 2).size() == 2);
  F2(1, 2) = 7; // out of range
  CHECK(Eigen::shortestEdgePath(V2, F2, 0, 2).empty());
}

TEST_CASE("cutMesh: a path through the interior of a grid opens a slit") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(9, 9, V, F);
  for (int l = 2; l <= 7; ++l) {
    // Horizontal path on row 4 from column 1: interior vertices only.
    std::vector<int> path;
    for (int i = 1; i < 1 + l; ++i) path.push_back(4 * 9 + i);
    INFO("path of " << l << " vertices");
    MatrixXd Vcut;
    MatrixXi Fcut;
    VectorXi origin;
    std::string error = "stale";
    REQUIRE(Eigen::cutMeshAlongPath(V, F, path, Vcut, Fcut, origin, &error));
    CHECK(error.empty());
    CHECK(Vcut.rows() == V.rows() + l - 2);
    checkCutCorrespondence(V, F, Vcut, Fcut, origin);
    if (l == 2) { // one edge between two interior vertices: neither fan is split, nothing opens
      CHECK(Fcut == F);
      continue;
    }
    checkCutEdgesOpened(F, Fcut, origin, pathEdges(path));
    // A slit is a hole: the Euler characteristic drops from 1 to 0, a second loop appears.
    CHECK(eulerCharacteristic(Fcut) == 0);
    const auto loops = Eigen::boundaryLoops(Fcut);
    REQUIRE(loops.size() == 2);
    CHECK(loops[0].size() == 32);
    CHECK(loops[1].size() == std::size_t(2 * (l - 1)));
    checkLoopIsBoundary(Fcut, loops[1]);
    // The copies are of the interior path vertices, one each.
    std::multiset<int> copied(origin.data() + V.rows(), origin.data() + origin.size());
    for (int i = 1; i + 1 < l; ++i) CHECK(copied.count(path[i]) == 1);
  }
}

TEST_CASE("cutMesh: a path from the boundary opens the disk, Euler characteristic kept") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(8, 6, V, F);
  const std::size_t loopBefore = Eigen::boundaryLoops(F)[0].size();
  for (int l = 2; l <= 5; ++l) {
    // Vertical path from the bottom boundary at column 3 upwards.
    std::vector<int> path;
    for (int j = 0; j < l; ++j) path.push_back(j * 8 + 3);
    MatrixXd Vcut;
    MatrixXi Fcut;
    VectorXi origin;
    REQUIRE(Eigen::cutMeshAlongPath(V, F, path, Vcut, Fcut, origin));
    CHECK(Vcut.rows() == V.rows() + l - 1);
    checkCutCorrespondence(V, F, Vcut, Fcut, origin);
    checkCutEdgesOpened(F, Fcut, origin, pathEdges(path));
    CHECK(eulerCharacteristic(Fcut) == eulerCharacteristic(F));
    CHECK(boundaryEdgeCount(Fcut) == boundaryEdgeCount(F) + 2 * (l - 1));
    const auto loops = Eigen::boundaryLoops(Fcut);
    REQUIRE(loops.size() == 1);
    CHECK(loops[0].size() == loopBefore + 2 * (l - 1));
    checkLoopIsBoundary(Fcut, loops[0]);
    // The loop still runs counter-clockwise around the same area (the slit has none).
    CHECK(signedArea(Vcut, loops[0]) == doctest::Approx(1.0));
  }

  // A path from boundary to boundary splits the grid in two pieces, each a disk.
  std::vector<int> across;
  for (int j = 0; j < 6; ++j) across.push_back(j * 8 + 3);
  MatrixXd Vcut;
  MatrixXi Fcut;
  VectorXi origin;
  REQUIRE(Eigen::cutMeshAlongPath(V, F, across, Vcut, Fcut, origin));
  CHECK(Vcut.rows() == V.rows() + 6);
  CHECK(eulerCharacteristic(Fcut) == 2);
  const auto loops = Eigen::boundaryLoops(Fcut);
  REQUIRE(loops.size() == 2);
  CHECK(loops[0].size() + loops[1].size() == loopBefore + 2 * 5);
}

TEST_CASE("cutMesh: a tree of edges cuts an icosphere into a disk") {
  MatrixXd V;
  MatrixXi F;
  Eigen::icosphereMesh(2, V, F);
  const int root = 0;
  // Shortest paths from one root share its Dijkstra tree, so their union is a tree.
  std::set<std::pair<int, int>> treeEdges;
  std::set<int> treeVertices{root};
  for (int target : {41, 97, 130, 11, 75}) {
    const std::vector<int> path = Eigen::shortestEdgePath(V, F, root, target);
    REQUIRE(path.size() >= 2);
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      treeEdges.insert({std::min(path[i], path[i + 1]), std::max(path[i], path[i + 1])});
      treeVertices.insert(path[i + 1]);
    }
  }
  REQUIRE(treeEdges.size() + 1 == treeVertices.size()); // a tree
  std::vector<std::array<int, 2>> cut;
  for (const auto& e : treeEdges) cut.push_back({e.second, e.first});

  MatrixXd Vcut;
  MatrixXi Fcut;
  VectorXi origin;
  std::string error;
  REQUIRE(Eigen::cutMesh(V, F, cut, Vcut, Fcut, origin, &error));
  checkCutCorrespondence(V, F, Vcut, Fcut, origin);
  checkCutEdgesOpened(F, Fcut, origin, cut);
  // A vertex with k tree edges gets k - 1 copies: sum (k - 1) = 2E - (E + 1) = E - 1.
  CHECK(Vcut.rows() == V.rows() + Index(treeEdges.size()) - 1);
  CHECK(eulerCharacteristic(F) == 2);
  CHECK(eulerCharacteristic(Fcut) == 1);
  const auto loops = Eigen::boundaryLoops(Fcut);
  REQUIRE(loops.size() == 1);
  CHECK(loops[0].size() == 2 * treeEdges.size());
  checkLoopIsBoundary(Fcut, loops[0]);
}

TEST_CASE("cutMesh: repeated cuts compose") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(8, 8, V, F);
  std::vector<int> first{3, 11, 19, 27}; // from the bottom boundary up column 3
  MatrixXd V1, V2, V3;
  MatrixXi F1, F2, F3;
  VectorXi origin1, origin2, origin3;
  REQUIRE(Eigen::cutMeshAlongPath(V, F, first, V1, F1, origin1));
  // Second cut on the cut mesh: from the left boundary (vertex 8*4) to the right along row 4.
  const std::vector<int> second = Eigen::shortestEdgePath(V1, F1, 4 * 8, 4 * 8 + 5, false);
  REQUIRE(second.size() == 6);
  REQUIRE(Eigen::cutMeshAlongPath(V1, F1, second, V2, F2, origin2));
  CHECK(V2.rows() == V1.rows() + 5);
  checkCutCorrespondence(V1, F1, V2, F2, origin2);
  for (Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) CHECK(origin1[origin2[F2(f, k)]] == F(f, k));
  CHECK(eulerCharacteristic(F2) == 1);
  REQUIRE(Eigen::boundaryLoops(F2).size() == 1);
  CHECK(Eigen::boundaryLoops(F2)[0].size() == 28 + 2 * 3 + 2 * 5);

  // Cutting along edges that are already boundary changes nothing.
  REQUIRE(Eigen::cutMeshAlongPath(V2, F2, second, V3, F3, origin3));
  CHECK(V3.rows() == V2.rows());
  CHECK(F3 == F2);

  // An empty cut is the identity.
  REQUIRE(Eigen::cutMesh(V, F, {}, V3, F3, origin3));
  CHECK(V3 == V);
  CHECK(F3 == F);
  CHECK(origin3 == VectorXi::LinSpaced(V.rows(), 0, int(V.rows()) - 1));
}

TEST_CASE("cutMesh: bad input gives false, a message, and untouched outputs") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(4, 4, V, F);
  MatrixXd Vcut = MatrixXd::Constant(2, 2, 7.0);
  MatrixXi Fcut = MatrixXi::Constant(1, 3, 7);
  VectorXi origin = VectorXi::Constant(3, 7);
  auto untouched = [&] {
    CHECK(Vcut == MatrixXd::Constant(2, 2, 7.0));
    CHECK(Fcut == MatrixXi::Constant(1, 3, 7));
    CHECK(origin == VectorXi::Constant(3, 7));
  };
  std::string error;
  CHECK_FALSE(Eigen::cutMesh(V, F, {{0, 5}, {0, 10}}, Vcut, Fcut, origin, &error)); // 0-10 is no edge
  CHECK(error.find("cut edge 1 (0, 10) is not an edge") != std::string::npos);
  untouched();
  CHECK_FALSE(Eigen::cutMesh(V, F, {{0, 16}}, Vcut, Fcut, origin, &error));
  CHECK(error.find("outside [0, 16)") != std::string::npos);
  untouched();
  CHECK_FALSE(Eigen::cutMesh(V, F, {{3, 3}}, Vcut, Fcut, origin, &error));
  CHECK(error.find("not an edge") != std::string::npos);
  untouched();
  CHECK_FALSE(Eigen::cutMeshAlongPath(V, F, {0, 1, 6, 8}, Vcut, Fcut, origin, &error)); // 6 -> 8 is no edge
  CHECK(error.find("path step 2 (6, 8)") != std::string::npos);
  untouched();
  CHECK_FALSE(Eigen::cutMeshAlongPath(V, F, {-2}, Vcut, Fcut, origin, &error));
  CHECK(!error.empty());
  untouched();
  MatrixXi badF = F;
  badF(3, 1) = 99;
  CHECK_FALSE(Eigen::cutMesh(V, badF, {}, Vcut, Fcut, origin, &error));
  CHECK(error.find("face 3") != std::string::npos);
  untouched();
  // Without an error string it still fails cleanly.
  CHECK_FALSE(Eigen::cutMesh(V, F, {{0, 10}}, Vcut, Fcut, origin));
  untouched();
}

TEST_CASE("cutMesh: a degenerate face (a repeated vertex) gets no copy of its own") {
  MatrixXd V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 0, 1;
  MatrixXd Vcut;
  MatrixXi Fcut;
  VectorXi origin;
  std::string error;
  REQUIRE_MESSAGE(Eigen::cutMesh(V, F, {}, Vcut, Fcut, origin, &error), error);
  CHECK(Vcut == V);  // no cut: the mesh as it was
  CHECK(Fcut == F);
  CHECK(origin == VectorXi::LinSpaced(3, 0, 2));
  // cut along (1, 2), a boundary edge here: still nothing to open
  REQUIRE_MESSAGE(Eigen::cutMesh(V, F, {{1, 2}}, Vcut, Fcut, origin, &error), error);
  CHECK(Fcut == F);
}

TEST_CASE("cotanLaplacian: zero-area triangles contribute nothing, non-finite coordinates are refused, thin ones kept") {
  // A flat 5 x 5 grid (coordinates in quarters, exact); face 10 is (6, 7, 12), the first face at 12.
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(5, 5, V, F);
  REQUIRE(F.row(10) == Eigen::RowVector3i(6, 7, 12));
  auto doubleArea = [&](const MatrixXd& P, Index f) {
    const Eigen::Vector3d a = P.row(F(f, 0)), b = P.row(F(f, 1)), c = P.row(F(f, 2));
    return (b - a).cross(c - a).norm();
  };
  std::string error = "untouched";
  CHECK(Eigen::cotanLaplacian(V, F, &error).rows() == V.rows());
  CHECK(error.empty());
  // the Laplacian of the mesh without face 10, for the zero-area cases
  MatrixXi withoutFace(F.rows() - 1, 3);
  withoutFace << F.topRows(10), F.bottomRows(F.rows() - 11);
  auto skipsFace10 = [&](const MatrixXd& P) {
    error = "untouched";
    const Eigen::SparseMatrix<double> L = Eigen::cotanLaplacian(P, F, &error);
    CHECK(error.empty());
    REQUIRE(L.rows() == P.rows());
    CHECK(Eigen::MatrixXd(L).allFinite());
    CHECK(Eigen::MatrixXd(L) == Eigen::MatrixXd(Eigen::cotanLaplacian(P, withoutFace)));
  };
  // vertex 12 on the edge (6, 7): zero area exactly
  MatrixXd P = V;
  P.row(12) << 0.375, 0.25, 0;
  REQUIRE(doubleArea(P, 10) == 0);
  skipsFace10(P);
  // vertex 12 on the line through 6 and a raised 7, up to rounding only
  P = V;
  P.row(7) << 0.5, 0.3, 0.1;
  P.row(12) = P.row(6) + (P.row(7) - P.row(6)) / 3.0;
  REQUIRE(doubleArea(P, 10) > 0);
  REQUIRE(doubleArea(P, 10) < 1e-15);
  skipsFace10(P);
  // a non-finite coordinate: refused, with and without a message
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    P = V;
    P(12, 1) = bad;
    error.clear();
    CHECK(Eigen::cotanLaplacian(P, F, &error).rows() == 0);
    CHECK(Eigen::cotanLaplacian(P, F).rows() == 0);
    INFO("error: " << error);
    for (const std::string part : {"cotanLaplacian", "face 10 (vertices 6, 7, 12)", "vertex 12", "non-finite"})
      CHECK(error.find(part) != std::string::npos);
  }
  // kept: a thin triangle (angles of about 1e-8), and a non-finite vertex on no triangle
  P = V;
  P.row(12) << 0.375, 0.25 + 1e-9, 0;
  const Eigen::SparseMatrix<double> thin = Eigen::cotanLaplacian(P, F, &error);
  CHECK(error.empty());
  REQUIRE(thin.rows() == V.rows());
  CHECK(Eigen::MatrixXd(thin).allFinite());
  CHECK(std::abs(thin.coeff(6, 7)) > 1e7);  // (the nearly straight angle at 12, opposite (6, 7))
  P.conservativeResize(V.rows() + 1, 3);
  P.row(V.rows()) << std::numeric_limits<double>::quiet_NaN(), 0, 0;
  CHECK(Eigen::cotanLaplacian(P, F, &error).rows() == P.rows());
  CHECK(error.empty());
}

TEST_CASE("massMatrix: hand-computed triangles, total area, positive diagonal") {
  // Right isosceles triangle (right angle at 0, not obtuse): Voronoi shares 1/4, 1/8, 1/8.
  MatrixXd V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  MatrixXi F(1, 3);
  F << 0, 1, 2;
  Eigen::SparseMatrix<double> M = Eigen::massMatrix(V, F);
  CHECK(M.nonZeros() == 3);
  CHECK(M.coeff(0, 0) == doctest::Approx(0.25));
  CHECK(M.coeff(1, 1) == doctest::Approx(0.125));
  CHECK(M.coeff(2, 2) == doctest::Approx(0.125));
  // Obtuse at vertex 0 (135 degrees), area 1/2: halves and quarters.
  V.row(2) << -1, 1, 0;
  M = Eigen::massMatrix(V, F);
  CHECK(M.coeff(0, 0) == doctest::Approx(0.25));
  CHECK(M.coeff(1, 1) == doctest::Approx(0.125));
  CHECK(M.coeff(2, 2) == doctest::Approx(0.125));
  // Equilateral triangle: a third of the area each; a degenerate one adds nothing.
  V << 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(0.75), 0;
  MatrixXi F2(2, 3);
  F2 << 0, 1, 2, 0, 1, 1;
  M = Eigen::massMatrix(V, F2);
  for (int i = 0; i < 3; ++i) CHECK(M.coeff(i, i) == doctest::Approx(std::sqrt(3.0) / 12));

  // Regular grid: interior vertices own an h x h square (the Voronoi cell of the lattice).
  Eigen::gridMesh(5, 5, V, F);
  M = Eigen::massMatrix(V, F);
  CHECK(M.sum() == doctest::Approx(1.0));
  CHECK(M.coeff(2 * 5 + 2, 2 * 5 + 2) == doctest::Approx(1.0 / 16));
  CHECK(M.nonZeros() == V.rows());

  // Jittered grid (obtuse triangles appear) in 3-D and an icosphere: sum = total area, diagonal > 0.
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  Eigen::gridMesh(12, 9, V, F);
  for (Index i = 0; i < V.rows(); ++i) V.row(i) += Eigen::RowVector3d(jitter(generator) / 11, jitter(generator) / 8, jitter(generator));
  MatrixXd S;
  MatrixXi G;
  Eigen::icosphereMesh(3, S, G);
  int obtuseCount = 0;
  for (const auto& mesh : {std::make_pair(V, F), std::make_pair(S, G)}) {
    double area = 0;
    for (Index f = 0; f < mesh.second.rows(); ++f) {
      const Eigen::RowVector3d a = mesh.first.row(mesh.second(f, 0)), b = mesh.first.row(mesh.second(f, 1)),
                               c = mesh.first.row(mesh.second(f, 2));
      area += 0.5 * (b - a).cross(c - a).norm();
      obtuseCount += (b - a).dot(c - a) < 0 || (a - b).dot(c - b) < 0 || (a - c).dot(b - c) < 0;
    }
    M = Eigen::massMatrix(mesh.first, mesh.second);
    CHECK(M.sum() == doctest::Approx(area).epsilon(1e-12));
    for (Index i = 0; i < M.rows(); ++i) CHECK(M.coeff(i, i) > 0);
    CHECK(M.nonZeros() == M.rows());
  }
  CHECK(obtuseCount > 10); // the obtuse branch was exercised
  CHECK(S.rows() > 0);

  // An unused vertex gets zero mass, even at a non-finite position (it is not read).
  V.conservativeResize(V.rows() + 1, 3);
  V.row(V.rows() - 1).setConstant(std::numeric_limits<double>::quiet_NaN());
  std::string error = "untouched";
  M = Eigen::massMatrix(V, F, &error);
  CHECK(error.empty());
  CHECK(M.coeff(V.rows() - 1, V.rows() - 1) == 0.0);
  // A used vertex at a non-finite position: refused, naming the face and the vertex.
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    MatrixXd P = V;
    P(F(3, 1), 2) = bad;
    CHECK(Eigen::massMatrix(P, F, &error).rows() == 0);
    CHECK(Eigen::massMatrix(P, F).rows() == 0);
    INFO("error: " << error);
    CHECK(error.find("massMatrix: face ") != std::string::npos);
    CHECK(error.find("vertex " + std::to_string(F(3, 1)) + " has a non-finite coordinate") != std::string::npos);
  }
}

TEST_CASE("meshTopology: disk, sphere, torus, holes, pieces, against independent counts") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(6, 4, V, F);
  Eigen::MeshTopology t = Eigen::meshTopology(F);
  CHECK(t.vertices == 24);
  CHECK(t.edges == Index(edgeUse(F).size()));
  CHECK(t.faces == F.rows());
  CHECK(t.eulerCharacteristic == 1);
  CHECK(t.eulerCharacteristic == eulerCharacteristic(F));
  CHECK(t.components == 1);
  CHECK(t.boundaryLoops == 1);
  CHECK(t.genus == 0);
  CHECK(t.isDisk());

  Eigen::icosphereMesh(2, V, F);
  t = Eigen::meshTopology(F);
  CHECK(t.eulerCharacteristic == 2);
  CHECK(t.boundaryLoops == 0);
  CHECK(t.genus == 0);
  CHECK_FALSE(t.isDisk());

  Eigen::torusMesh(12, 8, V, F);
  t = Eigen::meshTopology(F);
  CHECK(t.vertices == 96);
  CHECK(t.edges == 3 * 96);
  CHECK(t.eulerCharacteristic == 0);
  CHECK(t.eulerCharacteristic == eulerCharacteristic(F));
  CHECK(t.genus == 1);
  CHECK_FALSE(t.isDisk());
  // One face out: a torus with a hole is still genus 1, with one boundary loop; not a disk.
  MatrixXi Fh = F.bottomRows(F.rows() - 1);
  t = Eigen::meshTopology(Fh);
  CHECK(t.boundaryLoops == 1);
  CHECK(t.genus == 1);
  CHECK_FALSE(t.isDisk());
  // Cut along one meridian loop (around the tube): a tube, genus 0 with two boundary loops.
  std::vector<std::array<int, 2>> meridian;
  for (int j = 0; j < 8; ++j) meridian.push_back({3 * 8 + j, 3 * 8 + (j + 1) % 8});
  MatrixXd Vcut;
  MatrixXi Fcut;
  VectorXi origin;
  std::string error;
  REQUIRE_MESSAGE(Eigen::cutMesh(V, F, meridian, Vcut, Fcut, origin, &error), error);
  t = Eigen::meshTopology(Fcut);
  CHECK(t.boundaryLoops == 2);
  CHECK(t.genus == 0);
  CHECK(t.components == 1);

  // Two grids side by side: two pieces, each a disk, not a disk together; a vertex row of V
  // that no face uses does not count.
  Eigen::gridMesh(4, 4, V, F);
  MatrixXi two(2 * F.rows(), 3);
  two << F, (F.array() + 17).matrix();
  t = Eigen::meshTopology(two);
  CHECK(t.vertices == 32);
  CHECK(t.components == 2);
  CHECK(t.boundaryLoops == 2);
  CHECK(t.eulerCharacteristic == 2);
  CHECK(t.genus == 0);
  CHECK_FALSE(t.isDisk());

  // A grid with one vertex's fan removed: a hole, two loops.
  Eigen::gridMesh(5, 5, V, F);
  std::vector<int> keep;
  for (Index f = 0; f < F.rows(); ++f)
    if (F(f, 0) != 12 && F(f, 1) != 12 && F(f, 2) != 12) keep.push_back(int(f));
  MatrixXi holed(Index(keep.size()), 3);
  for (std::size_t k = 0; k < keep.size(); ++k) holed.row(Index(k)) = F.row(keep[k]);
  t = Eigen::meshTopology(holed);
  CHECK(t.boundaryLoops == 2);
  CHECK(t.genus == 0);
  CHECK(t.eulerCharacteristic == 0);

  // Invalid or empty input: all zero.
  t = Eigen::meshTopology(MatrixXi(0, 3));
  CHECK(t.faces == 0);
  CHECK(t.vertices == 0);
  MatrixXi bad(1, 3);
  bad << 0, -1, 2;
  CHECK(Eigen::meshTopology(bad).faces == 0);
}

TEST_CASE("meshTopology: not a consistently oriented manifold -> genus -1; huge unused indices cost nothing") {
  // A Möbius strip of 5 quads (10 vertices, 10 triangles): Euler characteristic 0 and, whatever
  // the order of its faces, a genus of -1 (not orientable), so that no disk tool accepts it.
  MatrixXi moebius(10, 3);
  moebius << 0, 9, 8, 3, 0, 2, 5, 2, 4, 5, 4, 7, 6, 9, 7, 7, 4, 6, 6, 8, 9, 5, 3, 2, 1, 0, 3, 1, 0, 8;
  for (int reversed = 0; reversed < 2; ++reversed) {
    CAPTURE(reversed);
    const MatrixXi faces = reversed ? MatrixXi(moebius.colwise().reverse()) : moebius;
    const Eigen::MeshTopology t = Eigen::meshTopology(faces);
    CHECK(t.eulerCharacteristic == 0);
    CHECK(t.genus == -1);
    CHECK_FALSE(t.isDisk());
  }
  // A grid with one face flipped is no oriented surface either; flipping it back gives a disk.
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(5, 5, V, F);
  REQUIRE(Eigen::meshTopology(F).isDisk());
  MatrixXi flipped = F;
  std::swap(flipped(12, 1), flipped(12, 2));
  CHECK(Eigen::meshTopology(flipped).genus == -1);
  CHECK_FALSE(Eigen::meshTopology(flipped).isDisk());
  // An edge on three triangles: genus -1.
  MatrixXi fin(3, 3);
  fin << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  CHECK(Eigen::meshTopology(fin).genus == -1);

  // A stray huge vertex index: the same counts as with the vertices renumbered, and cutToDisk
  // names its cut edges by the original indices (no allocation per possible index: 2e9 here).
  const int huge = 2000000000;
  Eigen::icosphereMesh(1, V, F);
  MatrixXi far = F;
  for (Index k = 0; k < far.size(); ++k)
    if (far.data()[k] == 5) far.data()[k] = huge;
  const Eigen::MeshTopology a = Eigen::meshTopology(F), b = Eigen::meshTopology(far);
  CHECK(b.vertices == a.vertices);
  CHECK(b.edges == a.edges);
  CHECK(b.components == a.components);
  CHECK(b.genus == 0);
  std::vector<std::array<int, 2>> cuts, farCuts;
  std::string error;
  REQUIRE(Eigen::cutToDisk(F, cuts, &error));
  REQUIRE_MESSAGE(Eigen::cutToDisk(far, farCuts, &error), error);
  REQUIRE(farCuts.size() == cuts.size());
  for (std::size_t e = 0; e < cuts.size(); ++e)
    for (int end = 0; end < 2; ++end) CHECK(farCuts[e][end] == (cuts[e][end] == 5 ? huge : cuts[e][end]));
  // ... and cutMeshToDisk refuses it against V before any work
  MatrixXd Vdisk;
  MatrixXi Fdisk;
  VectorXi origin;
  CHECK_FALSE(Eigen::cutMeshToDisk(V, far, Vdisk, Fdisk, origin, &error));
  CHECK(error.find("outside") != std::string::npos);
}

/** Cuts F along cutToDisk's edges and checks the result: a disk, every cut edge opened, no
  * dangling cut (each end of a cut edge meets another cut or boundary edge, except the two ends
  * of a closed sphere's path), faces kept. */
void checkCutToDisk(const MatrixXd& V, const MatrixXi& F, std::size_t expectedEdges = std::size_t(-1)) {
  std::vector<std::array<int, 2>> cuts;
  std::string error;
  REQUIRE_MESSAGE(Eigen::cutToDisk(F, cuts, &error), error);
  CHECK(error.empty());
  if (expectedEdges != std::size_t(-1)) CHECK(cuts.size() == expectedEdges);
  const auto use = edgeUse(F);
  std::map<int, int> degree;  // cut and boundary edges at each vertex
  std::set<std::pair<int, int>> distinct;
  for (const auto& e : cuts) {
    const std::pair<int, int> key{std::min(e[0], e[1]), std::max(e[0], e[1])};
    CHECK(use.count(key) == 1);
    CHECK(use.at(key) == 2);  // an interior edge
    distinct.insert(key);
    ++degree[e[0]];
    ++degree[e[1]];
  }
  CHECK(distinct.size() == cuts.size());
  bool closed = true;
  for (const auto& entry : use)
    if (entry.second == 1) {
      closed = false;
      ++degree[entry.first.first];
      ++degree[entry.first.second];
    }
  if (!closed || cuts.size() > 2)  // (a closed sphere's path of two edges has two ends)
    for (const auto& e : cuts) {
      CHECK(degree[e[0]] >= 2);
      CHECK(degree[e[1]] >= 2);
    }
  MatrixXd Vcut;
  MatrixXi Fcut;
  VectorXi origin;
  if (cuts.empty()) {
    CHECK(Eigen::meshTopology(F).isDisk());
    return;
  }
  REQUIRE_MESSAGE(Eigen::cutMesh(V, F, cuts, Vcut, Fcut, origin, &error), error);
  checkCutCorrespondence(V, F, Vcut, Fcut, origin);
  checkCutEdgesOpened(F, Fcut, origin, cuts);
  const Eigen::MeshTopology t = Eigen::meshTopology(Fcut);
  CHECK(t.isDisk());
  CHECK(t.faces == F.rows());
}

TEST_CASE("cutToDisk: spheres, tori, holes and real meshes become disks; bad meshes are refused") {
  MatrixXd V;
  MatrixXi F;
  Eigen::gridMesh(6, 5, V, F);
  checkCutToDisk(V, F, 0);  // a disk already

  Eigen::icosphereMesh(2, V, F);
  checkCutToDisk(V, F, 2);  // a closed sphere: a path of two edges

  Eigen::torusMesh(16, 9, V, F);
  checkCutToDisk(V, F);  // genus 1, closed
  const MatrixXi holedTorus = F.bottomRows(F.rows() - 3);
  checkCutToDisk(V, holedTorus);  // genus 1 with a hole

  // A grid with two holes (the fans of two interior vertices removed): two joining paths.
  Eigen::gridMesh(9, 9, V, F);
  std::vector<int> keep;
  for (Index f = 0; f < F.rows(); ++f) {
    bool touches = false;
    for (int c = 0; c < 3; ++c) touches = touches || F(f, c) == 20 || F(f, c) == 58;
    if (!touches) keep.push_back(int(f));
  }
  MatrixXi holes(Index(keep.size()), 3);
  for (std::size_t k = 0; k < keep.size(); ++k) holes.row(Index(k)) = F.row(keep[k]);
  REQUIRE(Eigen::meshTopology(holes).boundaryLoops == 3);
  checkCutToDisk(V, holes);

  // Shared meshes of higher genus and with holes, when present.
  for (const char* name : {"fertility.off.gz", "rocker-arm.off.gz", "bunny.off.gz"}) {
    CAPTURE(name);
    std::string error;
    if (!Eigen::readOFF(std::string(UC_TEST_MESH_DIR) + "/" + name, V, F, &error)) {
      MESSAGE("skipped, cannot read " << name << ": " << error);
      continue;
    }
    const Eigen::MeshTopology before = Eigen::meshTopology(F);
    MESSAGE(std::string(name) << ": genus " << before.genus << ", " << before.boundaryLoops << " boundary loops");
    checkCutToDisk(V, F);
  }

  // Refused: a non-manifold edge, opposite orientations, two pieces, empty input.
  std::vector<std::array<int, 2>> cuts{{7, 8}};
  std::string error;
  MatrixXi fin(3, 3);
  fin << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  CHECK_FALSE(Eigen::cutToDisk(fin, cuts, &error));
  CHECK(error.find("three or more") != std::string::npos);
  MatrixXi flipped(2, 3);
  flipped << 0, 1, 2, 0, 1, 3;
  CHECK_FALSE(Eigen::cutToDisk(flipped, cuts, &error));
  CHECK(error.find("consistently oriented") != std::string::npos);
  MatrixXi pieces(2, 3);
  pieces << 0, 1, 2, 3, 4, 5;
  CHECK_FALSE(Eigen::cutToDisk(pieces, cuts, &error));
  CHECK(error.find("one piece") != std::string::npos);
  CHECK_FALSE(Eigen::cutToDisk(MatrixXi(0, 3), cuts, &error));
  CHECK(cuts.size() == 1);  // untouched on failure

  // cutMeshToDisk = cutToDisk + cutMesh: a torus becomes a disk, copies mapped to their origins.
  Eigen::torusMesh(10, 7, V, F);
  MatrixXd Vdisk;
  MatrixXi Fdisk;
  VectorXi origin;
  REQUIRE_MESSAGE(Eigen::cutMeshToDisk(V, F, Vdisk, Fdisk, origin, &error), error);
  CHECK(Eigen::meshTopology(Fdisk).isDisk());
  checkCutCorrespondence(V, F, Vdisk, Fdisk, origin);
  CHECK_FALSE(Eigen::cutMeshToDisk(V.topRows(5), F, Vdisk, Fdisk, origin, &error));  // F indexes past V
  CHECK_FALSE(error.empty());
  CHECK(Fdisk.rows() == F.rows());  // untouched on failure
  // In place: V and F become the same disk.
  MatrixXd Vplace = V;
  MatrixXi Fplace = F;
  VectorXi placeOrigin;
  REQUIRE_MESSAGE(Eigen::cutMeshToDisk(Vplace, Fplace, placeOrigin, &error), error);
  CHECK(Vplace == Vdisk);
  CHECK(Fplace == Fdisk);
  CHECK(placeOrigin == origin);
}

TEST_CASE("boundaryLoops and cutMesh on a real mesh (camelhead)") {
  MatrixXd V;
  MatrixXi F;
  std::string error;
  const bool ok = Eigen::readOFF(std::string(UC_TEST_DATA_DIR) + "/camelhead.off.gz", V, F, &error);
  INFO(error);
  REQUIRE(ok);
  const auto loops = Eigen::boundaryLoops(F);
  REQUIRE(!loops.empty());
  std::size_t total = 0;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    total += loops[i].size();
    if (i > 0) CHECK(loops[i].size() <= loops[i - 1].size());
  }
  CHECK(int(total) == boundaryEdgeCount(F)); // every boundary edge in exactly one loop
  checkLoopIsBoundary(F, loops[0]);

  // A hop-count path from the boundary into the interior, trimmed to start at its last boundary
  // vertex, opens the longest loop by twice its length.
  std::set<int> onBoundary;
  for (const auto& loop : loops) onBoundary.insert(loop.begin(), loop.end());
  const std::vector<int> hops = bfsDistances(F, int(V.rows()), loops[0][0]);
  int target = -1;
  for (int v = 0; v < int(V.rows()) && target < 0; ++v)
    if (hops[v] == 25 && !onBoundary.count(v)) target = v;
  REQUIRE(target >= 0);
  std::vector<int> path = Eigen::shortestEdgePath(V, F, loops[0][0], target, false);
  REQUIRE(path.size() == 26);
  std::size_t lastOnBoundary = 0;
  for (std::size_t i = 0; i < path.size(); ++i)
    if (onBoundary.count(path[i])) lastOnBoundary = i;
  path.erase(path.begin(), path.begin() + std::ptrdiff_t(lastOnBoundary));
  REQUIRE(path.size() >= 2);
  const bool onLongest = std::count(loops[0].begin(), loops[0].end(), path[0]) == 1;
  MatrixXd Vcut;
  MatrixXi Fcut;
  VectorXi origin;
  REQUIRE(Eigen::cutMeshAlongPath(V, F, path, Vcut, Fcut, origin, &error));
  checkCutCorrespondence(V, F, Vcut, Fcut, origin);
  checkCutEdgesOpened(F, Fcut, origin, pathEdges(path));
  CHECK(Vcut.rows() == V.rows() + Index(path.size()) - 1);
  CHECK(eulerCharacteristic(Fcut) == eulerCharacteristic(F));
  const auto cutLoops = Eigen::boundaryLoops(Fcut);
  REQUIRE(cutLoops.size() == loops.size());
  if (onLongest) CHECK(cutLoops[0].size() == loops[0].size() + 2 * (path.size() - 1));
}

TEST_CASE("cutMesh: random cut sets against an independent wedge count") {
  // Oracle: around each vertex v, the triangles at v linked across shared uncut edges (v, w) form
  // the wedges; two corners of v get the same new index exactly when they lie in the same wedge.
  std::mt19937 generator(5);
  for (int trial = 0; trial < 40; ++trial) {
    MatrixXd V;
    MatrixXi F;
    if (trial % 2) Eigen::icosphereMesh(1, V, F);
    else Eigen::gridMesh(6, 5, V, F);
    const auto use = edgeUse(F);
    std::vector<std::array<int, 2>> cut;
    std::set<std::pair<int, int>> cutSet;
    std::bernoulli_distribution pick(0.05 + 0.05 * (trial % 5));
    for (const auto& e : use)
      if (pick(generator)) {
        cut.push_back({e.first.second, e.first.first});
        cutSet.insert(e.first);
      }
    MatrixXd Vcut;
    MatrixXi Fcut;
    Eigen::VectorXi origin;
    REQUIRE(Eigen::cutMesh(V, F, cut, Vcut, Fcut, origin));
    checkCutCorrespondence(V, F, Vcut, Fcut, origin);
    // Numbering: the first corner of v (in face order) keeps v, copies are numbered in the order
    // of their first corners.
    std::vector<char> seen(Vcut.rows(), 0);
    int nextCopy = int(V.rows());
    for (Index f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int i = Fcut(f, k);
        if (seen[i]) continue;
        seen[i] = 1;
        if (i >= V.rows()) CHECK(i == nextCopy++);
        else CHECK(i == F(f, k));
      }
    CHECK(nextCopy == Vcut.rows());

    Index expectedVertices = V.rows();
    for (int v = 0; v < int(V.rows()); ++v) {
      std::vector<std::pair<int, int>> corners; // (face, corner) at v
      for (int f = 0; f < int(F.rows()); ++f)
        for (int k = 0; k < 3; ++k)
          if (F(f, k) == v) corners.push_back({f, k});
      std::vector<int> component(corners.size(), -1);
      int components = 0;
      for (std::size_t s = 0; s < corners.size(); ++s) {
        if (component[s] >= 0) continue;
        std::vector<std::size_t> stack{s};
        component[s] = components;
        while (!stack.empty()) {
          const std::size_t a = stack.back();
          stack.pop_back();
          for (std::size_t b = 0; b < corners.size(); ++b) {
            if (component[b] >= 0) continue;
            // Faces a and b share an edge (v, w) that is not cut?
            bool linked = false;
            for (int ka = 0; ka < 3 && !linked; ++ka) {
              const int w = F(corners[a].first, ka);
              if (w == v) continue;
              for (int kb = 0; kb < 3; ++kb)
                if (F(corners[b].first, kb) == w && !cutSet.count({std::min(v, w), std::max(v, w)})) linked = true;
            }
            if (linked) {
              component[b] = components;
              stack.push_back(b);
            }
          }
        }
        ++components;
      }
      if (components > 0) expectedVertices += components - 1;
      for (std::size_t a = 0; a < corners.size(); ++a)
        for (std::size_t b = 0; b < corners.size(); ++b)
          CHECK((Fcut(corners[a].first, corners[a].second) == Fcut(corners[b].first, corners[b].second)) ==
                (component[a] == component[b]));
    }
    INFO("trial " << trial << ", " << cut.size() << " cut edges");
    CHECK(Vcut.rows() == expectedVertices);
  }
}
