// relief's BLAS and LAPACK kernels (fit/dense_kernels.h), which CHOLMOD (and any library of the
// process) calls in place of the system's: every flag each routine takes, against the product or
// solve written out with Eigen on whole matrices; they are the ones the process finds.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <dlfcn.h>

#include <cmath>
#include <limits>
#include <random>

#include "fit/dense_kernels.h"

namespace relief::fit {
namespace {

using Eigen::MatrixXd;

// A random matrix, stored with a leading dimension `leading` >= rows (the rows between filled
// with NaN, which a kernel must neither read nor write).
struct Stored {
    int rows, cols, leading;
    std::vector<double> data;
    Stored(int r, int c, unsigned seed, int pad = 3) : rows(r), cols(c), leading(r + pad) {
        std::mt19937 gen(seed);
        std::uniform_real_distribution<double> u(-1, 1);
        data.assign(static_cast<size_t>(leading) * c, std::numeric_limits<double>::quiet_NaN());
        for (int j = 0; j < c; ++j)
            for (int i = 0; i < r; ++i) at(i, j) = u(gen);
    }
    double& at(int i, int j) { return data[static_cast<size_t>(j) * leading + i]; }
    MatrixXd dense() {
        MatrixXd m(rows, cols);
        for (int j = 0; j < cols; ++j)
            for (int i = 0; i < rows; ++i) m(i, j) = at(i, j);
        return m;
    }
    bool paddingUntouched() const {
        for (int j = 0; j < cols; ++j)
            for (int i = rows; i < leading; ++i)
                if (!std::isnan(data[static_cast<size_t>(j) * leading + i])) return false;
        return true;
    }
};

// A well-conditioned triangle's stored matrix: the other triangle is NaN, never to be read.
Stored triangle(int n, bool lower, unsigned seed) {
    Stored t(n, n, seed);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            if (i == j) t.at(i, j) = 2 + std::abs(t.at(i, j));
            else if ((i > j) != lower) t.at(i, j) = std::numeric_limits<double>::quiet_NaN();
            else t.at(i, j) /= n;  // well conditioned at any size
        }
    return t;
}

MatrixXd triangleOf(Stored& t, bool lower, bool unit) {
    MatrixXd m = MatrixXd::Zero(t.rows, t.cols);
    for (int j = 0; j < t.cols; ++j)
        for (int i = 0; i < t.rows; ++i)
            if (i == j) m(i, j) = unit ? 1 : t.at(i, j);
            else if ((i > j) == lower) m(i, j) = t.at(i, j);
    return m;
}

// Small sizes take Eigen's coefficient-wise products; CHOLMOD's supernodes, its blocked ones.
struct Sizes {
    int m, n, k;
};
constexpr Sizes kSizes[] = {{7, 5, 6}, {150, 90, 120}};

TEST(DenseKernels, GemmEveryTransposeAndScale) {
    for (const Sizes size : kSizes)
        for (const char* ta : {"N", "T", "c"})
            for (const char* tb : {"n", "T", "C"})
                for (const double beta : {0.0, 1.0, -0.5}) {
                    const int m = size.m, n = size.n, k = size.k;
                    const bool tA = *ta != 'N' && *ta != 'n', tB = *tb != 'N' && *tb != 'n';
                    Stored a(tA ? k : m, tA ? m : k, 1), b(tB ? n : k, tB ? k : n, 2), c(m, n, 3);
                    if (beta == 0)  // C is not read when beta is 0: NaN in it must not reach the result
                        for (int j = 0; j < n; ++j) c.at(0, j) = std::numeric_limits<double>::quiet_NaN();
                    const MatrixXd A = tA ? a.dense().transpose() : a.dense(), B = tB ? b.dense().transpose() : b.dense();
                    const MatrixXd want = 1.5 * A * B + (beta == 0 ? MatrixXd::Zero(m, n) : MatrixXd(beta * c.dense()));
                    const double alpha = 1.5;
                    dgemm_(ta, tb, &m, &n, &k, &alpha, a.data.data(), &a.leading, b.data.data(), &b.leading, &beta,
                           c.data.data(), &c.leading);
                    EXPECT_LT((c.dense() - want).cwiseAbs().maxCoeff(), 1e-12) << m << ta << tb << beta;
                    EXPECT_TRUE(c.paddingUntouched());
                }
}

// The reference's quick returns: alpha 0 or k 0 with beta 1 leaves C as it was, unread operands
// (NaN here) never reach it; m or n 0 leaves y alone.
TEST(DenseKernels, QuickReturnsLeaveTheOutputAlone) {
    const int m = 4, n = 3, k = 2, zero = 0, one = 1;
    Stored a(m, k, 12), b(k, n, 13), c(m, n, 14);
    for (double& v : a.data) v = std::numeric_limits<double>::quiet_NaN();
    const MatrixXd before = c.dense();
    const double alpha0 = 0, beta1 = 1, alpha = 2;
    dgemm_("N", "N", &m, &n, &k, &alpha0, a.data.data(), &a.leading, b.data.data(), &b.leading, &beta1,
           c.data.data(), &c.leading);
    EXPECT_EQ(c.dense(), before);
    dgemm_("N", "N", &m, &n, &zero, &alpha, a.data.data(), &a.leading, b.data.data(), &b.leading, &beta1,
           c.data.data(), &c.leading);
    EXPECT_EQ(c.dense(), before);
    std::vector<double> y = {5, 6, 7};
    const double beta0 = 0;
    dgemv_("T", &zero, &n, &alpha, a.data.data(), &a.leading, y.data(), &one, &beta0, y.data(), &one);
    EXPECT_EQ(y, (std::vector<double>{5, 6, 7}));
}

TEST(DenseKernels, SyrkWritesOneTriangle) {
    for (const Sizes size : kSizes)
    for (const char* uplo : {"L", "u"})
        for (const char* trans : {"N", "t"}) {
            const int n = size.m, k = size.k;
            const bool lower = *uplo == 'L', t = *trans == 't';
            Stored a(t ? k : n, t ? n : k, 4), c(n, n, 5);
            const MatrixXd before = c.dense(), A = t ? a.dense().transpose() : a.dense();
            const MatrixXd full = -2 * A * A.transpose() + 0.5 * before;
            const double alpha = -2, beta = 0.5;
            dsyrk_(uplo, trans, &n, &k, &alpha, a.data.data(), &a.leading, &beta, c.data.data(), &c.leading);
            const MatrixXd got = c.dense();
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const bool inside = lower ? i >= j : i <= j;
                    EXPECT_NEAR(got(i, j), inside ? full(i, j) : before(i, j), 1e-12) << uplo << trans << i << j;
                }
        }
}

TEST(DenseKernels, TrsmEverySideTriangleAndDiagonal) {
    for (const Sizes size : kSizes)
    for (const char* side : {"L", "r"})
        for (const char* uplo : {"L", "U"})
            for (const char* trans : {"N", "T"})
                for (const char* diag : {"N", "u"}) {
                    const int m = size.m, n = size.n;
                    const bool left = *side == 'L', lower = *uplo == 'L', unit = *diag == 'u';
                    Stored a = triangle(left ? m : n, lower, 6), b(m, n, 7);
                    MatrixXd op = triangleOf(a, lower, unit);
                    if (*trans == 'T') op.transposeInPlace();
                    const MatrixXd rhs = 0.25 * b.dense();
                    const double alpha = 0.25;
                    dtrsm_(side, uplo, trans, diag, &m, &n, &alpha, a.data.data(), &a.leading, b.data.data(),
                           &b.leading);
                    const MatrixXd x = b.dense(), back = left ? MatrixXd(op * x) : MatrixXd(x * op);
                    EXPECT_LT((back - rhs).cwiseAbs().maxCoeff(), 1e-12) << m << side << uplo << trans << diag;
                    EXPECT_TRUE(b.paddingUntouched());
                }
}

TEST(DenseKernels, PotrfFactorsAndNamesTheMinorThatIsNotPositiveDefinite) {
    for (const int n : {8, 200})
        for (const char* uplo : {"L", "U"}) {
            Stored r(n, n, 8);
            const MatrixXd spd = r.dense() * r.dense().transpose() + n * MatrixXd::Identity(n, n);
            Stored a(n, n, 9);
            const auto fill = [&](int bad, double value) {
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) a.at(i, j) = i == j && j == bad ? value : spd(i, j);
            };
            fill(-1, 0);
            int info = -1;
            dpotrf_(uplo, &n, a.data.data(), &a.leading, &info);
            EXPECT_EQ(info, 0);
            const bool lower = *uplo == 'L';
            const MatrixXd f = triangleOf(a, lower, false);
            const MatrixXd product = lower ? MatrixXd(f * f.transpose()) : MatrixXd(f.transpose() * f);
            EXPECT_LT((product - spd).cwiseAbs().maxCoeff(), 1e-10 * n) << n << uplo;
            EXPECT_TRUE(a.paddingUntouched());
            // LAPACK's info: the order of the first leading minor that fails, a negative pivot or NaN.
            const int bad = n - 5;
            fill(bad, -1);
            dpotrf_(uplo, &n, a.data.data(), &a.leading, &info);
            EXPECT_EQ(info, bad + 1) << n << uplo;
            fill(bad, std::numeric_limits<double>::quiet_NaN());
            dpotrf_(uplo, &n, a.data.data(), &a.leading, &info);
            EXPECT_EQ(info, bad + 1) << n << uplo << " NaN";
        }
}

TEST(DenseKernels, GemvAndTrsvWithIncrements) {
    const int m = 5, n = 4;
    Stored a(m, n, 10);
    for (const char* trans : {"N", "T"})
        for (const int inc : {1, 2, -1}) {
            const bool t = *trans == 'T';
            const int nx = t ? m : n, ny = t ? n : m, step = std::abs(inc);
            std::vector<double> x(static_cast<size_t>(nx * step)), y(static_cast<size_t>(ny * step));
            Eigen::VectorXd xv(nx), yv(ny);
            for (int i = 0; i < nx; ++i) xv[i] = 0.3 * i - 1;
            for (int i = 0; i < ny; ++i) yv[i] = 0.1 * i + 2;
            // Element i of a vector with a negative increment is stored from its end.
            const auto slot = [&](int i, int count) { return static_cast<size_t>(inc > 0 ? i * inc : (count - 1 - i) * step); };
            for (int i = 0; i < nx; ++i) x[slot(i, nx)] = xv[i];
            for (int i = 0; i < ny; ++i) y[slot(i, ny)] = yv[i];
            const double alpha = 2, beta = -1;
            dgemv_(trans, &m, &n, &alpha, a.data.data(), &a.leading, x.data(), &inc, &beta, y.data(), &inc);
            const Eigen::VectorXd want = 2 * (t ? MatrixXd(a.dense().transpose()) : a.dense()) * xv - yv;
            for (int i = 0; i < ny; ++i) EXPECT_NEAR(y[slot(i, ny)], want[i], 1e-13) << trans << inc << i;
        }
    for (const char* uplo : {"L", "U"})
        for (const char* trans : {"N", "T"})
            for (const char* diag : {"N", "U"}) {
                std::vector<Eigen::VectorXd> byIncrement;
                for (const int inc : {1, -2}) {
                    const int order = 6, step = std::abs(inc);
                    Stored t = triangle(order, *uplo == 'L', 11);
                    MatrixXd op = triangleOf(t, *uplo == 'L', *diag == 'U');
                    if (*trans == 'T') op.transposeInPlace();
                    Eigen::VectorXd rhs(order);
                    std::vector<double> x(static_cast<size_t>(order * step));
                    const auto slot = [&](int i) { return static_cast<size_t>(inc > 0 ? i * inc : (order - 1 - i) * step); };
                    for (int i = 0; i < order; ++i) x[slot(i)] = rhs[i] = 1.0 / (i + 1);
                    dtrsv_(uplo, trans, diag, &order, t.data.data(), &t.leading, x.data(), &inc);
                    Eigen::VectorXd solved(order);
                    for (int i = 0; i < order; ++i) solved[i] = x[slot(i)];
                    EXPECT_LT((op * solved - rhs).cwiseAbs().maxCoeff(), 1e-13) << uplo << trans << diag << inc;
                    byIncrement.push_back(solved);
                }
                // Solved in place or gathered, the same arithmetic: the same bits.
                EXPECT_EQ(byIncrement[0], byIncrement[1]) << uplo << trans << diag;
            }
}

// The process finds relief's kernels before any library's: CHOLMOD, which calls them by name
// through the dynamic linker, gets these.
TEST(DenseKernels, AreTheOnesTheProcessFinds) {
    EXPECT_EQ(dlsym(RTLD_DEFAULT, "dgemm_"), reinterpret_cast<void*>(&dgemm_));
    EXPECT_EQ(dlsym(RTLD_DEFAULT, "dsyrk_"), reinterpret_cast<void*>(&dsyrk_));
    EXPECT_EQ(dlsym(RTLD_DEFAULT, "dtrsm_"), reinterpret_cast<void*>(&dtrsm_));
    EXPECT_EQ(dlsym(RTLD_DEFAULT, "dpotrf_"), reinterpret_cast<void*>(&dpotrf_));
    EXPECT_EQ(dlsym(RTLD_DEFAULT, "dgemv_"), reinterpret_cast<void*>(&dgemv_));
    EXPECT_EQ(dlsym(RTLD_DEFAULT, "dtrsv_"), reinterpret_cast<void*>(&dtrsv_));
    EXPECT_TRUE(denseKernelsAreTheProcesss());
}

}  // namespace
}  // namespace relief::fit
