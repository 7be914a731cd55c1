#pragma once
// CHOLMOD's supernodal LL' of symmetric matrices that share one sparsity
// pattern, each given as its lower triangle: ordered and analysed once, then
// factorized for each matrix. Its dense kernels (BLAS, LAPACK) are relief's own
// on Eigen (dense_kernels.h): the same bits whatever BLAS a machine has, a fit
// in 0.26-0.55 of the simplicial factorization's time. Internal to fit/.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <string>

namespace relief::fit {

class SparseCholesky {
public:
    enum class Factorized { ok, notPositiveDefinite, failed };

    SparseCholesky();
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky&) = delete;
    SparseCholesky& operator=(const SparseCholesky&) = delete;

    /// Orders `lower`'s pattern by nested dissection (METIS), which fills a
    /// net's 2-D stencil by a third less than minimum degree, and analyses it.
    /// False: CHOLMOD failed (status()).
    bool analyse(const Eigen::SparseMatrix<double>& lower);
    /// `other`'s ordering and analysis, copied: a second factorization of the
    /// same pattern, with the same bits, and METIS not run again.
    bool analyseAs(const SparseCholesky& other);
    /// A matrix of the analysed pattern.
    Factorized factorize(const Eigen::SparseMatrix<double>& lower);
    /// C^-1 b; empty when CHOLMOD failed (status()).
    Eigen::VectorXd solve(const Eigen::VectorXd& b);
    /// The sum over B's columns of b' C^-1 b, as ||L^-1 P B||^2, P the
    /// ordering: half the work of solving. NaN when CHOLMOD failed.
    double sumOfInverseForms(const Eigen::MatrixXd& b);
    /// CHOLMOD's status: 0, or its warning (> 0) or error (< 0) code.
    int status() const;
    /// CHOLMOD's code for memory it could not have.
    static constexpr int kOutOfMemory = -2;
    /// An error code in words: "out of memory", ...
    static std::string describe(int status);

private:
    struct Cholmod;  // its common and factor: cholmod.h stays out of the includers
    std::unique_ptr<Cholmod> cholmod_;
};

}  // namespace relief::fit
