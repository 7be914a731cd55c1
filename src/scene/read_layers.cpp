// [[layer]]: a vector file's layer drawn on the terrain, one table a layer.
#include <fmt/format.h>

#include "core/input_file.h"
#include "core/text_escape.h"
#include "scene/color_ramp.h"
#include "scene/read_sections.h"

namespace relief::scene {

namespace {

// Colours the layers take when the scene gives none, in turn: strong, and
// apart from every ramp's greens, browns and blues.
constexpr const char* kLayerColours[] = {"#c0392b", "#6c3483", "#d35400", "#1b2631", "#b7950b"};

// path = "summits.geojson": a vector file beside the scene; geo/ reads it when the scene is compiled.
void readLayerPath(Section& s, const SceneFile& f, LayerSpec& layer) {
    s.require("path", "the vector file, e.g. path = \"summits.geojson\"");
    if (auto path = s.fileBesideScene("path", f.path, layer.pathAsWritten)) layer.path = *path;
}

std::optional<LinearRgb> colourAt(Section& s, const std::string& key) {
    const auto text = s.string(key);
    LinearRgb c;
    if (!text) return std::nullopt;
    if (parseHexColor(*text, c)) return c;
    s.error(key, fmt::format("{} = \"{}\" must be a colour \"#rrggbb\"", s.qualified(key), printableExcerpt(*text)));
    return std::nullopt;
}

// How the layer is drawn: its colours, sizes and dashes.
void readLayerStyle(Section& s, LayerSpec& layer) {
    if (auto m = s.named<MarkerKind>("marker")) layer.marker = *m;
    if (auto v = s.number("marker_size_px", 4, 200, "pixels")) layer.markerSizePx = *v;
    if (auto v = s.number("label_size_px", LayerSpec::kMinLabelPx, 100, "pixels (smaller cannot be read)"))
        layer.labelSizePx = *v;
    if (auto v = s.number("width_px", 0.5, 50, "pixels")) layer.widthPx = *v;
    if (auto dash = s.numbers<2>("dash_px", "[on, off] in pixels, each 1 to 500")) {
        if ((*dash)[0] >= 1 && (*dash)[1] >= 1 && (*dash)[0] <= 500 && (*dash)[1] <= 500)
            layer.dashPx = {(*dash)[0], (*dash)[1]};
        else
            s.error("dash_px", "layer.dash_px must be [on, off] in pixels, each 1 to 500");
    }
    parseHexColor(kLayerColours[(layer.number - 1) % std::size(kLayerColours)], layer.colour);
    if (auto c = colourAt(s, "color")) layer.colour = *c;
    if (auto c = colourAt(s, "fill")) layer.fill = *c;
    if (auto v = s.number("fill_opacity", 0, 1, "")) layer.fillOpacity = *v;
    if (s.find("fill_opacity") && !layer.fill)
        s.warning("fill_opacity", "layer.fill_opacity is not used: the layer has no fill (fill = \"#rrggbb\")");
}

}  // namespace

void readLayer(Section& s, const SceneFile& f, SceneSpec& scene) {
    LayerSpec& layer = scene.layers.back();
    layer.number = static_cast<int>(scene.layers.size());
    if (layer.number > LayerSpec::kMaxLayers) {
        if (layer.number == LayerSpec::kMaxLayers + 1)
            f.diags.error(s.loc(), fmt::format("more than {} [[layer]] tables: merge some files into one (ogr2ogr "
                                               "-append)",
                                               LayerSpec::kMaxLayers));
        for (const auto& [k, v] : *s.table()) s.markKnown(std::string(k.str()));
        return;
    }
    readLayerPath(s, f, layer);
    if (auto v = s.string("layer")) layer.layer = *v;
    if (auto v = s.string("crs")) layer.crs = *v;
    if (auto v = s.string("label")) layer.labelField = *v;
    if (auto v = s.text("label_text")) layer.labelText = *v;
    if (!layer.labelField.empty() && !layer.labelText.empty())
        s.error("label_text", "layer: give label (an attribute's name) or label_text (one text), not both");
    if (auto v = s.text("legend")) layer.legend = *v;
    readLayerStyle(s, layer);
}

}  // namespace relief::scene
