// DenseKernels.h — the dense kernels of the supernodal factorization and solve (paper §3.4):
// Cholesky of a diagonal block (potrf), triangular solves (trsm/trsv), the Hermitian rank-k
// update that forms a supernode's update matrix (syrk/herk) and the products of the solve
// (gemm/gemv). All matrices are column-major with explicit leading dimensions.
//
// For float, double, complex<float> and complex<double> the kernels call BLAS/LAPACK (OpenBLAS)
// when EIGEN_UPDATABLE_CHOLESKY_USE_BLAS is defined (the CMake target defines it). OpenBLAS's
// ?trsm runs at about a third of its ?gemm's speed (28 against 85 GF/s on one core here), so the
// triangular solve of a front goes by panels of 32 columns, each solved by ?trsm and subtracted
// from the rest by ?gemm, and a large diagonal block is factored by halves (potrf, that panel
// solve, herk, potrf): the same algorithms, with most of the work in gemm. For every
// other scalar (e.g. long double), or without BLAS, they use Eigen's own dense code. Tiny
// blocks, where a BLAS call costs more than its arithmetic, take inline loops in all cases.
//
// Failure mode: potrf reports the first column whose pivot is not a positive finite number
// (NaN and Inf included), so that the caller can report NumericalIssue.

#ifndef EIGEN_UPDATABLE_CHOLESKY_DENSE_KERNELS_H
#define EIGEN_UPDATABLE_CHOLESKY_DENSE_KERNELS_H

#include <complex>
#include <cmath>

#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
extern "C" {
// Fortran BLAS / LAPACK with 32-bit integers (Debian's OpenBLAS and reference BLAS).
void spotrf_(const char*, const int*, float*, const int*, int*);
void dpotrf_(const char*, const int*, double*, const int*, int*);
void cpotrf_(const char*, const int*, void*, const int*, int*);
void zpotrf_(const char*, const int*, void*, const int*, int*);
void strsm_(const char*, const char*, const char*, const char*, const int*, const int*, const float*,
            const float*, const int*, float*, const int*);
void dtrsm_(const char*, const char*, const char*, const char*, const int*, const int*, const double*,
            const double*, const int*, double*, const int*);
void ctrsm_(const char*, const char*, const char*, const char*, const int*, const int*, const void*,
            const void*, const int*, void*, const int*);
void ztrsm_(const char*, const char*, const char*, const char*, const int*, const int*, const void*,
            const void*, const int*, void*, const int*);
void ssyrk_(const char*, const char*, const int*, const int*, const float*, const float*, const int*,
            const float*, float*, const int*);
void dsyrk_(const char*, const char*, const int*, const int*, const double*, const double*, const int*,
            const double*, double*, const int*);
void cherk_(const char*, const char*, const int*, const int*, const float*, const void*, const int*,
            const float*, void*, const int*);
void zherk_(const char*, const char*, const int*, const int*, const double*, const void*, const int*,
            const double*, void*, const int*);
void sgemm_(const char*, const char*, const int*, const int*, const int*, const float*, const float*,
            const int*, const float*, const int*, const float*, float*, const int*);
void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*, const double*,
            const int*, const double*, const int*, const double*, double*, const int*);
void cgemm_(const char*, const char*, const int*, const int*, const int*, const void*, const void*,
            const int*, const void*, const int*, const void*, void*, const int*);
void zgemm_(const char*, const char*, const int*, const int*, const int*, const void*, const void*,
            const int*, const void*, const int*, const void*, void*, const int*);
void sgemv_(const char*, const int*, const int*, const float*, const float*, const int*, const float*,
            const int*, const float*, float*, const int*);
void dgemv_(const char*, const int*, const int*, const double*, const double*, const int*, const double*,
            const int*, const double*, double*, const int*);
void cgemv_(const char*, const int*, const int*, const void*, const void*, const int*, const void*,
            const int*, const void*, void*, const int*);
void zgemv_(const char*, const int*, const int*, const void*, const void*, const int*, const void*,
            const int*, const void*, void*, const int*);
void strsv_(const char*, const char*, const char*, const int*, const float*, const int*, float*, const int*);
void dtrsv_(const char*, const char*, const char*, const int*, const double*, const int*, double*, const int*);
void ctrsv_(const char*, const char*, const char*, const int*, const void*, const int*, void*, const int*);
void ztrsv_(const char*, const char*, const char*, const int*, const void*, const int*, void*, const int*);
// triangular-pentagonal LQ and the application of its Q (LAPACK >= 3.7)
void stplqt_(const int*, const int*, const int*, const int*, float*, const int*, float*, const int*, float*,
             const int*, float*, int*);
void dtplqt_(const int*, const int*, const int*, const int*, double*, const int*, double*, const int*, double*,
             const int*, double*, int*);
void ctplqt_(const int*, const int*, const int*, const int*, void*, const int*, void*, const int*, void*,
             const int*, void*, int*);
void ztplqt_(const int*, const int*, const int*, const int*, void*, const int*, void*, const int*, void*,
             const int*, void*, int*);
void stpmlqt_(const char*, const char*, const int*, const int*, const int*, const int*, const int*, const float*,
              const int*, const float*, const int*, float*, const int*, float*, const int*, float*, int*);
void dtpmlqt_(const char*, const char*, const int*, const int*, const int*, const int*, const int*, const double*,
              const int*, const double*, const int*, double*, const int*, double*, const int*, double*, int*);
void ctpmlqt_(const char*, const char*, const int*, const int*, const int*, const int*, const int*, const void*,
              const int*, const void*, const int*, void*, const int*, void*, const int*, void*, int*);
void ztpmlqt_(const char*, const char*, const int*, const int*, const int*, const int*, const int*, const void*,
              const int*, const void*, const int*, void*, const int*, void*, const int*, void*, int*);
// OpenBLAS thread control; weak so that any other BLAS links too (then these are null).
void openblas_set_num_threads(int) __attribute__((weak));
int openblas_get_num_threads(void) __attribute__((weak));
}
#endif

namespace Eigen {
namespace internal {
namespace updatable_cholesky {

/** \internal Sets the number of threads the BLAS library uses (OpenBLAS only) and returns the
  * previous number, or 0 when the BLAS cannot be controlled. */
inline int setBlasThreads(int threads) {
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if (openblas_set_num_threads && openblas_get_num_threads) {
    int previous = openblas_get_num_threads();
    if (previous != threads) openblas_set_num_threads(threads);
    return previous;
  }
#endif
  EIGEN_UNUSED_VARIABLE(threads);
  return 0;
}

template <typename Scalar> struct BlasTraits { enum { Supported = 0 }; };
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
template <> struct BlasTraits<float> { enum { Supported = 1 }; };
template <> struct BlasTraits<double> { enum { Supported = 1 }; };
template <> struct BlasTraits<std::complex<float> > { enum { Supported = 1 }; };
template <> struct BlasTraits<std::complex<double> > { enum { Supported = 1 }; };

inline void blasPotrf(int n, float* a, int lda, int* info) { spotrf_("L", &n, a, &lda, info); }
inline void blasPotrf(int n, double* a, int lda, int* info) { dpotrf_("L", &n, a, &lda, info); }
inline void blasPotrf(int n, std::complex<float>* a, int lda, int* info) { cpotrf_("L", &n, a, &lda, info); }
inline void blasPotrf(int n, std::complex<double>* a, int lda, int* info) { zpotrf_("L", &n, a, &lda, info); }

#define EIGEN_UC_TRSM(T, F)                                                                          \
  inline void blasTrsm(char side, char trans, int m, int n, const T* a, int lda, T* b, int ldb) {    \
    const T one(1);                                                                                  \
    F(&side, "L", &trans, "N", &m, &n, &one, a, &lda, b, &ldb);                                      \
  }
EIGEN_UC_TRSM(float, strsm_)
EIGEN_UC_TRSM(double, dtrsm_)
EIGEN_UC_TRSM(std::complex<float>, ctrsm_)
EIGEN_UC_TRSM(std::complex<double>, ztrsm_)
#undef EIGEN_UC_TRSM

inline void blasHerk(int n, int k, float alpha, const float* a, int lda, float* c, int ldc, float beta = 1) {
  ssyrk_("L", "N", &n, &k, &alpha, a, &lda, &beta, c, &ldc);
}
inline void blasHerk(int n, int k, double alpha, const double* a, int lda, double* c, int ldc, double beta = 1) {
  dsyrk_("L", "N", &n, &k, &alpha, a, &lda, &beta, c, &ldc);
}
inline void blasHerk(int n, int k, float alpha, const std::complex<float>* a, int lda, std::complex<float>* c, int ldc, float beta = 1) {
  cherk_("L", "N", &n, &k, &alpha, a, &lda, &beta, c, &ldc);
}
inline void blasHerk(int n, int k, double alpha, const std::complex<double>* a, int lda, std::complex<double>* c, int ldc, double beta = 1) {
  zherk_("L", "N", &n, &k, &alpha, a, &lda, &beta, c, &ldc);
}

#define EIGEN_UC_GEMM(T, F)                                                                          \
  inline void blasGemm(char ta, int m, int n, int k, T alpha, const T* a, int lda, const T* b, int ldb, \
                       T beta, T* c, int ldc) {                                                      \
    F(&ta, "N", &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc);                               \
  }                                                                                                  \
  inline void blasGemmAdjointB(int m, int n, int k, T alpha, const T* a, int lda, const T* b, int ldb, \
                               T beta, T* c, int ldc) {                                              \
    F("N", "C", &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc);                               \
  }
#define EIGEN_UC_GEMV(T, F, TRSV)                                                                    \
  inline void blasGemv(char ta, int m, int n, T alpha, const T* a, int lda, const T* x, T beta, T* y) {  \
    const int one = 1;                                                                               \
    F(&ta, &m, &n, &alpha, a, &lda, x, &one, &beta, y, &one);                                        \
  }                                                                                                  \
  inline void blasTrsv(char ta, int n, const T* a, int lda, T* x) {                                  \
    const int one = 1;                                                                               \
    TRSV("L", &ta, "N", &n, a, &lda, x, &one);                                                       \
  }
EIGEN_UC_GEMV(float, sgemv_, strsv_)
EIGEN_UC_GEMV(double, dgemv_, dtrsv_)
EIGEN_UC_GEMV(std::complex<float>, cgemv_, ctrsv_)
EIGEN_UC_GEMV(std::complex<double>, zgemv_, ztrsv_)
#undef EIGEN_UC_GEMV

#define EIGEN_UC_TPLQT(T, LQT, MLQT, TRANS)                                                           \
  inline int blasTplqt(int m, int n, int mb, T* a, int lda, T* b, int ldb, T* t, int ldt, T* work) {    \
    const int l = 0;                                                                                 \
    int info = 0;                                                                                    \
    LQT(&m, &n, &l, &mb, a, &lda, b, &ldb, t, &ldt, work, &info);                                    \
    return info;                                                                                     \
  }                                                                                                  \
  inline int blasTpmlqtRightAdjoint(int m, int n, int k, int mb, const T* v, int ldv, const T* t, int ldt, \
                                    T* a, int lda, T* b, int ldb, T* work) {                         \
    const int l = 0;                                                                                 \
    int info = 0;                                                                                    \
    MLQT("R", TRANS, &m, &n, &k, &l, &mb, v, &ldv, t, &ldt, a, &lda, b, &ldb, work, &info);          \
    return info;                                                                                     \
  }
EIGEN_UC_TPLQT(float, stplqt_, stpmlqt_, "T")
EIGEN_UC_TPLQT(double, dtplqt_, dtpmlqt_, "T")
EIGEN_UC_TPLQT(std::complex<float>, ctplqt_, ctpmlqt_, "C")
EIGEN_UC_TPLQT(std::complex<double>, ztplqt_, ztpmlqt_, "C")
#undef EIGEN_UC_TPLQT

EIGEN_UC_GEMM(float, sgemm_)
EIGEN_UC_GEMM(double, dgemm_)
EIGEN_UC_GEMM(std::complex<float>, cgemm_)
EIGEN_UC_GEMM(std::complex<double>, zgemm_)
#undef EIGEN_UC_GEMM
#endif

/** \internal True when x is a usable Cholesky pivot: real part positive and finite. */
template <typename Scalar>
inline bool isGoodPivot(const Scalar& x) {
  typedef typename NumTraits<Scalar>::Real Real;
  const Real r = numext::real(x);
  return r > Real(0) && (numext::isfinite)(r);
}

/** \internal Below this many multiply-adds a kernel uses inline loops instead of a library call. */
enum { SmallKernelWork = 512 };

/** \internal Unblocked in-place Cholesky of the lower triangle of an n×n block. Returns -1 on
  * success, else the 0-based column whose pivot was not positive and finite. */
template <typename Scalar>
Index smallPotrf(Index n, Scalar* a, Index lda) {
  typedef typename NumTraits<Scalar>::Real Real;
  for (Index k = 0; k < n; ++k) {
    Scalar* ck = a + k * lda;
    Real d = numext::real(ck[k]);
    for (Index j = 0; j < k; ++j) d -= numext::abs2(a[k + j * lda]);
    if (!(d > Real(0)) || !(numext::isfinite)(d)) return k;
    d = std::sqrt(d);
    ck[k] = Scalar(d);
    const Real inv = Real(1) / d;
    for (Index i = k + 1; i < n; ++i) {
      Scalar s = ck[i];
      for (Index j = 0; j < k; ++j) s -= a[i + j * lda] * numext::conj(a[k + j * lda]);
      ck[i] = s * inv;
    }
  }
  return -1;
}

/** \internal Columns per panel of trsmRightLowerAdjoint() (BLAS), and the size above which
  * potrf() splits its block in two (BLAS). */
enum { TrsmPanelColumns = 32, PotrfLeafColumns = 128 };

/** \internal B := B · L^{-H} for the m×n block B and the n×n lower triangular L. */
template <typename Scalar>
void trsmRightLowerAdjoint(Index m, Index n, const Scalar* l, Index ldl, Scalar* b, Index ldb) {
  if (m == 0 || n == 0) return;
  if (m * n * n <= 2 * SmallKernelWork) {
    // Column j of X solves X(:,j) L(j,j)^* = B(:,j) - sum_{k<j} X(:,k) conj(L(j,k)).
    for (Index j = 0; j < n; ++j) {
      Scalar* bj = b + j * ldb;
      for (Index k = 0; k < j; ++k) {
        const Scalar f = numext::conj(l[j + k * ldl]);
        const Scalar* bk = b + k * ldb;
        for (Index i = 0; i < m; ++i) bj[i] -= bk[i] * f;
      }
      const Scalar inv = Scalar(1) / numext::conj(l[j + j * ldl]);
      for (Index i = 0; i < m; ++i) bj[i] *= inv;
    }
    return;
  }
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    // by panels of TrsmPanelColumns columns: each panel is solved by ?trsm, then subtracted
    // from the columns right of it by ?gemm (OpenBLAS's trsm runs at a third of its gemm's
    // speed; this is the same algorithm, with most of the work in gemm)
    for (Index j = 0; j < n; j += Index(TrsmPanelColumns)) {
      const Index w = (std::min)(Index(TrsmPanelColumns), n - j), rest = n - j - w;
      blasTrsm('R', 'C', int(m), int(w), l + j + j * ldl, int(ldl), b + j * ldb, int(ldb));
      if (rest > 0)
        blasGemmAdjointB(int(m), int(rest), int(w), Scalar(-1), b + j * ldb, int(ldb), l + (j + w) + j * ldl, int(ldl),
                         Scalar(1), b + (j + w) * ldb, int(ldb));
    }
    return;
  }
#endif
  Map<const Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > L(l, n, n, OuterStride<>(ldl));
  Map<Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > B(b, m, n, OuterStride<>(ldb));
  L.template triangularView<Lower>().adjoint().template solveInPlace<OnTheRight>(B);
}

/** \internal Lower triangle of C (n×n) += alpha · A · A^H for the n×k block A; with \a overwrite,
  * the lower triangle of C := alpha · A · A^H instead (its previous values are not read, so C
  * needs no zeroing first; the strict upper triangle is left as it is). */
template <typename Scalar>
void herkLower(Index n, Index k, typename NumTraits<Scalar>::Real alpha, const Scalar* a, Index lda, Scalar* c,
               Index ldc, bool overwrite = false) {
  if (n == 0) return;
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    if (overwrite && k > 0 && n * n * k > 2 * SmallKernelWork) {
      blasHerk(int(n), int(k), alpha, a, int(lda), c, int(ldc), typename NumTraits<Scalar>::Real(0));
      return;
    }
  }
#endif
  if (overwrite)
    for (Index j = 0; j < n; ++j) std::fill(c + j * ldc + j, c + j * ldc + n, Scalar(0));
  if (k == 0) return;
  if (n * n * k <= 2 * SmallKernelWork) {
    for (Index j = 0; j < n; ++j) {
      Scalar* cj = c + j * ldc;
      for (Index p = 0; p < k; ++p) {
        const Scalar* ap = a + p * lda;
        const Scalar f = alpha * numext::conj(ap[j]);
        for (Index i = j; i < n; ++i) cj[i] += ap[i] * f;
      }
    }
    return;
  }
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    blasHerk(int(n), int(k), alpha, a, int(lda), c, int(ldc));
    return;
  }
#endif
  Map<const Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > A(a, n, k, OuterStride<>(lda));
  Map<Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > C(c, n, n, OuterStride<>(ldc));
  C.template selfadjointView<Lower>().rankUpdate(A, alpha);
}

/** \internal In-place Cholesky A = L L^H of the lower triangle of the n×n block at a.
  * With BLAS, a block of more than PotrfLeafColumns columns is split in two halves: the first
  * is factored, the second gets its columns of L by trsmRightLowerAdjoint() and its Schur
  * complement by herk, then is factored (recursively; LAPACK's ?potrf at the leaves, whose own
  * blocking goes through the slower ?trsm). \returns -1 on success, else the 0-based column of
  * the first bad pivot. */
template <typename Scalar>
Index potrf(Index n, Scalar* a, Index lda) {
  if (n == 0) return -1;
  if (n * n * n <= 3 * SmallKernelWork) return smallPotrf(n, a, lda);
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    if (n > Index(PotrfLeafColumns)) {
      const Index n1 = (n / 2 + 7) / 8 * 8, n2 = n - n1;
      const Index bad = potrf(n1, a, lda);
      if (bad >= 0) return bad;
      trsmRightLowerAdjoint(n2, n1, a, lda, a + n1, lda);
      herkLower(n2, n1, typename NumTraits<Scalar>::Real(-1), a + n1, lda, a + n1 + n1 * lda, lda);
      const Index bad2 = potrf(n2, a + n1 + n1 * lda, lda);
      return bad2 >= 0 ? n1 + bad2 : -1;
    }
    int info = 0;
    blasPotrf(int(n), a, int(lda), &info);
    if (info > 0) return info - 1;
    if (info < 0) return 0;
  } else
#endif
  {
    Map<Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > m(a, n, n, OuterStride<>(lda));
    Index ret = llt_inplace<Scalar, Lower>::blocked(m);
    if (ret >= 0) return ret;
  }
  // LAPACK implementations differ in whether they catch NaN pivots: check the result.
  for (Index k = 0; k < n; ++k)
    if (!isGoodPivot(a[k + k * lda])) return k;
  return -1;
}

/** \internal Solves L X = B (adjoint=false) or L^H X = B (adjoint=true) in place, for the n×n
  * lower triangular L and the n×k block B. */
template <typename Scalar>
void trsmLeftLower(bool adjoint, Index n, Index k, const Scalar* l, Index ldl, Scalar* b, Index ldb) {
  if (n == 0 || k == 0) return;
  if (n * n * k <= 2 * SmallKernelWork) {
    for (Index c = 0; c < k; ++c) {
      Scalar* x = b + c * ldb;
      if (!adjoint) {
        for (Index j = 0; j < n; ++j) {
          const Scalar* lj = l + j * ldl;
          const Scalar xj = (x[j] /= lj[j]);
          for (Index i = j + 1; i < n; ++i) x[i] -= lj[i] * xj;
        }
      } else {
        for (Index j = n - 1; j >= 0; --j) {
          const Scalar* lj = l + j * ldl;
          Scalar s = x[j];
          for (Index i = j + 1; i < n; ++i) s -= numext::conj(lj[i]) * x[i];
          x[j] = s / numext::conj(lj[j]);
        }
      }
    }
    return;
  }
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    blasTrsm('L', adjoint ? 'C' : 'N', int(n), int(k), l, int(ldl), b, int(ldb));
    return;
  }
#endif
  Map<const Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > L(l, n, n, OuterStride<>(ldl));
  Map<Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > B(b, n, k, OuterStride<>(ldb));
  if (adjoint)
    L.template triangularView<Lower>().adjoint().solveInPlace(B);
  else
    L.template triangularView<Lower>().solveInPlace(B);
}

/** \internal C (m×k) = op(A) · B with op(A) = A (m×n block, adjoint=false) or A^H (A is n×m,
  * adjoint=true); B is n×k. Overwrites C when beta is 0, subtracts from C when beta is 1
  * (then the product is subtracted: C -= op(A) B). */
template <typename Scalar>
void gemmProduct(bool adjoint, bool subtract, Index m, Index k, Index n, const Scalar* a, Index lda,
                 const Scalar* b, Index ldb, Scalar* c, Index ldc) {
  if (m == 0 || k == 0) return;
  if (n == 0) {
    if (!subtract)
      for (Index j = 0; j < k; ++j)
        for (Index i = 0; i < m; ++i) c[i + j * ldc] = Scalar(0);
    return;
  }
  if (m * n * k <= 2 * SmallKernelWork) {
    for (Index j = 0; j < k; ++j) {
      Scalar* cj = c + j * ldc;
      const Scalar* bj = b + j * ldb;
      if (!adjoint) {
        if (!subtract)
          for (Index i = 0; i < m; ++i) cj[i] = Scalar(0);
        const Scalar sign = subtract ? Scalar(-1) : Scalar(1);
        for (Index p = 0; p < n; ++p) {
          const Scalar f = sign * bj[p];
          const Scalar* ap = a + p * lda;
          for (Index i = 0; i < m; ++i) cj[i] += ap[i] * f;
        }
      } else {
        for (Index i = 0; i < m; ++i) {
          const Scalar* ai = a + i * lda;
          Scalar s(0);
          for (Index p = 0; p < n; ++p) s += numext::conj(ai[p]) * bj[p];
          cj[i] = subtract ? cj[i] - s : s;
        }
      }
    }
    return;
  }
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) {
    blasGemm(adjoint ? 'C' : 'N', int(m), int(k), int(n), subtract ? Scalar(-1) : Scalar(1), a, int(lda), b,
             int(ldb), subtract ? Scalar(1) : Scalar(0), c, int(ldc));
    return;
  }
#endif
  Map<const Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > B(b, n, k, OuterStride<>(ldb));
  Map<Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > C(c, m, k, OuterStride<>(ldc));
  if (!adjoint) {
    Map<const Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > A(a, m, n, OuterStride<>(lda));
    if (subtract) C.noalias() -= A * B; else C.noalias() = A * B;
  } else {
    Map<const Matrix<Scalar, Dynamic, Dynamic>, 0, OuterStride<> > A(a, n, m, OuterStride<>(lda));
    if (subtract) C.noalias() -= A.adjoint() * B; else C.noalias() = A.adjoint() * B;
  }
}

/** \internal Below this many matrix entries a matrix-vector kernel uses Eigen's inline code. */
enum { SmallVectorKernelEntries = 4096 };

/** \internal y = A x (adjoint=false; A is m×n) or y -= A^H x (adjoint=true; A is m×n, y has n
  * entries): the two products of a one-column supernodal solve. */
template <typename Scalar>
void gemvProduct(bool adjoint, Index m, Index n, const Scalar* a, Index lda, const Scalar* x, Scalar* y) {
  if (m == 0 || n == 0) {
    if (!adjoint)
      for (Index i = 0; i < m; ++i) y[i] = Scalar(0);
    return;
  }
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) if (m * n >= SmallVectorKernelEntries) {
    blasGemv(adjoint ? 'C' : 'N', int(m), int(n), adjoint ? Scalar(-1) : Scalar(1), a, int(lda), x,
             adjoint ? Scalar(1) : Scalar(0), y);
    return;
  }
#endif
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  typedef Matrix<Scalar, Dynamic, 1> Vector;
  Map<const Dense, 0, OuterStride<> > A(a, m, n, OuterStride<>(lda));
  if (!adjoint)
    Map<Vector>(y, m).noalias() = A * Map<const Vector>(x, n);
  else
    Map<Vector>(y, n).noalias() -= A.adjoint() * Map<const Vector>(x, m);
}

/** \internal x := L^{-1} x (adjoint=false) or L^{-H} x (adjoint=true) for the n×n lower
  * triangular L. */
template <typename Scalar>
void trsvLower(bool adjoint, Index n, const Scalar* l, Index ldl, Scalar* x) {
  if (n == 0) return;
#ifdef EIGEN_UPDATABLE_CHOLESKY_USE_BLAS
  if constexpr (BlasTraits<Scalar>::Supported) if (n * n >= SmallVectorKernelEntries) {
    blasTrsv(adjoint ? 'C' : 'N', int(n), l, int(ldl), x);
    return;
  }
#endif
  typedef Matrix<Scalar, Dynamic, Dynamic> Dense;
  typedef Matrix<Scalar, Dynamic, 1> Vector;
  Map<const Dense, 0, OuterStride<> > L(l, n, n, OuterStride<>(ldl));
  Map<Vector> v(x, n);
  if (adjoint)
    L.template triangularView<Lower>().adjoint().solveInPlace(v);
  else
    L.template triangularView<Lower>().solveInPlace(v);
}

}  // namespace updatable_cholesky
}  // namespace internal
}  // namespace Eigen

#endif  // EIGEN_UPDATABLE_CHOLESKY_DENSE_KERNELS_H
