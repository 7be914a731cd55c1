#pragma once
// The fit's normal equations (A'A + lambda P) z = A's, assembled node by node
// in a stencil of the neighbours a node can share a sample with, then handed
// to Eigen as one sparse pattern for every lambda tried. Internal to fit/.
#include <Eigen/SparseCore>

#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

#include "fit/basis.h"

namespace relief::fit {

/// Hutchinson's probes of the influence matrix's trace: one 64-bit word of
/// signs a sample.
inline constexpr int kProbes = 64;

class NormalEquations {
public:
    /// A net rows x cols; `half`: the largest offset, in nodes along an axis,
    /// between two nodes one sample (or the penalty) weighs on. `probes`
    /// (0 or kProbes): also sum A'u for that many fixed +-1 probes u over the
    /// samples, for Hutchinson's estimate of the influence matrix's trace.
    /// `folds` (0 or more): also sum each fold's samples apart, for
    /// cross-validation by folds (the equations of all the samples but one
    /// fold's).
    NormalEquations(int rows, int cols, int half, int probes = 0, int folds = 0);

    /// One sample, its surface `row`: A'A += w w', A's += w z; the same into
    /// `fold`'s sums when it is one (0 .. folds - 1).
    void addSample(const SurfaceRow& row, const Vec3& sample, int fold = -1);
    /// The net's thin-plate energy: z_xx^2 + 2 z_xy^2 + z_yy^2 in second
    /// differences, each over its cell's area (dx, dy the spacing).
    void addThinPlate(double dx, double dy);
    /// The net's membrane energy, kept apart: z_x^2 + z_y^2 in first
    /// differences, each over its cell's area (the tension's term).
    void addMembrane(double dx, double dy);


    /// The lower triangles of A'A, the thin plate's and the membrane's
    /// energies, one pattern for all three.
    void toSparse(Eigen::SparseMatrix<double>& m, Eigen::SparseMatrix<double>& thinPlate,
                  Eigen::SparseMatrix<double>& membrane) const;
    const Eigen::VectorXd& rhs() const { return rhs_; }
    /// The lower triangle of A'A and A's of every sample but `fold`'s, in
    /// toSparse's pattern (one analysis factorizes both).
    void withoutFold(int fold, Eigen::SparseMatrix<double>& m, Eigen::VectorXd& rhs) const;
    int folds() const { return static_cast<int>(foldRhs_.size()); }
    /// A'U, nodes x probes: a sample's probe k is bit k of a hash of its x and
    /// y as +-1 (the same on every run and standard library, and whatever the
    /// samples' order: duplicates are merged before a fit).
    Eigen::MatrixXd probeSums() const;
    int probes() const { return probes_; }
    size_t samples() const { return samples_; }
    double diagonal(int node) const { return m_[slot(node, 0, 0)]; }

private:
    size_t slot(int node, int dr, int dc) const {
        return static_cast<size_t>(node) * width_ * width_ + static_cast<size_t>((dr + half_) * width_ + dc + half_);
    }
    void addPair(int p, int q, double v, std::vector<double>& store);
    /// A'A += w w' and A's += w z into `m` and `rhs`.
    void accumulate(const SurfaceRow& row, double z, std::vector<double>& m, Eigen::VectorXd& rhs) const;
    /// The lower triangles of the stores given, one pattern for all: a slot
    /// is kept where any of A'A's and the energies' is not zero.
    void toSparse(std::initializer_list<std::pair<const std::vector<double>*, Eigen::SparseMatrix<double>*>> out) const;
    /// store += scale d d', d one row of a difference operator (its nodes and coefficients).
    void addOuter(std::initializer_list<std::pair<int, double>> d, double scale, std::vector<double>& store);
    int rows_, cols_, half_, width_, probes_;
    std::vector<double> m_, p_, membrane_, probeSums_;  ///< probeSums_: node-major, probes_ a node
    Eigen::VectorXd rhs_;
    std::vector<std::vector<double>> foldM_;  ///< each fold's A'A, as m_
    std::vector<Eigen::VectorXd> foldRhs_;
    size_t samples_ = 0;
};

}  // namespace relief::fit
