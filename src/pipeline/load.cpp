// The scene loaded: a scene file, or the scene relief makes for elevation
// data named in its place (load_data.cpp), validated, its scheme resolved and
// the job's budget made from its [limits].
#include "pipeline/load.h"

#include <fmt/format.h>

#include "core/stopwatch.h"
#include "core/utf8_record.h"
#include "scene/read_scene_table.h"

namespace relief {

std::shared_ptr<const scene::SceneDocument> readSceneDocument(const std::filesystem::path& named,
                                                              Diagnostics& diags) {
    // "tiles/" is the folder "tiles", beside which its scene lies.
    const std::filesystem::path scenePath = named.has_filename() ? named : named.parent_path();
    std::string why;
    const InputKind kind = inputKindOf(scenePath, why);
    if (kind == InputKind::Neither) {
        diags.error(
            {scenePath.string(), 0, 0},
            fmt::format(
                "relief reads a scene file (TOML), a raster DEM GDAL opens (GeoTIFF, SRTM .hgt, ESRI "
                "ASCII grid, VRT, ...), a folder of such tiles or a CSV of lon,lat,elev samples, and this is none of "
                "them ({})",
                why));
        return nullptr;
    }
    checkUtf8(diags, {scenePath.string(), 0, 0}, scenePath.string(), "the file's name");
    if (kind != InputKind::Scene) return std::make_shared<const scene::SceneDocument>(sceneDocumentForData(scenePath));
    auto document = scene::readSceneFileOnce(scenePath, diags);
    if (!document) return nullptr;
    return std::make_shared<const scene::SceneDocument>(std::move(*document));
}

std::optional<LoadedScene> loadScene(const std::filesystem::path& scenePath, Diagnostics& diags,
                                     const scene::SceneOverrides& overrides) {
    const auto t0 = Clock::now();
    const auto document = readSceneDocument(scenePath, diags);
    if (!document) return std::nullopt;
    auto loaded = loadScene(*document, diags, overrides);
    if (loaded) loaded->seconds = secondsSince(t0);
    return loaded;
}

std::optional<LoadedScene> loadScene(const scene::SceneDocument& document, Diagnostics& diags,
                                     const scene::SceneOverrides& overrides) {
    const auto t0 = Clock::now();
    for (const auto& [key, value] : overrides)
        checkUtf8(diags, {"--set " + key, 0, 0}, value, "the value");
    auto spec = scene::readSceneDocument(document, diags, overrides);
    if (!spec) return std::nullopt;
    // The scene's own errors do not stop the scheme's checks: every problem is reported at once.
    auto resolved = subdiv::resolveScheme(spec->subdivision.scheme, diags);
    if (diags.hasErrors() || !resolved) return std::nullopt;
    const subdiv::Budget budget = subdiv::Budget::of(spec->limits);
    LoadedScene loaded{std::move(*spec), std::move(*resolved), budget, 0};
    loaded.seconds = secondsSince(t0);
    return loaded;
}

}  // namespace relief
