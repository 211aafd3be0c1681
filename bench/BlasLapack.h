// BlasLapack: the few Fortran BLAS/LAPACK routines (double, 32-bit integers) that the benchmark
// peers call directly. The prototypes match those of Eigen/src/UpdatableCholesky/DenseKernels.h,
// so both may be seen in one translation unit.

#ifndef UPDATABLE_CHOLESKY_BENCH_BLASLAPACK_H
#define UPDATABLE_CHOLESKY_BENCH_BLASLAPACK_H

extern "C" {
void dpotrf_(const char*, const int*, double*, const int*, int*);
void dpotrs_(const char*, const int*, const int*, const double*, const int*, double*, const int*, int*);
void dtrsm_(const char*, const char*, const char*, const char*, const int*, const int*, const double*,
            const double*, const int*, double*, const int*);
void dsyrk_(const char*, const char*, const int*, const int*, const double*, const double*, const int*,
            const double*, double*, const int*);
void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*, const double*,
            const int*, const double*, const int*, const double*, double*, const int*);
void dgemv_(const char*, const int*, const int*, const double*, const double*, const int*, const double*,
            const int*, const double*, double*, const int*);
void dgetrf_(const int*, const int*, double*, const int*, int*, int*);
void dgetrs_(const char*, const int*, const int*, const double*, const int*, const int*, double*, const int*, int*);
}

#endif // UPDATABLE_CHOLESKY_BENCH_BLASLAPACK_H
