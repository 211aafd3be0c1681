// Test matrix generators: sparsity patterns (random, banded, dense, diagonal, tridiagonal, arrows,
// star, 2-D and 3-D grids, disconnected blocks, relabelled, ...), Hermitian positive definite
// values on a pattern with a known lower bound on the smallest eigenvalue, and the forms in which
// a symmetric matrix is handed to the solver (both triangles, one triangle, garbage in the other).
// All randomness is seeded: every run sees the same matrices.
#ifndef UC_TEST_MATRICES_H
#define UC_TEST_MATRICES_H

#include "test_config.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace uctest {

/** A symmetric sparsity pattern: n and the strictly lower off-diagonal entries (i > j), each once. */
struct Pattern {
  Index n = 0;
  std::vector<std::pair<Index, Index>> edges;

  void add(Index i, Index j) {
    if (i == j) return;
    if (i < j) std::swap(i, j);
    edges.emplace_back(i, j);
  }
  void normalize() {
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  }
};

inline Pattern diagonalPattern(Index n) {
  Pattern p;
  p.n = n;
  return p;
}

inline Pattern densePattern(Index n) {
  Pattern p;
  p.n = n;
  for (Index j = 0; j < n; ++j)
    for (Index i = j + 1; i < n; ++i) p.add(i, j);
  return p;
}

inline Pattern tridiagonalPattern(Index n) {
  Pattern p;
  p.n = n;
  for (Index i = 1; i < n; ++i) p.add(i, i - 1);
  return p;
}

/** Arrow: diagonal plus one dense row/column. headLast: the dense one is the last (no fill in the
  * natural order); otherwise the first (the natural order fills the whole matrix). */
inline Pattern arrowPattern(Index n, bool headLast) {
  Pattern p;
  p.n = n;
  const Index head = headLast ? n - 1 : 0;
  for (Index i = 0; i < n; ++i) p.add(i, head);
  p.normalize();
  return p;
}

/** Star graph whose hub is vertex `hub` (in the middle of the numbering), plus a few leaf-leaf edges
  * away from the hub so that the tree is not trivial. */
inline Pattern starPattern(Index n, Index hub) {
  Pattern p;
  p.n = n;
  for (Index i = 0; i < n; ++i) p.add(i, hub);
  p.normalize();
  return p;
}

/** Path graph numbered in a scrambled way (deep, thin elimination tree under most orderings). */
inline Pattern scrambledPathPattern(Index n, std::mt19937& g) {
  std::vector<Index> order(n);
  for (Index i = 0; i < n; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), g);
  Pattern p;
  p.n = n;
  for (Index i = 1; i < n; ++i) p.add(order[i], order[i - 1]);
  p.normalize();
  return p;
}

/** 5-point grid graph of nx * ny vertices. */
inline Pattern gridPattern(Index nx, Index ny) {
  Pattern p;
  p.n = nx * ny;
  for (Index y = 0; y < ny; ++y)
    for (Index x = 0; x < nx; ++x) {
      const Index v = y * nx + x;
      if (x + 1 < nx) p.add(v, v + 1);
      if (y + 1 < ny) p.add(v, v + nx);
    }
  p.normalize();
  return p;
}

/** 7-point grid graph of nx * ny * nz vertices: large separators, hence large dense supernodes
  * near the root (where threaded BLAS is used). */
inline Pattern grid3dPattern(Index nx, Index ny, Index nz) {
  Pattern p;
  p.n = nx * ny * nz;
  for (Index z = 0; z < nz; ++z)
    for (Index y = 0; y < ny; ++y)
      for (Index x = 0; x < nx; ++x) {
        const Index v = (z * ny + y) * nx + x;
        if (x + 1 < nx) p.add(v, v + 1);
        if (y + 1 < ny) p.add(v, v + nx);
        if (z + 1 < nz) p.add(v, v + nx * ny);
      }
  p.normalize();
  return p;
}

/** Erdos-Renyi-like random graph with about avgDegree off-diagonal entries per row. */
inline Pattern randomPattern(Index n, double avgDegree, std::mt19937& g) {
  Pattern p;
  p.n = n;
  if (n < 2) return p;
  const double pairs = double(n) * double(n - 1) / 2;
  const double m = std::min(pairs, avgDegree * double(n) / 2);
  if (m > 0.3 * pairs) {  // dense-ish: flip a coin per pair
    std::bernoulli_distribution coin(m / pairs);
    for (Index j = 0; j < n; ++j)
      for (Index i = j + 1; i < n; ++i)
        if (coin(g)) p.add(i, j);
  } else {
    std::uniform_int_distribution<Index> pick(0, n - 1);
    for (Index k = 0; k < Index(m); ++k) p.add(pick(g), pick(g));
  }
  p.normalize();
  return p;
}

/** Random entries within a band of half-width bw, each present with probability prob, plus a
  * few long-range entries (like a mesh numbered along a sweep). */
inline Pattern bandedRandomPattern(Index n, Index bw, double prob, std::mt19937& g) {
  Pattern p;
  p.n = n;
  std::bernoulli_distribution coin(prob);
  for (Index j = 0; j < n; ++j)
    for (Index i = j + 1; i < std::min(n, j + bw + 1); ++i)
      if (coin(g)) p.add(i, j);
  std::uniform_int_distribution<Index> pick(0, std::max<Index>(n - 1, 0));
  for (Index k = 0; k < n / 50; ++k) p.add(pick(g), pick(g));
  p.normalize();
  return p;
}

/** Block diagonal: the given patterns side by side, disconnected from each other. */
inline Pattern blockDiagonal(const std::vector<Pattern>& blocks) {
  Pattern p;
  for (const Pattern& b : blocks) {
    for (auto e : b.edges) p.add(e.first + p.n, e.second + p.n);
    p.n += b.n;
  }
  p.normalize();
  return p;
}

/** Relabels the vertices of p with a random permutation. */
inline Pattern shuffled(const Pattern& p, std::mt19937& g) {
  std::vector<Index> perm(p.n);
  for (Index i = 0; i < p.n; ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), g);
  Pattern q;
  q.n = p.n;
  for (auto e : p.edges) q.add(perm[e.first], perm[e.second]);
  q.normalize();
  return q;
}

template <typename Scalar>
Scalar randomOffDiagonal(std::mt19937& g) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Scalar(u(g));
}
template <>
inline std::complex<float> randomOffDiagonal<std::complex<float>>(std::mt19937& g) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double re = u(g), im = u(g);
  return std::complex<float>(float(re), float(im));
}
template <>
inline std::complex<double> randomOffDiagonal<std::complex<double>>(std::mt19937& g) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double re = u(g), im = u(g);
  return std::complex<double>(re, im);
}

enum class Signs {
  Random,   // off-diagonal values of random sign (random phase for complex)
  Negative  // real negative off-diagonal values: a weighted graph Laplacian + margin*I, whose
            // smallest eigenvalue is close to margin (ill-conditioned for a small margin)
};

/** Hermitian positive definite matrix with pattern p (both triangles stored, column-major).
  * Diagonal = sum of the moduli of the row's off-diagonal entries + margin, so every eigenvalue
  * is >= margin (Gershgorin). */
template <typename Scalar, typename StorageIndex>
Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex> spdFromPattern(const Pattern& p, std::mt19937& g,
                                                                          double margin = 1.0,
                                                                          Signs signs = Signs::Random) {
  typedef typename Eigen::NumTraits<Scalar>::Real Real;
  std::vector<Eigen::Triplet<Scalar, StorageIndex>> t;
  t.reserve(2 * p.edges.size() + p.n);
  std::vector<double> rowSum(p.n, 0.0);
  std::uniform_real_distribution<double> w(0.1, 1.0);
  for (auto e : p.edges) {
    Scalar v = signs == Signs::Negative ? Scalar(-w(g)) : randomOffDiagonal<Scalar>(g);
    const double a = double(std::abs(v));
    rowSum[e.first] += a;
    rowSum[e.second] += a;
    t.emplace_back(StorageIndex(e.first), StorageIndex(e.second), v);
    t.emplace_back(StorageIndex(e.second), StorageIndex(e.first), Eigen::numext::conj(v));
  }
  for (Index i = 0; i < p.n; ++i) t.emplace_back(StorageIndex(i), StorageIndex(i), Scalar(Real(rowSum[i] + margin)));
  Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex> A(p.n, p.n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

/** The same pattern as A with new random values (same sign model, same margin). Used for
  * refactorizations on an analysed pattern. */
template <typename Scalar, typename StorageIndex>
Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex> revalued(
    const Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex>& A, std::mt19937& g, double margin = 1.0) {
  Pattern p;
  p.n = A.rows();
  for (Index j = 0; j < A.outerSize(); ++j)
    for (typename Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex>::InnerIterator it(A, j); it; ++it)
      if (it.row() > j) p.add(it.row(), j);
  p.normalize();
  return spdFromPattern<Scalar, StorageIndex>(p, g, margin);
}

/** How a symmetric matrix is handed to the solver. */
enum class Storage {
  Full,             // both triangles
  TriangleOnly,     // only the triangle UpLo names (e.g. upper-only input read with Upper)
  GarbageElsewhere  // the triangle UpLo names, and arbitrary values (huge, non-symmetric, one NaN)
                    // in the other strict triangle, which the solver must not read
};

inline std::string storageName(Storage s) {  // (std::string: doctest 2.4.9 prints a const char* as a pointer)
  return s == Storage::Full ? "both triangles" : s == Storage::TriangleOnly ? "one triangle only"
                                                                             : "garbage in the unread triangle";
}

/** Converts the canonical full matrix into the configuration's input type and storage form. */
template <typename Cfg>
typename Cfg::MatrixType toInput(const typename Cfg::FullMatrix& A, Storage s = Storage::Full, unsigned seed = 1) {
  typedef typename Cfg::Scalar Scalar;
  typedef typename Cfg::FullMatrix FullMatrix;
  typename Cfg::MatrixType M;
  if (s == Storage::Full) {
    M = A;
  } else if (s == Storage::TriangleOnly) {
    FullMatrix T = A.template triangularView<Cfg::UpLo>();
    M = T;
  } else {
    std::mt19937 g(seed);
    FullMatrix G = A;
    bool nanPlaced = false;
    for (Index j = 0; j < G.outerSize(); ++j)
      for (typename FullMatrix::InnerIterator it(G, j); it; ++it) {
        const bool unread = Cfg::UpLo == Eigen::Lower ? it.row() < it.col() : it.row() > it.col();
        if (!unread) continue;
        if (!nanPlaced) {
          it.valueRef() = Scalar(std::numeric_limits<typename Cfg::RealScalar>::quiet_NaN());
          nanPlaced = true;
        } else {
          it.valueRef() = Scalar(1000) * randomOffDiagonal<Scalar>(g);
        }
      }
    M = G;
  }
  M.makeCompressed();
  return M;
}

/** Scaled copy D A D with D = diag(10^u), u uniform in [-e, e]: badly scaled but exactly as easy for
  * Cholesky (which is invariant to symmetric diagonal scaling up to rounding). */
template <typename Scalar, typename StorageIndex>
Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex> diagonallyScaled(
    const Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex>& A, double e, std::mt19937& g) {
  typedef typename Eigen::NumTraits<Scalar>::Real Real;
  std::uniform_real_distribution<double> u(-e, e);
  Eigen::Matrix<Real, Eigen::Dynamic, 1> d(A.rows());
  for (Index i = 0; i < A.rows(); ++i) d[i] = Real(std::pow(10.0, u(g)));
  Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex> B = A;
  for (Index j = 0; j < B.outerSize(); ++j)
    for (typename Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex>::InnerIterator it(B, j); it; ++it)
      it.valueRef() *= Scalar(d[it.row()] * d[it.col()]);
  return B;
}

template <typename Cfg>
typename Cfg::Dense randomDense(Index rows, Index cols, std::mt19937& g) {
  typename Cfg::Dense B(rows, cols);
  for (Index j = 0; j < cols; ++j)
    for (Index i = 0; i < rows; ++i) B(i, j) = randomOffDiagonal<typename Cfg::Scalar>(g);
  return B;
}

}  // namespace uctest

#endif  // UC_TEST_MATRICES_H
