// FaceWeights: per-triangle corner quantities shared by the parameterizations: the corner angles
// (angle sums give the discrete Gaussian and geodesic curvatures used by Boundary First
// Flattening, Sawhney & Crane 2017, §3) and the Laplacian edge weights stored per corner
// (cotangent: the weight of the edge opposite a corner is half the cotangent of its angle; uniform:
// 1/2 per triangle, i.e. 1 per interior edge). Storing weights per face corner lets the same numbers
// assemble the Laplacian of the uncut mesh and of any mesh cut from it (faces keep their order):
// the matrix that the seam edits of the paper's §5.1 update in place (SeamCutSystem.h).

#ifndef EIGEN_MESHPARAMETERIZATION_FACEWEIGHTS_H
#define EIGEN_MESHPARAMETERIZATION_FACEWEIGHTS_H

namespace Eigen {

/** \ingroup MeshParameterization_Module
  * \brief Edge weights of the Laplacian a parameterization solves with. */
enum class LaplacianWeights
{
  Uniform,  ///< 1/2 per triangle and edge (1 per interior edge): Tutte's barycentric embedding
  Cotangent ///< half the cotangent of the opposite angle per triangle: the harmonic (cotan) Laplacian
};

namespace internal {
namespace meshparameterization {

/** \internal \returns the #F x 3 corner angles: entry (f, c) is the angle of triangle f at corner
  * c, in [0, pi] (atan2 of the cross and dot products; 0 for degenerate corners). */
inline MatrixXd cornerAngles(const MatrixXd& V, const MatrixXi& F)
{
  MatrixXd angles(F.rows(), 3);
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
    {
      const Vector3d p = V.row(F(f, c)).transpose();
      const Vector3d a = V.row(F(f, (c + 1) % 3)).transpose() - p, b = V.row(F(f, (c + 2) % 3)).transpose() - p;
      angles(f, c) = std::atan2(a.cross(b).norm(), a.dot(b));
    }
  return angles;
}

/** \internal Sets \a w to the #F x 3 weights of the edge opposite each corner, as one triangle's
  * contribution: cotangent (half the cotangent of the corner's angle, exactly as cotanLaplacian()
  * computes it) or uniform (1/2). \returns false, with \a problem naming the first face whose
  * cotangents are undefined (zero area up to rounding, or a non-finite corner: see
  * cotanLaplacian(), which skips the former), for cotangent weights; uniform weights read no geometry and always succeed. */
inline bool cornerEdgeWeights(const MatrixXd& V, const MatrixXi& F, LaplacianWeights weights, MatrixXd& w,
                              std::string& problem)
{
  w = MatrixXd::Constant(F.rows(), 3, 0.5);
  if (weights == LaplacianWeights::Uniform) return true;
  for (Index f = 0; f < F.rows(); ++f)
  {
    const Vector3d p[3] = {V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose()};
    double doubleArea = 0;
    if (internal::meshtools::cotanFace(p, doubleArea) != internal::meshtools::CotanFace::Defined)
    {
      problem = internal::meshtools::cotanFaceProblem(V, F, f);
      return false;
    }
    for (int c = 0; c < 3; ++c) w(f, c) = 0.5 * (p[(c + 1) % 3] - p[c]).dot(p[(c + 2) % 3] - p[c]) / doubleArea;
  }
  return true;
}

/** \internal Calls \a visit(f, a, b, w) for every triangle f and each of its edges (a, b), with w
  * the weight the triangle gives the edge (the weight of the opposite corner). */
template <typename Visit>
void forEachWeightedEdge(const MatrixXi& F, const MatrixXd& cornerWeights, Visit&& visit)
{
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) visit(f, F(f, (c + 1) % 3), F(f, (c + 2) % 3), cornerWeights(f, c));
}

/** \internal \returns the n x n Laplacian (positive semi-definite sign) assembled from per-corner
  * edge weights, plus \a shift on the diagonal. */
inline SparseMatrix<double> assembleLaplacian(const MatrixXi& F, const MatrixXd& cornerWeights, Index n, double shift)
{
  std::vector<Triplet<double>> triplets;
  triplets.reserve(std::size_t(6 * F.rows() + n));
  VectorXd diagonal = VectorXd::Constant(n, shift);
  forEachWeightedEdge(F, cornerWeights, [&](Index, int a, int b, double w) {
    triplets.emplace_back(a, b, -w);
    triplets.emplace_back(b, a, -w);
    diagonal[a] += w;
    diagonal[b] += w;
  });
  for (Index i = 0; i < n; ++i) triplets.emplace_back(int(i), int(i), diagonal[i]);
  SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  A.makeCompressed();
  return A;
}

} // namespace meshparameterization
} // namespace internal

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_FACEWEIGHTS_H
