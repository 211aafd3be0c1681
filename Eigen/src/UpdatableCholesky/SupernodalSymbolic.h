// SupernodalSymbolic.h — symbolic analysis of a supernodal Cholesky factorization (paper §3.2,
// §3.4): elimination tree, postorder, column counts of L (Gilbert–Ng–Peyton, with the row-subtree
// skeleton and a union-find for least common ancestors, never forming L's pattern), fundamental
// supernodes, relaxed amalgamation with the classic nrelax/zrelax rule, the supernodal elimination tree and
// the row structure of every supernode.
//
// Input: the pattern of the lower triangle of a symmetric n×n matrix C (already permuted by the
// fill-reducing ordering) given as compressed columns, once by column (rows i >= j of column j)
// and once by row (columns j < i of row i, i.e. the upper triangle by column). Output: a
// SupernodalPartition. Nothing here fails except by running out of memory.

#ifndef EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SYMBOLIC_H
#define EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SYMBOLIC_H

#include <algorithm>
#include <vector>

namespace Eigen {

/** \ingroup UpdatableCholesky_Module
  * \brief Tuning of relaxed supernode amalgamation (the usual nrelax/zrelax rule and defaults of supernodal codes).
  *
  * A child supernode is merged into its parent when the merged supernode has at most
  * \c nrelax[0] columns, or when the fraction of explicit zeros it would store stays below
  * \c zrelax[0] (merged size ≤ \c nrelax[1]), \c zrelax[1] (size ≤ \c nrelax[2]) or \c zrelax[2]
  * (any size). All zeros gives fundamental supernodes only. */
struct SupernodeRelaxation {
  int nrelax[3] = {4, 16, 48};          ///< column-count thresholds
  double zrelax[3] = {0.8, 0.1, 0.05};  ///< allowed fractions of explicit zeros
};

namespace internal {
namespace updatable_cholesky {

/** \internal A pattern stored by compressed columns: column j holds idx[ptr[j] .. ptr[j+1]). */
template <typename StorageIndex>
struct CompressedPattern {
  std::vector<Index> ptr;
  std::vector<StorageIndex> idx;
  Index size() const { return ptr.empty() ? 0 : Index(ptr.size()) - 1; }
};

/** \internal Elimination tree (Liu's algorithm with path compression). \a upper holds, for
  * every column k, the rows i < k of C. parent[j] = -1 for roots. */
template <typename StorageIndex>
void eliminationTree(const CompressedPattern<StorageIndex>& upper, std::vector<StorageIndex>& parent) {
  const Index n = upper.size();
  parent.assign(n, StorageIndex(-1));
  std::vector<StorageIndex> ancestor(n, StorageIndex(-1));
  for (Index k = 0; k < n; ++k) {
    for (Index p = upper.ptr[k]; p < upper.ptr[k + 1]; ++p) {
      Index i = upper.idx[p];
      while (i != -1 && i < k) {
        const Index next = ancestor[i];
        ancestor[i] = StorageIndex(k);
        if (next == -1) {
          parent[i] = StorageIndex(k);
          break;
        }
        i = next;
      }
    }
  }
}

/** \internal Postorder of a forest: post[k] is the node visited k-th; children are visited in
  * increasing order, so a postordered tree keeps its natural order where it already was one. */
template <typename StorageIndex>
void postorder(const std::vector<StorageIndex>& parent, std::vector<StorageIndex>& post) {
  const Index n = Index(parent.size());
  std::vector<StorageIndex> head(n, StorageIndex(-1)), next(n, StorageIndex(-1)), stack;
  for (Index j = n - 1; j >= 0; --j) {  // children lists in increasing order
    if (parent[j] == -1) continue;
    next[j] = head[parent[j]];
    head[parent[j]] = StorageIndex(j);
  }
  post.clear();
  post.reserve(n);
  stack.reserve(n);
  for (Index root = 0; root < n; ++root) {
    if (parent[root] != -1) continue;
    stack.push_back(StorageIndex(root));
    while (!stack.empty()) {
      const StorageIndex top = stack.back();
      const StorageIndex child = head[top];
      if (child == -1) {
        stack.pop_back();
        post.push_back(top);
      } else {
        head[top] = next[child];
        stack.push_back(child);
      }
    }
  }
}

/** \internal Column counts of L (diagonal included) for a postordered elimination tree, by the
  * Gilbert–Ng–Peyton method: every row subtree contributes +1 at its leaves and -1 at the least
  * common ancestor of consecutive leaves; a subtree sum then counts the row subtrees through a
  * column. \a lower holds, for every column j, the rows i >= j of C. */
template <typename StorageIndex>
void columnCounts(const CompressedPattern<StorageIndex>& lower, const std::vector<StorageIndex>& parent,
                  std::vector<StorageIndex>& count) {
  const Index n = lower.size();
  std::vector<StorageIndex> first(n, StorageIndex(-1)), maxFirst(n, StorageIndex(-1)),
      prevLeaf(n, StorageIndex(-1)), ancestor(n);
  count.assign(n, StorageIndex(0));
  for (Index k = 0; k < n; ++k) {
    ancestor[k] = StorageIndex(k);
    count[k] = first[k] == -1 ? 1 : 0;  // a leaf of the etree contributes its own diagonal
    for (Index j = k; j != -1 && first[j] == -1; j = parent[j]) first[j] = StorageIndex(k);
  }
  for (Index j = 0; j < n; ++j) {
    if (parent[j] != -1) --count[parent[j]];
    for (Index p = lower.ptr[j]; p < lower.ptr[j + 1]; ++p) {
      const Index i = lower.idx[p];
      if (i <= j || first[j] <= maxFirst[i]) continue;  // j is not a leaf of row subtree i
      maxFirst[i] = first[j];
      const Index previous = prevLeaf[i];
      prevLeaf[i] = StorageIndex(j);
      ++count[j];
      if (previous != -1) {
        Index q = previous;  // least common ancestor via the union-find, with path compression
        while (q != ancestor[q]) q = ancestor[q];
        for (Index s = previous; s != q;) {
          const Index up = ancestor[s];
          ancestor[s] = StorageIndex(q);
          s = up;
        }
        --count[q];
      }
    }
    if (parent[j] != -1) ancestor[j] = parent[j];
  }
  for (Index j = 0; j < n; ++j)
    if (parent[j] != -1) count[parent[j]] += count[j];
}

/** \internal The supernode partition of a postordered matrix: supernode s holds the columns
  * start[s] .. start[s+1]-1, its rows are rowIdx[rowPtr[s] .. rowPtr[s+1]) (its own columns first,
  * then the rows below in increasing order), and its parent in the supernodal tree is parent[s]. */
template <typename StorageIndex>
struct SupernodalPartition {
  std::vector<StorageIndex> start;        ///< first column of each supernode, plus n at the end
  std::vector<StorageIndex> colToSuper;   ///< supernode of every column
  std::vector<StorageIndex> parent;       ///< supernodal elimination tree (-1 for roots)
  std::vector<Index> rowPtr;              ///< row structure, compressed
  std::vector<StorageIndex> rowIdx;
  Index count() const { return start.empty() ? 0 : Index(start.size()) - 1; }
};

/** \internal Groups the columns of a postordered tree into fundamental supernodes, then merges
  * each supernode into the supernode that follows it when that one contains its parent and the
  * relaxation rule allows. Only the last column of a resulting supernode has
  * its etree parent outside it. */
template <typename StorageIndex>
void relaxedSupernodes(const std::vector<StorageIndex>& parent, const std::vector<StorageIndex>& colCount,
                       const SupernodeRelaxation& relax, std::vector<StorageIndex>& start) {
  const Index n = Index(parent.size());
  std::vector<StorageIndex> childCount(n, StorageIndex(0));
  for (Index j = 0; j < n; ++j)
    if (parent[j] != -1) ++childCount[parent[j]];
  // Fundamental supernodes: j continues j-1's supernode when j is j-1's parent, j-1 is its only
  // child, and their patterns nest exactly.
  std::vector<StorageIndex> fs;
  for (Index j = 0; j < n; ++j) {
    const bool continues = j > 0 && parent[j - 1] == j && childCount[j] == 1 && colCount[j - 1] == colCount[j] + 1;
    if (!continues) fs.push_back(StorageIndex(j));
  }
  const Index nfs = Index(fs.size());
  fs.push_back(StorageIndex(n));
  std::vector<StorageIndex> colToFs(n);
  for (Index s = 0; s < nfs; ++s)
    for (Index j = fs[s]; j < fs[s + 1]; ++j) colToFs[j] = StorageIndex(s);
  // Per group (keyed by its first fundamental supernode): columns, rows below, true entries.
  std::vector<double> cols(nfs), below(nfs), entries(nfs);
  for (Index s = 0; s < nfs; ++s) {
    cols[s] = double(fs[s + 1] - fs[s]);
    below[s] = double(colCount[fs[s]]) - cols[s];
    double e = 0;
    for (Index j = fs[s]; j < fs[s + 1]; ++j) e += double(colCount[j]);
    entries[s] = e;
  }
  // Going down, s may join the group that starts at s+1 when its parent lies in that group
  // (merged[t] links a fundamental supernode to the group it joined, with path compression).
  std::vector<StorageIndex> fsParent(nfs), merged(nfs, StorageIndex(-1));
  for (Index s = 0; s < nfs; ++s) {
    const Index p = parent[fs[s + 1] - 1];
    fsParent[s] = p == -1 ? StorageIndex(-1) : colToFs[p];
  }
  for (Index s = nfs - 2; s >= 0; --s) {
    if (fsParent[s] == -1) continue;
    Index group = fsParent[s];
    while (merged[group] != -1) group = merged[group];
    for (Index t = fsParent[s]; merged[t] != -1;) {
      const Index next = merged[t];
      merged[t] = StorageIndex(group);
      t = next;
    }
    if (group != s + 1) continue;
    const double ns = cols[s] + cols[s + 1];
    const double stored = ns * (ns + 1) / 2 + ns * below[s + 1];
    const double zeros = stored - (entries[s] + entries[s + 1]);
    const double fraction = stored > 0 ? zeros / stored : 0;
    bool merge = ns <= relax.nrelax[0] || zeros <= 0;
    if (!merge)
      merge = (ns <= relax.nrelax[1] && fraction < relax.zrelax[0]) ||
              (ns <= relax.nrelax[2] && fraction < relax.zrelax[1]) || fraction < relax.zrelax[2];
    if (merge) {
      cols[s] = ns;
      below[s] = below[s + 1];
      entries[s] += entries[s + 1];
      merged[s + 1] = StorageIndex(s);
    }
  }
  start.clear();
  for (Index s = 0; s < nfs; ++s)
    if (merged[s] == -1) start.push_back(fs[s]);
  start.push_back(StorageIndex(n));
}

/** \internal Fills the supernodal tree and the row structure of every supernode: the union of
  * the supernode's columns of C and of its children's rows below them. */
template <typename StorageIndex>
void supernodeRowStructure(const CompressedPattern<StorageIndex>& lower, const std::vector<StorageIndex>& parent,
                           SupernodalPartition<StorageIndex>& part) {
  const Index n = lower.size();
  const Index ns = part.count();
  part.colToSuper.resize(n);
  for (Index s = 0; s < ns; ++s)
    for (Index j = part.start[s]; j < part.start[s + 1]; ++j) part.colToSuper[j] = StorageIndex(s);
  part.parent.assign(ns, StorageIndex(-1));
  std::vector<StorageIndex> head(ns, StorageIndex(-1)), next(ns, StorageIndex(-1));
  for (Index s = ns - 1; s >= 0; --s) {
    const Index p = parent[part.start[s + 1] - 1];
    if (p == -1) continue;
    part.parent[s] = part.colToSuper[p];
    next[s] = head[part.parent[s]];
    head[part.parent[s]] = StorageIndex(s);
  }
  std::vector<StorageIndex> mark(n, StorageIndex(-1));
  part.rowPtr.assign(ns + 1, 0);
  part.rowIdx.clear();
  for (Index s = 0; s < ns; ++s) {
    const Index f = part.start[s], l = part.start[s + 1] - 1;
    const Index begin = Index(part.rowIdx.size());
    for (Index j = f; j <= l; ++j) part.rowIdx.push_back(StorageIndex(j));
    for (Index j = f; j <= l; ++j)
      for (Index p = lower.ptr[j]; p < lower.ptr[j + 1]; ++p) {
        const Index i = lower.idx[p];
        if (i > l && mark[i] != s) {
          mark[i] = StorageIndex(s);
          part.rowIdx.push_back(StorageIndex(i));
        }
      }
    for (Index c = head[s]; c != -1; c = next[c])
      for (Index p = part.rowPtr[c]; p < part.rowPtr[c + 1]; ++p) {
        const Index i = part.rowIdx[p];
        if (i > l && mark[i] != s) {
          mark[i] = StorageIndex(s);
          part.rowIdx.push_back(StorageIndex(i));
        }
      }
    std::sort(part.rowIdx.begin() + begin + (l - f + 1), part.rowIdx.end());
    part.rowPtr[s + 1] = Index(part.rowIdx.size());
  }
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SYMBOLIC_H
