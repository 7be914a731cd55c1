#include "fit/sparse_cholesky.h"

#include "fit/dense_kernels.h"

#include <Eigen/CholmodSupport>
#include <fmt/format.h>

#include <array>
#include <limits>
#include <stdexcept>

namespace relief::fit {

static_assert(SparseCholesky::kOutOfMemory == CHOLMOD_OUT_OF_MEMORY);

struct SparseCholesky::Cholmod {
    /// A solve's solution and workspace, which CHOLMOD reuses while their shape stays: each solve
    /// of its own, as a fresh 8 MB block (a 129 x 129 net's 64 probes) is paged in anew by the kernel.
    struct Buffers {
        cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
    };
    enum Use { kSolve, kPermuted, kForward, kUses };

    cholmod_common common;
    cholmod_factor* factor = nullptr;
    std::array<Buffers, kUses> buffers;

    /// The solution of `system` for b, held in `use`'s buffers until that use solves again; null
    /// when CHOLMOD failed.
    const cholmod_dense* solve(int system, const cholmod_dense& b, Use use) {
        cholmod_dense in = b;
        Buffers& at = buffers[use];
        const int done = cholmod_solve2(system, factor, &in, nullptr, &at.x, nullptr, &at.y, &at.e, &common);
        return done && common.status >= CHOLMOD_OK ? at.x : nullptr;
    }
    void release() {
        if (factor) cholmod_free_factor(&factor, &common);
        for (Buffers& b : buffers)
            for (cholmod_dense** d : {&b.x, &b.y, &b.e})
                if (*d) cholmod_free_dense(d, &common);
    }
};

namespace {

// A view of a column-major matrix as CHOLMOD's dense matrix, for reading.
cholmod_dense denseView(const Eigen::MatrixXd& m) {
    cholmod_dense d{};
    d.nrow = static_cast<size_t>(m.rows());
    d.ncol = static_cast<size_t>(m.cols());
    d.nzmax = d.nrow * d.ncol;
    d.d = d.nrow;
    d.x = const_cast<double*>(m.data());  // CHOLMOD's solves do not write their right-hand side
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    return d;
}

cholmod_sparse lowerView(const Eigen::SparseMatrix<double>& lower) {
    if (!lower.isCompressed()) throw std::logic_error("fit: the sparse Cholesky takes compressed matrices");
    return Eigen::viewAsCholmod(lower.selfadjointView<Eigen::Lower>());
}

}  // namespace

SparseCholesky::SparseCholesky() : cholmod_(std::make_unique<Cholmod>()) {
    // Else the machine's BLAS would decide the bits: a build defect, never the user's input.
    if (!denseKernelsAreTheProcesss())
        throw std::logic_error("fit: relief's dense kernels are not the ones this process calls (were they hidden "
                               "at link time?); CHOLMOD would use the machine's BLAS");
    cholmod_common& common = cholmod_->common;
    cholmod_start(&common);
    common.print = 0;  // its warnings would go to stdout
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_asis = 0;
    common.final_ll = 1;  // LL', so that L^-1 alone halves a quadratic form's solve
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NESDIS;
    common.postorder = 1;
}

SparseCholesky::~SparseCholesky() {
    cholmod_->release();
    cholmod_finish(&cholmod_->common);
}

int SparseCholesky::status() const { return cholmod_->common.status; }

std::string SparseCholesky::describe(int status) {
    if (status == CHOLMOD_OUT_OF_MEMORY) return "out of memory";
    if (status == CHOLMOD_TOO_LARGE) return "the net is too large for its indices";
    return fmt::format("status {}", status);
}

bool SparseCholesky::analyse(const Eigen::SparseMatrix<double>& lower) {
    if (cholmod_->factor) cholmod_free_factor(&cholmod_->factor, &cholmod_->common);
    cholmod_sparse a = lowerView(lower);
    cholmod_->factor = cholmod_analyze(&a, &cholmod_->common);
    return cholmod_->factor && cholmod_->common.status >= CHOLMOD_OK;
}

bool SparseCholesky::analyseAs(const SparseCholesky& other) {
    if (cholmod_->factor) cholmod_free_factor(&cholmod_->factor, &cholmod_->common);
    if (!other.cholmod_->factor) throw std::logic_error("fit: an analysis copied from none");
    cholmod_->factor = cholmod_copy_factor(other.cholmod_->factor, &cholmod_->common);
    return cholmod_->factor && cholmod_->common.status >= CHOLMOD_OK;
}

SparseCholesky::Factorized SparseCholesky::factorize(const Eigen::SparseMatrix<double>& lower) {
    if (!cholmod_->factor) throw std::logic_error("fit: a factorization before its analysis");
    cholmod_sparse a = lowerView(lower);
    double beta[2] = {0, 0};
    cholmod_factorize_p(&a, beta, nullptr, 0, cholmod_->factor, &cholmod_->common);
    if (cholmod_->common.status < CHOLMOD_OK) return Factorized::failed;
    // On success minor == n; otherwise the column where it stopped.
    if (cholmod_->factor->minor != cholmod_->factor->n) return Factorized::notPositiveDefinite;
    if (!cholmod_->factor->is_ll) throw std::logic_error("fit: CHOLMOD kept LDL' where LL' was asked for");
    return Factorized::ok;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) {
    const cholmod_dense* x = cholmod_->solve(CHOLMOD_A, denseView(b), Cholmod::kSolve);
    if (!x) return {};
    return Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), b.size());
}

double SparseCholesky::sumOfInverseForms(const Eigen::MatrixXd& b) {
    // b' C^-1 b = b' P' L^-T L^-1 P b = ||L^-1 P b||^2
    const cholmod_dense* permuted = cholmod_->solve(CHOLMOD_P, denseView(b), Cholmod::kPermuted);
    const cholmod_dense* y = permuted ? cholmod_->solve(CHOLMOD_L, *permuted, Cholmod::kForward) : nullptr;
    if (!y) return std::numeric_limits<double>::quiet_NaN();
    return Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(y->x), b.rows(), b.cols()).squaredNorm();
}

}  // namespace relief::fit
