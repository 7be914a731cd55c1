#include "fit/normal_equations.h"

#include <cmath>
#include <stdexcept>

namespace relief::fit {

NormalEquations::NormalEquations(int rows, int cols, int half)
    : rows_(rows), cols_(cols), half_(std::max(half, 2)), width_(2 * std::max(half, 2) + 1) {
    const size_t n = static_cast<size_t>(rows) * cols;
    m_.assign(n * width_ * width_, 0.0);
    p_.assign(n * width_ * width_, 0.0);
    rhs_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
}

void NormalEquations::addPair(int p, int q, double v, std::vector<double>& store) {
    const int dr = q / cols_ - p / cols_, dc = q % cols_ - p % cols_;
    store[slot(p, dr, dc)] += v;
}

void NormalEquations::addSample(const SurfaceRow& row, double z) {
    // The stencil holds offsets up to half_: a wider row (a basis whose span was not passed) would write
    // into another offset's slot.
    for (const auto* axis : {&row.x, &row.y})
        if (!axis->empty() && axis->back().first - axis->front().first > half_)
            throw std::logic_error("fit: a sample weighs on nodes further apart than the normal equations hold");
    // w = wy (x) wx: the pairs of nodes, (ry, cx) and (ry', cx'), each once.
    for (const auto& [r1, wy1] : row.y)
        for (const auto& [c1, wx1] : row.x) {
            const int p = r1 * cols_ + c1;
            const double wp = wy1 * wx1;
            rhs_[p] += wp * z;
            for (const auto& [r2, wy2] : row.y) {
                const double wpy = wp * wy2;
                const size_t base = slot(p, r2 - r1, 0);
                for (const auto& [c2, wx2] : row.x) m_[base + static_cast<size_t>(c2 - c1)] += wpy * wx2;
            }
        }
    zz_ += z * z;
    ++samples_;
}

void NormalEquations::addThinPlate(double dx, double dy) {
    const double area = dx * dy;
    // One row of D at a time: its nodes and coefficients; P += d d'.
    auto add = [&](std::initializer_list<std::pair<int, double>> terms, double scale) {
        for (const auto& [p, a] : terms)
            for (const auto& [q, b] : terms) addPair(p, q, scale * a * b, p_);
    };
    for (int r = 0; r < rows_; ++r)
        for (int c = 0; c < cols_; ++c) {
            const int n = r * cols_ + c;
            if (c >= 1 && c + 1 < cols_) add({{n - 1, 1}, {n, -2}, {n + 1, 1}}, area / std::pow(dx, 4));
            if (r >= 1 && r + 1 < rows_) add({{n - cols_, 1}, {n, -2}, {n + cols_, 1}}, area / std::pow(dy, 4));
            if (r + 1 < rows_ && c + 1 < cols_)
                add({{n, 1}, {n + 1, -1}, {n + cols_, -1}, {n + cols_ + 1, 1}}, 2 * area / (dx * dx * dy * dy));
        }
}

void NormalEquations::toSparse(Eigen::SparseMatrix<double>& m, Eigen::SparseMatrix<double>& p) const {
    using Triplet = Eigen::Triplet<double>;
    std::vector<Triplet> mt, pt;
    const int n = rows_ * cols_;
    for (int node = 0; node < n; ++node) {
        const int r = node / cols_, c = node % cols_;
        for (int dr = -half_; dr <= half_; ++dr)
            for (int dc = -half_; dc <= half_; ++dc) {
                const int r2 = r + dr, c2 = c + dc;
                if (r2 < 0 || r2 >= rows_ || c2 < 0 || c2 >= cols_) continue;
                const int q = r2 * cols_ + c2;
                if (q < node) continue;  // the lower triangle: row q >= column node
                const double a = m_[slot(node, dr, dc)], b = p_[slot(node, dr, dc)];
                if (a == 0 && b == 0) continue;
                mt.emplace_back(q, node, a);  // both patterns alike, zeros kept
                pt.emplace_back(q, node, b);
            }
    }
    m.resize(n, n);
    p.resize(n, n);
    m.setFromTriplets(mt.begin(), mt.end());
    p.setFromTriplets(pt.begin(), pt.end());
}

}  // namespace relief::fit
