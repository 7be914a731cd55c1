#include "geo/linear_gridding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>

#include <cpl_error.h>
#include <gdal_alg.h>
#include <ogr_geometry.h>
#include <omp.h>

namespace relief::geo {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Samples per band: bands are triangulated side by side, and fixing their
// number by the sample count alone (not the core count) keeps the output
// the same on every machine.
constexpr size_t kSamplesPerBand = 250000;
constexpr size_t kSamplesForBands = 50000;  // below this, one triangulation is fast enough
constexpr double kFirstMarginSpacings = 8;  // a band's margin, in mean sample spacings
constexpr double kMarginGrowth = 4;
constexpr int kMaxWidenings = 5;  // then the whole set

struct Box {
    double xmin = kInf, xmax = -kInf, ymin = kInf, ymax = -kInf;
};

// Nodes still to compute, row-major, and the margin their samples get.
struct Job {
    std::vector<size_t> nodes;
    double margin = 0;
};

struct JobResult {
    std::vector<size_t> unproven;  // in a triangle not shown to be global
    std::vector<size_t> notFound;  // outside this job's triangulation
    std::string error;
};

struct Triangulation {
    GDALTriangulation* dt = nullptr;
    ~Triangulation() {
        if (dt) GDALTriangulationFree(dt);
    }
};

// The samples ordered by y, to find those outside a band's slab quickly.
struct SamplesByY {
    std::vector<double> y;       // ascending
    std::vector<size_t> sample;  // the sample at each
};

// Whether no sample outside the slab [lo, hi] of y lies strictly inside the
// circle through a, b and c (the samples inside the slab were triangulated,
// so none of them does). Then the triangle is one of the whole set's.
bool circleEmptyOutsideSlab(double ax, double ay, double bx, double by, double cx, double cy,
                            double lo, double hi, const SamplesByY& sorted,
                            const std::vector<double>& xs, const std::vector<double>& ys) {
    bx -= ax, by -= ay, cx -= ax, cy -= ay;  // relative to a: exact enough at UTM magnitudes
    const double d = 2 * (bx * cy - by * cx);
    if (d == 0) return false;
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double ux = (cy * b2 - by * c2) / d, uy = (bx * c2 - cx * b2) / d;
    const double r2 = (ux * ux + uy * uy) * (1 - 1e-9);  // on the circle is not inside
    const double r = std::sqrt(r2), centreX = ax + ux, centreY = ay + uy;
    if (centreY - r >= lo && centreY + r <= hi) return true;
    const auto inside = [&](double from, double to) {  // a sample with y in [from, to) inside?
        auto i = std::lower_bound(sorted.y.begin(), sorted.y.end(), from);
        for (; i != sorted.y.end() && *i < to; ++i) {
            const size_t s = sorted.sample[size_t(i - sorted.y.begin())];
            const double ex = xs[s] - centreX, ey = ys[s] - centreY;
            if (ex * ex + ey * ey < r2) return true;
        }
        return false;
    };
    return !(centreY - r < lo && inside(centreY - r, lo)) &&
           !(centreY + r > hi && inside(std::nextafter(hi, kInf), centreY + r + 1e-300));
}

JobResult runJob(const Job& job, const std::vector<double>& xs, const std::vector<double>& ys,
                 const std::vector<double>& zs, const GridLayout& grid, const Box& data,
                 const SamplesByY& sorted, std::vector<double>& out) {
    JobResult result;
    CPLPushErrorHandler(CPLQuietErrorHandler);  // per thread: the message is returned
    struct PopHandler {
        ~PopHandler() { CPLPopErrorHandler(); }
    } pop;
    double nodeLo = kInf, nodeHi = -kInf;
    for (size_t n : job.nodes) {
        nodeLo = std::min(nodeLo, grid.y(int(n / grid.cols)));
        nodeHi = std::max(nodeHi, grid.y(int(n / grid.cols)));
    }
    // The slab; a side that reaches past the samples is unbounded.
    double lo = nodeLo - job.margin, hi = nodeHi + job.margin;
    if (lo <= data.ymin) lo = -kInf;
    if (hi >= data.ymax) hi = kInf;
    const bool whole = lo == -kInf && hi == kInf;

    std::vector<double> x, y;
    std::vector<size_t> index;
    for (size_t i = 0; i < ys.size(); ++i)
        if (ys[i] >= lo && ys[i] <= hi) index.push_back(i), x.push_back(xs[i]), y.push_back(ys[i]);
    Triangulation t;
    if (index.size() >= 3) t.dt = GDALTriangulationCreateDelaunay(int(index.size()), x.data(), y.data());
    if (!t.dt || !GDALTriangulationComputeBarycentricCoefficients(t.dt, x.data(), y.data())) {
        if (whole) {
            result.error = CPLGetLastErrorMsg();
            if (result.error.empty()) result.error = "the samples have no Delaunay triangulation";
        } else {
            result.unproven = job.nodes;  // too few samples near these nodes: widen
        }
        return result;
    }
    int facet = 0, checkedFacet = -1;
    bool checkedEmpty = false;
    for (size_t n : job.nodes) {
        const double px = grid.x(int(n % grid.cols)), py = grid.y(int(n / grid.cols));
        int found = -1;
        if (!GDALTriangulationFindFacetDirected(t.dt, facet, px, py, &found) || found < 0) {
            if (whole) out[n] = std::numeric_limits<double>::quiet_NaN();
            else result.notFound.push_back(n);
            continue;
        }
        facet = found;
        const int* v = t.dt->pasFacets[found].anVertexIdx;
        if (!whole && found != checkedFacet) {
            checkedFacet = found;
            checkedEmpty = circleEmptyOutsideSlab(x[v[0]], y[v[0]], x[v[1]], y[v[1]], x[v[2]], y[v[2]],
                                                  lo, hi, sorted, xs, ys);
        }
        if (!whole && !checkedEmpty) {
            result.unproven.push_back(n);
            continue;
        }
        double l1 = 0, l2 = 0, l3 = 0;
        GDALTriangulationComputeBarycentricCoordinates(t.dt, found, px, py, &l1, &l2, &l3);
        out[n] = l1 * zs[index[v[0]]] + l2 * zs[index[v[1]]] + l3 * zs[index[v[2]]];
    }
    return result;
}

// The samples' convex hull (GEOS, through OGR), to tell nodes outside it from
// nodes a band's triangulation did not reach.
class Hull {
public:
    Hull(const std::vector<double>& xs, const std::vector<double>& ys) {
        // The hull of a line through the samples is the samples' hull; a line takes them all in
        // one array, where a multipoint grows by one point (and one reallocation) at a time.
        if (xs.size() >= 2) {
            OGRLineString line;
            line.setPoints(int(xs.size()), xs.data(), ys.data());
            hull_.reset(line.ConvexHull());
        } else if (xs.size() == 1) {
            hull_ = std::make_unique<OGRPoint>(xs[0], ys[0]);
        }
        if (hull_) prepared_ = OGRCreatePreparedGeometry(hull_.get());
    }
    ~Hull() {
        if (prepared_) OGRDestroyPreparedGeometry(prepared_);
    }
    Hull(const Hull&) = delete;
    Hull& operator=(const Hull&) = delete;
    /// Unknown (no GEOS) counts as inside: the node is then widened to the whole set.
    bool outside(double x, double y) const {
        if (!prepared_) return false;
        OGRPoint p(x, y);
        return !OGRPreparedGeometryIntersects(prepared_, &p);
    }

private:
    std::unique_ptr<OGRGeometry> hull_;
    OGRPreparedGeometry* prepared_ = nullptr;
};

}  // namespace

std::string gridLinear(const std::vector<double>& xs, const std::vector<double>& ys,
                       const std::vector<double>& zs, const GridLayout& grid, double noData,
                       std::vector<double>& out, LinearGriddingStats* stats, int threads,
                       const std::function<void(double)>& progress) {
    const size_t nodes = size_t(grid.rows) * size_t(grid.cols);
    out.assign(nodes, noData);
    if (xs.empty() || nodes == 0) return {};
    Box data;
    for (size_t i = 0; i < xs.size(); ++i) {
        data.xmin = std::min(data.xmin, xs[i]), data.xmax = std::max(data.xmax, xs[i]);
        data.ymin = std::min(data.ymin, ys[i]), data.ymax = std::max(data.ymax, ys[i]);
    }
    const double spacing =
        std::sqrt(std::max((data.xmax - data.xmin) * (data.ymax - data.ymin), 1e-300) / double(xs.size()));
    const int bands = xs.size() < kSamplesForBands
                          ? 1
                          : int(std::clamp<size_t>((xs.size() + kSamplesPerBand - 1) / kSamplesPerBand, 2,
                                                   size_t(grid.rows)));
    std::vector<Job> jobs(static_cast<size_t>(bands));
    for (int b = 0; b < bands; ++b) {
        const size_t row0 = size_t(grid.rows) * size_t(b) / size_t(bands);
        const size_t row1 = size_t(grid.rows) * size_t(b + 1) / size_t(bands);
        for (size_t n = row0 * size_t(grid.cols); n < row1 * size_t(grid.cols); ++n) jobs[size_t(b)].nodes.push_back(n);
        jobs[size_t(b)].margin =
            bands == 1 ? kInf
                       : std::max(kFirstMarginSpacings * spacing, 1e-3 * (data.ymax - data.ymin));
    }
    SamplesByY sorted;
    if (bands > 1) {
        sorted.sample.resize(ys.size());
        for (size_t i = 0; i < ys.size(); ++i) sorted.sample[i] = i;
        std::sort(sorted.sample.begin(), sorted.sample.end(),
                  [&](size_t a, size_t b) { return ys[a] < ys[b] || (ys[a] == ys[b] && a < b); });
        sorted.y.reserve(ys.size());
        for (size_t i : sorted.sample) sorted.y.push_back(ys[i]);
    }
    // NaN marks "outside the hull" until the end: noData may be any value.
    LinearGriddingStats local;
    local.bands = bands;
    std::unique_ptr<Hull> hull;
    std::mutex progressMutex;
    size_t done = 0;
    const size_t firstRound = jobs.size();
    for (int round = 0; !jobs.empty(); ++round) {
        std::vector<JobResult> results(jobs.size());
        const int useThreads = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(1, std::min(useThreads, int(jobs.size()))))
        for (size_t j = 0; j < jobs.size(); ++j) {
            results[j] = runJob(jobs[j], xs, ys, zs, grid, data, sorted, out);
            if (progress && round == 0) {
                std::lock_guard<std::mutex> lock(progressMutex);
                progress(0.95 * double(++done) / double(firstRound));
            }
        }
        std::vector<Job> next;
        for (size_t j = 0; j < jobs.size(); ++j) {
            if (!results[j].error.empty()) return results[j].error;
            Job widened;
            widened.margin = round >= kMaxWidenings ? kInf : jobs[j].margin * kMarginGrowth;
            if (!results[j].notFound.empty() && !hull) hull = std::make_unique<Hull>(xs, ys);
            for (size_t n : results[j].notFound) {
                if (hull->outside(grid.x(int(n % grid.cols)), grid.y(int(n / grid.cols))))
                    out[n] = std::numeric_limits<double>::quiet_NaN();
                else
                    widened.nodes.push_back(n);
            }
            widened.nodes.insert(widened.nodes.end(), results[j].unproven.begin(), results[j].unproven.end());
            if (widened.nodes.empty()) continue;
            std::sort(widened.nodes.begin(), widened.nodes.end());
            next.push_back(std::move(widened));
            ++local.widenedBands;
        }
        jobs = std::move(next);
    }
    for (double& z : out)
        if (std::isnan(z)) z = noData, ++local.outsideHull;
    if (stats) *stats = local;
    return {};
}

}  // namespace relief::geo
