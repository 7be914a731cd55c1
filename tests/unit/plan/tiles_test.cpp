#include "plan/tiles.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "core/png_file.h"
#include "unit/test_dirs.h"

namespace relief::plan {
namespace {

namespace fs = std::filesystem;

// A plan of a 5 x 7 still in 3 tiles, each tile's pixels its rows' numbers,
// written as POV-Ray and renderTile leave them (a PNG, then its record).
RenderPlan planWithTiles(const fs::path& dir) {
    RenderPlan plan;
    plan.dir = dir;
    plan.width = 5, plan.height = 7, plan.tiles = 3;
    plan.hash = "sha256:0123456789abcdef0123", plan.reliefVersion = "1.0", plan.povrayVersion = "3.7.0.10";
    fs::create_directories(dir / "tiles");
    for (int k = 0; k < plan.tiles; ++k) {
        const TileRows rows = tileRows(plan.height, plan.tiles, k);
        std::vector<std::uint8_t> pixels;
        for (int row = rows.first; row <= rows.last; ++row)
            for (int x = 0; x < plan.width * 3; ++x) pixels.push_back(static_cast<std::uint8_t>(10 * row + x % 3));
        const int h = rows.last - rows.first + 1;
        EXPECT_NO_THROW(writePngAtomically(tileImage(plan, k), {plan.width, h, 3, false, pixels.data()}));
        TileRecord record;
        record.index = k, record.rows = rows, record.planHash = plan.hash;
        record.reliefVersion = plan.reliefVersion, record.povrayVersion = plan.povrayVersion, record.host = "here";
        std::string problem;
        record.imageSha256 = fileSha256(tileImage(plan, k), problem);
        std::ofstream(tileRecordPath(plan, k)) << tileRecordJson(record).dump();
    }
    return plan;
}

// The message stitchTiles gave, at the plan's plan.json; "" when it gave none.
std::string stitchError(const RenderPlan& plan) {
    Diagnostics diags;
    if (stitchTiles(plan, diags)) return "";
    EXPECT_EQ(diags.all().at(0).loc.file, (plan.dir / "plan.json").string());
    return diags.all().at(0).message;
}

// The still is its tiles' rows in order, every byte; nothing POV-Ray runs.
TEST(StitchTiles, TheStillIsItsTilesRowsInOrder) {
    const RenderPlan plan = planWithTiles(relief::testing::freshTestDir("relief-stitch"));
    Diagnostics diags;
    const auto still = stitchTiles(plan, diags);
    ASSERT_TRUE(still) << (diags.all().empty() ? "" : diags.all().front().message);
    ASSERT_EQ(still->width, 5);
    ASSERT_EQ(still->height, 7);
    ASSERT_EQ(still->channels, 3);
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 15; ++x) ASSERT_EQ(still->pixels[y * 15 + x], 10 * (y + 1) + x % 3) << y << " " << x;
}

// A tile that is not the plan's is named, and no still is made of it.
TEST(StitchTiles, ATileThatIsNotThePlansIsNamed) {
    {
        const RenderPlan plan = planWithTiles(relief::testing::freshTestDir("relief-stitch-record"));
        fs::remove(tileRecordPath(plan, 1));  // a tile half-written: its PNG, no record
        const std::string error = stitchError(plan);
        EXPECT_EQ(error.rfind("tile 2 of 3: ", 0), 0u) << error;
    }
    {
        RenderPlan plan = planWithTiles(relief::testing::freshTestDir("relief-stitch-hash"));
        plan.hash = "sha256:ffffffffffffffffffff";  // the tiles were rendered from another plan
        EXPECT_EQ(stitchError(plan), "tile 1 of 3: it was rendered from another plan (sha256:0123456789ab, not sha256:ffffffffffff)");
    }
    {
        const RenderPlan plan = planWithTiles(relief::testing::freshTestDir("relief-stitch-size"));
        const std::vector<std::uint8_t> pixels(5 * 4 * 3, 0);  // tile 3 is rows 5..7: 3 rows, not 4
        ASSERT_NO_THROW(writePngAtomically(tileImage(plan, 2), {5, 4, 3, false, pixels.data()}));
        EXPECT_EQ(stitchError(plan), "tile 3 of 3: its image is not the one rendered (its SHA-256 is not the record's): render the "
                         "tile again");
        auto record = nlohmann::json::parse(readFile(tileRecordPath(plan, 2)));
        std::string problem;
        record["image_sha256"] = fileSha256(tileImage(plan, 2), problem);  // and its record forged
        std::ofstream(tileRecordPath(plan, 2)) << record.dump();
        EXPECT_EQ(stitchError(plan), "tile 3 of 3: cannot read " + tileImage(plan, 2).string() +
                                         ": it is 5 x 4 pixels, not 5 x 3");
    }
}

}  // namespace
}  // namespace relief::plan
