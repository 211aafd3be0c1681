// ArapDeformation: as-rigid-as-possible surface modeling (Sorkine & Alexa 2007) with handle
// vertices and a region of interest, where every change of the constraint set is an in-place
// update of one Cholesky factor of the cotan Laplacian (Herholz & Sorkine-Hornung, "Sparse
// Cholesky Updates for Interactive Mesh Parameterization", §5.3 and Fig. 9): constrained vertices
// are Dirichlet dofs, added with removeDofs() and released with restoreDofs(), and each global
// step is one solveDirichlet() with the three coordinates as right-hand sides.

#ifndef EIGEN_MESHDEFORMATION_ARAPDEFORMATION_H
#define EIGEN_MESHDEFORMATION_ARAPDEFORMATION_H

namespace Eigen {

/** \ingroup MeshDeformation_Module
  * \brief What the last change of the constraint set of an ArapDeformation did.
  */
struct ArapConstraintEdit
{
  Index added = 0;       ///< vertices that became constrained (dofs removed from the factor)
  Index released = 0;    ///< vertices that became free (dofs restored in the factor)
  double seconds = 0.0;  ///< wall-clock time of the factor updates
};

/** \ingroup MeshDeformation_Module
  * \class ArapDeformation
  * \brief As-rigid-as-possible deformation of a triangle mesh whose constraints are edited in place.
  *
  * The deformed positions p' minimise the ARAP energy (Sorkine & Alexa 2007, eq. 3)
  * \f[ E(p') = \sum_i \sum_{j \in N(i)} w_{ij} \| (p'_i - p'_j) - R_i (p_i - p_j) \|^2 \f]
  * with cotan weights w_ij and one rotation R_i per vertex, subject to the constraints:
  * - handle vertices are held at given positions (setHandles(), addHandles(), removeHandles(),
  *   moveHandles());
  * - vertices outside the region of interest are held at their rest positions
  *   (setRegionOfInterest(); by default the whole mesh is free);
  * - vertices used by no non-degenerate triangle are held at rest (they have no energy).
  *
  * solve() alternates the local step (best rotations by SVD, reflections excluded) and the global
  * step (the cotan Laplacian system with the constrained vertices as Dirichlet values); the
  * energy never increases from one iteration to the next.
  *
  * compute() factors \f$ L + \epsilon I \f$ once (L the cotan Laplacian, \f$ \epsilon = 10^{-10}
  * \f$ times its mean diagonal so that the unconstrained matrix is positive definite). Every edit
  * of the constraint set then removes or restores only the dofs whose status changed, in place
  * (UpdatableSupernodalLLT::removeDofs() / restoreDofs(): no refactorization); moving handles
  * changes only the Dirichlet values. Each global step is refined against the exact L, so the
  * result is the one of L itself: \f$ \epsilon \f$ leaves no trace.
  *
  * \code
  * ArapDeformation<> arap(V, F);
  * arap.setRegionOfInterest(roi);          // the rest stays at rest
  * arap.setHandles(handles, targets);      // #handles x 3 positions
  * MatrixXd U = V;                         // initial guess, updated in place
  * arap.solve(U, 10);
  * arap.moveHandles(newTargets);           // no factor update at all
  * arap.solve(U, 10);
  * \endcode
  *
  * Bad input (indices out of range or repeated, wrong sizes, non-finite values, a connected
  * component without any constrained vertex) makes the call return false, leaves the object as it
  * was, and sets info() to InvalidInput and lastError() to a message saying what is wrong.
  *
  * \tparam Ordering_ the fill-reducing ordering of the factor (AMDOrdering<int>, MetisOrdering<int>, ...)
  *
  * \sa UpdatableSupernodalLLT, cotanLaplacian()
  */
template <typename Ordering_ = AMDOrdering<int> >
class ArapDeformation
{
public:
  /** The sparse matrix type of the Laplacian. */
  typedef SparseMatrix<double> SparseMatrixType;
  /** The solver holding the one factor that every constraint edit updates. */
  typedef UpdatableSupernodalLLT<SparseMatrixType, Lower, Ordering_> Solver;

  /** Default constructor: call compute() before anything else. */
  ArapDeformation() = default;

  /** Constructs and precomputes for the rest mesh (\a V, \a F); see compute(). */
  ArapDeformation(const MatrixXd& V, const MatrixXi& F) { compute(V, F); }

  /** Precomputation on the rest mesh: cotan Laplacian and its factorization. Clears the handles
    * and makes the whole mesh the region of interest.
    * \param V  #V x 3 rest positions (finite).
    * \param F  #F x 3 triangles, 0-based indices into the rows of V.
    * \returns true on success; false with info() and lastError() set otherwise. */
  bool compute(const MatrixXd& V, const MatrixXi& F);

  /** Replaces the handle set by \a handles, held at \a positions (#handles x 3, row k for
    * handle k), or at their rest positions when \a positions is empty. Only the vertices whose
    * constrained status changes are removed from or restored in the factor.
    * \returns false (and changes nothing) for out-of-range or repeated indices or wrong sizes. */
  bool setHandles(const std::vector<int>& handles, const MatrixXd& positions = MatrixXd());

  /** Adds \a handles (none may already be a handle) at \a positions (#handles x 3; empty: rest). */
  bool addHandles(const std::vector<int>& handles, const MatrixXd& positions = MatrixXd());

  /** Removes \a handles from the handle set (each must be a handle). */
  bool removeHandles(const std::vector<int>& handles);

  /** New positions for the current handles (#handles x 3, in the order of handles()). Only the
    * Dirichlet values change: the factor is not touched. */
  bool moveHandles(const MatrixXd& positions);

  /** Sets the region of interest: the vertices \a region may move, all others are held at their
    * rest positions (handles are held at their handle positions wherever they are). */
  bool setRegionOfInterest(const std::vector<int>& region);

  /** Makes the whole mesh the region of interest (the default). */
  bool clearRegionOfInterest();

  /** Runs \a iterations local/global iterations on \a U.
    * \param U           in: the initial guess (#V x 3; any other size starts from the rest mesh);
    *                    out: the deformed positions, constrained vertices exactly at their values.
    * \param iterations  number of local/global iterations (>= 0).
    * \param energies    if given, receives the ARAP energy after each iteration (non-increasing).
    * \returns false when some connected component of the mesh has no constrained vertex (the
    *          deformation is then not unique), before compute(), or for a negative count. */
  bool solve(MatrixXd& U, int iterations = 10, std::vector<double>* energies = nullptr);

  /** \returns the ARAP energy of \a U with the best rotations (the local step's). */
  double energy(const MatrixXd& U) const;

  /** \returns the handle vertices, in the order of handlePositions(). */
  const std::vector<int>& handles() const { return m_handles; }
  /** \returns the positions of the handles, #handles x 3. */
  const MatrixXd& handlePositions() const { return m_handlePositions; }
  /** \returns true when vertex \a v is currently a Dirichlet dof (handle, outside the region of
    * interest, or unused). */
  bool isConstrained(Index v) const { return m_constrained[std::size_t(v)] != 0; }
  /** \returns the currently constrained vertices in increasing order. */
  std::vector<int> constrainedVertices() const;
  /** \returns the Dirichlet values of all vertices (#V x 3): handle positions for handles, rest
    * positions for the other constrained vertices and, unused, for the free ones. */
  MatrixXd dirichletValues() const;
  /** \returns the rest positions. */
  const MatrixXd& restPositions() const { return m_rest; }
  /** \returns the cotan Laplacian of the rest mesh (positive semi-definite, both triangles). */
  const SparseMatrixType& laplacian() const { return m_laplacian; }
  /** \returns the solver, e.g. to read lastUpdate() of the factor. */
  const Solver& solver() const { return m_solver; }
  /** \returns what the last change of the constraint set did. */
  const ArapConstraintEdit& lastEdit() const { return m_lastEdit; }
  /** \returns Success, InvalidInput (bad input to the last call) or NumericalIssue. */
  ComputationInfo info() const { return m_info; }
  /** \returns the message of the last failed call, empty after a successful one. */
  const std::string& lastError() const { return m_error; }

protected:
  bool fail(ComputationInfo info, const std::string& message)
  {
    m_info = info;
    m_error = message;
    return false;
  }
  bool succeed()
  {
    m_info = Success;
    m_error.clear();
    return true;
  }
  bool checkComputed(const char* method)
  {
    if (m_isComputed) return true;
    return fail(InvalidInput, std::string("ArapDeformation::") + method + ": call compute() first");
  }
  /** Checks \a positions against \a count handles (#count x 3 finite, or empty for rest). */
  bool checkPositions(const MatrixXd& positions, std::size_t count, const char* method);
  /** \returns \a positions, or the rest positions of \a handles when it is empty (out-of-range
    * indices get zeros; replaceHandles() rejects them). */
  MatrixXd handleTargets(const std::vector<int>& handles, const MatrixXd& positions) const;
  /** Validates the new handle set and applies it with the constraint edit it implies. */
  bool replaceHandles(const std::vector<int>& handles, const MatrixXd& positions, const char* method);
  /** Brings the factor's removed dofs to the constrained set implied by handles and region. */
  bool updateConstraints(const char* method);
  /** Solves the global step for the rotations and refines it against the exact Laplacian. */
  void globalStep(const std::vector<Matrix3d>& rotations, const MatrixXd& dirichlet, MatrixXd& U) const;
  /** Fails when a connected component holds no constrained vertex. */
  bool checkWellPosed();

  MatrixXd m_rest;
  SparseMatrixType m_laplacian;
  Solver m_solver;
  std::vector<int> m_component;
  int m_componentCount = 0;
  std::vector<char> m_unused;       ///< vertices with no energy: always held at rest
  std::vector<char> m_inRegion;     ///< vertices inside the region of interest
  std::vector<char> m_constrained;  ///< the dofs removed from m_solver
  std::vector<int> m_handles;
  MatrixXd m_handlePositions;
  ArapConstraintEdit m_lastEdit;
  ComputationInfo m_info = InvalidInput;
  std::string m_error = "ArapDeformation: call compute() first";
  bool m_isComputed = false;
};

template <typename Ordering_>
bool ArapDeformation<Ordering_>::compute(const MatrixXd& V, const MatrixXi& F)
{
  m_isComputed = false;
  if (V.rows() == 0 || V.cols() != 3)
    return fail(InvalidInput, "ArapDeformation::compute: V must be #V x 3 with #V > 0, got " +
                                  std::to_string(V.rows()) + " x " + std::to_string(V.cols()));
  if (F.rows() > 0 && F.cols() != 3)
    return fail(InvalidInput, "ArapDeformation::compute: F must be #F x 3 (triangles), got " +
                                  std::to_string(F.cols()) + " columns");
  if (!V.allFinite()) return fail(InvalidInput, "ArapDeformation::compute: V holds NaN or Inf");
  for (Index f = 0; f < F.rows(); ++f)
    for (Index c = 0; c < 3; ++c)
      if (F(f, c) < 0 || F(f, c) >= V.rows())
        return fail(InvalidInput, "ArapDeformation::compute: face " + std::to_string(f) + " refers to vertex " +
                                      std::to_string(F(f, c)) + ", out of range [0, " + std::to_string(V.rows()) +
                                      ")");

  const Index n = V.rows();
  m_rest = V;
  m_laplacian = cotanLaplacian<double, int>(V, F);  // (V is finite: nothing refused; zero-area triangles left out)
  m_componentCount = internal::mesh_deformation::weightedComponents(m_laplacian, m_component);

  // L is singular (constants in its kernel): factor L + eps I so that the factor exists before
  // any constraint; globalStep() refines against L itself.
  const VectorXd diagonal = m_laplacian.diagonal();
  m_unused.assign(std::size_t(n), 0);
  double diagonalSum = 0.0;
  Index used = 0;
  for (Index v = 0; v < n; ++v)
  {
    if (diagonal[v] > 0.0)
    {
      diagonalSum += diagonal[v];
      ++used;
    }
    else
      m_unused[std::size_t(v)] = 1;
  }
  const double epsilon = 1e-10 * (used > 0 ? diagonalSum / double(used) : 1.0);
  SparseMatrixType identity(n, n);
  identity.setIdentity();
  const SparseMatrixType shifted = m_laplacian + epsilon * identity;

  m_solver.setUpdateCaching(true);
  m_solver.compute(shifted);
  if (m_solver.info() != Success)
    return fail(NumericalIssue, "ArapDeformation::compute: the factorization of the cotan Laplacian failed");

  m_inRegion.assign(std::size_t(n), 1);
  m_constrained.assign(std::size_t(n), 0);
  m_handles.clear();
  m_handlePositions.resize(0, 3);
  m_isComputed = true;
  return updateConstraints("compute");
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::checkPositions(const MatrixXd& positions, std::size_t count, const char* method)
{
  if (positions.size() == 0) return true;
  if (positions.rows() != Index(count) || positions.cols() != 3)
    return fail(InvalidInput, std::string("ArapDeformation::") + method + ": positions must be " +
                                  std::to_string(count) + " x 3 (one row per handle), got " +
                                  std::to_string(positions.rows()) + " x " + std::to_string(positions.cols()));
  if (!positions.allFinite())
    return fail(InvalidInput, std::string("ArapDeformation::") + method + ": positions hold NaN or Inf");
  return true;
}

template <typename Ordering_>
MatrixXd ArapDeformation<Ordering_>::handleTargets(const std::vector<int>& handles, const MatrixXd& positions) const
{
  if (positions.size() != 0) return positions;
  MatrixXd targets = MatrixXd::Zero(Index(handles.size()), 3);
  for (std::size_t k = 0; k < handles.size(); ++k)
    if (handles[k] >= 0 && handles[k] < m_rest.rows()) targets.row(Index(k)) = m_rest.row(handles[k]);
  return targets;
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::replaceHandles(const std::vector<int>& handles, const MatrixXd& positions,
                                                const char* method)
{
  std::string why;
  if (!internal::mesh_deformation::checkVertexList(handles, m_rest.rows(), "handle", why))
    return fail(InvalidInput, std::string("ArapDeformation::") + method + ": " + why);
  const std::vector<int> previousHandles = m_handles;
  const MatrixXd previousPositions = m_handlePositions;
  m_handles = handles;
  m_handlePositions = positions;
  if (!updateConstraints(method))
  {
    m_handles = previousHandles;
    m_handlePositions = previousPositions;
    return false;
  }
  return succeed();
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::setHandles(const std::vector<int>& handles, const MatrixXd& positions)
{
  if (!checkComputed("setHandles") || !checkPositions(positions, handles.size(), "setHandles")) return false;
  const MatrixXd targets = handleTargets(handles, positions);
  return replaceHandles(handles, targets, "setHandles");
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::addHandles(const std::vector<int>& handles, const MatrixXd& positions)
{
  if (!checkComputed("addHandles") || !checkPositions(positions, handles.size(), "addHandles")) return false;
  std::vector<int> combined = m_handles;
  combined.insert(combined.end(), handles.begin(), handles.end());
  MatrixXd targets(Index(combined.size()), 3);
  targets << m_handlePositions, handleTargets(handles, positions);
  return replaceHandles(combined, targets, "addHandles");
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::removeHandles(const std::vector<int>& handles)
{
  if (!checkComputed("removeHandles")) return false;
  std::string why;
  if (!internal::mesh_deformation::checkVertexList(handles, m_rest.rows(), "handle", why))
    return fail(InvalidInput, "ArapDeformation::removeHandles: " + why);
  std::vector<char> drop(std::size_t(m_rest.rows()), 0);
  for (int v : handles) drop[std::size_t(v)] = 1;
  std::vector<int> kept;
  std::vector<Index> keptRows;
  for (std::size_t k = 0; k < m_handles.size(); ++k)
  {
    if (drop[std::size_t(m_handles[k])])
      drop[std::size_t(m_handles[k])] = 0;  // found
    else
    {
      kept.push_back(m_handles[k]);
      keptRows.push_back(Index(k));
    }
  }
  for (std::size_t k = 0; k < handles.size(); ++k)
    if (drop[std::size_t(handles[k])])
      return fail(InvalidInput, "ArapDeformation::removeHandles: vertex " + std::to_string(handles[k]) +
                                    " (entry " + std::to_string(k) + ") is not a handle");
  MatrixXd targets(Index(kept.size()), 3);
  for (std::size_t k = 0; k < kept.size(); ++k) targets.row(Index(k)) = m_handlePositions.row(keptRows[k]);
  return replaceHandles(kept, targets, "removeHandles");
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::moveHandles(const MatrixXd& positions)
{
  if (!checkComputed("moveHandles")) return false;
  if (positions.size() == 0 && !m_handles.empty())
    return fail(InvalidInput, "ArapDeformation::moveHandles: positions must be " + std::to_string(m_handles.size()) +
                                  " x 3, got an empty matrix");
  if (!checkPositions(positions, m_handles.size(), "moveHandles")) return false;
  if (!m_handles.empty()) m_handlePositions = positions;
  return succeed();
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::setRegionOfInterest(const std::vector<int>& region)
{
  if (!checkComputed("setRegionOfInterest")) return false;
  std::string why;
  if (!internal::mesh_deformation::checkVertexList(region, m_rest.rows(), "region vertex", why))
    return fail(InvalidInput, "ArapDeformation::setRegionOfInterest: " + why);
  std::vector<char> previous(std::size_t(m_rest.rows()), 0);
  previous.swap(m_inRegion);
  for (int v : region) m_inRegion[std::size_t(v)] = 1;
  if (!updateConstraints("setRegionOfInterest"))
  {
    m_inRegion.swap(previous);
    return false;
  }
  return succeed();
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::clearRegionOfInterest()
{
  if (!checkComputed("clearRegionOfInterest")) return false;
  std::vector<char> previous(std::size_t(m_rest.rows()), 1);
  previous.swap(m_inRegion);
  if (!updateConstraints("clearRegionOfInterest"))
  {
    m_inRegion.swap(previous);
    return false;
  }
  return succeed();
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::updateConstraints(const char* method)
{
  std::vector<char> wanted(m_unused);
  for (std::size_t v = 0; v < wanted.size(); ++v)
    if (!m_inRegion[v]) wanted[v] = 1;
  for (int h : m_handles) wanted[std::size_t(h)] = 1;

  std::vector<int> added, released;
  internal::mesh_deformation::constraintChange(m_constrained, wanted, added, released);
  const auto start = std::chrono::steady_clock::now();
  // Two in-place updates: release the dofs that became free, then remove the newly constrained
  // ones. Both orders end in the factor of the same matrix.
  if (!released.empty() && m_solver.restoreDofs(released).info() != Success)
    return fail(m_solver.info(), std::string("ArapDeformation::") + method + ": restoring dofs in the factor failed");
  if (!added.empty() && m_solver.removeDofs(added).info() != Success)
  {
    m_solver.removeDofs(released);  // back to the previous constraint set
    return fail(m_solver.info(), std::string("ArapDeformation::") + method + ": removing dofs from the factor failed");
  }
  m_constrained.swap(wanted);
  m_lastEdit.added = Index(added.size());
  m_lastEdit.released = Index(released.size());
  m_lastEdit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return succeed();
}

template <typename Ordering_>
std::vector<int> ArapDeformation<Ordering_>::constrainedVertices() const
{
  std::vector<int> vertices;
  for (std::size_t v = 0; v < m_constrained.size(); ++v)
    if (m_constrained[v]) vertices.push_back(int(v));
  return vertices;
}

template <typename Ordering_>
MatrixXd ArapDeformation<Ordering_>::dirichletValues() const
{
  MatrixXd values = m_rest;
  for (std::size_t k = 0; k < m_handles.size(); ++k) values.row(m_handles[k]) = m_handlePositions.row(Index(k));
  return values;
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::checkWellPosed()
{
  std::vector<char> anchored(std::size_t(m_componentCount), 0);
  for (std::size_t v = 0; v < m_constrained.size(); ++v)
    if (m_constrained[v]) anchored[std::size_t(m_component[v])] = 1;
  for (std::size_t v = 0; v < m_component.size(); ++v)
    if (!anchored[std::size_t(m_component[v])])
      return fail(InvalidInput, "ArapDeformation::solve: the connected component of vertex " + std::to_string(v) +
                                    " has no constrained vertex, so its position is not unique; add a handle there "
                                    "or leave part of it out of the region of interest");
  return true;
}

template <typename Ordering_>
void ArapDeformation<Ordering_>::globalStep(const std::vector<Matrix3d>& rotations, const MatrixXd& dirichlet,
                                           MatrixXd& U) const
{
  MatrixXd rhs;
  internal::mesh_deformation::globalRightHandSide(m_rest, m_laplacian, rotations, rhs);
  U = m_solver.solveDirichlet(rhs, dirichlet);
  // Iterative refinement against L: the factor is that of L + eps I, so each correction shrinks
  // the error by about eps / lambda_min(L_II). The constrained rows carry no residual.
  const MatrixXd zero = MatrixXd::Zero(U.rows(), 3);
  double previous = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 20; ++step)
  {
    MatrixXd residual = rhs - m_laplacian * U;
    for (std::size_t v = 0; v < m_constrained.size(); ++v)
      if (m_constrained[v]) residual.row(Index(v)).setZero();
    const MatrixXd correction = m_solver.solveDirichlet(residual, zero);
    const double size = correction.norm();
    if (!(size < previous)) break;  // round-off level: the correction no longer shrinks
    U += correction;
    if (size <= 1e-14 * U.norm() || size > 0.5 * previous) break;  // converged, or stagnating at round-off
    previous = size;
  }
}

template <typename Ordering_>
bool ArapDeformation<Ordering_>::solve(MatrixXd& U, int iterations, std::vector<double>* energies)
{
  if (!checkComputed("solve")) return false;
  if (iterations < 0)
    return fail(InvalidInput, "ArapDeformation::solve: the iteration count " + std::to_string(iterations) +
                                  " is negative");
  if (!checkWellPosed()) return false;
  if (U.rows() != m_rest.rows() || U.cols() != 3) U = m_rest;
  if (energies) energies->clear();

  const MatrixXd dirichlet = dirichletValues();
  std::vector<Matrix3d> rotations;
  internal::mesh_deformation::fitRotations(m_rest, U, m_laplacian, rotations);
  for (int iteration = 0; iteration < iterations; ++iteration)
  {
    globalStep(rotations, dirichlet, U);
    internal::mesh_deformation::fitRotations(m_rest, U, m_laplacian, rotations);
    if (energies) energies->push_back(internal::mesh_deformation::arapEnergy(m_rest, U, m_laplacian, rotations));
  }
  return succeed();
}

template <typename Ordering_>
double ArapDeformation<Ordering_>::energy(const MatrixXd& U) const
{
  eigen_assert(m_isComputed && U.rows() == m_rest.rows() && U.cols() == 3 &&
               "ArapDeformation::energy: call compute() first and pass #V x 3 positions");
  std::vector<Matrix3d> rotations;
  internal::mesh_deformation::fitRotations(m_rest, U, m_laplacian, rotations);
  return internal::mesh_deformation::arapEnergy(m_rest, U, m_laplacian, rotations);
}

} // namespace Eigen

#endif // EIGEN_MESHDEFORMATION_ARAPDEFORMATION_H
