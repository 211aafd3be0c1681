// MassMatrix: the lumped (diagonal) mass matrix of a triangle mesh, each vertex weighted by its
// mixed Voronoi area (Meyer, Desbrun, Schroeder, Barr, "Discrete Differential-Geometry Operators
// for Triangulated 2-Manifolds", 2002): Voronoi areas in non-obtuse triangles, barycentric-like
// halves and quarters in obtuse ones. It is the M of the paper's Laplacian systems (§5).

#ifndef EIGEN_MESHTOOLS_MASSMATRIX_H
#define EIGEN_MESHTOOLS_MASSMATRIX_H

namespace Eigen {

/** \ingroup MeshTools_Module
  * \brief Lumped mass matrix of a triangle mesh: the diagonal matrix of mixed Voronoi vertex areas.
  *
  * Each triangle of area A splits its area among its corners. If no angle is obtuse, corner i
  * gets its Voronoi share \f$\tfrac18(|e_{ij}|^2\cot\theta_k + |e_{ik}|^2\cot\theta_j)\f$
  * (θ the angles at the other corners); if the angle at corner i is obtuse it gets A/2 and the
  * other two A/4 (Meyer et al. 2002). The shares of a triangle add up to A, so the diagonal sums
  * to the total area of the mesh, and every share is positive for a triangle of positive area:
  * the diagonal is positive for every vertex used by a non-degenerate triangle. Triangles of zero
  * area contribute nothing; vertices used by no triangle get a zero diagonal entry. A triangle
  * with a non-finite corner coordinate has no area: such a mesh is refused (an empty 0 x 0 result,
  * and \a error names the face and the vertex), as by cotanLaplacian().
  *
  * \param V      #V x 3 (or #V x 2, planar) vertex positions.
  * \param F      #F x 3 triangles, 0-based indices into the rows of V (checked by eigen_assert).
  * \param error  if not null, receives a message naming the first triangle with a non-finite
  *               corner when the mesh is refused, and is cleared otherwise.
  * \returns the #V x #V diagonal mass matrix (compressed; every diagonal entry stored); 0 x 0
  *          for a refused mesh.
  *
  * \sa cotanLaplacian()
  */
inline SparseMatrix<double> massMatrix(const MatrixXd& V, const MatrixXi& F, std::string* error = nullptr)
{
  eigen_assert((V.cols() == 2 || V.cols() == 3) && "massMatrix: V must have 2 or 3 columns");
  eigen_assert(internal::meshtools::checkTriangles(F, V.rows(), "massMatrix", nullptr) &&
               "massMatrix: F must be #F x 3 with indices into V");
  const Index n = V.rows();
  auto position = [&](int i) {
    Vector3d p = Vector3d::Zero();
    p.head(V.cols()) = V.row(i).transpose();
    return p;
  };

  VectorXd mass = VectorXd::Zero(n);
  for (Index f = 0; f < F.rows(); ++f)
  {
    const int corner[3] = {F(f, 0), F(f, 1), F(f, 2)};
    const Vector3d p[3] = {position(corner[0]), position(corner[1]), position(corner[2])};
    if (!p[0].allFinite() || !p[1].allFinite() || !p[2].allFinite())
    {
      if (error) *error = "massMatrix: " + internal::meshtools::cotanFaceProblem(V, F, f);
      return SparseMatrix<double>();
    }
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (!(area > 0.0)) continue;
    // Squared length of the side opposite each corner, and the corner's cotangent:
    // cot θ_i = (e_ij . e_ik) / (2 A).
    double squaredOpposite[3], cotangent[3];
    int obtuse = -1;
    for (int i = 0; i < 3; ++i)
    {
      const Vector3d toNext = p[(i + 1) % 3] - p[i], toPrevious = p[(i + 2) % 3] - p[i];
      const double dot = toNext.dot(toPrevious);
      if (dot < 0.0) obtuse = i;
      cotangent[i] = dot / (2.0 * area);
      squaredOpposite[i] = (p[(i + 2) % 3] - p[(i + 1) % 3]).squaredNorm();
    }
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      double share;
      if (obtuse < 0) share = (squaredOpposite[j] * cotangent[j] + squaredOpposite[k] * cotangent[k]) / 8.0;
      else share = (i == obtuse) ? area / 2.0 : area / 4.0;
      mass[corner[i]] += share;
    }
  }

  SparseMatrix<double> M(n, n);
  M.reserve(VectorXi::Ones(n));
  for (Index i = 0; i < n; ++i) M.insert(i, i) = mass[i];
  M.makeCompressed();
  if (error) error->clear();
  return M;
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_MASSMATRIX_H
