// The report's furniture: the numbers it shows (scale bar, ticks, north) and
// that it is drawn, as text, where it belongs.
#include "annotate/overlay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "emit/mesh.h"

namespace relief::annotate {
namespace {

// A 1 km square around the origin, 100 m high, 10 m per scene unit.
emit::ScenePlacement square() {
    emit::ScenePlacement p;
    p.metresPerUnit = 10;
    p.boundsMin = {-50, 0, -50};
    p.boundsMax = {50, 10, 50};
    return p;
}

emit::CameraView view(double azimuthDeg, double elevationDeg, bool perspective = true) {
    scene::LookSpec look;
    look.camera.azimuthDeg = azimuthDeg;
    look.camera.elevationDeg = elevationDeg;
    look.camera.projection = perspective ? scene::Projection::Perspective : scene::Projection::Orthographic;
    scene::RenderSpec render;
    render.width = 800;
    render.height = 600;
    return emit::placeCamera(square(), look, render);
}

// Where north points on the image: POV-Ray's axes are left-handed (x east,
// z north), so a camera south of the terrain sees east on its right.
TEST(Overlay, NorthArrowFollowsTheCamera) {
    EXPECT_NEAR(northOnImageDeg(view(180, 35), 0, 800, 600), 0, 1e-6);    // looking north: up
    EXPECT_NEAR(std::abs(northOnImageDeg(view(0, 35), 0, 800, 600)), 180, 1e-6);  // looking south: down
    EXPECT_NEAR(northOnImageDeg(view(90, 89), 0, 800, 600), 90, 0.1);     // from the east, overhead: right
    EXPECT_NEAR(northOnImageDeg(view(270, 89), 0, 800, 600), -90, 0.1);   // from the west: left
    // Looking north-north-east (the default camera), north is to the left of up.
    const double n = northOnImageDeg(view(200, 35), 0, 800, 600);
    EXPECT_LT(n, -15);
    EXPECT_GT(n, -45);
    // Overhead, the arrow turns by the meridian convergence: grid north 2° east
    // of true north puts true north 2° to the left.
    EXPECT_NEAR(northOnImageDeg(view(180, 89.9), 2, 800, 600), -2, 0.05);
    // East of the target lands right of it, in the image.
    const emit::CameraView v = view(180, 35);
    EXPECT_GT(emit::projectToImage(v, v.target + SceneVec3{1, 0, 0}, 800, 600)[0], 400);
    EXPECT_LT(emit::projectToImage(v, v.target + SceneVec3{0, 1, 0}, 800, 600)[1], 300);  // up is up
}

// The bar is a round length near a fifth of the width, drawn at its true
// pixel length for the view's scale.
TEST(Overlay, ScaleBarIsRoundAndTrue) {
    const ScaleBar a = chooseScaleBar(2.5, 800);  // 160 px = 400 m -> 200 m
    EXPECT_EQ(a.metres, 200);
    EXPECT_DOUBLE_EQ(a.pixels, 80);
    EXPECT_EQ(a.label, "200 m");
    const ScaleBar b = chooseScaleBar(31.3, 960);  // 6 km -> 5 km
    EXPECT_EQ(b.metres, 5000);
    EXPECT_EQ(b.label, "5 km");
    EXPECT_NEAR(b.pixels * 31.3, 5000, 1e-9);
    // Orthographic: the view's width in metres over its pixels, everywhere.
    const emit::CameraView o = view(180, 35, false);
    EXPECT_NEAR(metresPerPixelAtTarget(o, 10, 800), o.orthoHeight * o.aspect * 10 / 800, 1e-12);
    // Perspective, at the target: two tangents of the half angle at its distance.
    const emit::CameraView p = view(180, 35);
    EXPECT_NEAR(metresPerPixelAtTarget(p, 10, 800), 2 * length(p.target - p.eye) * p.tanHalfFov * 10 / 800, 1e-12);
}

TEST(Overlay, LegendTicksAreRoundAndInside) {
    EXPECT_EQ(legendTicks(36.2, 250.9), (std::vector<double>{50, 100, 150, 200, 250}));
    EXPECT_EQ(legendTicks(-5, 5), (std::vector<double>{-4, -2, 0, 2, 4}));
    EXPECT_EQ(legendTicks(100, 100), (std::vector<double>{100}));  // flat terrain: no 0/0
}

TEST(Overlay, AutoOnlyOnStillsWideEnough) {
    scene::OverlaySpec spec;
    EXPECT_FALSE(overlaysWanted(spec, 160));
    EXPECT_TRUE(overlaysWanted(spec, 480));
    spec.enabled = scene::OverlaySpec::Enabled::On;
    EXPECT_TRUE(overlaysWanted(spec, 160));
    spec.enabled = scene::OverlaySpec::Enabled::Off;
    EXPECT_FALSE(overlaysWanted(spec, 4000));
}

// A grey 640 x 480 still, and facts for every overlay: a two-colour legend
// from 10 to 300 m, 2 m a pixel, credits.
PngImage8 greyStill() {
    PngImage8 image;
    image.width = 640;
    image.height = 480;
    image.channels = 3;
    image.pixels.assign(640 * 480 * 3, 128);
    return image;
}

OverlayFacts sampleFacts(std::string credits) {
    OverlayFacts facts;
    facts.credits = std::move(credits);
    facts.palette = {{0, 0.5, 0}, {1, 1, 1}};
    facts.zMinM = 10;
    facts.zMaxM = 300;
    facts.metresPerPixel = 2;
    return facts;
}

// Drawn on a grey still: the title's corner, the legend's column and the
// scale bar's corner change; the middle, where the terrain is, does not. A
// hostile title is set as text (Pango never sees markup) and cut to one line.
TEST(Overlay, DrawsInTheCornersAndKeepsTheMiddle) {
    PngImage8 image = greyStill();
    scene::OverlaySpec spec;
    spec.title = "<b>x</b> &amp; #fopen {{terrain}} " + std::string(5000, 'W');
    OverlayFacts facts = sampleFacts("Data: someone, CC BY 4.0");
    OverlayRecord record;
    Diagnostics diags;
    ASSERT_TRUE(drawOverlays(image, spec, facts, {}, diags, &record));
    EXPECT_EQ(record.drawn, (std::vector<std::string>{"title", "north_arrow", "credits", "scale_bar", "legend"}));
    // No terrain known: every item in its own place.
    EXPECT_EQ(record.placement, (std::map<std::string, std::string>{{"title", "top-left"},
                                                                     {"north_arrow", "top-right"},
                                                                     {"credits", "bottom-right"},
                                                                     {"scale_bar", "bottom-left"},
                                                                     {"legend", "right"}}));
    EXPECT_TRUE(record.onTerrain.empty());
    EXPECT_EQ(record.scaleBar.metres, 200);
    auto changed = [&](int x0, int y0, int x1, int y1) {
        int n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                for (int c = 0; c < 3; ++c) n += image.pixels[(size_t(y) * 640 + x) * 3 + c] != 128;
        return n;
    };
    EXPECT_GT(changed(0, 0, 400, 40), 500);     // the title
    EXPECT_EQ(changed(440, 0, 560, 40), 0);      // ...cut at 62 % of the width, before the north arrow
    EXPECT_GT(changed(540, 100, 600, 300), 500); // the legend
    EXPECT_GT(changed(0, 400, 200, 480), 200);   // the scale bar
    EXPECT_GT(changed(300, 440, 640, 480), 100); // the credits
    EXPECT_EQ(changed(200, 150, 480, 380), 0);   // the middle
}

// Terrain over the left half of the still, top to bottom: the title crosses
// to the top right; the north arrow, its corner taken, goes down to the bottom
// right; the credits, their corner taken and the other on the terrain, go
// there (on the terrain, said so); the scale bar takes the first corner no
// overlay holds; the legend keeps the right edge.
TEST(Overlay, ItemsMoveOffTheTerrainWhereTheyCan) {
    PngImage8 image = greyStill();
    scene::OverlaySpec spec;
    spec.title = "Somewhere";
    OverlayFacts facts = sampleFacts("Data: someone");
    std::vector<std::array<double, 2>> left;
    for (int x = 0; x < 320; x += 9)
        for (int y : {0, 479}) left.push_back({double(x), double(y)});
    facts.terrain = TerrainOnImage::fromPoints(left, 640);
    EXPECT_TRUE(facts.terrain.covers(100, 240));
    EXPECT_TRUE(facts.terrain.covers(6, 10));  // between two points' bands: filled in
    EXPECT_FALSE(facts.terrain.covers(400, 240));
    OverlayRecord record;
    Diagnostics diags;
    ASSERT_TRUE(drawOverlays(image, spec, facts, {}, diags, &record));
    EXPECT_EQ(record.placement.at("title"), "top-right");
    EXPECT_EQ(record.placement.at("north_arrow"), "bottom-right");
    EXPECT_EQ(record.placement.at("credits"), "bottom-left");
    EXPECT_EQ(record.placement.at("scale_bar"), "top-left");
    EXPECT_EQ(record.placement.at("legend"), "right");
    EXPECT_EQ(record.onTerrain, (std::vector<std::string>{"credits", "scale_bar"}));
    // The title is drawn where it was placed: in the top right quarter.
    int ink = 0;
    for (int y = 0; y < 40; ++y)
        for (int x = 320; x < 640; ++x) ink += image.pixels[(size_t(y) * 640 + x) * 3] != 128;
    EXPECT_GT(ink, 200);
}

bool inside(const PixelBox& b, int w, int h) { return b.x0 >= 0 && b.y0 >= 0 && b.x1 <= w && b.y1 <= h; }

// Each item at each place the author may give it, alone on the still: it goes
// there (its box in that corner or at the middle of that edge), wholly inside;
// "off" draws nothing.
TEST(Overlay, EachItemGoesWhereTheAuthorPutsIt) {
    const OverlayFacts facts = sampleFacts("Data: someone, CC BY 4.0");
    const std::vector<std::pair<std::string, std::string>> drawnAs = {
        {"title", "title"}, {"north_arrow", "north_arrow"}, {"credits", "credits"},
        {"scale_bar", "scale_bar"}, {"legend", "legend"}};
    for (const auto& [item, name] : drawnAs)
        for (const std::string& where : scene::kFurniturePlaces) {
            scene::OverlaySpec spec;
            spec.title = "Somewhere";
            for (const std::string& other : scene::kFurnitureItems) spec.places[other] = "off";
            spec.places[item] = where;
            PngImage8 image = greyStill();
            OverlayRecord record;
            Diagnostics diags;
            ASSERT_TRUE(drawOverlays(image, spec, facts, {}, diags, &record));
            EXPECT_TRUE(record.leftOut.empty()) << item << " " << where;
            if (where == "off") {
                EXPECT_TRUE(record.drawn.empty()) << item;
                continue;
            }
            ASSERT_EQ(record.drawn, std::vector<std::string>{name}) << item << " " << where;
            const PixelBox b = record.boxes.at(name);
            EXPECT_TRUE(inside(b, 640, 480)) << item << " " << where;
            if (where == "auto") continue;
            EXPECT_EQ(record.placement.at(name), where);
            const double u = 6.4, cx = (b.x0 + b.x1) / 2, cy = (b.y0 + b.y1) / 2;
            const auto has = [&](const char* side) { return where.find(side) != std::string::npos; };
            if (item == "north_arrow") {
                // Placed by the square it fills at any angle: its centre as far from each edge it keeps to.
                const PixelPoint c = *record.northCentre;
                const double fromX = has("left") ? c.x - 2 * u : has("right") ? 640 - 2 * u - c.x : -1;
                const double fromY = has("top") ? c.y - 2 * u : has("bottom") ? 480 - 2 * u - c.y : -1;
                if (fromX < 0) {
                    EXPECT_NEAR(c.x, 320, 1e-9) << where;
                }
                if (fromY < 0) {
                    EXPECT_NEAR(c.y, 240, 1e-9) << where;
                }
                if (fromX >= 0 && fromY >= 0) {
                    EXPECT_NEAR(fromX, fromY, 1e-9) << where;
                }
                EXPECT_GT(std::max(fromX, fromY), 0) << where;
                continue;
            }
            const double x = has("left") ? b.x0 : has("right") ? b.x1 : cx;
            if (item == "legend" && (where == "left" || where == "right")) {  // down that edge from the top
                EXPECT_NEAR(x, where == "left" ? 2 * u : 640 - 2 * u, 1e-9) << where;
                EXPECT_NEAR(b.y0, 13.4 * u, 1e-9) << where;
                continue;
            }
            const double y = has("top") ? b.y0 : has("bottom") ? b.y1 : cy;
            EXPECT_NEAR(x, has("left") ? 2 * u : has("right") ? 640 - 2 * u : 320, 1e-9) << item << " " << where;
            EXPECT_NEAR(y, has("top") ? 2 * u : has("bottom") ? 480 - 2 * u : 240, 1e-9) << item << " " << where;
        }
}

// Two items the author put in one corner: the first keeps it, the second is
// left out with a warning naming both, never drawn over the first. On a
// still too small for the furniture, every item drawn is inside and apart,
// and each left out is said.
TEST(Overlay, ItemsThatWouldOverlapAreLeftOutAndSaid) {
    scene::OverlaySpec spec;
    spec.title = "Somewhere";
    spec.places = {{"credits", "bottom-right"}, {"scale_bar", "bottom-right"}};
    PngImage8 image = greyStill();
    OverlayRecord record;
    Diagnostics diags;
    ASSERT_TRUE(drawOverlays(image, spec, sampleFacts("Data: someone"), {"still.png", 0, 0}, diags, &record));
    EXPECT_EQ(record.drawn, (std::vector<std::string>{"title", "north_arrow", "credits", "legend"}));
    ASSERT_EQ(record.leftOut.size(), 1u);
    EXPECT_EQ(record.leftOut[0].item, "scale_bar");
    EXPECT_EQ(record.leftOut[0].inTheWay, "the credits");
    ASSERT_EQ(diags.all().size(), 1u);
    EXPECT_EQ(formatDiagnostic(diags.all()[0]),
              "still.png: warning: the scale bar is left out: no free place for it on a 640 x 480 still (in the "
              "way: the credits); give overlay.place.scale_bar a free place, or make the still larger");

    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{120, 80}, {160, 100}, {200, 400}, {400, 120}}) {
        PngImage8 small;
        small.width = w, small.height = h, small.channels = 3;
        small.pixels.assign(size_t(w) * h * 3, 128);
        scene::OverlaySpec all;
        all.title = "A title long enough to matter";
        all.subtitle = "and a subtitle";
        OverlayRecord r;
        Diagnostics d;
        ASSERT_TRUE(drawOverlays(small, all, sampleFacts("Data: someone, CC BY 4.0"), {}, d, &r));
        for (const auto& [item, box] : r.boxes) {
            EXPECT_TRUE(inside(box, w, h)) << item << " on " << w << " x " << h;
            for (const auto& [other, otherBox] : r.boxes) {
                if (other < item && !(box == otherBox)) {
                    EXPECT_FALSE(box.meets(otherBox, 0)) << item << " meets " << other << " on " << w << " x " << h;
                }
            }
        }
        for (const std::string item : {"title", "north_arrow", "credits", "scale_bar", "legend"}) {
            const auto out = std::count_if(r.leftOut.begin(), r.leftOut.end(),
                                           [&](const OverlayRecord::LeftOut& l) { return l.item == item; });
            EXPECT_EQ(r.boxes.count(item) + out, 1u) << item << " on " << w << " x " << h;  // drawn or said
        }
        EXPECT_EQ(d.warningCount(), static_cast<int>(r.leftOut.size()));
    }
}

// Imperial and given lengths: feet under a mile, miles from one; a length as
// written, its pixels true.
TEST(Overlay, ScaleBarInTheUnitsAsked) {
    scene::OverlaySpec imperial;
    imperial.scaleBarImperial = true;
    const ScaleBar ft = chooseScaleBar(2.5, 800, imperial);  // 400 m = 1312 ft -> 1000 ft
    EXPECT_EQ(ft.label, "1000 ft");
    EXPECT_DOUBLE_EQ(ft.metres, 304.8);
    EXPECT_DOUBLE_EQ(ft.pixels, 304.8 / 2.5);
    const ScaleBar mi = chooseScaleBar(31.3, 960, imperial);  // 6010 m = 3.7 mi -> 2 mi
    EXPECT_EQ(mi.label, "2 mi");
    EXPECT_DOUBLE_EQ(mi.metres, 2 * 1609.344);
    scene::OverlaySpec given;
    given.scaleBarUnit = scene::LengthUnit{"km", 1000};
    given.scaleBarLength = 1.5;
    const ScaleBar km = chooseScaleBar(10, 800, given);
    EXPECT_EQ(km.label, "1.5 km");
    EXPECT_DOUBLE_EQ(km.pixels, 150);
}

// The legend in feet: its title says so and its ticks are round feet, placed
// at their heights in metres.
TEST(Overlay, LegendInFeet) {
    scene::OverlaySpec spec;
    spec.legendFeet = true;
    spec.places = {{"north_arrow", "off"}, {"credits", "off"}, {"scale_bar", "off"}};
    PngImage8 image = greyStill();
    OverlayRecord record;
    Diagnostics diags;
    ASSERT_TRUE(drawOverlays(image, spec, sampleFacts(""), {}, diags, &record));  // 10-300 m: 32.8-984 ft
    std::vector<std::string> texts;
    for (const auto& t : record.texts) texts.push_back(t.text);
    EXPECT_EQ(texts, (std::vector<std::string>{"Elevation (ft)", "200", "400", "600", "800"}));
    spec.legendTitle = "Höhe";
    spec.legendFeet = false;
    record = {};
    ASSERT_TRUE(drawOverlays(image, spec, sampleFacts(""), {}, diags, &record));
    EXPECT_EQ(record.texts.front().text, "Höhe");
    EXPECT_EQ(record.texts[1].text, "50");
}

}  // namespace
}  // namespace relief::annotate
