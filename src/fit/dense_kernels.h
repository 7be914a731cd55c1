#pragma once
// The dense kernels CHOLMOD's supernodal Cholesky calls (BLAS dgemm, dsyrk,
// dtrsm, dgemv, dtrsv; LAPACK dpotrf), defined by relief on Eigen's. An
// executable's own definitions come before any shared library's, so CHOLMOD
// calls these whichever BLAS the machine has installed (Debian's reference
// BLAS, or OpenBLAS with kernels chosen for the CPU it runs on): a fit has the
// same bits on every x86-64 machine, as the reference BLAS alone, too slow for
// the supernodes, would not give them. Internal to fit/.
//
// Eigen's blocked products round according to their blocking, which depends
// on the cache sizes Eigen reads from the CPU and on its thread count; both
// are fixed here before the first factorization.

namespace relief::fit {

/// Fixes Eigen's dense products to one thread and to fixed cache sizes (once
/// a process; SparseCholesky calls it). Referencing it also brings the
/// kernels into every executable that factorizes.
void fixDenseKernels();

}  // namespace relief::fit

// Fortran's calling convention (every argument by address, matrices column-major with a leading
// dimension; flags are one character, either case), 32-bit integers as Debian's CHOLMOD has them.
extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy);
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx);
}
