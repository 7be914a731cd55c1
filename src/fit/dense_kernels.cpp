#include "fit/dense_kernels.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <dlfcn.h>

#include <cmath>
#include <cstddef>

namespace relief::fit {

namespace {

// Before main: no call, from CHOLMOD or any other library, sees Eigen's own choices.
const bool kEigenFixed = [] {
    Eigen::setNbThreads(1);
    // A common x86-64's L1, L2 and L3 (a mismatch costs speed, never bits).
    Eigen::setCpuCacheSizes(32 * 1024, 1024 * 1024, 8 * 1024 * 1024);
    return true;
}();

}  // namespace

bool denseKernelsAreTheProcesss() {
    return kEigenFixed && dlsym(RTLD_DEFAULT, "dgemm_") == reinterpret_cast<void*>(&dgemm_) &&
           dlsym(RTLD_DEFAULT, "dpotrf_") == reinterpret_cast<void*>(&dpotrf_);
}

namespace {

using DenseMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;
using MatrixAt = Eigen::Map<DenseMatrix, 0, Eigen::OuterStride<>>;
using ConstMatrixAt = Eigen::Map<const DenseMatrix, 0, Eigen::OuterStride<>>;

MatrixAt matrixAt(double* p, int rows, int cols, int leading) {
    return MatrixAt(p, rows, cols, Eigen::OuterStride<>(leading));
}
ConstMatrixAt matrixAt(const double* p, int rows, int cols, int leading) {
    return ConstMatrixAt(p, rows, cols, Eigen::OuterStride<>(leading));
}
bool flagIs(const char* flag, char c) { return (*flag | 0x20) == c; }  // either case; c lower

// op(A) X = B (OnTheLeft) or X op(A) = B (OnTheRight), in place in B; op(A) = A or A', A
// triangular (lower or upper), its diagonal ones when `unit`.
template <int Side, class Triangle>
void solveTriangle(const Triangle& a, bool lower, bool unit, MatrixAt& b) {
    if (lower) unit ? a.template triangularView<Eigen::UnitLower>().template solveInPlace<Side>(b)
                    : a.template triangularView<Eigen::Lower>().template solveInPlace<Side>(b);
    else unit ? a.template triangularView<Eigen::UnitUpper>().template solveInPlace<Side>(b)
              : a.template triangularView<Eigen::Upper>().template solveInPlace<Side>(b);
}

template <int Side>
void solveTriangle(const ConstMatrixAt& a, bool lower, bool transposed, bool unit, MatrixAt& b) {
    if (transposed) solveTriangle<Side>(a.transpose(), !lower, unit, b);
    else solveTriangle<Side>(a, lower, unit, b);
}

// Element i of a BLAS vector of n with increment inc (a negative one walks it from its end).
std::ptrdiff_t elementAt(int i, int n, int inc) {
    return inc > 0 ? static_cast<std::ptrdiff_t>(i) * inc : static_cast<std::ptrdiff_t>(i - n + 1) * inc;
}

}  // namespace

// C functions, declared in this namespace only to reach its helpers: a function of C language
// linkage is one function whatever namespace names it (the header's global dgemm_ is this one).
extern "C" {

// C = alpha op(A) op(B) + beta C (C not read when beta is 0).
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc) {
    if (*m == 0 || *n == 0 || ((*alpha == 0 || *k == 0) && *beta == 1)) return;
    MatrixAt C = matrixAt(c, *m, *n, *ldc);
    if (*beta == 0) C.setZero();
    else if (*beta != 1) C *= *beta;
    if (*k == 0 || *alpha == 0) return;
    const bool ta = !flagIs(transa, 'n'), tb = !flagIs(transb, 'n');
    const ConstMatrixAt A = matrixAt(a, ta ? *k : *m, ta ? *m : *k, *lda);
    const ConstMatrixAt B = matrixAt(b, tb ? *n : *k, tb ? *k : *n, *ldb);
    if (!ta && !tb) C.noalias() += *alpha * A * B;
    else if (!ta) C.noalias() += *alpha * A * B.transpose();
    else if (!tb) C.noalias() += *alpha * A.transpose() * B;
    else C.noalias() += *alpha * A.transpose() * B.transpose();
}

// C = alpha A A' + beta C (trans "N") or alpha A' A + beta C, C's lower or upper triangle only.
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc) {
    if (*n == 0 || ((*alpha == 0 || *k == 0) && *beta == 1)) return;
    MatrixAt C = matrixAt(c, *n, *n, *ldc);
    const bool lower = flagIs(uplo, 'l'), transposed = !flagIs(trans, 'n');
    const auto scale = [&](auto triangle) {
        if (*beta == 0) triangle.setZero();
        else if (*beta != 1) triangle *= *beta;
    };
    lower ? scale(C.triangularView<Eigen::Lower>()) : scale(C.triangularView<Eigen::Upper>());
    if (*k == 0 || *alpha == 0) return;
    const ConstMatrixAt A = matrixAt(a, transposed ? *k : *n, transposed ? *n : *k, *lda);
    if (lower) transposed ? C.selfadjointView<Eigen::Lower>().rankUpdate(A.transpose(), *alpha)
                          : C.selfadjointView<Eigen::Lower>().rankUpdate(A, *alpha);
    else transposed ? C.selfadjointView<Eigen::Upper>().rankUpdate(A.transpose(), *alpha)
                    : C.selfadjointView<Eigen::Upper>().rankUpdate(A, *alpha);
}

// B = alpha op(A)^-1 B (side "L") or alpha B op(A)^-1, A triangular.
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb) {
    if (*m == 0 || *n == 0) return;
    MatrixAt B = matrixAt(b, *m, *n, *ldb);
    if (*alpha == 0) {
        B.setZero();
        return;
    }
    if (*alpha != 1) B *= *alpha;
    const bool left = flagIs(side, 'l');
    const ConstMatrixAt A = matrixAt(a, left ? *m : *n, left ? *m : *n, *lda);
    const bool lower = flagIs(uplo, 'l'), transposed = !flagIs(transa, 'n'), unit = flagIs(diag, 'u');
    if (left) solveTriangle<Eigen::OnTheLeft>(A, lower, transposed, unit, B);
    else solveTriangle<Eigen::OnTheRight>(A, lower, transposed, unit, B);
}

// A = L L' (uplo "L") or U' U in place; info 0, or the order of the first leading minor that is
// not positive definite (a pivot not above 0, or NaN).
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info) {
    *info = 0;
    if (*n == 0) return;
    MatrixAt A = matrixAt(a, *n, *n, *lda);
    // Eigen's in-place factorization, internal for the column where it stopped, which LAPACK reports.
    const Eigen::Index stopped = flagIs(uplo, 'l') ? Eigen::internal::llt_inplace<double, Eigen::Lower>::blocked(A)
                                                   : Eigen::internal::llt_inplace<double, Eigen::Upper>::blocked(A);
    if (stopped >= 0) {
        *info = static_cast<int>(stopped) + 1;
        return;
    }
    for (int j = 0; j < *n; ++j)
        if (std::isnan(A(j, j))) {
            *info = j + 1;
            return;
        }
}

// y = alpha op(A) x + beta y (y not read when beta is 0).
void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy) {
    if (*m == 0 || *n == 0 || (*alpha == 0 && *beta == 1)) return;
    const bool transposed = !flagIs(trans, 'n');
    const int ny = transposed ? *n : *m, nx = transposed ? *m : *n;
    for (int i = 0; i < ny; ++i) {
        double& yi = y[elementAt(i, ny, *incy)];
        yi = *beta == 0 ? 0 : *beta * yi;
    }
    if (*alpha == 0) return;
    const ConstMatrixAt A = matrixAt(a, *m, *n, *lda);
    for (int j = 0; j < *n; ++j) {
        if (transposed) {
            double sum = 0;
            for (int i = 0; i < *m; ++i) sum += A(i, j) * x[elementAt(i, nx, *incx)];
            y[elementAt(j, ny, *incy)] += *alpha * sum;
        } else {
            const double xj = *alpha * x[elementAt(j, nx, *incx)];
            for (int i = 0; i < *m; ++i) y[elementAt(i, ny, *incy)] += xj * A(i, j);
        }
    }
}

// x = op(A)^-1 x, A triangular.
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx) {
    if (*n == 0) return;
    const auto solveColumn = [&](double* column) {
        MatrixAt b = matrixAt(column, *n, 1, *n);
        solveTriangle<Eigen::OnTheLeft>(matrixAt(a, *n, *n, *lda), flagIs(uplo, 'l'), !flagIs(trans, 'n'),
                                        flagIs(diag, 'u'), b);
    };
    if (*incx == 1) return solveColumn(x);
    DenseMatrix column(*n, 1);  // a strided vector, gathered
    for (int i = 0; i < *n; ++i) column(i, 0) = x[elementAt(i, *n, *incx)];
    solveColumn(column.data());
    for (int i = 0; i < *n; ++i) x[elementAt(i, *n, *incx)] = column(i, 0);
}

}  // extern "C"

}  // namespace relief::fit
