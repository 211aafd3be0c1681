// WeightedComponents: the connected components of the graph of a symmetric sparse matrix's
// non-zero off-diagonal entries. For a cotan Laplacian these are the blocks of its kernel: a
// Dirichlet problem on the Laplacian is well posed exactly when every component holds a
// constrained vertex (Sorkine & Alexa 2007, the global step of ARAP). ArapDeformation (paper §5.3)
// checks this before it solves.

#ifndef EIGEN_MESHDEFORMATION_WEIGHTEDCOMPONENTS_H
#define EIGEN_MESHDEFORMATION_WEIGHTEDCOMPONENTS_H

namespace Eigen {
namespace internal {
namespace mesh_deformation {

/** Labels the connected components of the graph whose edges are the non-zero off-diagonal
  * entries of the column-major symmetric matrix \a A (both triangles stored). Structural zeros
  * (e.g. the zero cotan weights of a regular grid's diagonals) do not connect.
  * \param A          n x n symmetric sparse matrix, both triangles stored.
  * \param component  output: n labels in [0, count), numbered in order of their smallest vertex.
  * \returns the number of components. */
inline int weightedComponents(const SparseMatrix<double>& A, std::vector<int>& component)
{
  const Index n = A.rows();
  component.assign(std::size_t(n), -1);
  std::vector<Index> stack;
  int count = 0;
  for (Index seed = 0; seed < n; ++seed)
  {
    if (component[std::size_t(seed)] >= 0) continue;
    component[std::size_t(seed)] = count;
    stack.assign(1, seed);
    while (!stack.empty())
    {
      const Index v = stack.back();
      stack.pop_back();
      for (SparseMatrix<double>::InnerIterator it(A, v); it; ++it)
        if (it.row() != v && it.value() != 0.0 && component[std::size_t(it.row())] < 0)
        {
          component[std::size_t(it.row())] = count;
          stack.push_back(it.row());
        }
    }
    ++count;
  }
  return count;
}

} // namespace mesh_deformation
} // namespace internal
} // namespace Eigen

#endif // EIGEN_MESHDEFORMATION_WEIGHTEDCOMPONENTS_H
