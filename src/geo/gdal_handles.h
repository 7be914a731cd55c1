#pragma once
// Owners of GDAL's and OGR's C handles, each released by the call its library
// names for it, on every path out.
#include <memory>

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

namespace relief::geo {

struct DatasetCloser {
    void operator()(void* ds) const { GDALClose(ds); }
};
struct SrsDeleter {
    void operator()(void* s) const { OSRDestroySpatialReference(static_cast<OGRSpatialReferenceH>(s)); }
};
struct TransformDeleter {
    void operator()(void* t) const { OCTDestroyCoordinateTransformation(static_cast<OGRCoordinateTransformationH>(t)); }
};
struct FeatureDeleter {
    void operator()(void* f) const { OGR_F_Destroy(static_cast<OGRFeatureH>(f)); }
};
struct GeometryDeleter {
    void operator()(void* g) const { OGR_G_DestroyGeometry(static_cast<OGRGeometryH>(g)); }
};

using Dataset = std::unique_ptr<void, DatasetCloser>;
using Srs = std::unique_ptr<void, SrsDeleter>;
using Transform = std::unique_ptr<void, TransformDeleter>;
using Feature = std::unique_ptr<void, FeatureDeleter>;
using Geometry = std::unique_ptr<void, GeometryDeleter>;

}  // namespace relief::geo
