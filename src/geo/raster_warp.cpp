#include "geo/raster_warp.h"

#include <cmath>

#include <cpl_conv.h>
#include <cpl_error.h>

#include "geo/crs_frame.h"

namespace relief::geo {

namespace {

// The chain when the net's frame is the raster's CRS: the geotransform alone.
void netPixelToRasterPixel(const NetToRaster& t, bool dstToSrc, double& x, double& y) {
    const GeoGrid& net = *t.net;
    const auto& geo = t.raster->geo;
    const auto& inverse = t.raster->inverse;
    if (dstToSrc) {
        const double e = net.x0 + (x - 0.5) * net.dx, n = net.y0 + (net.rows() - 0.5 - y) * net.dy;
        x = (inverse[0] + e * inverse[1] + n * inverse[2]) * t.scaleX;
        y = (inverse[3] + e * inverse[4] + n * inverse[5]) * t.scaleY;
        return;
    }
    const double px = x / t.scaleX, py = y / t.scaleY;
    const double e = geo[0] + px * geo[1] + py * geo[2], n = geo[3] + px * geo[4] + py * geo[5];
    x = (e - net.x0) / net.dx + 0.5;
    y = net.rows() - 0.5 - (n - net.y0) / net.dy;
}

int transformNetToRaster(void* arg, int dstToSrc, int count, double* x, double* y, double* z, int* ok) {
    const auto& t = *static_cast<const NetToRaster*>(arg);
    const GeoGrid& net = *t.net;
    const RasterPlace& raster = *t.raster;
    for (int i = 0; i < count; ++i) {
        ok[i] = FALSE;
        if (t.inRasterCrs) {
            netPixelToRasterPixel(t, dstToSrc, x[i], y[i]);
        } else if (dstToSrc) {
            const Vec3 p{net.x0 + (x[i] - 0.5) * net.dx, net.y0 + (net.rows() - 0.5 - y[i]) * net.dy, 0};
            const auto g = reverse(net.frame, p);
            if (!g || !raster.toPixel(g->lonDeg, g->latDeg, x[i], y[i])) continue;
            if (t.wrapPixels > 0 && (x[i] < 0 || x[i] > raster.width)) {
                // Only onto the raster: a node off it stays where it is (continuous for the approximator).
                const double wrapped = x[i] + (x[i] < 0 ? t.wrapPixels : -t.wrapPixels);
                if (wrapped >= 0 && wrapped <= raster.width) x[i] = wrapped;
            }
            x[i] *= t.scaleX, y[i] *= t.scaleY;
        } else {
            x[i] /= t.scaleX, y[i] /= t.scaleY;
            // The whole geotransform: a drape's image may be rotated.
            const auto& geo = raster.geo;
            double cx = geo[0] + x[i] * geo[1] + y[i] * geo[2];
            double cy = geo[3] + x[i] * geo[4] + y[i] * geo[5], cz = 0;
            if (!OCTTransform(raster.crs.toWgs84.get(), 1, &cx, &cy, &cz)) continue;
            const auto p = forward(net.frame, {cx, cy, 0});
            if (!p) continue;
            x[i] = (p->x - net.x0) / net.dx + 0.5;
            y[i] = net.rows() - 0.5 - (p->y - net.y0) / net.dy;
        }
        if (z) z[i] = 0;
        ok[i] = std::isfinite(x[i]) && std::isfinite(y[i]);
    }
    return TRUE;
}

int CPL_STDCALL reportWarpProgress(double fraction, const char*, void* fn) {
    (*static_cast<const GridProgressFn*>(fn))(fraction);
    return TRUE;
}

// Searched by value: the scene's enum may gain values in any order.
struct ResamplingRow {
    scene::Resample resample;
    GDALResampleAlg gdal;
};
constexpr ResamplingRow kResamplings[] = {
    {scene::Resample::Bilinear, GRA_Bilinear},
    {scene::Resample::Cubic, GRA_Cubic},
    {scene::Resample::Average, GRA_Average},
    {scene::Resample::Nearest, GRA_NearestNeighbour},
};

}  // namespace

NetToRaster netToRaster(const GeoGrid& net, const RasterPlace& raster) {
    const bool inRasterCrs =
        net.frame.kind == scene::FrameKind::Raster && net.frame.crsWkt == crsFrame(raster.crs.srs.get()).crsWkt;
    return {&net, &raster, raster.wrapPixels(), inRasterCrs};
}

Dataset memRaster(int cols, int rows, int bands, GDALDataType type) {
    return Dataset(GDALCreate(GDALGetDriverByName("MEM"), "", cols, rows, bands, type, nullptr));
}

GDALWarpOptions* warpOptions(GDALDatasetH src, GDALDatasetH dst, const std::vector<int>& srcBands) {
    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->hSrcDS = src;
    wo->hDstDS = dst;
    wo->nBandCount = static_cast<int>(srcBands.size());
    wo->panSrcBands = static_cast<int*>(CPLMalloc(srcBands.size() * sizeof(int)));
    wo->panDstBands = static_cast<int*>(CPLMalloc(srcBands.size() * sizeof(int)));
    for (size_t b = 0; b < srcBands.size(); ++b) wo->panSrcBands[b] = srcBands[b], wo->panDstBands[b] = int(b) + 1;
    return wo;
}

CPLErr warpOntoNet(GDALWarpOptions* wo, const NetToRaster& chain, double maxErrorPixels,
                   const GridProgressFn& progress) {
    struct ApproxDeleter {
        void operator()(void* t) const { GDALDestroyApproxTransformer(t); }
    };
    std::unique_ptr<void, ApproxDeleter> approx(
        GDALCreateApproxTransformer(transformNetToRaster, const_cast<NetToRaster*>(&chain), maxErrorPixels));
    wo->pfnTransformer = GDALApproxTransform;
    wo->pTransformerArg = approx.get();
    if (progress) {
        wo->pfnProgress = reportWarpProgress;
        wo->pProgressArg = const_cast<GridProgressFn*>(&progress);
    }
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALWarpOperation warp;
    CPLErr err = warp.Initialize(wo);
    if (err == CE_None) err = warp.ChunkAndWarpImage(0, 0, chain.net->cols(), chain.net->rows());
    CPLPopErrorHandler();
    GDALDestroyWarpOptions(wo);
    return err;
}

GDALResampleAlg gdalResampling(scene::Resample r) {
    for (const auto& row : kResamplings)
        if (row.resample == r) return row.gdal;
    return GRA_Bilinear;
}

}  // namespace relief::geo
