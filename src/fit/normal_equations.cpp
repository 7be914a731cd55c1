#include "fit/normal_equations.h"

#include <array>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace relief::fit {

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
    std::uint64_t z = x + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// A sample's 64 probe signs, from its position's bits.
std::uint64_t probeBits(const Vec3& sample) {
    return splitmix64(splitmix64(std::bit_cast<std::uint64_t>(sample.x)) ^ std::bit_cast<std::uint64_t>(sample.y));
}

}  // namespace

NormalEquations::NormalEquations(int rows, int cols, int half, int probes, int folds)
    : rows_(rows), cols_(cols), half_(std::max(half, 2)), width_(2 * std::max(half, 2) + 1), probes_(probes) {
    if (probes < 0 || probes > kProbes) throw std::logic_error("fit: at most 64 probes, one word of signs a sample");
    const size_t n = static_cast<size_t>(rows) * cols;
    m_.assign(n * width_ * width_, 0.0);
    p_.assign(n * width_ * width_, 0.0);
    membrane_.assign(n * width_ * width_, 0.0);
    probeSums_.assign(n * static_cast<size_t>(probes), 0.0);
    rhs_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
    foldM_.assign(static_cast<size_t>(std::max(folds, 0)), m_);
    foldRhs_.assign(static_cast<size_t>(std::max(folds, 0)), rhs_);
}

void NormalEquations::addPair(int p, int q, double v, std::vector<double>& store) {
    const int dr = q / cols_ - p / cols_, dc = q % cols_ - p % cols_;
    store[slot(p, dr, dc)] += v;
}

void NormalEquations::addSample(const SurfaceRow& row, const Vec3& sample, int fold) {
    // The stencil holds offsets up to half_: a wider row (a basis whose span was not passed) would write
    // into another offset's slot.
    for (const auto* axis : {&row.x, &row.y})
        if (!axis->empty() && axis->back().first - axis->front().first > half_)
            throw std::logic_error("fit: a sample weighs on nodes further apart than the normal equations hold");
    if (fold >= folds()) throw std::logic_error("fit: a sample's fold is not one of the equations' folds");
    accumulate(row, sample.z, m_, rhs_);
    if (fold >= 0) accumulate(row, sample.z, foldM_[static_cast<size_t>(fold)], foldRhs_[static_cast<size_t>(fold)]);
    std::array<double, kProbes> signs{};
    const std::uint64_t bits = probeBits(sample);
    for (int k = 0; k < probes_; ++k) signs[static_cast<size_t>(k)] = (bits >> k) & 1 ? 1.0 : -1.0;
    for (const auto& [r1, wy1] : row.y)
        for (const auto& [c1, wx1] : row.x) {
            double* sums = probeSums_.data() + static_cast<size_t>(r1 * cols_ + c1) * probes_;
            for (int k = 0; k < probes_; ++k) sums[k] += wy1 * wx1 * signs[static_cast<size_t>(k)];
        }
    ++samples_;
}

void NormalEquations::accumulate(const SurfaceRow& row, double z, std::vector<double>& m, Eigen::VectorXd& rhs) const {
    // w = wy (x) wx: the pairs of nodes, (ry, cx) and (ry', cx'), each once.
    for (const auto& [r1, wy1] : row.y)
        for (const auto& [c1, wx1] : row.x) {
            const int p = r1 * cols_ + c1;
            const double wp = wy1 * wx1;
            rhs[p] += wp * z;
            for (const auto& [r2, wy2] : row.y) {
                const double wpy = wp * wy2;
                const size_t base = slot(p, r2 - r1, 0);
                for (const auto& [c2, wx2] : row.x) m[base + static_cast<size_t>(c2 - c1)] += wpy * wx2;
            }
        }
}

void NormalEquations::addOuter(std::initializer_list<std::pair<int, double>> d, double scale, std::vector<double>& store) {
    for (const auto& [p, a] : d)
        for (const auto& [q, b] : d) addPair(p, q, scale * a * b, store);
}

void NormalEquations::addThinPlate(double dx, double dy) {
    const double area = dx * dy;
    for (int r = 0; r < rows_; ++r)
        for (int c = 0; c < cols_; ++c) {
            const int n = r * cols_ + c;
            if (c >= 1 && c + 1 < cols_) addOuter({{n - 1, 1}, {n, -2}, {n + 1, 1}}, area / std::pow(dx, 4), p_);
            if (r >= 1 && r + 1 < rows_) addOuter({{n - cols_, 1}, {n, -2}, {n + cols_, 1}}, area / std::pow(dy, 4), p_);
            if (r + 1 < rows_ && c + 1 < cols_)
                addOuter({{n, 1}, {n + 1, -1}, {n + cols_, -1}, {n + cols_ + 1, 1}}, 2 * area / (dx * dx * dy * dy), p_);
        }
}

void NormalEquations::addMembrane(double dx, double dy) {
    const double area = dx * dy;
    for (int r = 0; r < rows_; ++r)
        for (int c = 0; c < cols_; ++c) {
            const int n = r * cols_ + c;
            if (c + 1 < cols_) addOuter({{n, -1}, {n + 1, 1}}, area / (dx * dx), membrane_);
            if (r + 1 < rows_) addOuter({{n, -1}, {n + cols_, 1}}, area / (dy * dy), membrane_);
        }
}

Eigen::MatrixXd NormalEquations::probeSums() const {
    const Eigen::Index n = static_cast<Eigen::Index>(rows_) * cols_;
    return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(probeSums_.data(), n, probes_);
}

void NormalEquations::toSparse(Eigen::SparseMatrix<double>& m, Eigen::SparseMatrix<double>& thinPlate,
                               Eigen::SparseMatrix<double>& membrane) const {
    toSparse({{&m_, &m}, {&p_, &thinPlate}, {&membrane_, &membrane}});
}

void NormalEquations::withoutFold(int fold, Eigen::SparseMatrix<double>& m, Eigen::VectorXd& rhs) const {
    const std::vector<double>& out = foldM_.at(static_cast<size_t>(fold));
    std::vector<double> kept(m_.size());
    for (size_t i = 0; i < kept.size(); ++i) kept[i] = m_[i] - out[i];
    toSparse({{&kept, &m}});
    rhs = rhs_ - foldRhs_[static_cast<size_t>(fold)];
}

void NormalEquations::toSparse(
    std::initializer_list<std::pair<const std::vector<double>*, Eigen::SparseMatrix<double>*>> out) const {
    const int n = rows_ * cols_;
    for (const auto& [store, matrix] : out) {
        matrix->resize(n, n);
        matrix->reserve(static_cast<Eigen::Index>(n) * (width_ * width_ / 2 + 1));
    }
    // Column by column, rows ascending (dr, then dc): CSC's own order, filled in place.
    for (int node = 0; node < n; ++node) {
        for (const auto& [store, matrix] : out) matrix->startVec(node);
        const int r = node / cols_, c = node % cols_;
        for (int dr = 0; dr <= half_; ++dr)
            for (int dc = -half_; dc <= half_; ++dc) {
                const int r2 = r + dr, c2 = c + dc;
                if (r2 >= rows_ || c2 < 0 || c2 >= cols_ || (dr == 0 && dc < 0)) continue;  // the lower triangle
                const size_t at = slot(node, dr, dc);
                if (m_[at] == 0 && p_[at] == 0 && membrane_[at] == 0) continue;
                // The patterns alike, zeros kept.
                for (const auto& [store, matrix] : out) matrix->insertBack(r2 * cols_ + c2, node) = (*store)[at];
            }
    }
    for (const auto& [store, matrix] : out) matrix->finalize();
}

}  // namespace relief::fit
