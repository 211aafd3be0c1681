// MatrixAssembly.h — reading the user's sparse matrix into the supernodal factor: its triangle
// permuted by the fill-reducing ordering, and the per-supernode maps by which a factorization does
// step (1) of the paper's Algorithm 1, L(k:n, k) <- A(k:n, k), a supernode at a time (§3.1, §3.4).
//
// The input may be column- or row-major, compressed or not, and the solver reads only its
// UpLo triangle (diagonal included), which it keeps in an InputStore (InputStore.h). Analysis
// permutes that triangle into the lower triangle of C = P A P^T (conjugating entries that cross
// the diagonal) and builds, per supernode, a map from positions in the store to offsets in the
// supernode's dense block. A numeric factorization then scatters values straight from the store,
// with no permuted copy.

#ifndef EIGEN_UPDATABLE_CHOLESKY_MATRIX_ASSEMBLY_H
#define EIGEN_UPDATABLE_CHOLESKY_MATRIX_ASSEMBLY_H

#include <cstring>
#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal The kept triangle of C = P A P^T stored by columns: column j holds rows i >= j and,
  * for each, the position of its value in the solver's InputStore (~position when the value
  * must be conjugated because the entry crossed the diagonal). */
template <typename StorageIndex>
struct PermutedLowerEntries {
  CompressedPattern<StorageIndex> pattern;
  std::vector<Index> source;
};

/** \internal Permutes the stored kept triangle \a a (outer vectors rows when \a RowMajor) by
  * \a perm (perm[old] = new) into the lower triangle; the sources are pool positions of \a a.
  * Optionally also returns the strict upper triangle by columns. The permuted numbering has
  * \a positions columns (a.cols when negative): more than a.cols when the factor keeps free
  * positions (SupernodalFactor::n), whose columns are empty. */
template <bool RowMajor, typename Scalar, typename StorageIndex>
void permuteTriangle(const InputStore<Scalar, StorageIndex>& a, const std::vector<StorageIndex>& perm,
                     PermutedLowerEntries<StorageIndex>& lower, CompressedPattern<StorageIndex>* upper,
                     Index positions = -1) {
  const Index n = positions < 0 ? Index(a.cols) : positions;
  const StorageIndex* inner = a.inner.data();
  auto forEachKept = [&](auto&& visit) {
    for (Index o = 0; o < a.outerSize(); ++o)
      for (Index p = a.begin[o]; p < a.end[o]; ++p) {
        const Index row = RowMajor ? o : Index(inner[p]);
        const Index col = RowMajor ? Index(inner[p]) : o;
        const Index pi = perm[row], pj = perm[col];
        // Entry A(row,col) is C(pi,pj); stored in the lower triangle as C(max,min), conjugated
        // when it crossed the diagonal.
        if (pi >= pj)
          visit(pi, pj, p);
        else
          visit(pj, pi, ~p);
      }
  };
  std::vector<Index> count(n + 1, 0), upperCount(n + 1, 0);
  forEachKept([&](Index i, Index j, Index) {
    ++count[j + 1];
    if (i != j) ++upperCount[i + 1];
  });
  for (Index j = 0; j < n; ++j) {
    count[j + 1] += count[j];
    upperCount[j + 1] += upperCount[j];
  }
  lower.pattern.ptr = count;
  lower.pattern.idx.resize(count[n]);
  lower.source.resize(count[n]);
  if (upper) {
    upper->ptr = upperCount;
    upper->idx.resize(upperCount[n]);
  }
  forEachKept([&](Index i, Index j, Index src) {
    const Index q = count[j]++;
    lower.pattern.idx[q] = StorageIndex(i);
    lower.source[q] = src;
    if (upper && i != j) upper->idx[upperCount[i]++] = StorageIndex(j);
  });
}

/** \internal Builds every supernode's assembly map from the permuted lower entries. */
template <typename Scalar, typename StorageIndex>
void buildAssemblyMaps(const PermutedLowerEntries<StorageIndex>& lower, SupernodalFactor<Scalar, StorageIndex>& factor) {
  std::vector<StorageIndex> position(factor.n, StorageIndex(-1));
  for (auto& node : factor.nodes) {
    const Index nr = node.nrows();
    for (Index k = 0; k < nr; ++k) position[node.rows[k]] = StorageIndex(k);
    const Index begin = lower.pattern.ptr[node.firstCol], end = lower.pattern.ptr[node.firstCol + node.ncols];
    node.assemblySource.resize(end - begin);
    node.assemblyTarget.resize(end - begin);
    for (Index c = 0; c < node.ncols; ++c) {
      const Index j = node.firstCol + c;
      for (Index p = lower.pattern.ptr[j]; p < lower.pattern.ptr[j + 1]; ++p) {
        const Index src = lower.source[p];
        const Index offset = c * nr + position[lower.pattern.idx[p]];
        node.assemblySource[p - begin] = src >= 0 ? src : ~src;
        node.assemblyTarget[p - begin] = src >= 0 ? offset : ~offset;
      }
    }
  }
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_MATRIX_ASSEMBLY_H
