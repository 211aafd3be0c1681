// SupernodalFactor.h — storage of a supernodal Cholesky factor, one object per supernode
// (paper §4.2, "Implementation"): each supernode keeps its own row indices and its own dense
// block, so that later updates can insert or remove rows and columns of one supernode without
// moving the others. The factor also keeps the supernodal elimination tree, each supernode's
// relative row positions inside its parent (for the extend-add of update matrices), the map
// that scatters the input matrix's values into the blocks, and the flop counts.

#ifndef EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_FACTOR_H
#define EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_FACTOR_H

#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal One supernode: columns firstCol .. firstCol+ncols-1 of L, stored as a dense
  * column-major block of rows.size() × ncols values (lower trapezoid meaningful). */
template <typename Scalar, typename StorageIndex>
struct Supernode {
  Index firstCol = 0;                        ///< first column (in the permuted numbering)
  Index ncols = 0;                           ///< number of columns
  std::vector<StorageIndex> rows;            ///< its columns first, then the rows below, increasing
  std::vector<StorageIndex> parentPosition;  ///< for each row below, its position in the parent's rows
  Matrix<Scalar, Dynamic, Dynamic> values;   ///< the dense block L(rows, columns)
  /** Entries of the input matrix scattered into \c values: value source[k] goes to offset
    * target[k] of the block; a negative target ~t means "conjugate, then store at t". Listed
    * column by column (increasing local column), which the Dirichlet coupling relies on. */
  std::vector<Index> assemblySource, assemblyTarget;

  Index nrows() const { return Index(rows.size()); }
  Index below() const { return Index(rows.size()) - ncols; }
  /** Flops of this supernode's dense work: potrf, trsm and the update-matrix herk. */
  double flops() const { return flopsOf(ncols, below()); }
  /** Flops of the dense work of a supernode of \a columns columns and \a below rows below them. */
  static double flopsOf(Index columns, Index below) {
    const double c = double(columns), m = double(below);
    return c * c * c / 3.0 + m * c * c + m * m * c;
  }
};

/** \internal The whole factor: the supernodes in postorder, and their tree. */
template <typename Scalar, typename StorageIndex>
struct SupernodalFactor {
  typedef Supernode<Scalar, StorageIndex> Node;
  /** The number of positions: the columns of every supernode and the free positions after them
    * (SupernodalFactor::ownedEnd()); n >= the number of dofs. At a free position colToSuper
    * holds its owner; no row list names one. */
  Index n = 0;
  std::vector<Node> nodes;
  std::vector<StorageIndex> parent;         ///< supernodal elimination tree, -1 for roots
  std::vector<StorageIndex> firstChild, nextSibling;  ///< children lists in increasing order
  std::vector<StorageIndex> firstDescendant;          ///< subtree of s = [firstDescendant[s], s]
  std::vector<StorageIndex> colToSuper;
  /** The last row of each supernode (kept by the renumberings of insertDofs()/mergeDofs(), which
    * skip the supernodes that lie wholly below the first column that moves without reading them). */
  std::vector<StorageIndex> lastRow;

  Index count() const { return Index(nodes.size()); }
  /** The end of the positions supernode \a s owns: its columns, then its free positions (room
    * for the copies of later insertions, which no row names), up to the next supernode's first
    * column (n for the last). */
  Index ownedEnd(Index s) const { return s + 1 < count() ? nodes[s + 1].firstCol : n; }
  /** The free positions of supernode \a s. */
  Index freePositions(Index s) const { return ownedEnd(s) - nodes[s].firstCol - nodes[s].ncols; }

  /** Sets lastRow[s] from supernode s's rows (after they changed). */
  void noteLastRow(Index s) { lastRow[s] = nodes[s].rows.empty() ? StorageIndex(-1) : nodes[s].rows.back(); }

  /** Builds the supernodes from a partition (values left empty). */
  void build(const SupernodalPartition<StorageIndex>& part) {
    const Index ns = part.count();
    n = Index(part.colToSuper.size());
    nodes.assign(ns, Node());
    parent = part.parent;
    colToSuper = part.colToSuper;
    firstChild.assign(ns, StorageIndex(-1));
    nextSibling.assign(ns, StorageIndex(-1));
    firstDescendant.resize(ns);
    for (Index s = 0; s < ns; ++s) firstDescendant[s] = StorageIndex(s);
    for (Index s = ns - 1; s >= 0; --s) {
      if (parent[s] == -1) continue;
      nextSibling[s] = firstChild[parent[s]];
      firstChild[parent[s]] = StorageIndex(s);
    }
    for (Index s = 0; s < ns; ++s)
      if (parent[s] != -1 && firstDescendant[s] < firstDescendant[parent[s]])
        firstDescendant[parent[s]] = firstDescendant[s];
    for (Index s = 0; s < ns; ++s) {
      Node& node = nodes[s];
      node.firstCol = part.start[s];
      node.ncols = part.start[s + 1] - part.start[s];
      node.rows.assign(part.rowIdx.begin() + part.rowPtr[s], part.rowIdx.begin() + part.rowPtr[s + 1]);
    }
    lastRow.resize(ns);
    for (Index s = 0; s < ns; ++s) noteLastRow(s);
    std::vector<StorageIndex> position(n, StorageIndex(-1));
    for (Index p = 0; p < ns; ++p) {
      const Node& pn = nodes[p];
      for (Index k = 0; k < pn.nrows(); ++k) position[pn.rows[k]] = StorageIndex(k);
      for (Index c = firstChild[p]; c != -1; c = nextSibling[c]) {
        Node& cn = nodes[c];
        cn.parentPosition.resize(cn.below());
        for (Index k = 0; k < cn.below(); ++k) cn.parentPosition[k] = position[cn.rows[cn.ncols + k]];
      }
    }
  }

  /** Number of stored entries of L (lower trapezoids, explicit zeros of relaxation included). */
  Index nonZeros() const {
    Index nnz = 0;
    for (const Node& node : nodes) nnz += node.ncols * (node.ncols + 1) / 2 + node.ncols * node.below();
    return nnz;
  }

  /** Flops of a full numeric factorization. */
  double flops() const {
    double f = 0;
    for (const Node& node : nodes) f += node.flops();
    return f;
  }

  /** The largest number of rows of any supernode (workspace of the solve). */
  Index maxRows() const {
    Index m = 0;
    for (const Node& node : nodes) m = (std::max)(m, node.nrows());
    return m;
  }
};

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_FACTOR_H
