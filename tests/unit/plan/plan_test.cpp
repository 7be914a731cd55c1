// The render plan: strips that cover the still once, a plan that reads back
// as written, tile records held to their plan.
#include <gtest/gtest.h>

#include <fstream>

#include "core/atomic_file.h"
#include "plan/plan.h"
#include "unit/test_dirs.h"

namespace relief::plan {
namespace {

namespace fs = std::filesystem;

TEST(Plan, TilesCoverEveryRowOnce) {
    for (int height : {1, 2, 7, 120, 1081, 2160})
        for (int tiles : {1, 2, 3, 7, 64, 5000}) {
            int next = 1;
            const int n = std::min(tiles, height);
            for (int k = 0; k < n; ++k) {
                const TileRows r = tileRows(height, tiles, k);
                EXPECT_EQ(r.first, next) << height << " rows, " << tiles << " tiles, tile " << k;
                EXPECT_GE(r.last, r.first);
                EXPECT_LE(r.last - r.first + 1, height / n + 1);  // as equal as whole rows make them
                next = r.last + 1;
            }
            EXPECT_EQ(next, height + 1) << height << " rows, " << tiles << " tiles";
        }
}

RenderPlan samplePlan(const fs::path& dir) {
    RenderPlan p;
    p.dir = dir;
    p.povrayVersion = "3.7.0.10.unofficial";
    p.pov = {"x.pov", dir / "out" / "x.pov", "the .pov"};
    p.reads = {{"x.height.png", dir / "out" / "x.height.png", "the height field's PNG"}};
    p.width = 480;
    p.height = 320;
    p.tiles = 3;
    p.alpha = true;
    p.still = dir / "out" / "x.png";
    p.sidecar = dir / "out" / "x.json";
    p.overlays = true;
    p.overlaySpec.title = "Maungawhau <b>&amp;</b>";
    p.overlayFacts.palette = {{0.1, 0.2, 0.3}, {0.4, 0.5, 0.6000000000000001}};
    p.overlayFacts.metresPerPixel = 1.0 / 3.0;
    p.overlayFacts.terrain.top = {1.5, 2.25};
    p.overlayFacts.terrain.bottom = {9.125, 10};
    p.sidecar0 = {{"relief_version", "x"}};
    writeFileAtomically(dir / "x.pov", "// a scene\n");
    writeFileAtomically(dir / "x.height.png", "png bytes");
    return p;
}

TEST(Plan, ReadsBackAsWrittenWithItsHash) {
    const fs::path dir = testing::freshTestDir("plan-roundtrip");
    RenderPlan p = samplePlan(dir);
    Diagnostics diags;
    ASSERT_TRUE(writePlan(p, diags));
    EXPECT_EQ(p.hash.rfind("sha256:", 0), 0u);
    const auto q = readPlan(dir, diags);
    ASSERT_TRUE(q);
    EXPECT_EQ(q->hash, p.hash);
    EXPECT_EQ(q->pov.final, p.pov.final);
    EXPECT_EQ(q->reads.size(), 1u);
    EXPECT_EQ(q->tiles, 3);
    EXPECT_TRUE(q->alpha);
    EXPECT_EQ(q->overlaySpec.title, p.overlaySpec.title);
    // The facts come back to the bit: the overlays drawn elsewhere are the same pixels.
    EXPECT_EQ(q->overlayFacts.palette[1].b, p.overlayFacts.palette[1].b);
    EXPECT_EQ(q->overlayFacts.metresPerPixel, p.overlayFacts.metresPerPixel);
    EXPECT_EQ(q->overlayFacts.terrain.bottom, p.overlayFacts.terrain.bottom);
    // Another file's bytes, another hash.
    writeFileAtomically(dir / "x.height.png", "other png bytes");
    RenderPlan r = samplePlan(dir);
    writeFileAtomically(dir / "x.height.png", "other png bytes");
    ASSERT_TRUE(writePlan(r, diags));
    EXPECT_NE(r.hash, p.hash);
}

TEST(Plan, ADamagedOrForeignPlanIsNamed) {
    const fs::path dir = testing::freshTestDir("plan-damaged");
    Diagnostics diags;
    EXPECT_FALSE(readPlan(dir, diags));
    EXPECT_EQ(formatDiagnostic(diags.all().at(0)),
              (dir / "plan.json").string() +
                  ": error: no render plan here: the plan's folder must be on a filesystem this machine sees");
    RenderPlan p = samplePlan(dir);
    ASSERT_TRUE(writePlan(p, diags));
    std::string text = readFile(dir / "plan.json");
    text.replace(text.find("\"x.pov\""), 7, "\"../../etc/passwd\"");
    writeFileAtomically(dir / "plan.json", text);
    Diagnostics damaged;
    EXPECT_FALSE(readPlan(dir, damaged));
    EXPECT_NE(formatDiagnostic(damaged.all().at(0)).find("the render plan is damaged"), std::string::npos);
}

TEST(Plan, TileRecordsAreHeldToTheirPlan) {
    const fs::path dir = testing::freshTestDir("plan-records");
    RenderPlan p = samplePlan(dir);
    Diagnostics diags;
    ASSERT_TRUE(writePlan(p, diags));
    p.reliefVersion = readPlan(dir, diags)->reliefVersion;
    fs::create_directories(dir / "tiles");
    writeFileAtomically(tileImage(p, 1), "png");
    TileRecord r;
    r.index = 1;
    r.rows = tileRows(p.height, p.tiles, 1);
    r.planHash = p.hash;
    r.reliefVersion = p.reliefVersion;
    r.povrayVersion = p.povrayVersion;
    r.host = "node7";
    const auto check = [&](const TileRecord& rec) {
        writeFileAtomically(tileRecordPath(p, 1), tileRecordJson(rec).dump());
        std::string problem;
        return readTileRecord(p, 1, problem) ? std::string("good") : problem;
    };
    EXPECT_EQ(check(r), "good");
    TileRecord other = r;
    other.planHash = "sha256:0123456789abcdef0123";
    EXPECT_EQ(check(other).rfind("it was rendered from another plan (sha256:0123456789ab", 0), 0u);
    other = r;
    other.povrayVersion = "3.8.0";
    EXPECT_EQ(check(other), "it was rendered by POV-Ray 3.8.0 on node7, the plan made for 3.7.0.10.unofficial");
    other = r;
    other.rows.last += 1;
    EXPECT_EQ(check(other), "its record is of another tile");
    EXPECT_EQ(missingTiles(p), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(check(r), "good");
    EXPECT_EQ(missingTiles(p), (std::vector<int>{0, 2}));
}

}  // namespace
}  // namespace relief::plan
