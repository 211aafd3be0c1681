// SupernodalSolve.h — supernodal forward and backward substitution with a block of right-hand
// sides (paper §3.1: the solve that follows every factorization or update). Forward: for each
// supernode in postorder, X_S := L11^{-1} X_S, then the rows below receive -L21 X_S (gathered
// product, scattered subtraction). Backward: in reverse order, X_S -= L21^H X_below, then
// X_S := L11^{-H} X_S. X is in the permuted numbering, column-major with leading dimension ldx.
//
// The solve reads the whole factor twice and does two flops per entry read, so it is bound by
// memory traffic and by the fixed cost of each supernode. Small supernodes (the vast majority on
// meshes) and up to four right-hand sides therefore go through inline kernels that read every
// entry of L once per pass for all right-hand sides together, four columns at a time, with no
// library call, while the next column block and the next supernode are prefetched. Large
// supernodes and blocks of more right-hand sides use the BLAS-2/3 kernels of DenseKernels.h.

#ifndef EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H
#define EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H

#include <vector>

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Supernodes up to this many columns are solved with the inline kernels (memory bound
  * there: as fast as BLAS and without its per-call cost); larger ones with BLAS-2/3. */
enum { SmallSolveColumns = 128 };
/** \internal Bytes of the next supernode's block prefetched while the current one is solved. */
enum { SolvePrefetchBytes = 4096 };

/** \internal Asks the memory system for the first bytes of a supernode's block and rows. */
template <typename Scalar, typename StorageIndex>
EIGEN_STRONG_INLINE void prefetchSupernode(const Supernode<Scalar, StorageIndex>& node) {
  const char* v = reinterpret_cast<const char*>(node.values.data());
  const Index bytes = (std::min)(Index(node.values.size() * sizeof(Scalar)), Index(SolvePrefetchBytes));
  for (Index b = 0; b < bytes; b += 64) internal::prefetch(v + b);
  const char* r = reinterpret_cast<const char*>(node.rows.data());
  const Index rowBytes = (std::min)(Index(node.rows.size() * sizeof(StorageIndex)), Index(512));
  for (Index b = 0; b < rowBytes; b += 64) internal::prefetch(r + b);
}

/** \internal Asks the memory system for the cache lines of [begin, end): the next column block of
  * a supernode, requested while the current one is solved (several short column streams in one
  * page defeat the hardware prefetcher). */
template <typename Scalar>
EIGEN_STRONG_INLINE void prefetchRange(const Scalar* begin, const Scalar* end) {
  for (const char* p = reinterpret_cast<const char*>(begin); p < reinterpret_cast<const char*>(end); p += 64)
    internal::prefetch(p);
}

/** \internal A packet with every lane equal to \a x. Real scalars use pset1. Complex ones are
  * built by an unaligned load of an array of copies: Eigen 3.4's pset1 for the complex<float>
  * packets (Packet2cf, Packet4cf, Packet8cf) reads the complex<float> through a double*, which
  * breaks strict aliasing. On a local x[b][c] just written as floats, GCC -O3 then gave the
  * scalar loads of x[b][c] the value of that double load, which type-based alias analysis places
  * before the float stores: x read as uninitialised (0), and the rows below the triangle of a
  * column block got no update (complex<float>, K = 2, SSE2/SSE3 builds). ploadu reads the
  * scalars as floats (doubles for complex<double>), which is well defined. */
template <typename Packet, typename Scalar>
EIGEN_STRONG_INLINE Packet broadcastPacket(const Scalar& x) {
  if constexpr (NumTraits<Scalar>::IsComplex) {
    enum { Size = unpacket_traits<Packet>::size };
    Scalar lanes[Size];
    for (int q = 0; q < Size; ++q) lanes[q] = x;
    return ploadu<Packet>(lanes);
  } else {
    return pset1<Packet>(x);
  }
}

/** \internal One block of B ≤ 4 columns j0.. of a small supernode in the forward pass, for K
  * right-hand sides held in v (nr×K, leading dimension nr, the supernode's rows): solves the B×B
  * diagonal triangle, then v(i,:) -= L(i, block) x_block for every row i below the triangle, in
  * one loop that reads each of the B columns of L once. */
template <int B, int K, typename Scalar>
EIGEN_STRONG_INLINE void forwardColumnBlock(Index nr, Index nc, Index j0, const Scalar* L, Scalar* v) {
  const Scalar* l[B];
  Scalar x[B][K];
  for (int b = 0; b < B; ++b) l[b] = L + (j0 + b) * nr;
  prefetchRange(L + (j0 + B) * nr + j0 + B, L + (std::min)(j0 + 2 * B, nc) * nr);  // the next block
  for (int b = 0; b < B; ++b) {
    const Scalar inverse = Scalar(1) / l[b][j0 + b];  // off the dependency chain of x
    for (int c = 0; c < K; ++c) {
      Scalar t = v[j0 + b + c * nr];
      for (int e = 0; e < b; ++e) t -= l[e][j0 + b] * x[e][c];
      x[b][c] = t * inverse;
      v[j0 + b + c * nr] = x[b][c];
    }
  }
  typedef typename packet_traits<Scalar>::type Packet;
  enum { Size = unpacket_traits<Packet>::size };
  Packet xp[B][K];
  for (int b = 0; b < B; ++b)
    for (int c = 0; c < K; ++c) xp[b][c] = broadcastPacket<Packet>(x[b][c]);
  Index i = j0 + B;
  for (; i + Size <= nr; i += Size) {  // every entry of L is loaded once for the K right-hand sides
    Packet lp[B];
    for (int b = 0; b < B; ++b) lp[b] = ploadu<Packet>(l[b] + i);
    for (int c = 0; c < K; ++c) {
      Packet sum = pmul(lp[0], xp[0][c]);
      for (int b = 1; b < B; ++b) sum = pmadd(lp[b], xp[b][c], sum);
      pstoreu(v + i + c * nr, psub(ploadu<Packet>(v + i + c * nr), sum));
    }
  }
  for (; i < nr; ++i)
    for (int c = 0; c < K; ++c) {
      Scalar sum = l[0][i] * x[0][c];
      for (int b = 1; b < B; ++b) sum += l[b][i] * x[b][c];
      v[i + c * nr] -= sum;
    }
}

/** \internal One block of B ≤ 4 columns j0.. of a small supernode in the backward pass:
  * v(block,:) -= L(i, block)^H v(i,:) over the rows i below the block (one loop reading each of
  * the B columns once), then the B×B triangle L(block, block)^H is solved. */
template <int B, int K, typename Scalar>
EIGEN_STRONG_INLINE void backwardColumnBlock(Index nr, Index j0, const Scalar* L, Scalar* v) {
  typedef typename packet_traits<Scalar>::type Packet;
  enum { Size = unpacket_traits<Packet>::size };
  if (j0 >= 4) prefetchRange(L + (j0 - 4) * nr + j0 - 4, L + j0 * nr);  // the next block (the one before)
  const Scalar* l[B];
  Packet acc[B][K];
  for (int b = 0; b < B; ++b) {
    l[b] = L + (j0 + b) * nr;
    for (int c = 0; c < K; ++c) acc[b][c] = broadcastPacket<Packet>(Scalar(0));
  }
  Index i = j0 + B;
  for (; i + Size <= nr; i += Size) {  // every entry of L is loaded once for the K right-hand sides
    Packet lp[B];
    for (int b = 0; b < B; ++b) lp[b] = pconj(ploadu<Packet>(l[b] + i));
    for (int c = 0; c < K; ++c) {
      const Packet w = ploadu<Packet>(v + i + c * nr);
      for (int b = 0; b < B; ++b) acc[b][c] = pmadd(lp[b], w, acc[b][c]);
    }
  }
  Scalar sum[B][K];
  for (int b = 0; b < B; ++b)
    for (int c = 0; c < K; ++c) sum[b][c] = predux(acc[b][c]);
  for (; i < nr; ++i)
    for (int c = 0; c < K; ++c) {
      const Scalar w = v[i + c * nr];
      for (int b = 0; b < B; ++b) sum[b][c] += numext::conj(l[b][i]) * w;
    }
  for (int b = B - 1; b >= 0; --b) {
    const Scalar inverse = Scalar(1) / numext::conj(l[b][j0 + b]);
    for (int c = 0; c < K; ++c) {
      Scalar t = v[j0 + b + c * nr] - sum[b][c];
      for (int e = b + 1; e < B; ++e) t -= numext::conj(l[b][j0 + e]) * v[j0 + e + c * nr];
      v[j0 + b + c * nr] = t * inverse;
    }
  }
}

/** \internal The column blocks of the forward pass over a small supernode (nr rows, nc columns,
  * block L) for K right-hand sides held in v (nr×K, leading dimension nr). */
template <int K, typename Scalar>
EIGEN_STRONG_INLINE void forwardColumnBlocks(Index nr, Index nc, const Scalar* L, Scalar* v) {
  Index j = 0;
  for (; j + 4 <= nc; j += 4) forwardColumnBlock<4, K>(nr, nc, j, L, v);
  switch (nc - j) {
    case 3: forwardColumnBlock<3, K>(nr, nc, j, L, v); break;
    case 2: forwardColumnBlock<2, K>(nr, nc, j, L, v); break;
    case 1: forwardColumnBlock<1, K>(nr, nc, j, L, v); break;
    default: break;
  }
}

/** \internal Forward pass over one small supernode with K right-hand sides: x_S and zeros for
  * the rows below are laid out contiguously in v, the column blocks run over v, then x_S is
  * written back and the rows below are scattered into X. */
template <int K, typename Scalar, typename StorageIndex>
void forwardSmallSupernode(const Supernode<Scalar, StorageIndex>& node, Scalar* X, Index ldx, Scalar* v) {
  const Index nr = node.nrows(), nc = node.ncols;
  const Scalar* L = node.values.data();
  for (int c = 0; c < K; ++c) {
    const Scalar* xs = X + node.firstCol + c * ldx;
    Scalar* vc = v + c * nr;
    for (Index i = 0; i < nc; ++i) vc[i] = xs[i];
    for (Index i = nc; i < nr; ++i) vc[i] = Scalar(0);
  }
  forwardColumnBlocks<K>(nr, nc, L, v);
  const StorageIndex* rows = node.rows.data();
  for (int c = 0; c < K; ++c) {
    Scalar* xc = X + c * ldx;
    const Scalar* vc = v + c * nr;
    for (Index i = 0; i < nc; ++i) xc[node.firstCol + i] = vc[i];
    for (Index i = nc; i < nr; ++i) xc[rows[i]] += vc[i];
  }
}

/** \internal Backward pass over one small supernode with K right-hand sides: x_S and the
  * gathered rows below in v, the column blocks from the last to the first, x_S written back. */
template <int K, typename Scalar, typename StorageIndex>
void backwardSmallSupernode(const Supernode<Scalar, StorageIndex>& node, Scalar* X, Index ldx, Scalar* v) {
  const Index nr = node.nrows(), nc = node.ncols;
  const Scalar* L = node.values.data();
  const StorageIndex* rows = node.rows.data();
  for (int c = 0; c < K; ++c) {
    const Scalar* xc = X + c * ldx;
    Scalar* vc = v + c * nr;
    for (Index i = 0; i < nc; ++i) vc[i] = xc[node.firstCol + i];
    for (Index i = nc; i < nr; ++i) vc[i] = xc[rows[i]];
  }
  const Index full = nc / 4 * 4;
  switch (nc - full) {
    case 3: backwardColumnBlock<3, K>(nr, full, L, v); break;
    case 2: backwardColumnBlock<2, K>(nr, full, L, v); break;
    case 1: backwardColumnBlock<1, K>(nr, full, L, v); break;
    default: break;
  }
  for (Index j = full - 4; j >= 0; j -= 4) backwardColumnBlock<4, K>(nr, j, L, v);
  for (int c = 0; c < K; ++c) {
    Scalar* xs = X + node.firstCol + c * ldx;
    const Scalar* vc = v + c * nr;
    for (Index i = 0; i < nc; ++i) xs[i] = vc[i];
  }
}

/** \internal Forward pass over one supernode with BLAS kernels, for any number k of right-hand
  * sides (matrix-vector kernels for k = 1). \a work holds below()*k scalars. */
template <typename Scalar, typename StorageIndex>
void forwardLargeSupernode(const Supernode<Scalar, StorageIndex>& node, Scalar* X, Index ldx, Index k, Scalar* work) {
  const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
  const Scalar* L = node.values.data();
  Scalar* xs = X + node.firstCol;
  if (k == 1) {
    trsvLower(false, nc, L, nr, xs);
    if (m == 0) return;
    gemvProduct(false, m, nc, L + nc, nr, xs, work);
  } else {
    trsmLeftLower(false, nc, k, L, nr, xs, ldx);
    if (m == 0) return;
    gemmProduct(false, false, m, k, nc, L + nc, nr, xs, ldx, work, m);
  }
  const StorageIndex* rows = node.rows.data() + nc;
  for (Index c = 0; c < k; ++c) {
    Scalar* xc = X + c * ldx;
    const Scalar* wc = work + c * m;
    for (Index i = 0; i < m; ++i) xc[rows[i]] -= wc[i];
  }
}

/** \internal Backward pass over one supernode with BLAS kernels, for any number k of
  * right-hand sides. \a work holds below()*k scalars. */
template <typename Scalar, typename StorageIndex>
void backwardLargeSupernode(const Supernode<Scalar, StorageIndex>& node, Scalar* X, Index ldx, Index k, Scalar* work) {
  const Index nr = node.nrows(), nc = node.ncols, m = nr - nc;
  const Scalar* L = node.values.data();
  Scalar* xs = X + node.firstCol;
  const StorageIndex* rows = node.rows.data() + nc;
  for (Index c = 0; c < k; ++c) {
    const Scalar* xc = X + c * ldx;
    Scalar* wc = work + c * m;
    for (Index i = 0; i < m; ++i) wc[i] = xc[rows[i]];
  }
  if (k == 1) {
    if (m > 0) gemvProduct(true, m, nc, L + nc, nr, work, xs);
    trsvLower(true, nc, L, nr, xs);
  } else {
    if (m > 0) gemmProduct(true, true, nc, k, m, L + nc, nr, work, m, xs, ldx);
    trsmLeftLower(true, nc, k, L, nr, xs, ldx);
  }
}

/** \internal X := L^{-1} X for K ≤ 4 right-hand sides (K = 0: any number k, BLAS
  * kernels only), one pass over L. \a work holds maxRows()*k scalars. */
template <int K, typename Scalar, typename StorageIndex>
void forwardSolvePass(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Index k, Scalar* work) {
  const Index ns = f.count();
  for (Index s = 0; s < ns; ++s) {
    const auto& node = f.nodes[s];
    if (s + 1 < ns) prefetchSupernode(f.nodes[s + 1]);
    if (K > 0 && node.ncols <= SmallSolveColumns)
      forwardSmallSupernode<(K > 0 ? K : 1)>(node, X, ldx, work);
    else
      forwardLargeSupernode(node, X, ldx, k, work);
  }
}

/** \internal X := L^{-H} X, as forwardSolvePass in reverse. */
template <int K, typename Scalar, typename StorageIndex>
void backwardSolvePass(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Index k, Scalar* work) {
  for (Index s = f.count() - 1; s >= 0; --s) {
    const auto& node = f.nodes[s];
    if (s > 0) prefetchSupernode(f.nodes[s - 1]);
    if (K > 0 && node.ncols <= SmallSolveColumns)
      backwardSmallSupernode<(K > 0 ? K : 1)>(node, X, ldx, work);
    else
      backwardLargeSupernode(node, X, ldx, k, work);
  }
}

/** \internal X := L^{-1} X for the k columns of X. \a work must hold maxRows()*k scalars. */
template <typename Scalar, typename StorageIndex>
void forwardSolve(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Index k, Scalar* work) {
  switch (k) {
    case 1: return forwardSolvePass<1>(f, X, ldx, k, work);
    case 2: return forwardSolvePass<2>(f, X, ldx, k, work);
    case 3: return forwardSolvePass<3>(f, X, ldx, k, work);
    case 4: return forwardSolvePass<4>(f, X, ldx, k, work);
    default: return forwardSolvePass<0>(f, X, ldx, k, work);
  }
}

/** \internal X := L^{-H} X for the k columns of X. \a work must hold maxRows()*k scalars. */
template <typename Scalar, typename StorageIndex>
void backwardSolve(const SupernodalFactor<Scalar, StorageIndex>& f, Scalar* X, Index ldx, Index k, Scalar* work) {
  switch (k) {
    case 1: return backwardSolvePass<1>(f, X, ldx, k, work);
    case 2: return backwardSolvePass<2>(f, X, ldx, k, work);
    case 3: return backwardSolvePass<3>(f, X, ldx, k, work);
    case 4: return backwardSolvePass<4>(f, X, ldx, k, work);
    default: return backwardSolvePass<0>(f, X, ldx, k, work);
  }
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_SUPERNODAL_SOLVE_H
