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

/// A point or vector in a local frame, metres unless a name says otherwise:
/// x = east, y = north, z = up.
struct Vec3 {
    double x = 0, y = 0, z = 0;
    friend Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
    friend Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    friend Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
    friend bool operator==(const Vec3&, const Vec3&) = default;
};

inline Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }

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
