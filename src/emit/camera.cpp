#include "emit/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "core/number_format.h"
#include "geo/normalize.h"

namespace relief::emit {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
// cos(elevation) below this is straight down: 90 degrees less 0.06 arcseconds.
constexpr double kStraightDown = 3e-7;
}  // namespace

SceneVec3 sceneDirection(double azimuthDeg, double altitudeDeg) {
    const double a = azimuthDeg * kDeg, e = altitudeDeg * kDeg;
    return {std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e)};
}

namespace {

// The orbit's axes: `back` from the target to the eye, `r` horizontal and
// `u` completing them (left-handed axes: u points up); POV-Ray's `angle` is
// the horizontal field of view.
struct OrbitAxes {
    SceneVec3 back, right, r, u;
    double rightLen = 0, tanH = 0, tanV = 0;
};

OrbitAxes orbitAxes(const scene::CameraSpec& camera, double aspect) {
    OrbitAxes a;
    a.back = sceneDirection(camera.azimuthDeg, camera.elevationDeg);
    a.right = {a.back.z, 0, -a.back.x};
    a.rightLen = length(a.right);
    if (a.rightLen < kStraightDown) {
        // Straight down (or up) the azimuth no longer turns the view: the
        // still is a map, north up and east right, as the orbit at azimuth
        // 180 tends to (and as POV-Ray draws a camera its sky is parallel to).
        a.back = {0, camera.elevationDeg > 0 ? 1.0 : -1.0, 0};
        a.right = {-1, 0, 0};
        a.rightLen = 1;
    }
    a.r = (1.0 / a.rightLen) * a.right;
    a.u = cross(a.r, a.back);
    a.tanH = std::tan(0.5 * camera.fovDeg * kDeg);
    a.tanV = a.tanH / aspect;
    return a;
}

// The nearest distance at which all eight corners of the bounding box are in
// view, plus a 6 % margin.
double boxFitDistance(const ScenePlacement& where, const SceneVec3& target, const OrbitAxes& a) {
    const SceneVec3 lo = where.boundsMin, hi = where.boundsMax;
    double fitDistance = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const SceneVec3 c{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
        const SceneVec3 v = c - target;
        fitDistance = std::max({fitDistance, dot(v, a.back) + std::fabs(dot(v, a.r)) / a.tanH,
                                dot(v, a.back) + std::fabs(dot(v, a.u)) / a.tanV});
    }
    return fitDistance * 1.06;
}

// The box of the frame an outline fills, in the frame's units (x right, y up,
// -1 to 1): its centre and half sizes. The whole frame less a margin, or what
// an inset leaves (a framed map's annotations and furniture around it).
struct FitBox {
    double cx = 0, cy = 0, hx = 0, hy = 0;
};
constexpr double kMargin = 0.04;  // of the half-frame, on the widest side
FitBox fitBoxOf(const FrameInsetPx& inset, const scene::RenderSpec& render) {
    if (inset == FrameInsetPx{}) return {0, 0, 1 - kMargin, 1 - kMargin};
    const double W = render.width, H = render.height;
    const auto [left, top, right, bottom] = inset;
    const double x0 = -1 + 2 * left / W, x1 = 1 - 2 * right / W, y0 = -1 + 2 * bottom / H, y1 = 1 - 2 * top / H;
    return {0.5 * (x0 + x1), 0.5 * (y0 + y1), std::max(0.5 * (x1 - x0), 0.05), std::max(0.5 * (y1 - y0), 0.05)};
}

// A tight fit: the terrain's own outline, not its bounding box, fills `box`
// of the frame, centred in it (the target moves across the view, the eye back
// or forth); a few rounds settle a perspective view. The outline's extent is
// measured in units where `box` is the default one, whose arithmetic is then
// the plain fit's, bit for bit.
void fitOutline(const ScenePlacement& where, const scene::CameraSpec& camera, const OrbitAxes& a, double aspect,
                double distance, const FitBox& box, CameraView& view) {
    const bool perspective = camera.projection == scene::Projection::Perspective;
    const SceneVec3 screenRight = (-1.0 / a.rightLen) * a.right, screenUp = (-1.0 / length(a.u)) * a.u;
    const SceneVec3 forward = -1.0 * a.back;
    const double sx = (1 - kMargin) / box.hx, sy = (1 - kMargin) / box.hy;  // 1 for the default box
    SceneVec3 t = view.target;
    double d = distance;
    for (int round = 0; round < 40; ++round) {
        const SceneVec3 eye = t + d * a.back;
        double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
        bool behind = false;
        for (const SceneVec3& p : where.outline) {
            const SceneVec3 v = p - eye;
            double x = dot(v, screenRight), y = dot(v, screenUp);
            if (perspective) {
                const double z = dot(v, forward);
                if (z <= 1e-9 * d) {
                    behind = true;
                    break;
                }
                x /= z * a.tanH, y /= z * a.tanV;
            } else {
                x /= view.orthoHeight * aspect / 2, y /= view.orthoHeight / 2;
            }
            x = (x - box.cx) * sx, y = (y - box.cy) * sy;
            xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
        }
        if (behind) {
            d *= 2;
            continue;
        }
        const double cx = 0.5 * (xmin + xmax), cy = 0.5 * (ymin + ymax);
        const double half = std::max(0.5 * (xmax - xmin), 0.5 * (ymax - ymin));
        const double scale = half / (1 - kMargin);
        // The move, in the frame's units, that brings the outline's centre to the box's once scaled.
        const double mx = cx / sx + box.cx - scale * box.cx, my = cy / sy + box.cy - scale * box.cy;
        if (perspective) {
            t = t + (mx * d * a.tanH) * screenRight + (my * d * a.tanV) * screenUp;
            d *= scale;
        } else {
            t = t + (mx * view.orthoHeight * aspect / 2) * screenRight + (my * view.orthoHeight / 2) * screenUp;
            view.orthoHeight *= scale;
        }
        if (std::abs(cx) < 1e-6 && std::abs(cy) < 1e-6 && std::abs(half - (1 - kMargin)) < 1e-6) break;
    }
    view.eye = t + d * a.back;
    view.target = t;
}

// A camera placed by geography: the eye and the target as given. Returns the
// image's left and down axes as plain numbers; looking straight down, east
// stays right.
std::pair<SceneVec3, SceneVec3> placeAtPoints(const ScenePlacement& where, const CameraPoints& points,
                                              CameraView& view) {
    view.eye = where.scenePoint(*points.eyeM);
    if (points.targetM) view.target = where.scenePoint(*points.targetM);
    const SceneVec3 toEye = view.eye - view.target;
    const double d = length(toEye);
    const SceneVec3 b = d > 0 ? (1.0 / d) * toEye : SceneVec3{0, 1, 0};
    SceneVec3 side{b.z, 0, -b.x};
    if (length(side) < 1e-9) side = {-1, 0, 0};
    const SceneVec3 left = (1.0 / length(side)) * side;
    return {left, cross(left, b)};
}

}  // namespace

CameraView placeCamera(const ScenePlacement& where, const scene::CameraSpec& given, const CameraPoints& points,
                       const scene::RenderSpec& render, const FrameInsetPx& insetPx) {
    // A panorama or a sphere is placed as the default perspective camera would be: its eye there.
    using scene::Projection;
    const bool wide = given.projection == Projection::Panoramic || given.projection == Projection::Spherical;
    scene::CameraSpec camera = given;
    if (wide) camera.fovDeg = scene::CameraSpec{}.fovDeg, camera.projection = Projection::Perspective;
    const SceneVec3 lo = where.boundsMin, hi = where.boundsMax;
    const SceneVec3 target{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z)};
    const double radius = 0.5 * length(hi - lo);
    const double aspect = static_cast<double>(render.width) / render.height;
    const OrbitAxes axes = orbitAxes(camera, aspect);
    const double distance =
        camera.distanceM > 0 ? camera.distanceM / where.metresPerUnit : boxFitDistance(where, target, axes);
    CameraView view;
    view.eye = target + distance * axes.back;
    view.target = target;
    view.orthoHeight = 2.1 * radius;
    if (camera.distanceM <= 0 && !points.eyeM && !where.outline.empty())
        fitOutline(where, camera, axes, aspect, distance, fitBoxOf(insetPx, render), view);
    // The image's axes as plain numbers (r and u for the orbit).
    SceneVec3 leftPlain = axes.r, downPlain = axes.u;
    if (points.eyeM) std::tie(leftPlain, downPlain) = placeAtPoints(where, points, view);
    // As POV-Ray draws the image (left-handed: its right is cross(y, direction)
    // taken as plain numbers), those point left and down.
    view.right = (-1.0 / length(leftPlain)) * leftPlain;
    view.up = (-1.0 / length(downPlain)) * downPlain;
    view.radius = radius;
    view.aspect = aspect;
    view.tanHalfFov = axes.tanH;
    view.perspective = camera.projection == scene::Projection::Perspective;
    view.wide = wide;
    if (wide) {
        view.tanHalfFov = (given.projection == Projection::Spherical ? 360 : given.fovDeg) * kDeg / 2;
        // Looking level, towards the target: the cylinder's axis and the sphere's poles vertical,
        // the horizon straight across the still's middle. Straight down: towards north.
        SceneVec3 level{view.target.x - view.eye.x, 0, view.target.z - view.eye.z};
        if (length(level) < 1e-9 * std::max(1.0, length(view.target - view.eye))) level = {0, 0, 1};
        view.target = view.eye + (std::max(length(view.target - view.eye), 1e-9) / length(level)) * level;
        const SceneVec3 side{level.z, 0, -level.x};
        view.right = (1.0 / length(side)) * side;
        view.up = {0, 1, 0};
    }
    return view;
}

std::array<double, 2> projectToImage(const CameraView& view, const SceneVec3& p, int widthPx, int heightPx) {
    const SceneVec3 v = p - view.eye;
    const double x = dot(v, view.right), y = dot(v, view.up);
    if (!view.perspective) {
        const double h = view.orthoHeight, w = h * view.aspect;
        return {widthPx * (0.5 + x / w), heightPx * (0.5 - y / h)};
    }
    const double depth = std::max(dot(v, view.target - view.eye) / length(view.target - view.eye), 1e-12);
    const double tanV = view.tanHalfFov / view.aspect;
    return {widthPx * (0.5 + 0.5 * x / (depth * view.tanHalfFov)), heightPx * (0.5 - 0.5 * y / (depth * tanV))};
}

double finestMetresPerPixel(const CameraView& view, const ScenePlacement& where, int widthPx) {
    if (!view.perspective) return view.orthoHeight * view.aspect * where.metresPerUnit / widthPx;
    // The terrain's nearest point to the eye: there one pixel covers the least ground.
    const SceneVec3 lo = where.boundsMin, hi = where.boundsMax;
    const SceneVec3 nearest{std::clamp(view.eye.x, lo.x, hi.x), std::clamp(view.eye.y, lo.y, hi.y),
                            std::clamp(view.eye.z, lo.z, hi.z)};
    const double distance = std::max(length(view.eye - nearest), 1e-9);
    return 2 * distance * view.tanHalfFov * where.metresPerUnit / widthPx;
}

std::optional<CameraPoints> cameraPointsInFrame(const scene::CameraSpec& camera, const geo::Frame& frame,
                                                Diagnostics& diags) {
    const auto toFrame = [&](const GeoPoint& g, const char* key) -> std::optional<Vec3> {
        if (auto p = geo::forward(frame, g)) return p;
        diags.error(camera.locs.at(key), fmt::format("{} = [{}, {}, {}] cannot be placed in the scene's frame ({}): "
                                                     "put it nearer the terrain, or use frame.kind = \"local\"",
                                                     key, formatShortest(g.lonDeg), formatShortest(g.latDeg),
                                                     formatShortest(g.heightM), frame.describe()));
        return std::nullopt;
    };
    CameraPoints points;
    if (camera.position && !(points.eyeM = toFrame(*camera.position, "camera.position"))) return std::nullopt;
    if (camera.lookAt && !(points.targetM = toFrame(*camera.lookAt, "camera.look_at"))) return std::nullopt;
    if (points.eyeM && points.targetM && length(*points.eyeM - *points.targetM) < 1e-3) {
        diags.error(camera.locs.at("camera.look_at"),
                    "camera.look_at is where camera.position is: a camera must "
                    "look at a point away from itself");
        return std::nullopt;
    }
    return points;
}

}  // namespace relief::emit
