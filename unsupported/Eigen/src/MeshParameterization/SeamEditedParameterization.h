// SeamEditedParameterization: the edit loop shared by the seam-editable parameterizations
// (TutteEmbedding, BoundaryFirstFlattening) of Herholz & Sorkine-Hornung §5.1: compute once
// (factor the Laplacian, remove the boundary), then addSeam()/undo() update the factor in place
// through a SeamCutSystem and lay the cut mesh out again. A derived class only says how to lay it out.

#ifndef EIGEN_MESHPARAMETERIZATION_SEAMEDITEDPARAMETERIZATION_H
#define EIGEN_MESHPARAMETERIZATION_SEAMEDITEDPARAMETERIZATION_H

namespace Eigen {

namespace internal {
namespace meshparameterization {

/** \internal CRTP base: Derived provides
  * - `bool cornerWeightsFor(const MatrixXd& V, const MatrixXi& F, MatrixXd& weights, std::string& problem)`
  *   (the Laplacian's per-corner weights, see LaplacianWeights; false with a message naming the
  *   first face where they are undefined), and
  * - `bool layout(std::string& problem)`, which fills m_uv from m_system (called after every
  *   change of the cut mesh). */
template <typename Derived, typename Ordering_>
class SeamEditedParameterization
{
public:
  /** The system type: factor, cut mesh, Dirichlet solves. */
  typedef SeamCutSystem<Ordering_> System;

  /** Factors the Laplacian of (\a V, \a F), removes its boundary loop from the factor, cuts
    * along \a initialSeam if given (needed for a closed mesh: a simple path cuts a sphere to a
    * disk; this cut cannot be undone) and computes the parameterization.
    * \returns false with a message in \a error (and info() != Success) on failure, among others
    * on a vertex with a non-finite coordinate (named in the message) and, where the weights are
    * cotangents, on a triangle of zero area up to rounding (named too; thin ones are kept). */
  bool compute(const MatrixXd& V, const MatrixXi& F, const std::vector<int>& initialSeam = {},
               std::string* error = nullptr)
  {
    m_info = InvalidInput;
    m_uv.resize(0, 2);
    std::string problem;
    if (V.cols() != 3 || F.cols() != 3 || F.rows() == 0 || F.minCoeff() < 0 || F.maxCoeff() >= V.rows())
      return fail("V must be #V x 3 and F #F x 3 with indices into V", error);
    MatrixXd weights;
    if (!derived().cornerWeightsFor(V, F, weights, problem)) return fail(problem, error);
    if (!m_system.compute(V, F, weights, m_shift, &problem)) return fail(problem, error);
    if (!initialSeam.empty() && !m_system.addSeam(initialSeam, &problem)) return fail(problem, error);
    m_system.clearHistory();
    if (m_system.boundaryLoop().size() < 3)
      return fail("the mesh has no boundary: give an initial seam that cuts it open", error);
    return relayout(error);
  }

  /** Cuts the mesh along \a path (vertex indices of the current cut mesh, cutVertices(); it must
    * start on the boundary and go inside without reaching the boundary again), updates the factor
    * in place (removeDofs of the seam) and lays the cut mesh out again.
    * \returns false with a message (and nothing changed) on a bad path, and on a path that cuts
    * nothing open (along boundary edges only, or a single edge between inner vertices): such a call
    * records no undo step, so the next undo() takes back the last seam that did cut. */
  bool addSeam(const std::vector<int>& path, std::string* error = nullptr)
  {
    std::string problem;
    if (!m_system.addSeam(path, &problem)) return fail(problem, error, false);
    if (relayout(error)) return true;
    m_system.undo();
    relayout(nullptr);
    return false;
  }

  /** Takes the last seam back (restoreDofs in place) and lays the mesh out again.
    * \returns false when there is nothing to undo. */
  bool undo(std::string* error = nullptr)
  {
    std::string problem;
    if (!m_system.undo(&problem)) return fail(problem, error, false);
    return relayout(error);
  }

  /** Sets the diagonal shift \f$ \varepsilon \f$ of the factored Laplacian \f$ A + \varepsilon I \f$
    * (default 1e-8; the Laplacian of a closed or free mesh is singular). Takes effect at compute(). */
  Derived& setShift(double shift)
  {
    m_shift = shift;
    return derived();
  }

  /** \returns the uv coordinates, one row per vertex of the cut mesh (cutVertices()). */
  const MatrixXd& uv() const { return m_uv; }
  /** \returns the vertex positions of the cut mesh that uv() parameterizes. */
  const MatrixXd& cutVertices() const { return m_system.cutVertices(); }
  /** \returns the triangles of the cut mesh (same order as the input triangles). */
  const MatrixXi& cutFaces() const { return m_system.cutFaces(); }
  /** \returns for each cut vertex the input vertex it copies. */
  const VectorXi& origin() const { return m_system.origin(); }
  /** \returns the system: factor, boundary loop, timings of the last update. */
  const System& system() const { return m_system; }
  /** \returns Success after a successful compute()/addSeam()/undo(), InvalidInput or
    * NumericalIssue after a failed compute(). */
  ComputationInfo info() const { return m_info; }
  /** \returns the milliseconds of the last layout (the solves after an edit). */
  double lastLayoutMs() const { return m_lastLayoutMs; }

protected:
  Derived& derived() { return *static_cast<Derived*>(this); }

  bool fail(const std::string& message, std::string* error, bool invalidate = true)
  {
    if (invalidate) m_info = InvalidInput;
    if (error) *error = message;
    return false;
  }

  /** Checks that the cut mesh can be laid out in the plane by \a who: one piece of genus 0
    * with one boundary loop, or with several when \a holesAllowed (the others stay free).
    * Otherwise \a problem says what the cut mesh is and which cuts would make it a disk. */
  bool cutMeshIsDiskLike(const char* who, bool holesAllowed, std::string& problem) const
  {
    const MeshTopology& t = m_system.topology();
    const std::string chi = "Euler characteristic " + std::to_string(t.eulerCharacteristic) + ", " +
                            std::to_string(t.boundaryLoops) + " boundary loop(s)";
    if (t.components != 1)
      problem = std::string(who) + " needs a mesh in one piece; the cut mesh has " + std::to_string(t.components) +
                " (lay out each piece on its own)";
    else if (t.genus < 0)
      problem = std::string(who) + " needs a disk; the cut mesh is not an orientable manifold surface (" + chi + ")";
    else if (t.genus > 0)
      problem = std::string(who) + " needs a disk; the cut mesh has genus " + std::to_string(t.genus) + " (" + chi +
                "): cut it along " + std::to_string(2 * t.genus) +
                " more seams, loops around and through its handles that start and end on the boundary";
    else if (!holesAllowed && t.boundaryLoops != 1)
      problem = std::string(who) + " needs a disk (one boundary loop); the cut mesh has " +
                std::to_string(t.boundaryLoops) + " (join the holes by seams)";
    else
      return true;
    return false;
  }

  bool relayout(std::string* error)
  {
    std::string problem;
    const auto start = std::chrono::steady_clock::now();
    const bool ok = derived().layout(problem);
    m_lastLayoutMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!ok) return fail(problem, error);
    m_info = Success;
    if (error) error->clear();
    return true;
  }

  System m_system;
  MatrixXd m_uv;
  double m_shift = 1e-8;
  double m_lastLayoutMs = 0;
  ComputationInfo m_info = InvalidInput;
};

} // namespace meshparameterization
} // namespace internal

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_SEAMEDITEDPARAMETERIZATION_H
