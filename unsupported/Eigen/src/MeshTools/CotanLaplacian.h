// CotanLaplacian: assembles the cotangent Laplacian of a triangle mesh as a sparse matrix.
//
// Input: vertex positions V (#V x 2 or #V x 3) and triangles F (#F x 3). Output: the #V x #V
// symmetric positive semi-definite cotan Laplacian (positive diagonal, rows summing to zero),
// with both triangles stored, assembled from triplets. It is the system matrix A of the paper's
// orbifold Tutte (§5.2) and ARAP (§5.3) applications and of its benchmarks (§6). A triangle of zero
// area (up to rounding) contributes nothing; a non-finite corner is refused with a message naming
// it. The classification is shared with the parameterizations' corner weights (FaceWeights.h),
// which refuse both.

#ifndef EIGEN_MESHTOOLS_COTANLAPLACIAN_H
#define EIGEN_MESHTOOLS_COTANLAPLACIAN_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal Whether a triangle has cotangent weights. */
enum class CotanFace { Defined, ZeroArea, NonFinite };

/** \internal Classifies the triangle \a p and sets \a doubleArea to twice its area: NonFinite when
  * a corner has a non-finite coordinate; ZeroArea when twice the area is at most 16 machine
  * epsilons times the longest edge squared (its cotangents are undefined or meaningless; thin
  * triangles lie far above that); Defined otherwise. */
inline CotanFace cotanFace(const Vector3d p[3], double& doubleArea)
{
  for (int c = 0; c < 3; ++c)
    if (!p[c].allFinite()) return CotanFace::NonFinite;
  doubleArea = (p[1] - p[0]).cross(p[2] - p[0]).norm();
  const double longest =
      (std::max)({(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm()});
  const bool defined = std::isfinite(doubleArea) && std::isfinite(longest) &&
                       doubleArea > 16 * NumTraits<double>::epsilon() * longest;
  return defined ? CotanFace::Defined : CotanFace::ZeroArea;
}

/** \internal \returns why face \a f of (\a V, \a F), not Defined by cotanFace(), has no cotangent
  * weights: the corner with a non-finite coordinate, or its zero area. */
inline std::string cotanFaceProblem(const MatrixXd& V, const MatrixXi& F, Index f)
{
  const std::string face = "face " + std::to_string(f) + " (vertices " + std::to_string(F(f, 0)) + ", " +
                           std::to_string(F(f, 1)) + ", " + std::to_string(F(f, 2)) + ")";
  for (int c = 0; c < 3; ++c)
    if (!V.row(F(f, c)).allFinite())
      return face + ": vertex " + std::to_string(F(f, c)) + " has a non-finite coordinate";
  return face + " has zero area (up to rounding): its cotangent weights are undefined";
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Cotangent Laplacian of a triangle mesh, with the positive semi-definite sign.
  *
  * For an edge (i,j) with opposite angles \f$\alpha_{ij}\f$ and \f$\beta_{ij}\f$ (one of them absent
  * on a boundary edge) the off-diagonal entry is \f$L_{ij} = -\tfrac12(\cot\alpha_{ij} + \cot\beta_{ij})\f$,
  * and \f$L_{ii} = -\sum_{j\neq i} L_{ij}\f$. This is the stiffness matrix of linear finite elements,
  * so \f$x^T L x\f$ is the Dirichlet energy of the piecewise-linear function x: L is symmetric positive
  * semi-definite with the constants in its kernel (one per connected component), and its diagonal is
  * positive for every vertex used by a non-degenerate triangle. Obtuse angles can make off-diagonal
  * entries positive. Cotangents are computed in double precision and then converted to \a Scalar.
  *
  * Both triangles are stored (the full symmetric matrix), so the result can be handed to a solver
  * with either \c Lower or \c Upper. Every edge of F is a structural entry, even when its weight is
  * exactly zero (e.g. the diagonals of a regular grid). Vertices used by no triangle give empty
  * rows and columns (their coordinates are not read).
  *
  * A triangle of zero area has no defined cotangents, and one of area zero up to rounding (twice
  * its area at most 16 machine epsilons times its longest edge squared) has huge, meaningless
  * ones: such a triangle contributes nothing (thin triangles are kept). A non-finite corner
  * coordinate would make the weights NaN: such a mesh is refused, the result is then an empty
  * 0 x 0 matrix and \a error names the first such face and vertex.
  *
  * \tparam Scalar        scalar type of the result (float, double, long double, std::complex<...>).
  * \tparam StorageIndex  index type of the result (int or long).
  * \param V      #V x 3 (or #V x 2, planar) vertex positions.
  * \param F      #F x 3 triangles, 0-based indices into the rows of V.
  * \param error  if not null, receives a message naming the first triangle with a non-finite
  *               corner when the mesh is refused, and is cleared otherwise.
  * \returns the #V x #V column-major cotan Laplacian, compressed; 0 x 0 for a refused mesh.
  *
  * \sa readOFF(), gridMesh(), icosphereMesh()
  */
template <typename Scalar = double, typename StorageIndex = int>
SparseMatrix<Scalar, ColMajor, StorageIndex> cotanLaplacian(const MatrixXd& V, const MatrixXi& F,
                                                            std::string* error = nullptr)
{
  eigen_assert((V.cols() == 2 || V.cols() == 3) && "cotanLaplacian: V must have 2 or 3 columns");
  eigen_assert((F.cols() == 3 || F.rows() == 0) && "cotanLaplacian: F must have 3 columns (triangles)");
  eigen_assert(V.rows() <= Index(NumTraits<StorageIndex>::highest()) &&
               "cotanLaplacian: too many vertices for StorageIndex");
  const Index n = V.rows();

  auto position = [&](int i) {
    Vector3d p = Vector3d::Zero();
    p.head(V.cols()) = V.row(i).transpose();
    return p;
  };

  // Off-diagonal entries go into the triplet list; the diagonal is summed separately so the list
  // holds 6 entries per triangle instead of 9.
  std::vector<Triplet<Scalar, StorageIndex>> triplets;
  triplets.reserve(std::size_t(6 * F.rows() + n));
  std::vector<double> diagonal(std::size_t(n), 0.0);

  for (Index f = 0; f < F.rows(); ++f)
  {
    const int corner[3] = {F(f, 0), F(f, 1), F(f, 2)};
    eigen_assert(corner[0] >= 0 && corner[0] < n && corner[1] >= 0 && corner[1] < n && corner[2] >= 0 &&
                 corner[2] < n && "cotanLaplacian: face index out of range");
    const Vector3d p[3] = {position(corner[0]), position(corner[1]), position(corner[2])};
    // All three angles share the same |cross product| = twice the triangle area.
    double doubleArea = 0;
    const internal::meshtools::CotanFace kind = internal::meshtools::cotanFace(p, doubleArea);
    if (kind == internal::meshtools::CotanFace::NonFinite)
    {
      if (error) *error = "cotanLaplacian: " + internal::meshtools::cotanFaceProblem(V, F, f);
      return SparseMatrix<Scalar, ColMajor, StorageIndex>();
    }
    if (kind == internal::meshtools::CotanFace::ZeroArea) continue;

    for (int c = 0; c < 3; ++c)
    {
      // Angle at corner c is opposite the edge (a, b).
      const int a = (c + 1) % 3, b = (c + 2) % 3;
      const double halfCot = 0.5 * (p[a] - p[c]).dot(p[b] - p[c]) / doubleArea;
      const StorageIndex ia = StorageIndex(corner[a]), ib = StorageIndex(corner[b]);
      triplets.emplace_back(ia, ib, Scalar(-halfCot));
      triplets.emplace_back(ib, ia, Scalar(-halfCot));
      diagonal[std::size_t(ia)] += halfCot;
      diagonal[std::size_t(ib)] += halfCot;
    }
  }
  for (Index i = 0; i < n; ++i)
    if (diagonal[std::size_t(i)] != 0.0) triplets.emplace_back(StorageIndex(i), StorageIndex(i), Scalar(diagonal[std::size_t(i)]));

  SparseMatrix<Scalar, ColMajor, StorageIndex> L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  L.makeCompressed();
  if (error) error->clear();
  return L;
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_COTANLAPLACIAN_H
