#include "emit/write_scene.h"

#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_escape.h"

namespace relief::emit {

namespace {

constexpr int kPositionDecimals = 5;  // 1e-5 units: finer than float32 at 100 units
constexpr int kNormalDecimals = 5;
constexpr int kColorDecimals = 5;

// Buffered sink: the writer formats into a fixed block and hands it to stdio
// in large pieces.
class BlockWriter {
public:
    explicit BlockWriter(std::FILE* out) : out_(out) {}
    ~BlockWriter() { flush(); }
    // Room for `n` more characters.
    char* reserve(size_t n) {
        if (used_ + n > kSize) flush();
        return buf_ + used_;
    }
    void commit(char* end) { used_ = static_cast<size_t>(end - buf_); }
    void put(std::string_view s) {
        char* p = reserve(s.size());
        std::memcpy(p, s.data(), s.size());
        commit(p + s.size());
    }
    size_t total() const { return total_ + used_; }

private:
    void flush() {
        std::fwrite(buf_, 1, used_, out_);
        total_ += used_;
        used_ = 0;
    }
    static constexpr size_t kSize = 1 << 20;
    std::FILE* out_;
    char buf_[kSize];
    size_t used_ = 0;
    size_t total_ = 0;
};

// <a,b,c>: a point, a direction or a colour.
inline char* writeTriple(char* p, double a, double b, double c, int decimals) {
    *p++ = '<';
    p = writeFixed(p, a, decimals);
    *p++ = ',';
    p = writeFixed(p, b, decimals);
    *p++ = ',';
    p = writeFixed(p, c, decimals);
    *p++ = '>';
    return p;
}
inline char* writeVector(char* p, const SceneVec3& v, int decimals) {
    return writeTriple(p, v.x, v.y, v.z, decimals);
}

std::string vec(const SceneVec3& v, int decimals = 6) {
    char buf[120];
    return std::string(buf, writeVector(buf, v, decimals));
}

}  // namespace

size_t writeMesh2(const Mesh& mesh, std::FILE* out, const WriteProgressFn& progress) {
    auto w = std::make_unique<BlockWriter>(out);
    // The faces are about half the bytes, vertices and normals a quarter each.
    int lastPercent = -1;
    auto report = [&](double fraction) {
        const int percent = static_cast<int>(100 * fraction);
        if (progress && percent != lastPercent) progress(fraction), lastPercent = percent;
    };
    // `name { count, <x,y,z>, ... }` for the vertex and the normal arrays, each
    // vector computed from the grid as it is written (Mesh::position, normal).
    const size_t nodes = static_cast<size_t>(mesh.rows) * static_cast<size_t>(mesh.cols);
    auto vectorSection = [&](const char* open, auto vectorAt, int decimals, double from) {
        w->put(open);
        w->commit(writeUnsigned(w->reserve(24), mesh.vertices));
        const size_t step = std::max<size_t>(nodes / 100, 1);
        for (size_t i = 0; i < nodes; ++i) {
            if (i % step == 0) report(from + 0.25 * static_cast<double>(i) / static_cast<double>(nodes));
            if (!mesh.isVertex(i)) continue;
            char* p = w->reserve(128);
            *p++ = ',';
            *p++ = '\n';
            w->commit(writeVector(p, vectorAt(i), decimals));
        }
    };
    vectorSection("mesh2 {\n  vertex_vectors {\n    ", [&](size_t i) { return mesh.position(i); }, kPositionDecimals, 0);
    vectorSection("\n  }\n  normal_vectors {\n    ", [&](size_t i) { return mesh.normal(i); }, kNormalDecimals, 0.25);
    // An image drape colours the mesh as a whole (drapeTextureSdl): no texture per vertex.
    const bool perVertex = mesh.colouring != scene::TextureSpec::Colouring::Image;
    if (perVertex) {
        w->put("\n  }\n  texture_list {\n    ");
        char* p = w->reserve(24);
        w->commit(writeUnsigned(p, mesh.textureColours().size()));
    }
    for (const LinearRgb& c : perVertex ? mesh.textureColours() : std::vector<LinearRgb>{}) {
        char* p = w->reserve(160);
        const char open[] = ",\n    texture { pigment { rgb ";
        std::memcpy(p, open, sizeof open - 1);
        p += sizeof open - 1;
        p = writeTriple(p, c.r, c.g, c.b, kColorDecimals);
        const char close[] = " } finish { TerrainFinish } }";
        std::memcpy(p, close, sizeof close - 1);
        p += sizeof close - 1;
        w->commit(p);
    }
    w->put("\n  }\n  face_indices {\n    ");
    {
        char* p = w->reserve(24);
        w->commit(writeUnsigned(p, static_cast<std::uint64_t>(mesh.triangles)));
    }
    // A face by its corner nodes: their vertices, then their palette entries.
    auto face = [&](size_t a, size_t b, size_t c) {
        char* p = w->reserve(96);
        *p++ = ',';
        *p++ = '\n';
        *p++ = '<';
        p = writeUnsigned(p, mesh.vertexOf(a));
        *p++ = ',';
        p = writeUnsigned(p, mesh.vertexOf(b));
        *p++ = ',';
        p = writeUnsigned(p, mesh.vertexOf(c));
        *p++ = '>';
        if (!perVertex) {
            w->commit(p);
            return;
        }
        *p++ = ',';
        p = writeUnsigned(p, mesh.palette(a));
        *p++ = ',';
        p = writeUnsigned(p, mesh.palette(b));
        *p++ = ',';
        p = writeUnsigned(p, mesh.palette(c));
        w->commit(p);
    };
    mesh.forEachFace(face, [&](double fraction) { report(0.5 + 0.5 * fraction); });
    w->put("\n  }\n  inside_vector <0, 1, 0>\n}");
    report(1);
    return w->total();
}

namespace {

// The sun's disc: kSunSamples x kSunSamples points, POV-Ray sampling the
// corners first and refining kSunAdaptive times where they disagree.
constexpr int kSunSamples = 9;
constexpr int kSunAdaptive = 1;

// render.quality = "high": the sun a disc of its angular diameter, seen from
// the terrain `distance` away, so that a shadow's edge blurs over the width
// the sun spans from the ground it falls on. Sampled on a fixed grid (no
// jitter): a pixel's light depends on nothing but its own rays.
std::string sunAreaSdl(double distance, double diameterDeg, scene::Quality quality) {
    if (!scene::qualityLevel(quality).softSun) return "";
    const double width = 2 * distance * std::tan(0.5 * diameterDeg * 3.14159265358979323846 / 180);
    return fmt::format(
        "\n    area_light <{0}, 0, 0>, <0, 0, {0}>, {1}, {1}\n    adaptive {2}\n    circular\n    orient",
        fixedNumber(width), kSunSamples, kSunAdaptive);
}

}  // namespace

Bindings sceneBindings(const ScenePlacement& where, const CameraView& view, const SunDirection& sun,
                       GeometryWriters writers, const scene::LookSpec& look, const scene::RenderSpec& render,
                       const ParameterList& header) {
    const scene::CameraSpec& camera = look.camera;
    Bindings b;
    std::string head;
    for (const auto& [key, value] : header)
        head += fmt::format("// {}: {}\n", oneLineText(key), oneLineText(value));
    b["header"].text = head;

    const SceneVec3 target = view.target;
    const double radius = view.radius;
    b["camera_location"].text = vec(view.eye);
    b["camera_look_at"].text = vec(target);
    // Looking (nearly) straight down, the written eye's rounding could turn
    // the view, and POV-Ray's sky (y) no longer orients it: the view's own up
    // is written as the sky.
    const SceneVec3 sight = target - view.eye;
    const std::string sky =
        std::hypot(sight.x, sight.z) < 1e-3 * length(sight) ? " sky " + vec(view.up) : std::string();
    if (view.wide && camera.projection == scene::Projection::Spherical) {
        b["camera_projection"].text = std::string("spherical");
        b["camera_right"].text = fmt::format("x*{}", fixedNumber(view.aspect));
        b["camera_up"].text = "y" + sky;
        b["camera_angle"].text = "angle 360 180";
    } else if (view.wide) {
        // A vertical cylinder of radius 1 about the eye: `up` its height across the still, as wide
        // in radians a pixel as the angle across it, so that pixels are square at the horizon.
        const double acrossRad = camera.fovDeg * std::numbers::pi / 180;
        b["camera_projection"].text = std::string("cylinder 1");
        b["camera_right"].text = fmt::format("x*{}", fixedNumber(acrossRad));
        b["camera_up"].text = fmt::format("y*{}", fixedNumber(acrossRad / view.aspect)) + sky;
        b["camera_angle"].text = fmt::format("angle {}", fixedNumber(camera.fovDeg));
    } else if (view.perspective) {
        b["camera_projection"].text = std::string("perspective");
        b["camera_right"].text = fmt::format("x*{}", fixedNumber(view.aspect));
        b["camera_up"].text = "y" + sky;
        b["camera_angle"].text = fmt::format("angle {}", fixedNumber(camera.fovDeg));
    } else {
        b["camera_projection"].text = "orthographic";
        b["camera_right"].text = fmt::format("x*{}", fixedNumber(view.orthoHeight * view.aspect));
        b["camera_up"].text = fmt::format("y*{}", fixedNumber(view.orthoHeight)) + sky;
        b["camera_angle"].text = "";
    }
    const SceneVec3 sunDir = sceneDirection(sun.azimuthDeg, sun.altitudeDeg);
    b["sun_position"].text = vec(target + (100.0 * radius) * sunDir);
    b["scene_center"].text = vec(target);
    b["sun_area"].text = sunAreaSdl(100.0 * radius, look.lighting.sunDiameterDeg, render.quality);
    switch (render.background) {
        case scene::Background::Sky:
            // Pale at the horizon, deeper blue overhead.
            b["background"].text = std::string(
                "sky_sphere {\n"
                "  pigment {\n"
                "    gradient y\n"
                "    color_map {\n"
                "      [0.0 color rgb <0.78, 0.85, 0.93>]\n"
                "      [0.4 color rgb <0.38, 0.55, 0.80>]\n"
                "      [1.0 color rgb <0.16, 0.30, 0.62>]\n"
                "    }\n"
                "  }\n"
                "}");
            break;
        case scene::Background::Colour: {
            const auto& c = render.backgroundColour;
            b["background"].text = fmt::format("background {{ color rgb <{}, {}, {}> }}", fixedNumber(c.r),
                                               fixedNumber(c.g), fixedNumber(c.b));
            break;
        }
        case scene::Background::Transparent:
            // Rays that miss the terrain keep alpha 0 in the PNG (POV-Ray's +UA).
            b["background"].text = std::string("background { color rgbt <1, 1, 1, 1> }");
            break;
    }
    // [water]: a surface at the level, over the terrain's extent, seen through.
    b["water"].text = "";
    if (look.water.levelM) {
        const double y = where.scenePoint({where.originM.x, where.originM.y, *look.water.levelM}).y;
        const auto& c = look.water.colour;
        b["water"].text = fmt::format(
            "// Water at {} m above sea level ([water] level_m).\n"
            "box {{\n"
            "  <{}, {}, {}>, <{}, {}, {}>\n"
            "  pigment {{ color rgbt <{}, {}, {}, {}> }}\n"
            "  finish {{ ambient 0.1 diffuse 0.6 specular 0.5 roughness 0.01 reflection 0.08 }}\n"
            "}}",
            formatShortest(*look.water.levelM), fixedNumber(where.boundsMin.x), fixedNumber(y - 1e-4 * radius), fixedNumber(where.boundsMin.z),
            fixedNumber(where.boundsMax.x), fixedNumber(y), fixedNumber(where.boundsMax.z), fixedNumber(c.r), fixedNumber(c.g), fixedNumber(c.b),
            fixedNumber(look.water.transparency));
    }
    // [atmosphere] haze: distance fog the colour of the horizon. At haze 1 the
    // centre of the view keeps e^-0.3 = 74 % of its light and a ridge a
    // terrain's radius beyond it about 65 %: far reads as far, near stays clear.
    b["atmosphere"].text = "";
    if (look.atmosphere.haze > 0)
        b["atmosphere"].text = fmt::format("fog {{ fog_type 1 distance {} color rgb <0.78, 0.85, 0.93> }}",
                                           fixedNumber(length(view.eye - view.target) / (0.3 * look.atmosphere.haze)));
    b["terrain"].writer = std::move(writers.terrain);
    if (writers.base) b["base"].writer = std::move(writers.base);
    else b["base"].text = "";
    if (writers.onSurface) b["contours"].writer = std::move(writers.onSurface);
    else b["contours"].text = "";
    return b;
}

std::optional<Template> loadSceneTemplate(const std::filesystem::path& templatesDir,
                                          Diagnostics& diags) {
    const auto path = templatesDir / "scene.pov.in";
    std::string problem;
    auto text = readInputFile(path, kMaxTemplateBytes, problem);
    if (!text) {
        diags.error({path.string(), 0, 0},
                    fmt::format("cannot read the scene template: {}; give the folder with --templates or set "
                                "RELIEF_TEMPLATES",
                                problem));
        return std::nullopt;
    }
    return Template{path.string(), std::move(*text)};
}

bool writeScene(const std::filesystem::path& out, const Template& tmpl, const ScenePlacement& where,
                const CameraView& view, const SunDirection& sun, GeometryWriters writers, const scene::LookSpec& look,
                const scene::RenderSpec& render, const ParameterList& header, Diagnostics& diags) {
    const Bindings bindings = sceneBindings(where, view, sun, std::move(writers), look, render, header);
    if (!checkTemplate(tmpl, bindings, diags)) return false;
    AtomicFile file(out);
    renderTemplate(tmpl, bindings, file.stream());
    file.commit();
    return true;
}

}  // namespace relief::emit
