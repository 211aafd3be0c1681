// SeamCutSystem: the linear-algebra core of interactive seam editing for parameterizations
// (Herholz & Sorkine-Hornung, "Sparse Cholesky Updates for Interactive Mesh Parameterization",
// §4.1 and §5.1). The Laplacian of the whole uncut mesh is factored once; the boundary of the
// mesh being parameterized is a set of Dirichlet dofs removed from that factor in place
// (UpdatableSupernodalLLT::removeDofs). Cutting the mesh along a seam that starts on the boundary
// makes every seam vertex a boundary vertex: its copies are all known, so the interior system of
// the cut mesh is the original one minus the seam (no dofs are added), and the cut is one more
// removeDofs; undo is restoreDofs. Only the coupling of interior vertices to the (copied) boundary
// vertices depends on the cut, and it is read from the cut mesh's faces at solve time.

#ifndef EIGEN_MESHPARAMETERIZATION_SEAMCUTSYSTEM_H
#define EIGEN_MESHPARAMETERIZATION_SEAMCUTSYSTEM_H

namespace Eigen {

/** \ingroup MeshParameterization_Module
  * \class SeamCutSystem
  * \brief A mesh Laplacian factored once, and a cut mesh whose boundary loop gives the Dirichlet
  * dofs, edited by seam cuts and undos through in-place factor updates.
  *
  * State: the uncut mesh (V, F) with n vertices; the current cut mesh (cutVertices(),
  * cutFaces(), origin()): vertices i < n are the original ones, copies made by the cuts are
  * appended, origin()[i] names the original vertex of cut vertex i; its boundary loop
  * (boundaryLoop(), the longest one, counter-clockwise, starting at its smallest index); and the
  * factor of \f$ A + \varepsilon I \f$ (A the Laplacian of the uncut mesh from per-corner weights,
  * see LaplacianWeights) with the original vertices of the boundary loop removed.
  *
  * A seam (addSeam()) must keep every vertex that has copies on the boundary loop: a path that
  * starts on the boundary loop, runs inside the surface and does not reach the boundary again
  * (on a closed mesh, the first seam may be any simple path: it cuts the sphere to a disk).
  *
  * \tparam Ordering_  fill-reducing ordering of the factor (AMDOrdering<int>, MetisOrdering<int>, ...).
  *
  * \sa TutteEmbedding, BoundaryFirstFlattening, UpdatableSupernodalLLT::removeDofs()
  */
template <typename Ordering_ = AMDOrdering<int>>
class SeamCutSystem
{
public:
  /** The solver type: an updatable supernodal Cholesky factorization of the Laplacian. */
  typedef UpdatableSupernodalLLT<SparseMatrix<double>, Lower, Ordering_> Solver;

  /** Empty system (isValid() is false): call compute() before anything else. */
  SeamCutSystem() = default;

  /** Factors the Laplacian of (\a V, \a F) with corner weights \a cornerWeights (#F x 3, see
    * LaplacianWeights) plus \a shift times the identity, and removes the boundary loop's vertices.
    * A closed mesh has no boundary loop yet; give it a seam before solving.
    * \returns false with a message in \a error on bad input or a failed factorization. */
  bool compute(const MatrixXd& V, const MatrixXi& F, const MatrixXd& cornerWeights, double shift,
               std::string* error = nullptr)
  {
    m_isValid = false;
    m_history.clear();
    std::string problem;
    if (V.cols() != 3 || V.rows() < 3) problem = "V must be #V x 3 with at least 3 vertices";
    else if (F.cols() != 3 || F.rows() < 1) problem = "F must be #F x 3 with at least one triangle";
    else if (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()) problem = "face index out of range";
    else if (cornerWeights.rows() != F.rows() || cornerWeights.cols() != 3) problem = "corner weights must be #F x 3";
    else if (!V.allFinite())
    {
      Index v = 0;
      while (V.row(v).allFinite()) ++v;
      problem = "vertex " + std::to_string(v) + " has a non-finite coordinate";
    }
    else if (!cornerWeights.allFinite()) problem = "the corner weights must be finite";
    else if (!(shift >= 0)) problem = "the shift must be >= 0";
    if (!problem.empty()) return fail(problem, error);

    m_vertices = V;
    m_faces = F;
    m_cornerWeights = cornerWeights;
    m_shift = shift;
    m_matrix = internal::meshparameterization::assembleLaplacian(F, cornerWeights, V.rows(), shift);
    m_solver.setUpdateCaching(true);
    m_solver.compute(m_matrix);
    if (m_solver.info() != Success) return fail("the Laplacian + shift is not positive definite (add a shift)", error);
    m_cutVertices = V;
    m_cutFaces = F;
    m_origin = VectorXi::LinSpaced(V.rows(), 0, int(V.rows() - 1));
    {  // a cut in place splits only the seam's vertices; a general cut also every vertex where
       // several fans meet: in place only when there is none (a cut with no edges splits nothing)
      MatrixXd splitV;
      MatrixXi splitF;
      VectorXi splitOrigin;
      m_cutsInPlace = cutMesh(V, F, {}, splitV, splitF, splitOrigin) && splitV.rows() == V.rows();
    }
    m_removed.assign(std::size_t(V.rows()), 0);
    std::vector<int> newlyRemoved;
    if (!adoptCut(newlyRemoved, problem)) return fail(problem, error);
    if (!removeFromFactor(newlyRemoved, problem)) return fail(problem, error);
    m_isValid = true;
    if (error) error->clear();
    return true;
  }

  /** Cuts the current cut mesh along \a path (indices of cutVertices(), consecutive ones joined by
    * an edge) and removes the seam's new boundary vertices from the factor in place.
    * \returns false with a message (nothing changed) when the path is not an edge path, leaves a
    * copied vertex off the boundary loop (it does not start on the boundary, or it reaches the
    * boundary again and splits the mesh), cuts nothing open (it runs along boundary edges only, or
    * is a single edge between inner vertices; then no undo step is recorded either), or the update
    * fails. */
  bool addSeam(const std::vector<int>& path, std::string* error = nullptr)
  {
    if (!m_isValid) return fail("compute() first", error, false);
    if (path.size() < 2) return fail("a seam needs at least two vertices", error, false);
    const auto start = std::chrono::steady_clock::now();
    std::string problem;
    if (m_cutsInPlace)
    {  // a seam from the loop inwards: cut in place, the loop spliced (else the general cut below)
      Snapshot local;
      local.vertexCount = m_cutVertices.rows();
      local.loop = m_boundaryLoop;
      local.topology = m_topology;
      if (internal::meshtools::seamCutInPlace(m_cutVertices, m_cutFaces, m_origin, m_boundaryLoop, m_onBoundary, path,
                                              local.edits, m_cutMark))
      {
        local.newBoundary.assign(path.begin() + 1, path.end());
        m_lastCutInPlace = true;
        // a cut from the loop inwards keeps one piece and one loop (and so the Euler
        // characteristic): each vertex it adds comes with one edge
        const Index added = m_cutVertices.rows() - local.vertexCount;
        m_topology.vertices += added;
        m_topology.edges += added;
        std::rotate(m_boundaryLoop.begin(), std::min_element(m_boundaryLoop.begin(), m_boundaryLoop.end()),
                    m_boundaryLoop.end());
        m_onLoop.resize(std::size_t(m_cutVertices.rows()), 0);
        for (int v : m_boundaryLoop) m_onLoop[std::size_t(v)] = 1;
        return commitCut(local, newlyRemovedOfLoop(), true, start, error);
      }
    }
    Snapshot previous;
    previous.vertices = m_cutVertices;
    previous.faces = m_cutFaces;
    previous.origin = m_origin;
    previous.loop = m_boundaryLoop;
    previous.topology = m_topology;
    previous.onBoundary = m_onBoundary;
    m_lastCutInPlace = false;
    MatrixXd cutV;
    MatrixXi cutF;
    VectorXi localOrigin;
    if (!cutMeshAlongPath(m_cutVertices, m_cutFaces, path, cutV, cutF, localOrigin, &problem))
      return fail(problem, error, false);
    if (cutV.rows() == m_cutVertices.rows())  // no vertex split: the same faces, nothing to undo
      return fail("the seam cuts nothing open (its edges are boundary edges already, or it is a single edge "
                  "between inner vertices): nothing changed and no undo step was recorded",
                  error, false);
    m_cutVertices.swap(cutV);
    m_cutFaces.swap(cutF);
    VectorXi composed(localOrigin.size());
    for (Index i = 0; i < localOrigin.size(); ++i) composed[i] = previous.origin[localOrigin[i]];
    m_origin.swap(composed);
    std::vector<int> newlyRemoved;
    const bool ok = adoptCut(newlyRemoved, problem);
    return commitCut(previous, newlyRemoved, ok, start, error, problem);
  }

  /** Undoes the last addSeam(): the cut mesh comes back and the seam's dofs are restored in the
    * factor in place. \returns false when there is nothing to undo. */
  bool undo(std::string* error = nullptr)
  {
    if (m_history.empty()) return fail("nothing to undo", error, false);
    Snapshot& last = m_history.back();
    const auto start = std::chrono::steady_clock::now();
    if (!last.newlyRemoved.empty()) m_solver.restoreDofs(last.newlyRemoved);
    m_lastUpdateMs = msSince(start);
    if (m_solver.info() != Success) return fail("restoreDofs failed", error, false);
    for (int v : last.newlyRemoved) m_removed[std::size_t(v)] = 0;
    restore(last);
    m_history.pop_back();
    if (error) error->clear();
    return true;
  }

  /** Forgets the undo history: the seams so far become part of the starting mesh. */
  void clearHistory() { m_history.clear(); }

  /** \returns the number of seams that undo() can take back. */
  Index undoableSeams() const { return Index(m_history.size()); }

  /** Solves the Dirichlet problem on the cut mesh: X with \f$ (A_{II} + \varepsilon I) X_I =
    * \mathrm{rhs}_I - A_{IB} X_B \f$ and \f$ X_B = \f$ \a boundaryValues_B, where I are the
    * interior and B the boundary-loop vertices of the cut mesh and A its Laplacian.
    * \a rhs and \a boundaryValues are (#cut vertices) x k; only their interior, respectively
    * boundary, rows are read. Each of the \a shiftRefinements steps of iterative refinement
    * (one more solve each) moves the result towards the solution without the shift,
    * \f$ A_{II} X_I = \mathrm{rhs}_I - A_{IB} X_B \f$: the error shrinks by a factor of about
    * \f$ \varepsilon \|A_{II}^{-1}\| \f$ per step. \returns the (#cut vertices) x k solution. */
  MatrixXd solve(const MatrixXd& rhs, const MatrixXd& boundaryValues, int shiftRefinements = 0) const
  {
    MatrixXd X = solveShifted(rhs, boundaryValues);
    const MatrixXd zero = MatrixXd::Zero(X.rows(), X.cols());
    for (int step = 0; step < shiftRefinements && m_shift != 0; ++step)
    {
      // Residual of the unshifted interior equations: (A_II X_I) - (rhs_I - A_IB X_B) = -shift X_I.
      MatrixXd correction = solveShifted(m_shift * X, zero);
      for (Index i = 0; i < X.rows(); ++i)
        if (!m_onLoop[std::size_t(i)]) X.row(i) += correction.row(i);
    }
    return X;
  }

  /** \returns \f$ A X \f$ for the Laplacian A of the cut mesh (without the shift); X is
    * (#cut vertices) x k. */
  MatrixXd applyLaplacian(const MatrixXd& X) const
  {
    MatrixXd Y = MatrixXd::Zero(X.rows(), X.cols());
    internal::meshparameterization::forEachWeightedEdge(m_cutFaces, m_cornerWeights, [&](Index, int a, int c, double w) {
      for (Index j = 0; j < X.cols(); ++j)
      {
        const double flow = w * (X(a, j) - X(c, j));
        Y(a, j) += flow;
        Y(c, j) -= flow;
      }
    });
    return Y;
  }

private:
  /** The Dirichlet solve of solve() with the shifted interior matrix. */
  MatrixXd solveShifted(const MatrixXd& rhs, const MatrixXd& boundaryValues) const
  {
    eigen_assert(m_isValid && "SeamCutSystem::solve(): compute() first");
    const Index nc = m_cutVertices.rows(), k = rhs.cols();
    eigen_assert(rhs.rows() == nc && boundaryValues.rows() == nc && boundaryValues.cols() == k);
    // Right-hand side in the numbering of the factor (original vertices); removed rows stay 0,
    // so solve() returns 0 there and the interior rows solve A_II x_I = b_I.
    MatrixXd b = MatrixXd::Zero(m_vertices.rows(), k);
    for (Index i = 0; i < nc; ++i)
      if (!m_onLoop[std::size_t(i)]) b.row(i) = rhs.row(i);
    internal::meshparameterization::forEachWeightedEdge(m_cutFaces, m_cornerWeights, [&](Index, int a, int c, double w) {
      // A_ac = -w: moving -A_IB g_B to the right-hand side adds w * g.
      const bool aKnown = m_onLoop[std::size_t(a)] != 0, cKnown = m_onLoop[std::size_t(c)] != 0;
      if (aKnown == cKnown) return;
      const int free = aKnown ? c : a, known = aKnown ? a : c;
      for (Index j = 0; j < k; ++j) b(free, j) += w * boundaryValues(known, j);
    });
    const MatrixXd x = m_solver.solve(b);
    MatrixXd X(nc, k);
    for (Index i = 0; i < nc; ++i) X.row(i) = m_onLoop[std::size_t(i)] ? boundaryValues.row(i) : x.row(i);
    return X;
  }

public:
  /** \returns the interior system of the cut mesh, \f$ A_{II} + \varepsilon I \f$, assembled from
    * scratch (what a solver without updates would factor), and in \a interior (if not null) the
    * original vertex of each of its rows. For comparisons and benchmarks. */
  SparseMatrix<double> interiorMatrix(std::vector<int>* interior = nullptr) const
  {
    std::vector<int> position(std::size_t(m_vertices.rows()), -1), rows;
    for (Index i = 0; i < m_vertices.rows(); ++i)
      if (!m_removed[std::size_t(i)])
      {
        position[std::size_t(i)] = int(rows.size());
        rows.push_back(int(i));
      }
    std::vector<Triplet<double>> triplets;
    for (Index j = 0; j < m_matrix.outerSize(); ++j)
      for (SparseMatrix<double>::InnerIterator it(m_matrix, j); it; ++it)
        if (position[std::size_t(it.row())] >= 0 && position[std::size_t(j)] >= 0)
          triplets.emplace_back(position[std::size_t(it.row())], position[std::size_t(j)], it.value());
    SparseMatrix<double> A(Index(rows.size()), Index(rows.size()));
    A.setFromTriplets(triplets.begin(), triplets.end());
    A.makeCompressed();
    if (interior) interior->swap(rows);
    return A;
  }

  /** \returns true after a successful compute(). */
  bool isValid() const { return m_isValid; }
  /** \returns the vertex positions of the uncut mesh. */
  const MatrixXd& vertices() const { return m_vertices; }
  /** \returns the triangles of the uncut mesh. */
  const MatrixXi& faces() const { return m_faces; }
  /** \returns the vertex positions of the current cut mesh. */
  const MatrixXd& cutVertices() const { return m_cutVertices; }
  /** \returns the triangles of the current cut mesh (same order as faces()). */
  const MatrixXi& cutFaces() const { return m_cutFaces; }
  /** \returns for each cut vertex the original vertex it copies. */
  const VectorXi& origin() const { return m_origin; }
  /** \returns the boundary loop of the cut mesh (empty for a closed mesh without seams). */
  const std::vector<int>& boundaryLoop() const { return m_boundaryLoop; }
  /** \returns the number of boundary loops of the cut mesh (the longest is boundaryLoop()). */
  Index loopCount() const { return m_topology.boundaryLoops; }
  /** \returns the topology of the cut mesh (pieces, boundary loops, genus): the disk-based
    * layouts need MeshTopology::isDisk(). */
  const MeshTopology& topology() const { return m_topology; }
  /** \returns true when cut vertex \a i lies on the boundary loop (a Dirichlet dof). */
  bool isOnBoundaryLoop(Index i) const { return m_onLoop[std::size_t(i)] != 0; }
  /** \returns the per-corner edge weights (#F x 3). */
  const MatrixXd& cornerWeights() const { return m_cornerWeights; }
  /** \returns the shift added to the diagonal. */
  double shift() const { return m_shift; }
  /** \returns the factorization (for statistics such as lastUpdate()). */
  const Solver& solver() const { return m_solver; }
  /** \returns the milliseconds of the last factor update (removeDofs or restoreDofs). */
  double lastUpdateMs() const { return m_lastUpdateMs; }
  /** \returns the milliseconds the last addSeam() spent cutting the mesh and tracing its boundary. */
  double lastCutMs() const { return m_lastCutMs; }
  /** \returns whether the last addSeam() cut in place (a seam from the boundary loop into the
    * interior of a mesh whose vertices each join one fan: the seam's neighbourhood is rewritten
    * and the loop spliced, with the same result as cutMeshAlongPath()) rather than rebuilding
    * the cut mesh. */
  bool lastCutInPlace() const { return m_lastCutInPlace; }

private:
  struct Snapshot
  {
    MatrixXd vertices;
    MatrixXi faces;
    VectorXi origin;
    std::vector<int> loop;
    std::vector<int> newlyRemoved;
    MeshTopology topology;
    std::vector<char> onBoundary;  ///< (a general cut) the boundary flags before it
    /** A cut in place: the number of vertices before it (else -1), its rewritten corners and the
      * path vertices it put on the boundary; vertices, faces and origin above are then empty. */
    Index vertexCount = -1;
    std::vector<internal::meshtools::CornerEdit> edits;
    std::vector<int> newBoundary;
  };

  static double msSince(std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  bool fail(const std::string& message, std::string* error, bool invalidate = true)
  {
    if (invalidate) m_isValid = false;
    if (error) *error = "SeamCutSystem: " + message;
    return false;
  }

  /** Traces the boundary loop of the current cut mesh, checks that every copied vertex lies on
    * it, and lists the original vertices of the loop that are not removed yet. */
  bool adoptCut(std::vector<int>& newlyRemoved, std::string& problem)
  {
    const Index n = m_vertices.rows(), nc = m_cutVertices.rows();
    const std::vector<int> partner = internal::meshtools::sidePartners(m_cutFaces);  // (one sort for both)
    std::vector<std::vector<int>> loops = internal::meshtools::boundaryLoopsFromPartners(m_cutFaces, partner);
    m_topology = internal::meshtools::topologyFromPartners(m_cutFaces, partner, Index(loops.size()));
    m_boundaryLoop.clear();
    if (!loops.empty())
    {
      m_boundaryLoop = loops.front();
      std::rotate(m_boundaryLoop.begin(), std::min_element(m_boundaryLoop.begin(), m_boundaryLoop.end()),
                  m_boundaryLoop.end());
    }
    m_onLoop.assign(std::size_t(nc), 0);
    for (int v : m_boundaryLoop) m_onLoop[std::size_t(v)] = 1;
    m_onBoundary.assign(std::size_t(nc), 0);
    for (const auto& other : loops)
      for (int v : other) m_onBoundary[std::size_t(v)] = 1;
    // Every copy, and every vertex that has one, must be known (on the loop): only then is the
    // interior of the cut mesh a subset of the original vertices.
    std::vector<char> hasCopy(std::size_t(n), 0);
    for (Index i = n; i < nc; ++i) hasCopy[std::size_t(m_origin[i])] = 1;
    for (Index i = 0; i < nc; ++i)
      if ((i >= n || hasCopy[std::size_t(i)]) && !m_onLoop[std::size_t(i)])
      {
        problem = "cut vertex " + std::to_string(i) + " (original " + std::to_string(m_origin[i]) +
                  ") is split but not on the boundary loop: a seam must start on the boundary and must not "
                  "reach it again";
        return false;
      }
    newlyRemoved = newlyRemovedOfLoop();
    return true;
  }

  /** The original vertices of the boundary loop that are not removed from the factor yet, once
    * each, in the loop's order. */
  std::vector<int> newlyRemovedOfLoop()
  {
    std::vector<int> list;
    m_listed.resize(std::size_t(m_vertices.rows()), 0);  // (all zero between calls)
    for (int v : m_boundaryLoop)
    {
      const int o = m_origin[v];
      if (!m_removed[std::size_t(o)] && !m_listed[std::size_t(o)])
      {
        m_listed[std::size_t(o)] = 1;
        list.push_back(o);
      }
    }
    for (int o : list) m_listed[std::size_t(o)] = 0;
    return list;
  }

  /** Ends an addSeam() whose cut is applied to the cut mesh (\a cutOk, else \a problem says why
    * it is refused): the loop's new vertices leave the factor, and \a previous goes on the undo
    * history; on failure the cut mesh of \a previous comes back. */
  bool commitCut(Snapshot& previous, const std::vector<int>& newlyRemoved, bool cutOk,
                 std::chrono::steady_clock::time_point start, std::string* error, std::string problem = std::string())
  {
    m_lastCutMs = msSince(start);
    if (!cutOk || !removeFromFactor(newlyRemoved, problem))
    {
      restore(previous);
      return fail(problem, error, false);
    }
    previous.newlyRemoved = newlyRemoved;
    m_history.push_back(std::move(previous));
    if (error) error->clear();
    return true;
  }

  /** Removes \a dofs from the factor in place and marks them. */
  bool removeFromFactor(const std::vector<int>& dofs, std::string& problem)
  {
    m_lastUpdateMs = 0;
    if (dofs.empty()) return true;
    const auto start = std::chrono::steady_clock::now();
    m_solver.removeDofs(dofs);
    m_lastUpdateMs = msSince(start);
    if (m_solver.info() != Success)
    {
      problem = "removeDofs failed";
      return false;
    }
    for (int v : dofs) m_removed[std::size_t(v)] = 1;
    return true;
  }

  /** Puts the cut mesh of \a snapshot back (the factor is not touched). */
  void restore(const Snapshot& snapshot)
  {
    if (snapshot.vertexCount >= 0)
    {  // a cut in place: its corners back, its copies dropped
      for (std::size_t e = snapshot.edits.size(); e-- > 0;)
        m_cutFaces(snapshot.edits[e].face, snapshot.edits[e].corner) = snapshot.edits[e].vertex;
      m_cutVertices.conservativeResize(snapshot.vertexCount, m_cutVertices.cols());
      m_origin.conservativeResize(snapshot.vertexCount);
      for (int v : snapshot.newBoundary) m_onBoundary[std::size_t(v)] = 0;
      m_onBoundary.resize(std::size_t(snapshot.vertexCount));
    }
    else
    {
      m_cutVertices = snapshot.vertices;
      m_cutFaces = snapshot.faces;
      m_origin = snapshot.origin;
      m_onBoundary = snapshot.onBoundary;
    }
    m_boundaryLoop = snapshot.loop;
    m_onLoop.assign(std::size_t(m_cutVertices.rows()), 0);
    for (int v : m_boundaryLoop) m_onLoop[std::size_t(v)] = 1;
    m_topology = snapshot.topology;
  }

  MatrixXd m_vertices, m_cutVertices, m_cornerWeights;
  MatrixXi m_faces, m_cutFaces;
  VectorXi m_origin;
  SparseMatrix<double> m_matrix;
  Solver m_solver;
  double m_shift = 0;
  std::vector<int> m_boundaryLoop;
  std::vector<char> m_onLoop, m_removed;
  std::vector<char> m_onBoundary;  ///< by cut vertex: on any boundary loop
  std::vector<int> m_cutMark;      ///< scratch of the cuts in place (all -1 between them)
  std::vector<char> m_listed;      ///< scratch of newlyRemovedOfLoop() (all zero between calls)
  bool m_cutsInPlace = false;      ///< no vertex of the mesh joins several fans: seams may be cut in place
  MeshTopology m_topology;
  std::vector<Snapshot> m_history;
  double m_lastUpdateMs = 0, m_lastCutMs = 0;
  bool m_lastCutInPlace = false;
  bool m_isValid = false;
};

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_SEAMCUTSYSTEM_H
