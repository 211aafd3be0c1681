// OrbifoldTutte: Euclidean orbifold Tutte embeddings of sphere-type meshes (Aigerman & Lipman
// 2015, "Orbifold Tutte Embeddings"), types I-IV, computed as in Herholz & Sorkine-Hornung,
// "Sparse Cholesky Updates for Interactive Mesh Parameterization", §5.2 (eq. 20-23): the mesh is
// cut into a disk along the cone chain (OrbifoldCut.h), the Dirichlet (cotan) energy of the cut
// mesh is minimised under linear constraints B X = b (cones fixed, seam copies related by the
// orbifold's rotations) through the Schur complement C = B blkdiag(A^-1, A^-1) B^T on one
// UpdatableSupernodalLLT factor of the cut Laplacian A, shared by x and y
// (FactorSchurComplement.h). When the cones move, the factor is updated: the old seam is merged
// back and the new one inserted (mergeDofs/insertDofs, paper §4.2) instead of refactoring.

#ifndef EIGEN_MESHPARAMETERIZATION_ORBIFOLDTUTTE_H
#define EIGEN_MESHPARAMETERIZATION_ORBIFOLDTUTTE_H

namespace Eigen {

namespace internal {
namespace mesh_parameterization {

/** \internal True when the solver has insertDofs(matrix, origin) and mergeDofs(matrix, origin). */
template <typename Solver, typename = void>
struct SupportsDofInsertion : std::false_type
{
};
template <typename Solver>
struct SupportsDofInsertion<
    Solver, std::void_t<decltype(std::declval<Solver&>().insertDofs(std::declval<const typename Solver::MatrixType&>(),
                                                                     std::declval<const VectorXi&>())),
                        decltype(std::declval<Solver&>().mergeDofs(std::declval<const typename Solver::MatrixType&>(),
                                                                    std::declval<const VectorXi&>()))>>
    : std::true_type
{
};

} // namespace mesh_parameterization
} // namespace internal

/** \ingroup MeshParameterization_Module
  * \class OrbifoldTutteEmbedding
  * \brief Orbifold Tutte embedding of a closed genus-0 triangle mesh (Aigerman & Lipman 2015),
  * solved on an updatable sparse Cholesky factor (Herholz & Sorkine-Hornung, §5.2).
  *
  * Given 3 or 4 cone vertices and an orbifold type (OrbifoldType), the mesh is cut along shortest
  * edge paths c1 -> c2 -> ... -> ck into a disk. The embedding X (one uv per cut vertex)
  * minimises the cotan Dirichlet energy of the cut mesh subject to
  * - the cone images fixed at the corners of the fundamental domain,
  * - each right seam copy equal to its left copy rotated by the cone's angle 2π/k about the
  *   cone image (for the middle segment of type IV, translated), which also makes the map
  *   harmonic across the seam (the "smoothness" constraints of the paper).
  * The result tiles the plane: it is a Tutte embedding into the orbifold, bijective for positive
  * edge weights (cotan weights are positive on Delaunay meshes).
  *
  * How it is solved: the KKT system (eq. 20) is reduced to its Schur complement (eq. 21-23),
  * C = B blkdiag(A^-1, A^-1) B^T, λ = C^-1 (B A^-1 f - b), X = A^-1 (f - B^T λ), where A is the cut
  * cotan Laplacian plus ρ at the first cone (A would be singular otherwise; since that cone is
  * fixed, adding ρ (x_c1 - p_c1)^2 / 2 to the energy, i.e. ρ to A and f = ρ p_c1, leaves the
  * minimiser exactly unchanged). C needs only the rows of L^-1 P at the constrained vertices, on
  * their elimination-tree paths. x and y share the factor.
  *
  * Edits: moveCone() and setCones() recut the mesh; when the solver supports insertDofs() and
  * mergeDofs() the previous seam is merged back into the factor and the new one inserted
  * (paper §4.2), otherwise the cut Laplacian is refactored; lastStatistics() says which.
  *
  * \code
  * OrbifoldTutteEmbedding<> orbifold;
  * if (!orbifold.setup(V, F, {c1, c2, c3}, OrbifoldType::I) || !orbifold.compute()) std::cerr << orbifold.error();
  * renderUVCheckerboard(orbifold.uv(), orbifold.cutFaces(), "orbifold.png");
  * orbifold.moveCone(1, v);   // new cut: the factor is updated, the embedding recomputed
  * \endcode
  *
  * \tparam Ordering_ fill-reducing ordering of the solver (AMDOrdering, MetisOrdering, ...).
  * \sa OrbifoldType, UpdatableSupernodalLLT
  */
template <typename Ordering_ = AMDOrdering<int>>
class OrbifoldTutteEmbedding
{
public:
  /** The sparse matrix type of the Laplacians. */
  typedef SparseMatrix<double, ColMajor, int> MatrixType;
  /** The solver holding the factor of the cut Laplacian. */
  typedef UpdatableSupernodalLLT<MatrixType, Lower, Ordering_> SolverType;
  /** True when the solver can insert and merge dofs (factor updates on edits). */
  static constexpr bool supportsFactorUpdates = internal::mesh_parameterization::SupportsDofInsertion<SolverType>::value;

  /** What the last compute() or edit did and how long each step took. */
  struct Statistics
  {
    double cutSeconds = 0;     ///< cone paths, cutting, Laplacian and constraint assembly
    double factorSeconds = 0;  ///< factor update (merge + insert) or refactorization
    double schurSeconds = 0;   ///< C = B A^-1 B^T and its solve for λ
    double solveSeconds = 0;   ///< X = A^-1 (f - B^T λ)
    bool factorUpdated = false;     ///< true: the factor was updated in place; false: refactored
    Index seamVertices = 0;         ///< vertices of the cone chain
    Index constraints = 0;          ///< rows of B
    /** \returns factor + Schur + solve seconds (the cost of an edit once the cut is known). */
    double editSeconds() const { return factorSeconds + schurSeconds + solveSeconds; }
  };

  /** Empty embedding: call setup() and compute(). */
  OrbifoldTutteEmbedding() = default;

  /** Sets the mesh, the cones (in chain order, see OrbifoldType) and the orbifold type.
    * Assembles the cotan Laplacian of the closed mesh once. \returns false (see error()) on bad
    * input: F not a #F x 3 index matrix into V, a mesh that is not a closed, consistently oriented
    * surface of genus 0 in one piece (one fan of triangles around each vertex), a vertex on no
    * triangle, a triangle of zero area up to rounding or a non-finite coordinate (no cotan
    * weights, see cotanLaplacian()), wrong cone count, repeated or out-of-range cones. Faces
    * counter-clockwise seen from outside give a counter-clockwise (positively oriented) layout. */
  bool setup(const MatrixXd& V, const MatrixXi& F, const std::vector<int>& cones, OrbifoldType type)
  {
    m_info = InvalidInput;
    m_hasFactor = false;
    m_uv.resize(0, 2);
    if (V.cols() != 3 || F.cols() != 3 || V.rows() == 0 || F.rows() == 0 || F.minCoeff() < 0 ||
        F.maxCoeff() >= V.rows())
      return fail("the mesh must be #V x 3 positions and #F x 3 vertex indices (0-based)");
    if (!checkCones(cones, type, Index(V.rows()))) return false;
    std::string why;
    if (!internal::mesh_parameterization::checkSphereTopology(F, why)) return fail(why);
    {
      std::vector<char> used(std::size_t(V.rows()), 0);
      for (Index k = 0; k < F.size(); ++k) used[std::size_t(F.data()[k])] = 1;
      for (Index v = 0; v < V.rows(); ++v)
        if (!used[std::size_t(v)])
          return fail("vertex " + std::to_string(v) + " is on no triangle (remove unused vertices first)");
    }
    {  // every triangle needs its cotangent weights (cotanLaplacian() would leave a zero-area one out)
      MatrixXd weights;
      if (!internal::meshparameterization::cornerEdgeWeights(V, F, LaplacianWeights::Cotangent, weights, why))
        return fail(why);
    }
    m_V = V;
    m_F = F;
    m_cones = cones;
    m_type = type;
    m_L0 = cotanLaplacian<double, int>(V, F);
    m_rho = m_L0.diagonal().mean();  // (> 0: every triangle has a positive area)
    m_isSetup = true;
    m_info = Success;
    m_error.clear();
    return true;
  }

  /** Cuts the mesh along the cone chain, factors the cut Laplacian (or updates the factor of a
    * previous cut) and solves for the embedding. \returns false (see error(), info()) on failure. */
  bool compute()
  {
    if (!m_isSetup) return fail("setup() was not called or failed");
    return run();
  }

  /** Edit: moves cone \a cone (0-based chain position) to vertex \a vertex and recomputes the
    * embedding on the new cut, updating the factor (see supportsFactorUpdates). */
  bool moveCone(int cone, int vertex)
  {
    if (!m_isSetup) return fail("setup() was not called or failed");
    if (cone < 0 || cone >= int(m_cones.size())) return fail("moveCone: no cone " + std::to_string(cone));
    std::vector<int> cones = m_cones;
    cones[std::size_t(cone)] = vertex;
    return setCones(cones, m_type);
  }

  /** Edit: new cones and orbifold type on the same mesh; recomputes the embedding on the new cut,
    * updating the factor (see supportsFactorUpdates). Bad cones are rejected before anything
    * changes; if the solve itself fails, info() says so and the object needs a new compute(). */
  bool setCones(const std::vector<int>& cones, OrbifoldType type)
  {
    if (!m_isSetup) return fail("setup() was not called or failed");
    if (!checkCones(cones, type, Index(m_V.rows()))) return false;
    const std::vector<int> previousCones = m_cones;
    const OrbifoldType previousType = m_type;
    m_cones = cones;
    m_type = type;
    if (run()) return true;
    m_cones = previousCones;
    m_type = previousType;
    return false;
  }

  /** \returns Success after a successful compute()/edit, else InvalidInput or NumericalIssue. */
  ComputationInfo info() const { return m_info; }
  /** \returns what went wrong in the last call, empty after a success. */
  const std::string& error() const { return m_error; }

  /** \returns the embedding: one uv per vertex of the cut mesh (#Vcut x 2). */
  const MatrixXd& uv() const { return m_uv; }
  /** \returns the vertices of the cut mesh (#Vcut x 3; row i is the position of origin()[i]). */
  const MatrixXd& cutVertices() const { return m_cut.Vcut; }
  /** \returns the faces of the cut mesh (same rows and orientation as the input faces). */
  const MatrixXi& cutFaces() const { return m_cut.Fcut; }
  /** \returns for each cut vertex the input vertex it copies (origin()[i] == i for i < #V). */
  const VectorXi& origin() const { return m_cut.origin; }
  /** \returns the vertices of the cone chain c1 -> ... -> ck along which the mesh was cut. */
  const std::vector<int>& seam() const { return m_cut.chain; }
  /** \returns the cones, in chain order. */
  const std::vector<int>& cones() const { return m_cones; }
  /** \returns the orbifold type. */
  OrbifoldType type() const { return m_type; }
  /** \returns the cone images in the plane (one row per cone, chain order; left copies). */
  MatrixX2d coneImages() const { return internal::mesh_parameterization::orbifoldConePositions(m_type); }
  /** \returns the area of the fundamental domain bounded by the cone images: the total signed uv
    * area of every embedding of this type. */
  double domainArea() const { return internal::mesh_parameterization::orbifoldDomainArea(m_type); }
  /** \returns the constraint matrix B (m x 2 #Vcut, columns x then y) of the last solve. */
  const SparseMatrix<double>& constraintMatrix() const { return m_B; }
  /** \returns the constraint right-hand side b of the last solve. */
  const VectorXd& constraintRhs() const { return m_b; }
  /** \returns the solver (its factor is that of the cut Laplacian + ρ at the first cone). */
  const SolverType& solver() const { return m_llt; }
  /** \returns the solver, e.g. to set its thread count before compute(). */
  SolverType& solver() { return m_llt; }
  /** \returns what the last compute() or edit did. */
  const Statistics& lastStatistics() const { return m_stats; }

private:
  typedef std::chrono::steady_clock Clock;
  static double secondsSince(Clock::time_point start)
  {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  bool fail(const std::string& message, ComputationInfo info = InvalidInput)
  {
    m_error = "OrbifoldTutteEmbedding: " + message;
    m_info = info;
    return false;
  }

  bool checkCones(const std::vector<int>& cones, OrbifoldType type, Index n)
  {
    const std::size_t count = internal::mesh_parameterization::orbifoldConeOrders(type).size();
    if (count == 0) return fail("unknown orbifold type");
    if (cones.size() != count)
      return fail("this orbifold type needs " + std::to_string(count) + " cones, got " + std::to_string(cones.size()));
    for (std::size_t i = 0; i < count; ++i)
    {
      if (cones[i] < 0 || cones[i] >= n) return fail("cone " + std::to_string(i) + " is not a vertex index");
      for (std::size_t j = 0; j < i; ++j)
        if (cones[i] == cones[j]) return fail("cones " + std::to_string(j) + " and " + std::to_string(i) + " coincide");
    }
    return true;
  }

  /** The Laplacian \a L plus ρ on the diagonal at \a anchor. */
  MatrixType anchored(const MatrixType& L, int anchor) const
  {
    MatrixType K = L;
    K.coeffRef(anchor, anchor) += m_rho;
    return K;
  }

  /** Brings the factor to the cut Laplacian \a Kcut: merge the previous seam and insert the new
    * one when the solver can, else refactor. The one place that chooses. */
  bool updateFactor(const MatrixType& Kcut, int anchor)
  {
    m_stats.factorUpdated = false;
    if constexpr (supportsFactorUpdates)
    {
      bool ok = true;
      if (!m_hasFactor || !m_factorIsInserted)
      {
        m_llt.compute(anchored(m_L0, anchor));  // the uncut mesh: once, the edits update it
        ok = m_llt.info() == Success;
      }
      else
      {
        m_llt.mergeDofs(anchored(m_L0, m_factorAnchor), m_factorOrigin);  // the previous seam merged back
        ok = m_llt.info() == Success;
        if (ok && m_factorAnchor != anchor)
        {
          const std::vector<int> columns = {m_factorAnchor, anchor};
          m_llt.updateColumns(anchored(m_L0, anchor), columns);
          ok = m_llt.info() == Success;
        }
      }
      if (ok)
      {
        m_llt.insertDofs(Kcut, m_cut.origin);  // the new seam
        ok = m_llt.info() == Success;
      }
      m_factorIsInserted = ok;
      m_stats.factorUpdated = ok && m_hasFactor;
      if (ok)
      {
        m_factorAnchor = anchor;
        m_factorOrigin = m_cut.origin;
        m_hasFactor = true;
        return true;
      }
    }
    m_llt.compute(Kcut);
    m_hasFactor = m_llt.info() == Success;
    m_factorIsInserted = false;
    return m_hasFactor;
  }

  /** Cut, assemble, factor, solve. */
  bool run()
  {
    using namespace internal::mesh_parameterization;
    m_stats = Statistics();
    Clock::time_point start = Clock::now();
    OrbifoldCutResult cut;
    std::string why;
    if (!orbifoldCut(m_V, m_F, m_cones, m_type, cut, why)) return fail(why);
    const MatrixX2d coneImage = orbifoldConePositions(m_type);
    const Index N = cut.Vcut.rows();
    const int anchor = cut.left[std::size_t(cut.conePosition[0])];
    const MatrixType Kcut = anchored(cotanLaplacian<double, int>(cut.Vcut, cut.Fcut), anchor);

    // Constraints: fixed cone images (left copies), then one rotation per right seam copy.
    std::vector<int> fixedCone(std::size_t(N), -1);
    for (std::size_t i = 0; i < m_cones.size(); ++i) fixedCone[std::size_t(cut.left[std::size_t(cut.conePosition[i])])] = int(i);
    std::vector<Triplet<double>> entries;  // (row, vertex + N * coordinate)
    std::vector<double> rhs;
    for (std::size_t i = 0; i < m_cones.size(); ++i)
      for (int d = 0; d < 2; ++d)
      {
        entries.emplace_back(int(rhs.size()), cut.left[std::size_t(cut.conePosition[i])] + int(N) * d, 1.0);
        rhs.push_back(coneImage(Index(i), d));
      }
    for (const OrbifoldSeamPair& pair : cut.pairs)
    {
      // X(right) - R X(left) = X(centerRight) - R X(centerLeft); the center's left copy is fixed.
      const Matrix2d R = planeRotation(pair.angle);
      const Vector2d centerLeft = coneImage.row(pair.centerCone).transpose();
      const bool rightFixed = fixedCone[std::size_t(pair.centerRight)] >= 0;
      for (int d = 0; d < 2; ++d)
      {
        const int row = int(rhs.size());
        entries.emplace_back(row, pair.right + int(N) * d, 1.0);
        for (int e = 0; e < 2; ++e)
          if (R(d, e) != 0) entries.emplace_back(row, pair.left + int(N) * e, -R(d, e));
        double value = -(R.row(d) * centerLeft)(0);
        if (rightFixed)
          value += coneImage(fixedCone[std::size_t(pair.centerRight)], d);
        else
          entries.emplace_back(row, pair.centerRight + int(N) * d, -1.0);
        rhs.push_back(value);
      }
    }
    const Index m = Index(rhs.size());
    m_B.resize(m, 2 * N);
    m_B.setFromTriplets(entries.begin(), entries.end());
    m_b = Map<const VectorXd>(rhs.data(), m);
    m_cut = std::move(cut);
    m_stats.seamVertices = Index(m_cut.chain.size());
    m_stats.constraints = m;
    m_stats.cutSeconds = secondsSince(start);

    start = Clock::now();
    if (!updateFactor(Kcut, anchor))
      return fail("the cut Laplacian could not be factored (is the mesh a closed surface of genus 0?)", NumericalIssue);
    m_stats.factorSeconds = secondsSince(start);

    // The constrained vertices E and B restricted to them: B = [Bx By], Bx E = BxE, ...
    start = Clock::now();
    std::vector<int> localOf(std::size_t(N), -1), constrained;
    for (const auto& t : entries)
    {
      const int v = t.col() % int(N);
      if (localOf[std::size_t(v)] < 0)
      {
        localOf[std::size_t(v)] = int(constrained.size());
        constrained.push_back(v);
      }
    }
    const Index s = Index(constrained.size());
    std::vector<Triplet<double>> partEntries[2];
    for (const auto& t : entries) partEntries[t.col() / int(N)].emplace_back(t.row(), localOf[std::size_t(t.col() % int(N))], t.value());
    SparseMatrix<double> BE[2];
    for (int d = 0; d < 2; ++d)
    {
      BE[d].resize(m, s);
      BE[d].setFromTriplets(partEntries[d].begin(), partEntries[d].end());
    }
    MatrixXd S;  // E^T A^-1 E
    if (!unitVectorSchurComplement(m_llt.matrixL().nestedExpression(), m_llt.permutationP().indices(), constrained, S))
      return fail("the factor has a non-positive diagonal", NumericalIssue);
    MatrixXd C = MatrixXd::Zero(m, m);
    for (int d = 0; d < 2; ++d)
    {
      const MatrixXd SBt = S * SparseMatrix<double>(BE[d].transpose());
      C.noalias() += BE[d] * SBt;
    }
    // f = ρ p_c1 at the anchor: B A^-1 f = sum_d BE_d S e_anchor ρ p_d.
    const Vector2d anchorImage = coneImage.row(0).transpose();
    const VectorXd anchorColumn = S.col(localOf[std::size_t(anchor)]);
    VectorXd schurRhs = -m_b;
    for (int d = 0; d < 2; ++d) schurRhs.noalias() += BE[d] * (anchorColumn * (m_rho * anchorImage(d)));
    const LLT<MatrixXd> cholC(C);
    if (cholC.info() != Success) return fail("the constraints are dependent (C is singular)", NumericalIssue);
    const VectorXd lambda = cholC.solve(schurRhs);
    m_stats.schurSeconds = secondsSince(start);

    start = Clock::now();
    MatrixXd load = MatrixXd::Zero(N, 2);
    load.row(anchor) = m_rho * anchorImage.transpose();
    const VectorXd Btl = m_B.transpose() * lambda;
    load.col(0) -= Btl.head(N);
    load.col(1) -= Btl.tail(N);
    m_uv = m_llt.solve(load);
    m_stats.solveSeconds = secondsSince(start);
    m_info = Success;
    m_error.clear();
    return true;
  }

  MatrixXd m_V, m_uv;
  MatrixXi m_F;
  MatrixType m_L0;                 ///< cotan Laplacian of the closed mesh
  double m_rho = 1;                ///< anchor weight (mean diagonal of m_L0)
  std::vector<int> m_cones;
  OrbifoldType m_type = OrbifoldType::I;
  internal::mesh_parameterization::OrbifoldCutResult m_cut;
  SparseMatrix<double> m_B;
  VectorXd m_b;
  SolverType m_llt;
  bool m_isSetup = false, m_hasFactor = false, m_factorIsInserted = false;
  int m_factorAnchor = -1;         ///< vertex with ρ in the factored matrix
  VectorXi m_factorOrigin;         ///< origin of the cut held by the factor (undoes its insertDofs)
  ComputationInfo m_info = InvalidInput;
  std::string m_error;
  Statistics m_stats;
};

} // namespace Eigen

#endif // EIGEN_MESHPARAMETERIZATION_ORBIFOLDTUTTE_H
