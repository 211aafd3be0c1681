// InputStore.h — the solver's copy of the matrix it factors: the kept (UpLo) triangle only, by
// outer vector in the user's orientation and numbering, in a pool where an outer vector may be
// replaced by appending its new entries (paper §4.2: a cut touches a few columns, so the copy
// should cost what they cost, not what the whole matrix costs).
//
// The supernodes' assembly maps hold positions in this pool. An insertion (insertDofs) or the
// merge of trailing dofs rewrites only the outer vectors whose kept entries differ; every other
// entry keeps its position, so the maps of the supernodes that do not own a rewritten entry stay
// valid as they are. The positions a rewrite leaves behind are garbage; the pool is compacted
// (and every map renewed) when garbage outgrows the live entries.

#ifndef EIGEN_UPDATABLE_CHOLESKY_INPUT_STORE_H
#define EIGEN_UPDATABLE_CHOLESKY_INPUT_STORE_H

#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal True when entry (outer \a o, inner \a i) of a matrix of the given orientation lies in
  * the triangle \a UpLo (Lower: row >= col) that the solver reads. */
template <int UpLo, bool RowMajor>
inline bool inKeptTriangle(Index o, Index i) {
  const Index row = RowMajor ? o : i, col = RowMajor ? i : o;
  return UpLo == Lower ? row >= col : row <= col;
}

/** \internal The kept triangle of the current matrix: outer vector o holds the pool entries
  * [begin[o], end[o]) in the order of the user's matrix. */
template <typename Scalar, typename StorageIndex>
struct InputStore {
  Index rows = 0, cols = 0;
  std::vector<Index> begin, end;    ///< per outer vector, its range in the pool
  std::vector<StorageIndex> inner;  ///< pool: inner indices
  std::vector<Scalar> values;       ///< pool: values
  Index live = 0;                   ///< entries in use (the rest of the pool is garbage)

  Index outerSize() const { return Index(begin.size()); }
  /** True when the pool holds more garbage than live entries (compact at the next rewrite). */
  bool wasteful() const { return Index(inner.size()) > 2 * live + 16; }

  /** A compact copy of the kept triangle of the compressed matrix \a a. */
  template <int UpLo, typename CompressedMatrix>
  void assign(const CompressedMatrix& a) {
    constexpr bool rowMajor = bool(CompressedMatrix::IsRowMajor);
    rows = a.rows();
    cols = a.cols();
    const Index no = a.outerSize();
    const auto* outer = a.outerIndexPtr();
    const auto* in = a.innerIndexPtr();
    const auto* val = a.valuePtr();
    begin.resize(no);
    end.resize(no);
    inner.clear();
    values.clear();
    inner.reserve(a.nonZeros() / 2 + no);
    values.reserve(a.nonZeros() / 2 + no);
    for (Index o = 0; o < no; ++o) {
      begin[o] = Index(inner.size());
      for (Index p = outer[o]; p < outer[o + 1]; ++p)
        if (inKeptTriangle<UpLo, rowMajor>(o, in[p])) {
          inner.push_back(StorageIndex(in[p]));
          values.push_back(val[p]);
        }
      end[o] = Index(inner.size());
    }
    live = Index(inner.size());
  }

  /** True when the kept triangle of \a a (compressed) has exactly the stored pattern. */
  template <int UpLo, typename CompressedMatrix>
  bool matchesPattern(const CompressedMatrix& a) const {
    constexpr bool rowMajor = bool(CompressedMatrix::IsRowMajor);
    if (a.rows() != rows || a.cols() != cols || a.outerSize() != outerSize()) return false;
    const auto* outer = a.outerIndexPtr();
    const auto* in = a.innerIndexPtr();
    for (Index o = 0; o < outerSize(); ++o) {
      Index q = begin[o];
      for (Index p = outer[o]; p < outer[o + 1]; ++p) {
        if (!inKeptTriangle<UpLo, rowMajor>(o, in[p])) continue;
        if (q == end[o] || inner[q] != in[p]) return false;
        ++q;
      }
      if (q != end[o]) return false;
    }
    return true;
  }

  /** Copies the kept values of \a a, whose kept pattern matches (matchesPattern()). */
  template <int UpLo, typename CompressedMatrix>
  void copyValues(const CompressedMatrix& a) {
    constexpr bool rowMajor = bool(CompressedMatrix::IsRowMajor);
    const auto* outer = a.outerIndexPtr();
    const auto* in = a.innerIndexPtr();
    const auto* val = a.valuePtr();
    for (Index o = 0; o < outerSize(); ++o) {
      Index q = begin[o];
      for (Index p = outer[o]; p < outer[o + 1]; ++p)
        if (inKeptTriangle<UpLo, rowMajor>(o, in[p])) values[q++] = val[p];
    }
  }

  /** Bytes held. */
  Index bytes() const {
    return Index((begin.capacity() + end.capacity()) * sizeof(Index) + inner.capacity() * sizeof(StorageIndex) +
                 values.capacity() * sizeof(Scalar));
  }
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_INPUT_STORE_H
