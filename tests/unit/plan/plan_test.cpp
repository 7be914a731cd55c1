// The render plan: strips that cover the still once, a plan that reads back
// as written, tile records held to their plan.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "plan/plan.h"
#include "relief/version.h"
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
    p.pov = {"x.pov", dir / "out" / "x.pov", "the .pov", ""};
    p.reads = {{"x.height.png", dir / "out" / "x.height.png", "the height field's PNG", ""}};
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
    // Read back, the outputs are beside the plan's folder, whatever it was planned beside.
    EXPECT_EQ(q->pov.final, dir.parent_path() / "x.pov");
    EXPECT_EQ(q->still, dir.parent_path() / "x.png");
    EXPECT_EQ(q->sidecar, dir.parent_path() / "x.json");
    EXPECT_EQ(q->pov.sha256, p.pov.sha256);
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

// plan.json's text with `from` replaced by `to`, its hash made right again (as a forger would).
void forge(const fs::path& dir, const std::string& from, const std::string& to) {
    auto j = nlohmann::ordered_json::parse(readFile(dir / "plan.json"));
    std::string text = j.dump();
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
    j = nlohmann::ordered_json::parse(text);
    j.erase("hash");
    j["hash"] = planFieldsHash(j);
    writeFileAtomically(dir / "plan.json", j.dump(1));
}

std::string firstError(const fs::path& dir) {
    Diagnostics diags;
    if (readPlan(dir, diags)) return "read";
    return formatDiagnostic(diags.all().at(0));
}

TEST(Plan, ADamagedOrForeignPlanIsNamed) {
    const fs::path dir = testing::freshTestDir("plan-damaged");
    EXPECT_EQ(firstError(dir), (dir / "plan.json").string() +
                                   ": error: no render plan here: the plan's folder must be on a filesystem this "
                                   "machine sees");
    RenderPlan p = samplePlan(dir);
    Diagnostics diags;
    ASSERT_TRUE(writePlan(p, diags));
    const std::string written = readFile(dir / "plan.json");
    // Edited: its hash tells.
    std::string text = written;
    text.replace(text.find("\"x.pov\""), 7, "\"../../etc/passwd\"");
    writeFileAtomically(dir / "plan.json", text);
    EXPECT_EQ(firstError(dir), (dir / "plan.json").string() +
                                   ": error: the render plan was changed after relief wrote it (its fields do not "
                                   "give the hash it holds): make it again");
    // Forged: what it says is checked all the same.
    const std::string damaged = (dir / "plan.json").string() +
                                ": error: the render plan is damaged (its files or sizes are not a plan's): make it "
                                "again";
    for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
             {"\"name\":\"x.pov\"", "\"name\":\"../../etc/passwd\""},
             {"\"still\":\"x.png\"", "\"still\":\"../x.png\""},
             {"\"still\":\"x.png\"", "\"still\":\"x.toml\""},
             {"\"sidecar\":\"x.json\"", "\"sidecar\":\"/tmp/x.json\""},
             {"\"name\":\"x.height.png\"", "\"name\":\"x.pov\""},
             {"\"name\":\"x.height.png\"", "\"name\":\"plan.json\""},
             {"\"width\":480", "\"width\":1000000000"},
             {"\"tiles\":3", "\"tiles\":321"},
             {"\"antialias_depth\":3", "\"antialias_depth\":100"}}) {
        writeFileAtomically(dir / "plan.json", written);
        forge(dir, from, to);
        EXPECT_EQ(firstError(dir), damaged) << to;
    }
    writeFileAtomically(dir / "plan.json", written);
    forge(dir, "\"relief_version\":\"", "\"relief_version\":\"0.0.1-");
    EXPECT_NE(firstError(dir).find("a render plan made by relief 0.0.1-"), std::string::npos);
    // A file edited, swapped for a link, missing: named.
    writeFileAtomically(dir / "plan.json", written);
    EXPECT_EQ(firstError(dir), "read");
    writeFileAtomically(dir / "x.height.png", "other png bytes");
    EXPECT_EQ(firstError(dir), (dir / "x.height.png").string() +
                                   ": error: differs from the file the plan was made with (its SHA-256 is not the "
                                   "one plan.json holds): make the plan again");
    writeFileAtomically(dir / "elsewhere.png", "png bytes");
    fs::remove(dir / "x.height.png");
    fs::create_symlink(dir / "elsewhere.png", dir / "x.height.png");
    EXPECT_EQ(firstError(dir), (dir / "x.height.png").string() +
                                   ": error: the plan's file cannot be used: it is a link, and relief follows none "
                                   "out of its own folders");
    fs::remove(dir / "x.height.png");
    EXPECT_EQ(firstError(dir), (dir / "x.height.png").string() + ": error: the plan's file is missing: make the plan again");
}

// fuzz_plan's seed is a whole plan (its .pov the fuzz target's own), so that the fuzzer starts from
// plans the reader takes: a format that moves on without it fails here, not quietly in the fuzzer.
TEST(Plan, TheFuzzSeedIsAWholePlan) {
    const fs::path dir = testing::freshTestDir("plan-fuzz-seed");
    writeFileAtomically(dir / "scene.pov", "// the .pov of the fuzz target's plan\n");
    auto j = nlohmann::ordered_json::parse(readFile(fs::path(RELIEF_SOURCE_DIR) / "tests/data/plans/small-3-tiles.json"));
    j["relief_version"] = kVersion;  // a seed outlives a version
    j.erase("hash");
    j["hash"] = planFieldsHash(j);
    writeFileAtomically(dir / "plan.json", j.dump(1));
    EXPECT_EQ(firstError(dir), "read");
}

TEST(Plan, KeepsNamesThatAreNotUtf8) {
    const fs::path dir = testing::freshTestDir("plan-latin1");
    RenderPlan p = samplePlan(dir);
    const std::string name = "caf\xe9";
    fs::rename(dir / "x.pov", dir / (name + ".pov"));
    p.pov.name = name + ".pov";
    p.still = dir / (name + ".png");
    Diagnostics diags;
    ASSERT_TRUE(writePlan(p, diags));
    const auto q = readPlan(dir, diags);
    ASSERT_TRUE(q) << formatDiagnostic(diags.all().at(0));
    EXPECT_EQ(q->pov.name, name + ".pov");
    EXPECT_EQ(q->still, dir.parent_path() / (name + ".png"));
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
    std::string sha;
    r.imageSha256 = fileSha256(tileImage(p, 1), sha);
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
    // Its image is the one it records, a plain file.
    writeFileAtomically(tileImage(p, 1), "another png");
    EXPECT_EQ(check(r), "its image is not the one rendered (its SHA-256 is not the record's): render the tile again");
    fs::remove(tileImage(p, 1));
    EXPECT_EQ(check(r), "its image is missing");
    fs::create_symlink(dir / "x.pov", tileImage(p, 1));
    EXPECT_EQ(check(r), "its image cannot be used: it is a link, and relief follows none out of its own folders");
}

}  // namespace
}  // namespace relief::plan
