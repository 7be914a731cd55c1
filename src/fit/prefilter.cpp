#include "fit/prefilter.h"

#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fit/basis.h"

namespace relief::fit {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// An axis's refined values at the net's own nodes (refined index m^d i) as weights on the nodes.
Sparse nodeMatrix(const AxisBasis& b, long long stride) {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < b.nodes; ++i)
        for (const auto& [node, w] : b.weights[static_cast<size_t>(i * stride)]) t.emplace_back(i, node, w);
    Sparse k(b.nodes, b.nodes);
    k.setFromTriplets(t.begin(), t.end());
    return k;
}

bool isIdentity(const Sparse& k) {
    for (int c = 0; c < k.outerSize(); ++c)
        for (Sparse::InnerIterator it(k, c); it; ++it)
            if (it.value() != (it.row() == it.col() ? 1.0 : 0.0)) return false;
    return true;
}

// The filter's gain at the net's own frequency (+1, -1, +1, ...): how much
// undoing it amplifies the finest detail.
double nyquistGain(const Sparse& k) {
    Eigen::VectorXd alternating(k.cols());
    for (Eigen::Index i = 0; i < k.cols(); ++i) alternating[i] = i % 2 ? -1 : 1;
    const Eigen::VectorXd response = k * alternating;
    const Eigen::Index mid = k.cols() / 2;
    return 1 / std::max(std::abs(response[mid]), 1e-300);
}

}  // namespace

std::optional<PrefilterReport> prefilterNet(const subdiv::Scheme& scheme, int depth, const scene::NetSpec& spec,
                                            geo::ControlNet& net, Diagnostics& diags) {
    const SourceLoc at = spec.locs.at("net.fit");
    PrefilterReport report;
    report.depth = depth;
    const long long stride = std::llround(std::pow(scheme.arity, depth));
    const Sparse kx = nodeMatrix(axisBasis(scheme, net.cols(), depth), stride);
    const Sparse ky = nodeMatrix(axisBasis(scheme, net.rows(), depth), stride);
    if (isIdentity(kx) && isIdentity(ky)) {
        diags.warning(at, fmt::format("net.fit = true does nothing: {} interpolates, its surface passes through the "
                                      "net already",
                                      scheme.name));
        return report;
    }
    report.gain = std::max(nyquistGain(kx), nyquistGain(ky));
    Eigen::SparseLU<Sparse> lx, ly;
    lx.compute(kx);
    ly.compute(ky);
    if (lx.info() != Eigen::Success || ly.info() != Eigen::Success || !(report.gain <= kMaxPrefilterGain)) {
        diags.error(at, fmt::format("net.fit = true: {}'s surface cannot be made to pass through the net: its filter "
                                    "at the net's finest detail is {:.3g} (undoing it would amplify that detail {:.3g} "
                                    "times, at most {} is allowed); choose parameters further from the scheme's "
                                    "smoothest, or leave net.fit out",
                                    scheme.name, 1 / report.gain, report.gain, kMaxPrefilterGain));
        return std::nullopt;
    }
    const int rows = net.rows(), cols = net.cols();
    Eigen::MatrixXd v(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) v(r, c) = net.grid.at(r, c).z;
    // W = V Kx^-T, a row at a time; Z = Ky^-1 W, a column at a time.
    Eigen::MatrixXd w(rows, cols);
    for (int r = 0; r < rows; ++r) w.row(r) = lx.solve(Eigen::VectorXd(v.row(r).transpose())).transpose();
    Eigen::MatrixXd z(rows, cols);
    for (int c = 0; c < cols; ++c) z.col(c) = ly.solve(Eigen::VectorXd(w.col(c)));
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            report.largestChangeM = std::max(report.largestChangeM, std::abs(z(r, c) - v(r, c)));
            net.grid.at(r, c).z = z(r, c);
        }
    return report;
}

}  // namespace relief::fit
