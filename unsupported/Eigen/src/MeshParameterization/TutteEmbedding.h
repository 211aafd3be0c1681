// TutteEmbedding: Tutte (uniform weights) and harmonic (cotangent weights) parameterization of a
// disk-like mesh with its boundary loop fixed on the unit circle (Tutte 1963; Floater 1997;
// Herholz & Sorkine-Hornung §4.1: "if the boundary conditions form a convex polygon and A is the
// combinatorial Laplacian, we obtain a Tutte embedding"), with interactive seams (§5.1): a seam
// from the boundary joins the boundary, its vertices are removed from the factor in place, the new
// boundary goes onto the circle and the interior is solved again without refactoring.

#ifndef EIGEN_MESHPARAMETERIZATION_TUTTEEMBEDDING_H
#define EIGEN_MESHPARAMETERIZATION_TUTTEEMBEDDING_H

namespace Eigen {

/** \ingroup MeshParameterization_Module
  * \brief How boundary vertices are spaced along the unit circle. */
enum class BoundarySpacing
{
  Uniform,  ///< equal angles between consecutive boundary vertices
  ArcLength ///< angles proportional to the 3-D lengths of the boundary edges
};

/** \ingroup MeshParameterization_Module
  * \class TutteEmbedding
  * \brief Tutte / harmonic map of a mesh to the unit disk, editable by seam cuts.
  *
  * The boundary loop of the (cut) mesh, counter-clockwise, goes onto the unit circle starting at
  * angle 0 at its smallest vertex index; every other vertex solves the Laplace equation
  * \f$ ((A + \varepsilon I)\,uv)_i = 0 \f$ with A the uniform (Tutte) or cotangent (harmonic)
  * Laplacian of the cut mesh. With uniform weights the map of a disk is a bijection onto the
  * (convex) polygon of the boundary (Tutte's theorem); cotangent weights can flip triangles where
  * they are negative. Other boundary loops (holes) stay free. The cut mesh must be one piece of
  * genus 0 (MeshTopology); a mesh with handles fails with a message naming its genus (cut it with
  * cutToDisk() first). Cotangent weights also need every triangle to have a nonzero area (beyond
  * rounding): compute() refuses a mesh with a zero-area triangle and names it; uniform weights take
  * such a mesh. A non-finite vertex coordinate is refused with either weights.
  *
  * \code
  * Eigen::TutteEmbedding<> tutte;
  * tutte.setWeights(Eigen::LaplacianWeights::Uniform).compute(V, F);   // factor + solve
  * tutte.addSeam(Eigen::shortestEdgePath(V, F, boundaryVertex, interiorVertex));  // removeDofs + solve
  * Eigen::renderUVCheckerboard(tutte.uv(), tutte.cutFaces(), "tutte.png");
  * tutte.undo();                                                        // restoreDofs + solve
  * \endcode
  *
  * \tparam Ordering_  fill-reducing ordering of the factor (AMDOrdering<int>, MetisOrdering<int>, ...).
  * \sa BoundaryFirstFlattening, SeamCutSystem
  */
template <typename Ordering_ = AMDOrdering<int>>
class TutteEmbedding
    : public internal::meshparameterization::SeamEditedParameterization<TutteEmbedding<Ordering_>, Ordering_>
{
  typedef internal::meshparameterization::SeamEditedParameterization<TutteEmbedding<Ordering_>, Ordering_> Base;
  friend Base;

public:
  /** Chooses the Laplacian weights (default Uniform: a Tutte embedding). Takes effect at compute(). */
  TutteEmbedding& setWeights(LaplacianWeights weights)
  {
    m_weights = weights;
    return *this;
  }
  /** \returns the Laplacian weights. */
  LaplacianWeights weights() const { return m_weights; }

  /** Chooses how the boundary is spaced on the circle (default ArcLength); applies at the next
    * compute(), addSeam() or undo(). */
  TutteEmbedding& setBoundarySpacing(BoundarySpacing spacing)
  {
    m_spacing = spacing;
    return *this;
  }
  /** \returns the boundary spacing. */
  BoundarySpacing boundarySpacing() const { return m_spacing; }

  /** \returns the positions on the unit circle of the boundary loop of the cut mesh, one row per
    * cut vertex (rows of vertices off the loop are 0). */
  MatrixXd circleBoundary() const
  {
    const std::vector<int>& loop = this->m_system.boundaryLoop();
    const MatrixXd& V = this->m_system.cutVertices();
    MatrixXd g = MatrixXd::Zero(V.rows(), 2);
    const std::size_t m = loop.size();
    std::vector<double> position(m + 1, 0.0); // cumulative spacing, position[m] = total
    for (std::size_t i = 0; i < m; ++i)
      position[i + 1] = position[i] + (m_spacing == BoundarySpacing::Uniform
                                           ? 1.0
                                           : (V.row(loop[(i + 1) % m]) - V.row(loop[i])).norm());
    const double total = position[m] > 0 ? position[m] : 1.0;
    for (std::size_t i = 0; i < m; ++i)
    {
      const double angle = 2.0 * EIGEN_PI * position[i] / total;
      g.row(loop[i]) << std::cos(angle), std::sin(angle);
    }
    return g;
  }

protected:
  bool cornerWeightsFor(const MatrixXd& V, const MatrixXi& F, MatrixXd& weights, std::string& problem) const
  {
    if (internal::meshparameterization::cornerEdgeWeights(V, F, m_weights, weights, problem)) return true;
    problem = "TutteEmbedding with cotangent weights: " + problem;
    return false;
  }

  bool layout(std::string& problem)
  {
    if (!this->cutMeshIsDiskLike("TutteEmbedding", true, problem)) return false;
    const MatrixXd g = circleBoundary();
    this->m_uv = this->m_system.solve(MatrixXd::Zero(g.rows(), 2), g);
    return true;
  }

  LaplacianWeights m_weights = LaplacianWeights::Uniform;
  BoundarySpacing m_spacing = BoundarySpacing::ArcLength;
};

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_TUTTEEMBEDDING_H
