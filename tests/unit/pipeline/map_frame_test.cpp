#include "pipeline/map_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "emit/graticule.h"
#include "geo/normalize.h"
#include "pipeline/load.h"
#include "pipeline/surface.h"
#include "pipeline/view.h"
#include "unit/test_dirs.h"

namespace relief {
namespace {

namespace fs = std::filesystem;
using Side = annotate::MapFrame::Side;

struct Framed {
    std::string name;  ///< the DEM, for messages
    LoadedScene loaded;
    Surface surface;
};

std::optional<Framed> framed(const fs::path& dem, scene::SceneOverrides sets) {
    sets.emplace_back("overlay.frame", "true");
    sets.emplace_back("subdivision.depth", "0");
    Diagnostics diags;
    auto loaded = loadScene(dem, diags, sets);
    if (!loaded) return std::nullopt;
    auto surface = buildSurface(*loaded, diags, 1);
    if (!surface) return std::nullopt;
    return Framed{dem.filename().string(), std::move(*loaded), std::move(*surface)};
}

// The data a map is made from, swept: a LiDAR DEM in NZTM (a span of seconds), a Pseudo-Mercator
// continent (of degrees), a geographic raster (put in UTM), each framed in degrees and in metres
// and at a landscape, a portrait and a square still, with and without the furniture around it.
struct Case {
    const char* dem;
    scene::SceneOverrides sets;
};
const std::vector<const char*> kDems = {"tests/data/rasters/maungawhau-20m.tif", "scenes/data/rasters/asia.tif",
                                        "scenes/data/rasters/cyl_elev.tif"};
const std::vector<scene::SceneOverrides> kLooks = {
    {{"render.width", "960"}, {"render.height", "600"}, {"overlay.title", "\"A map\""}},
    {{"render.width", "600"}, {"render.height", "900"}, {"overlay.frame_units", "\"metres\""}},
    {{"render.width", "500"}, {"render.height", "500"}, {"overlay.legend", "false"}, {"overlay.scale_bar", "false"}},
    {{"render.width", "800"}, {"render.height", "500"}, {"overlay.frame_units", "\"metres\""},
     {"overlay.subtitle", "\"below\""}},
};

// Every DEM framed in every look: all of them, or fewer when one cannot be made (the tests count them).
std::vector<Framed> everyFramedMap() {
    std::vector<Framed> out;
    for (const char* dem : kDems)
        for (const auto& look : kLooks)
            if (auto f = framed(testing::kSourceDir / dem, look)) out.push_back(std::move(*f));
    return out;
}

// Every tick marks what it says: the longitude or latitude (or the coordinate) at its point of the
// edge is its value; the values step evenly by the frame interval, an annotation at every third,
// fourth or fifth, at most six and at least one along each edge, its label the graticule's.
TEST(MapFrame, EveryTickMarksItsValueOnEveryEdge) {
    const std::vector<Framed> maps = everyFramedMap();
    ASSERT_EQ(maps.size(), kDems.size() * kLooks.size());
    for (const Framed& f : maps) {
        const char* dem = f.name.c_str();
        const scene::SceneSpec& spec = f.loaded.scene;
        Diagnostics diags;
        const auto ticks = mapFrameTicks(spec, f.surface.net, diags);
        ASSERT_TRUE(ticks) << dem;
        const geo::GeoGrid& net = f.surface.net;
        std::map<Side, std::vector<MapFrameTicks::Tick>> bySide;
        for (const auto& t : ticks->ticks) bySide[t.side].push_back(t);
        ASSERT_EQ(bySide.size(), 4u) << dem;
        for (const auto& [side, along] : bySide) {
            const std::string where = std::string(dem) + " side " + std::to_string(int(side)) +
                                      (spec.overlay.frameMetres ? " (metres)" : " (degrees)");
            ASSERT_GE(along.size(), 3u) << where;
            const double minor = along[1].value - along[0].value;
            std::vector<int> annotated;  // the ticks' indices
            for (size_t i = 0; i < along.size(); ++i) {
                const auto& t = along[i];
                const bool alongX = annotate::MapFrame::alongX(side);
                const double x = alongX ? t.atM : side == Side::Left ? ticks->x0 : ticks->x1;
                const double y = alongX ? (side == Side::Bottom ? ticks->y0 : ticks->y1) : t.atM;
                if (spec.overlay.frameMetres) {
                    EXPECT_EQ(t.value, t.atM) << where;
                } else {
                    const auto g = geo::reverse(net.frame, Vec3{x, y, 0});
                    ASSERT_TRUE(g) << where;
                    EXPECT_NEAR(alongX ? g->lonDeg : g->latDeg, t.value, 1e-3 * std::abs(minor)) << where;  // far below a pixel
                }
                if (i > 0) {
                    EXPECT_NEAR(t.value - along[i - 1].value, minor, 1e-9 * std::abs(minor)) << where;
                }
                if (!t.label.empty()) annotated.push_back(int(i));
            }
            EXPECT_GE(annotated.size(), 1u) << where;
            EXPECT_LE(annotated.size(), 6u) << where;
            for (size_t k = 1; k < annotated.size(); ++k) {
                const int per = annotated[k] - annotated[k - 1];
                EXPECT_TRUE(per == 3 || per == 4 || per == 5) << where << ": " << per;
            }
        }
    }
}

// The map fills what the annotations and the furniture leave of the still: its neat line touches
// that room on one axis and is centred in it on the other, at every size and aspect swept.
TEST(MapFrame, TheMapFillsTheRoomTheFrameLeaves) {
    const std::vector<Framed> maps = everyFramedMap();
    ASSERT_EQ(maps.size(), kDems.size() * kLooks.size());
    for (const Framed& f : maps) {
        const char* dem = f.name.c_str();
        const scene::SceneSpec& spec = f.loaded.scene;
        Diagnostics diags;
        const auto view = resolveView(spec, f.surface.net, f.surface.refined, diags);
        ASSERT_TRUE(view && view->frameTicks) << dem;
        const int W = spec.render.width, H = spec.render.height;
        const auto [left, top, right, bottom] = frameInsetOf(spec, view->frameTicks);
        const auto frame = mapFrameOnImage(*view->frameTicks, view->where, view->camera, W, H);
        const PixelBox room{left, top, W - right, H - bottom};
        const PixelBox& m = frame.map;
        const std::string where = std::string(dem) + " " + std::to_string(W) + " x " + std::to_string(H);
        constexpr double kPx = 0.5;
        EXPECT_GE(m.x0, room.x0 - kPx) << where;
        EXPECT_GE(m.y0, room.y0 - kPx) << where;
        EXPECT_LE(m.x1, room.x1 + kPx) << where;
        EXPECT_LE(m.y1, room.y1 + kPx) << where;
        const bool fillsWidth = std::abs(m.w() - room.w()) < kPx, fillsHeight = std::abs(m.h() - room.h()) < kPx;
        EXPECT_TRUE(fillsWidth || fillsHeight) << where << ": map " << m.w() << " x " << m.h() << " in "
                                               << room.w() << " x " << room.h();
        EXPECT_NEAR(m.x0 + m.x1, room.x0 + room.x1, 2 * kPx) << where;
        EXPECT_NEAR(m.y0 + m.y1, room.y0 + room.y1, 2 * kPx) << where;
        // Every tick on the neat line's side, within it.
        for (const auto& t : frame.ticks) {
            const bool alongX = annotate::MapFrame::alongX(t.side);
            EXPECT_GE(t.px, (alongX ? m.x0 : m.y0) - kPx) << where;
            EXPECT_LE(t.px, (alongX ? m.x1 : m.y1) + kPx) << where;
        }
    }
}

// A frame where no map can be: the eye at a place, a camera looking across.
TEST(MapFrame, AViewThatIsNoMapIsRefusedAtTheKey) {
    const fs::path dem = testing::kSourceDir / "tests/data/rasters/maungawhau-20m.tif";
    for (const auto& sets : std::vector<scene::SceneOverrides>{
             {{"overlay.frame", "true"}, {"camera.elevation_deg", "40"}},
             {{"overlay.frame", "true"}, {"camera.projection", "\"perspective\""}},
             {{"overlay.frame", "true"}, {"camera.position", "[174.7620,-36.8790,2000]"}}}) {
        Diagnostics diags;
        loadScene(dem, diags, sets);
        ASSERT_TRUE(diags.hasErrors()) << sets.back().first;
        const std::string message = diags.all().back().message;
        EXPECT_NE(message.find("overlay.frame draws a map's frame around a view from straight above"),
                  std::string::npos)
            << message;
    }
    // Left out, the camera keys are the map's.
    Diagnostics diags;
    const auto loaded = loadScene(dem, diags, {{"overlay.frame", "true"}});
    ASSERT_TRUE(loaded);
    EXPECT_EQ(loaded->scene.look.camera.elevationDeg, 90);
    EXPECT_EQ(loaded->scene.look.camera.projection, scene::Projection::Orthographic);
}

}  // namespace
}  // namespace relief
