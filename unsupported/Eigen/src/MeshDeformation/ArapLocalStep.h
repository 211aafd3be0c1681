// ArapLocalStep: the per-vertex parts of as-rigid-as-possible deformation (Sorkine & Alexa 2007,
// "As-Rigid-As-Possible Surface Modeling", §2-3): the best rotation of every vertex cell (SVD of
// the weighted edge covariance, eq. 5-6, with the reflection fix), the ARAP energy (eq. 3) and the
// right-hand side of the global step (eq. 8-9). Cells are the one-ring "spokes" with cotan weights,
// read from the off-diagonal entries of the positive semi-definite cotan Laplacian. These are the
// parts of an ARAP iteration that the paper's factor updates leave as they are (§5.3, §6.4).

#ifndef EIGEN_MESHDEFORMATION_ARAPLOCALSTEP_H
#define EIGEN_MESHDEFORMATION_ARAPLOCALSTEP_H

namespace Eigen {
namespace internal {
namespace mesh_deformation {

/** Calls \a f(i, j, w_ij) for every spoke (i, j), j != i, of every vertex cell i, where
  * w_ij = -L(j, i) is the cotan weight of edge ij; each edge is visited once from each end. */
template <typename Function>
void forEachSpoke(const SparseMatrix<double>& laplacian, Function&& f)
{
  for (Index i = 0; i < laplacian.outerSize(); ++i)
    for (SparseMatrix<double>::InnerIterator it(laplacian, i); it; ++it)
      if (it.row() != i) f(i, it.row(), -it.value());
}

/** The local step: for every vertex i the rotation R_i maximising tr(R_i S_i) with the covariance
  * \f$ S_i = \sum_j w_{ij} (p_i - p_j)(p'_i - p'_j)^T \f$ (rest p = \a rest, deformed p' =
  * \a deformed), i.e. \f$ R_i = V_i U_i^T \f$ from the SVD \f$ S_i = U_i \Sigma_i V_i^T \f$. When
  * det(R_i) < 0 the column of U_i of the smallest singular value changes sign, so R_i is a
  * rotation (Sorkine & Alexa, §3). \a rotations is resized to #V. */
inline void fitRotations(const MatrixXd& rest, const MatrixXd& deformed, const SparseMatrix<double>& laplacian,
                         std::vector<Matrix3d>& rotations)
{
  const Index n = rest.rows();
  const Matrix3Xd p = rest.transpose(), q = deformed.transpose();  // contiguous positions
  std::vector<Matrix3d> covariance(std::size_t(n), Matrix3d::Zero());
  forEachSpoke(laplacian, [&](Index i, Index j, double w) {
    covariance[std::size_t(i)].noalias() += (w * (p.col(i) - p.col(j))) * (q.col(i) - q.col(j)).transpose();
  });
  rotations.resize(std::size_t(n));
  for (Index i = 0; i < n; ++i)
  {
    JacobiSVD<Matrix3d, NoQRPreconditioner> svd(covariance[std::size_t(i)], ComputeFullU | ComputeFullV);
    Matrix3d u = svd.matrixU();
    Matrix3d rotation = svd.matrixV() * u.transpose();
    if (rotation.determinant() < 0)
    {
      u.col(2) = -u.col(2);  // singular values are sorted decreasingly: column 2 is the smallest
      rotation = svd.matrixV() * u.transpose();
    }
    rotations[std::size_t(i)] = rotation;
  }
}

/** The ARAP energy \f$ \sum_i \sum_{j} w_{ij} \| (p'_i - p'_j) - R_i (p_i - p_j) \|^2 \f$ of
  * \a deformed for the given rotations (Sorkine & Alexa, eq. 3 with unit cell weights). */
inline double arapEnergy(const MatrixXd& rest, const MatrixXd& deformed, const SparseMatrix<double>& laplacian,
                         const std::vector<Matrix3d>& rotations)
{
  double energy = 0.0;
  forEachSpoke(laplacian, [&](Index i, Index j, double w) {
    const Vector3d restEdge = (rest.row(i) - rest.row(j)).transpose();
    const Vector3d deformedEdge = (deformed.row(i) - deformed.row(j)).transpose();
    energy += w * (deformedEdge - rotations[std::size_t(i)] * restEdge).squaredNorm();
  });
  return energy;
}

/** The right-hand side of the global step (Sorkine & Alexa, eq. 9):
  * \f$ b_i = \sum_j \tfrac{w_{ij}}{2} (R_i + R_j)(p_i - p_j) \f$, one row per vertex, so that
  * the minimiser over p' for fixed rotations solves L p' = b. */
inline void globalRightHandSide(const MatrixXd& rest, const SparseMatrix<double>& laplacian,
                                const std::vector<Matrix3d>& rotations, MatrixXd& rhs)
{
  rhs.setZero(rest.rows(), 3);
  forEachSpoke(laplacian, [&](Index i, Index j, double w) {
    const Vector3d restEdge = (rest.row(i) - rest.row(j)).transpose();
    rhs.row(i) += (0.5 * w * (rotations[std::size_t(i)] + rotations[std::size_t(j)]) * restEdge).transpose();
  });
}

} // namespace mesh_deformation
} // namespace internal
} // namespace Eigen

#endif // EIGEN_MESHDEFORMATION_ARAPLOCALSTEP_H
