// FixedOrdering: an Eigen ordering functor that returns a permutation computed beforehand, so that
// several solvers in one benchmark factor exactly the same permuted matrix.

#ifndef UPDATABLE_CHOLESKY_BENCH_FIXEDORDERING_H
#define UPDATABLE_CHOLESKY_BENCH_FIXEDORDERING_H

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <stdexcept>

namespace bench {

/** Ordering functor (Eigen's `ordering(A, Pinv)` protocol) that hands out a fixed permutation.
  *
  * The permutation is given as Eigen's ordering functors produce it: `Pinv.indices()[k]` is the
  * original index placed at position k (CHOLMOD's `Perm`). A solver that exposes its functor
  * instance (UpdatableSupernodalLLT::ordering()) gets it through #permutation; solvers that
  * default-construct the functor internally (SimplicialLLT) get the one set with setDefault(). */
template <typename StorageIndex>
class FixedOrdering
{
public:
  typedef Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, StorageIndex> PermutationType;

  /** The permutation handed out; initialised from the default set with setDefault(). */
  const PermutationType* permutation = defaultPermutation();

  /** Sets the permutation that newly constructed functors hand out (not owned; must outlive them). */
  static void setDefault(const PermutationType* p) { defaultPermutation() = p; }

  /** Fills \a Pinv with the fixed permutation; \a A only provides the size, which must match. */
  template <typename MatrixType>
  void operator()(const MatrixType& A, PermutationType& Pinv) const
  {
    if (!permutation) throw std::logic_error("FixedOrdering: no permutation set");
    if (permutation->size() != A.cols())
      throw std::logic_error("FixedOrdering: permutation size does not match the matrix");
    Pinv = *permutation;
  }

private:
  static const PermutationType*& defaultPermutation()
  {
    static const PermutationType* p = nullptr;
    return p;
  }
};

} // namespace bench

#endif // UPDATABLE_CHOLESKY_BENCH_FIXEDORDERING_H
