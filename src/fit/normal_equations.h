#pragma once
// The fit's normal equations (A'A + lambda P) z = A's, assembled node by node
// in a stencil of the neighbours a node can share a sample with, then handed
// to Eigen as one sparse pattern for every lambda tried. Internal to fit/.
#include <Eigen/SparseCore>

#include <vector>

#include "fit/basis.h"

namespace relief::fit {

class NormalEquations {
public:
    /// A net rows x cols; `half`: the largest offset, in nodes along an axis,
    /// between two nodes one sample (or the penalty) weighs on.
    NormalEquations(int rows, int cols, int half);

    /// One sample of height z, its surface `row`: A'A += w w', A's += w z.
    void addSample(const SurfaceRow& row, double z);
    /// The net's thin-plate energy: z_xx^2 + 2 z_xy^2 + z_yy^2 in second
    /// differences, each over its cell's area (dx, dy the spacing).
    void addThinPlate(double dx, double dy);


    /// A'A's and P's lower triangles, one pattern for both.
    void toSparse(Eigen::SparseMatrix<double>& m, Eigen::SparseMatrix<double>& p) const;
    const Eigen::VectorXd& rhs() const { return rhs_; }
    double samplesSquared() const { return zz_; }  ///< s's
    size_t samples() const { return samples_; }
    double diagonal(int node) const { return m_[slot(node, 0, 0)]; }

private:
    size_t slot(int node, int dr, int dc) const {
        return static_cast<size_t>(node) * width_ * width_ + static_cast<size_t>((dr + half_) * width_ + dc + half_);
    }
    void addPair(int p, int q, double v, std::vector<double>& store);
    int rows_, cols_, half_, width_;
    std::vector<double> m_, p_;
    Eigen::VectorXd rhs_;
    double zz_ = 0;
    size_t samples_ = 0;
};

}  // namespace relief::fit
