#include "emit/sky_light.h"

#include <algorithm>
#include <cmath>

namespace relief::emit {

void addSkyLight(ScenePlacement& where, const geo::GeoGrid& refined, const geo::SkyViewOptions& options) {
    where.skyLight = std::make_shared<const std::vector<float>>(geo::skyViewFactor(refined, options));
}

void nodeTextures(Mesh& mesh) {
    if (!mesh.skyLight && !mesh.fills && !mesh.fade) return;
    const size_t nodes = mesh.grid->grid.points.size();
    constexpr int kSteps = kSkyLightLevels + 1;  // 0/128 .. 128/128
    const size_t fills = mesh.fills ? mesh.fills->fills.size() + 1 : 1;
    const size_t fades = mesh.fade ? kFadeLevels + 1 : 1;
    // Each (palette entry, light, fill) used has a block of `fades` entries: a table of every fade
    // of every combination would be 17 times the size of the one without.
    std::vector<std::int32_t> blockOf(mesh.paletteColors.size() * kSteps * fills, -1), entryOf;
    mesh.litTexture.assign(nodes, 0);
    mesh.litColours.clear();
    for (size_t node = 0; node < nodes; ++node) {
        if (!mesh.isVertex(node)) continue;
        const unsigned base = mesh.basePalette(node);
        const long level = std::clamp(std::lround(mesh.skyLightAt(node) * kSkyLightLevels), 0L, long{kSkyLightLevels});
        std::int32_t& block = blockOf[(static_cast<size_t>(base) * kSteps + level) * fills + mesh.fillAt(node)];
        if (block < 0) {
            block = static_cast<std::int32_t>(entryOf.size());
            entryOf.resize(entryOf.size() + fades, -1);
        }
        std::int32_t& entry = entryOf[static_cast<size_t>(block) + mesh.fadeAt(node)];
        if (entry < 0) {
            entry = static_cast<std::int32_t>(mesh.litColours.size());
            // The colour of a node with this palette entry, fill, fade and (quantized) light.
            const LinearRgb c = mesh.tintedColour(node, mesh.paletteColors[base]);
            const double light = double(level) / kSkyLightLevels;
            mesh.litColours.push_back({c.r * light, c.g * light, c.b * light});
        }
        mesh.litTexture[node] = static_cast<std::uint32_t>(entry);
    }
}

}  // namespace relief::emit
