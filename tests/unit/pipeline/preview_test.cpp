#include "pipeline/preview.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>

#include "emit/camera.h"
#include "unit/test_dirs.h"

namespace relief {
namespace {

// A point of the page's (the model's axes: x east, y up, z south, metres) from the still's
// camera as relief places it from [camera] keys: the path a used view takes to POV-Ray.
Vec3 modelPointOf(const emit::ScenePlacement& where, const SceneVec3& p) {
    return {p.x * where.metresPerUnit, p.y * where.metresPerUnit, -p.z * where.metresPerUnit};
}

// [lon, lat, height] read back from the TOML text the keys are written as.
GeoPoint parsedLonLatHeight(const std::string& text) {
    GeoPoint g;
    EXPECT_EQ(std::sscanf(text.c_str(), "[%lf, %lf, %lf]", &g.lonDeg, &g.latDeg, &g.heightM), 3) << text;
    return g;
}

// The view a page sends, turned into [camera] keys, read by relief as a scene's camera and placed
// as the still's: the eye and the target where the page had them, for views all round the terrain
// (straight down, grazing, from far, off-centre targets), in every kind of frame and with the
// heights exaggerated or not. The keys' text is what is read back (formatted to round trip).
TEST(PreviewCamera, AViewUsedIsTheStillsCameraInEveryFrame) {
    struct Setting {
        const char* name;
        scene::SceneOverrides overrides;
    };
    const std::vector<Setting> settings = {
        {"utm, x1", {{"frame.kind", "\"utm\""}}},
        {"local tangent plane (the Earth's fall), x2.5", {{"frame.kind", "\"local\""}, {"vertical.exaggeration", "2.5"}}},
        {"the raster's own CRS, x1.5", {{"frame.kind", "\"raster\""}, {"vertical.exaggeration", "1.5"}}},
    };
    std::mt19937 random(20261208);
    std::uniform_real_distribution<double> unit(0, 1);
    for (const Setting& setting : settings) {
        SCOPED_TRACE(setting.name);
        PreviewJob job;
        job.scenePath = testing::kSourceDir / "scenes/data/rasters/volcano2.tif";
        job.overrides = setting.overrides;
        job.overrides.push_back({"subdivision.depth", "0"});
        Diagnostics diags;
        const auto preview = previewScene(job, diags);
        ASSERT_TRUE(preview) << (diags.all().empty() ? "" : diags.all()[0].message);
        const auto& bounds = preview->page["bounds"];
        const auto at = [&](int corner, int k) { return bounds[corner][k].get<double>(); };
        const Vec3 lo{at(0, 0), at(0, 1), at(0, 2)}, hi{at(1, 0), at(1, 1), at(1, 2)};
        const double span = length(hi - lo);
        for (int i = 0; i < 60; ++i) {
            // Elevations 0.5 to 90 degrees (the last few straight down), any bearing, 0.3 to 5 spans
            // away, the target anywhere over the terrain's box.
            const double elevation = i >= 56 ? 90 : 0.5 + 89 * unit(random), bearing = 360 * unit(random);
            const double distance = span * (0.3 + 4.7 * unit(random));
            const Vec3 target{lo.x + (hi.x - lo.x) * unit(random), lo.y + (hi.y - lo.y) * unit(random),
                              lo.z + (hi.z - lo.z) * unit(random)};
            const double a = bearing * std::numbers::pi / 180, e = elevation * std::numbers::pi / 180;
            Vec3 eye = target + distance * Vec3{std::sin(a) * std::cos(e), std::sin(e), -std::cos(a) * std::cos(e)};
            if (elevation == 90) eye.z += 1e-6 * distance;  // as the page nudges a view straight down
            const PageView view{eye, target, 5 + 100 * unit(random)};
            SCOPED_TRACE(::testing::Message() << "view " << i << ": elevation " << elevation << ", bearing " << bearing);
            const auto keys = cameraKeysOf(*preview, view, diags);
            ASSERT_TRUE(keys);
            const auto toml = keys->toml();
            scene::CameraSpec camera;
            camera.position = parsedLonLatHeight(toml[0].second);
            camera.lookAt = parsedLonLatHeight(toml[1].second);
            camera.fovDeg = std::strtod(toml[2].second.c_str(), nullptr);
            EXPECT_EQ(camera.fovDeg, view.fovDeg);
            const auto points = emit::cameraPointsInFrame(camera, preview->frame, diags);
            ASSERT_TRUE(points && points->eyeM && points->targetM);
            const Vec3 eyeBack = modelPointOf(preview->where, preview->where.scenePoint(*points->eyeM));
            const Vec3 targetBack = modelPointOf(preview->where, preview->where.scenePoint(*points->targetM));
            // A micrometre a kilometre: the still's eye where the page's was (and so its heading,
            // which a view straight down takes from an offset of a millionth of the distance).
            EXPECT_LT(length(eyeBack - view.eye), 1e-9 * distance + 1e-9) << "eye";
            EXPECT_LT(length(targetBack - view.target), 1e-9 * distance + 1e-9) << "target";
        }
    }
}

TEST(PreviewCamera, AFlyoverNeedsTwoKeyframesAtTwoPlaces) {
    PreviewJob job;
    job.scenePath = testing::kSourceDir / "scenes/data/rasters/volcano2.tif";
    job.overrides = {{"subdivision.depth", "0"}};
    Diagnostics diags;
    const auto preview = previewScene(job, diags);
    ASSERT_TRUE(preview);
    const PageView a{{100, 800, 900}, {0, 100, 0}, 40}, b{{-900, 500, 200}, {0, 100, 0}, 40};
    const PageView one[] = {a}, twice[] = {a, a, b}, two[] = {a, b};
    Diagnostics refused;
    EXPECT_FALSE(flyoverKeysOf(*preview, one, refused));
    EXPECT_FALSE(flyoverKeysOf(*preview, twice, refused));
    ASSERT_EQ(refused.errorCount(), 2);
    EXPECT_NE(refused.all()[1].message.find("keyframes 1 and 2 are one place"), std::string::npos);
    const auto keys = flyoverKeysOf(*preview, two, diags);
    ASSERT_TRUE(keys);
    ASSERT_EQ(keys->size(), 3u);  // path, waypoints and (one target) look_at
    EXPECT_EQ((*keys)[0].second, "\"flyover\"");
    EXPECT_EQ((*keys)[2].first, "look_at");
}

}  // namespace
}  // namespace relief
