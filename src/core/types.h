#pragma once
// Small shared value types.
#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace relief {

/// Three components and their arithmetic, tagged with the axes they are in so
/// that a point in one cannot be passed where the other is meant.
template <class Axes>
struct Vector3 {
    double x = 0, y = 0, z = 0;
    friend Vector3 operator+(Vector3 a, Vector3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
    friend Vector3 operator-(Vector3 a, Vector3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    friend Vector3 operator*(double s, Vector3 a) { return {s * a.x, s * a.y, s * a.z}; }
    friend bool operator==(const Vector3&, const Vector3&) = default;
};
template <class Axes>
Vector3<Axes> cross(Vector3<Axes> a, Vector3<Axes> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class Axes>
double dot(Vector3<Axes> a, Vector3<Axes> b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class Axes>
double length(Vector3<Axes> a) {
    return std::sqrt(dot(a, a));
}

struct FrameAxes;
struct SceneAxes;
/// A point or vector in a local frame, metres unless a name says otherwise:
/// x = east, y = north, z = up (right-handed).
using Vec3 = Vector3<FrameAxes>;
/// A point or vector in POV-Ray's scene: x = east, y = up, z = north
/// (left-handed, so the map is not mirrored), in scene units
/// (emit::ScenePlacement says how many metres one is, and carries frame
/// points into the scene).
using SceneVec3 = Vector3<SceneAxes>;

/// A place on the Earth: WGS84 longitude and latitude in degrees, and a height
/// in metres as the data's heights are (relief moves no height between
/// datums). Longitude first wherever the two travel together, as scene files
/// write them ([lon, lat, height_m]).
struct GeoPoint {
    double lonDeg = 0, latDeg = 0, heightM = 0;
};

/// A box in a frame's metres: x from west to east, y from south to north.
struct FrameBox {
    double west = 0, south = 0, east = 0, north = 0;
};
/// A box of longitudes (west to east) and latitudes (south to north), degrees.
struct LonLatBox {
    double west = 0, south = 0, east = 0, north = 0;
};

/// A point on a still: pixels from its top left corner, y down.
struct PixelPoint {
    double x = 0, y = 0;
};
/// A box of pixels on an image (a still, a raster), y down: (x0, y0) its top
/// left corner, (x1, y1) its bottom right.
struct PixelBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    double w() const { return x1 - x0; }
    double h() const { return y1 - y0; }
    /// Whether the two boxes overlap, or come closer than `pad` pixels.
    bool meets(const PixelBox& o, double pad) const {
        return x0 < o.x1 + pad && o.x0 < x1 + pad && y0 < o.y1 + pad && o.y0 < y1 + pad;
    }
    friend bool operator==(const PixelBox&, const PixelBox&) = default;
};

/// A colour as light adds up: linear 0..1 components of an sRGB colour.
struct LinearRgb {
    double r = 0, g = 0, b = 0;
    friend bool operator==(const LinearRgb&, const LinearRgb&) = default;
};
/// The colour a fraction `t` of the way from `a` to `b`.
inline LinearRgb mix(const LinearRgb& a, const LinearRgb& b, double t) {
    return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)};
}

/// Allocator for the large point arrays of refined grids. Big blocks are
/// 2 MiB aligned and marked for transparent huge pages: a refined 2049^2 grid
/// is 100 MB, and with 4 KiB pages the kernel's page faults cost more than the
/// refinement itself (measured: ~60 % of the refiner's time on this machine).
template <class T>
struct BigBufferAllocator {
    using value_type = T;
    BigBufferAllocator() = default;
    template <class U>
    BigBufferAllocator(const BigBufferAllocator<U>&) {}

    T* allocate(std::size_t n) {
        const std::size_t bytes = n * sizeof(T);
        constexpr std::size_t kHuge = std::size_t{2} << 20;
        if (bytes < kHuge) {
            if (void* p = std::malloc(bytes ? bytes : 1)) return static_cast<T*>(p);
            throw std::bad_alloc();
        }
        const std::size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
        void* p = std::aligned_alloc(kHuge, rounded);
        if (!p) throw std::bad_alloc();
        ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint: ignored where THP is off
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t) { std::free(p); }

    /// resize() leaves new elements unwritten: zeroing a 100 MB grid is one
    /// more pass over memory than refining into it (every writer of a Grid
    /// sets every point it sizes). Only for implicit-lifetime types.
    template <class U>
    void construct(U*) noexcept {
        static_assert(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>);
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    friend bool operator==(const BigBufferAllocator&, const BigBufferAllocator&) { return true; }
};

/// A rows x cols lattice of points, row-major. Row 0 is the southern edge
/// (smallest y), column 0 the western edge (smallest x).
struct Grid {
    int rows = 0;
    int cols = 0;
    std::vector<Vec3, BigBufferAllocator<Vec3>> points;  ///< rows * cols

    Vec3& at(int r, int c) { return points[static_cast<size_t>(r) * cols + c]; }
    const Vec3& at(int r, int c) const { return points[static_cast<size_t>(r) * cols + c]; }

    /// The lowest and highest z of every point, masked or not ({1e300, -1e300} when empty).
    std::pair<double, double> zRange() const {
        double zmin = 1e300, zmax = -1e300;
        for (const Vec3& p : points) zmin = std::min(zmin, p.z), zmax = std::max(zmax, p.z);
        return {zmin, zmax};
    }
};

/// The size of the triangle mesh a rows x cols grid becomes: one vertex per
/// node, two triangles per cell. The one formula the output budget, the
/// mesh2 writer, the sidecar and the command line all use.
struct MeshSize {
    long long vertices = 0;
    long long triangles = 0;
};
inline MeshSize gridMeshSize(long long rows, long long cols) {
    return {rows * cols, rows > 1 && cols > 1 ? 2 * (rows - 1) * (cols - 1) : 0};
}

}  // namespace relief
