#pragma once
// The dense kernels CHOLMOD's supernodal Cholesky calls (BLAS dgemm, dsyrk,
// dtrsm, dgemv, dtrsv; LAPACK dpotrf), defined by relief on Eigen's. An
// executable's own definitions come before any shared library's, so CHOLMOD
// calls these whichever BLAS the machine has installed (Debian's reference
// BLAS, too slow for the supernodes, or OpenBLAS, whose kernels and so whose
// bits follow the CPU): a fit has the same bits on every x86-64 machine.
// They are the whole process's: every library in it that calls these six
// routines by name (LAPACK's own, Armadillo's through GDAL) gets them too, so
// they keep the reference's meaning to the letter, flags, increments, quick
// returns and LAPACK's info included.
//
// Eigen's blocked products round according to their blocking, which depends
// on the cache sizes Eigen reads from the CPU and on its thread count; both
// are fixed when the program starts, before any call.

namespace relief::fit {

/// Whether the process calls these kernels, where a link that hid them (hidden
/// visibility, --exclude-libs) would leave CHOLMOD on the machine's BLAS.
/// SparseCholesky refuses to factorize otherwise; referencing this also
/// brings the kernels into every executable that factorizes.
bool denseKernelsAreTheProcesss();

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
