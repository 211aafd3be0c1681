// BoundaryFirstFlattening: conformal flattening of a disk-like mesh with prescribed (here zero)
// boundary scale factors, i.e. minimal area distortion (Sawhney & Crane 2017, "Boundary First
// Flattening", §4-5: Dirichlet-to-Neumann map, boundary curve from target curvature and lengths,
// length-preserving closure, extension to the interior), with interactive cuts as in Herholz &
// Sorkine-Hornung §5.1: a new cut makes new boundary vertices, removed from the interior factor in
// place, and both Dirichlet solves of BFF reuse the updated factor.

#ifndef EIGEN_MESHPARAMETERIZATION_BOUNDARYFIRSTFLATTENING_H
#define EIGEN_MESHPARAMETERIZATION_BOUNDARYFIRSTFLATTENING_H

namespace Eigen {

/** \ingroup MeshParameterization_Module
  * \class BoundaryFirstFlattening
  * \brief Boundary First Flattening with zero boundary scale factors, editable by seam cuts.
  *
  * With A the cotangent Laplacian (positive semi-definite sign) of the cut mesh, I its interior
  * and B its boundary loop (counter-clockwise), \f$\Omega_i = 2\pi - \sum\theta\f$ the angle defect of
  * interior vertices and \f$k_i = \pi - \sum\theta\f$ the turning angle of boundary vertices:
  *
  * 1. Scale factors (Yamabe / Poisson problem): \f$ A_{II} u_I = -\Omega_I \f$ (solved with the factor of
  *    \f$ A_{II} + \varepsilon I \f$ and one step of refinement),
  *    \f$ u_B = 0 \f$ (the flattened metric \f$ e^{2u} g \f$ has no interior curvature).
  * 2. Dirichlet-to-Neumann: \f$ h = (A u)_B \f$, the normal derivative of u along the boundary;
  *    target turning angles \f$ \tilde k = k + h \f$ (they sum to \f$ 2\pi \f$ by Gauss-Bonnet).
  * 3. Target lengths \f$ \tilde l_{ij} = e^{(u_i + u_j)/2} l_{ij} = l_{ij} \f$; tangents
  *    \f$ T_i = (\cos\varphi_i, \sin\varphi_i) \f$ with \f$ \varphi_i = \sum_{j \le i} \tilde k_j \f$.
  * 4. Closure: the lengths \f$ l^* \f$ nearest to \f$ \tilde l \f$ in the norm
  *    \f$ \sum (l^*_i - \tilde l_i)^2 / \tilde l_i \f$ with \f$ \sum l^*_i T_i = 0 \f$:
  *    \f$ l^*_i = \tilde l_i - \tilde l_i T_i^T M^{-1} r \f$, \f$ M = \sum \tilde l_i T_i T_i^T \f$,
  *    \f$ r = \sum \tilde l_i T_i \f$ (the paper's length-preserving correction); the boundary
  *    curve is \f$ \gamma_{i+1} = \gamma_i + l^*_i T_i \f$.
  * 5. Interior: the harmonic extension of \f$ \gamma \f$ (both coordinates, Dirichlet, cotan weights).
  *
  * Steps 1 and 5 are Dirichlet solves with the factor of the whole Laplacian from which the
  * boundary (and every seam) was removed in place (SeamCutSystem).
  *
  * The cut mesh must be a topological disk (MeshTopology::isDisk(): one piece, genus 0, one
  * boundary loop); otherwise compute()/addSeam() fail with a message naming its genus, pieces or
  * holes. cutToDisk() gives the cuts that make any orientable mesh one. compute() also refuses a
  * triangle of zero area (up to rounding) or a vertex with a non-finite coordinate, naming it:
  * its angles and cotangent weights are undefined.
  *
  * \tparam Ordering_  fill-reducing ordering of the factor (AMDOrdering<int>, MetisOrdering<int>, ...).
  * \sa TutteEmbedding, SeamCutSystem
  */
template <typename Ordering_ = AMDOrdering<int>>
class BoundaryFirstFlattening
    : public internal::meshparameterization::SeamEditedParameterization<BoundaryFirstFlattening<Ordering_>, Ordering_>
{
  typedef internal::meshparameterization::SeamEditedParameterization<BoundaryFirstFlattening<Ordering_>, Ordering_>
      Base;
  friend Base;

public:
  /** \returns the conformal scale factors u of the last layout, one per cut vertex (0 on the boundary). */
  const VectorXd& scaleFactors() const { return m_scaleFactors; }
  /** \returns the target turning angles \f$ \tilde k \f$ along boundaryLoop() (sum \f$ 2\pi \f$). */
  const VectorXd& targetCurvatures() const { return m_targetCurvatures; }
  /** \returns the 3-D lengths of the boundary edges (loop[i], loop[i+1]) of boundaryLoop(). */
  const VectorXd& boundaryLengths() const { return m_lengths; }
  /** \returns the lengths of the same edges in the flattening, after the closure correction. */
  const VectorXd& flatBoundaryLengths() const { return m_flatLengths; }
  /** \returns the boundary loop of the cut mesh (counter-clockwise, from its smallest index). */
  const std::vector<int>& boundaryLoop() const { return this->m_system.boundaryLoop(); }

protected:
  bool cornerWeightsFor(const MatrixXd& V, const MatrixXi& F, MatrixXd& weights, std::string& problem)
  {
    if (!internal::meshparameterization::cornerEdgeWeights(V, F, LaplacianWeights::Cotangent, weights, problem))
    {
      problem = "BoundaryFirstFlattening: " + problem;
      return false;
    }
    m_angles = internal::meshparameterization::cornerAngles(V, F);
    return true;
  }

  bool layout(std::string& problem)
  {
    const auto& system = this->m_system;
    if (!this->cutMeshIsDiskLike("BoundaryFirstFlattening", false, problem)) return false;
    const MatrixXi& F = system.cutFaces();
    const MatrixXd& V = system.cutVertices();
    const std::vector<int>& loop = system.boundaryLoop();
    const Index nc = V.rows();
    const std::size_t m = loop.size();

    // Angle sums: interior angle defects and boundary turning angles.
    VectorXd angleSum = VectorXd::Zero(nc);
    for (Index f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c) angleSum[F(f, c)] += m_angles(f, c);

    // 1. Scale factors: A_II u_I = -Omega_I with u_B = 0. The factor holds A_II + eps I; one step
    //    of refinement removes the shift's effect, which would otherwise spoil Gauss-Bonnet in
    //    step 2 by eps * sum(u) (3e-4 rad on camelhead).
    MatrixXd rhs(nc, 1);
    for (Index i = 0; i < nc; ++i) rhs(i, 0) = -(2.0 * EIGEN_PI - angleSum[i]);
    const MatrixXd u = system.solve(rhs, MatrixXd::Zero(nc, 1), 1);
    m_scaleFactors = u.col(0);

    // 2. Dirichlet-to-Neumann: h = (A u)_B; target turning angles k + h.
    const MatrixXd Au = system.applyLaplacian(u);
    m_targetCurvatures.resize(Index(m));
    for (std::size_t i = 0; i < m; ++i) m_targetCurvatures[Index(i)] = (EIGEN_PI - angleSum[loop[i]]) + Au(loop[i], 0);

    // 3. Target lengths and tangents of the boundary curve.
    m_lengths.setZero(Index(m));
    VectorXd target = VectorXd::Zero(Index(m));
    Matrix<double, Dynamic, 2> tangents(Index(m), 2);
    double direction = 0;
    for (std::size_t i = 0; i < m; ++i)
    {
      const int a = loop[i], b = loop[(i + 1) % m];
      m_lengths[Index(i)] = (V.row(b) - V.row(a)).norm();
      target[Index(i)] = std::exp(0.5 * (m_scaleFactors[a] + m_scaleFactors[b])) * m_lengths[Index(i)];
      direction += m_targetCurvatures[Index(i)];
      tangents.row(Index(i)) << std::cos(direction), std::sin(direction);
    }

    // 4. Closure: the nearest lengths (weighted by 1/target) that close the curve.
    const Matrix2d M = tangents.transpose() * target.asDiagonal() * tangents;
    const Vector2d gap = tangents.transpose() * target;
    const FullPivLU<Matrix2d> lu(M);
    if (!lu.isInvertible())
    {
      problem = "BoundaryFirstFlattening: the boundary tangents span no plane (degenerate boundary)";
      return false;
    }
    const Vector2d multiplier = lu.solve(gap);
    m_flatLengths = target - target.cwiseProduct(tangents * multiplier);
    if (!(m_flatLengths.minCoeff() > 0))
    {
      problem = "BoundaryFirstFlattening: the closure correction made a boundary length non-positive";
      return false;
    }
    MatrixXd gamma = MatrixXd::Zero(nc, 2);
    Vector2d point = Vector2d::Zero();
    for (std::size_t i = 0; i < m; ++i)
    {
      gamma.row(loop[i]) = point.transpose();
      point += m_flatLengths[Index(i)] * tangents.row(Index(i)).transpose();
    }

    // 5. Harmonic extension of the boundary curve.
    this->m_uv = system.solve(MatrixXd::Zero(nc, 2), gamma);
    if (!this->m_uv.allFinite())
    {
      problem = "BoundaryFirstFlattening: the solve produced non-finite values";
      return false;
    }
    return true;
  }

  MatrixXd m_angles;
  VectorXd m_scaleFactors, m_targetCurvatures, m_lengths, m_flatLengths;
};

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_BOUNDARYFIRSTFLATTENING_H
