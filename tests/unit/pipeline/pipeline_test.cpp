#include "pipeline.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"

namespace relief {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = RELIEF_SOURCE_DIR;

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("relief-pipeline-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(Pipeline, OutputPathsSitBesideTheStill) {
    const OutputPaths p = outputPathsFor("out/x/still.png");
    EXPECT_EQ(p.pov, fs::path("out/x/still.pov"));
    EXPECT_EQ(p.sidecar, fs::path("out/x/still.json"));
}

// Compiling only: the .pov is byte-identical to the golden one, and the
// library writes the sidecar, whose sizes come from the one mesh size formula.
TEST(Pipeline, CompileJobWritesThePovAndItsSidecar) {
    const fs::path dir = freshDir("compile");
    SceneJob job;
    job.until = SceneJob::Until::Pov;
    job.scenePath = kSource / "tests/golden/small/scene.toml";
    job.output = dir / "small.pov";
    job.templatesDir = kSource / "templates";
    job.threads = 1;
    Diagnostics diags;
    std::vector<ProgressEvent> events;
    const JobOutcome outcome = runSceneJob(job, diags, [&](const ProgressEvent& e) { events.push_back(e); });
    ASSERT_EQ(outcome.status, JobStatus::Ok) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    // Reading, compiling, then each task's percentages in order (how many of the
    // gridding's depends on GDAL's threads), each ending at 100 %; no render.
    ASSERT_GE(events.size(), 6u);
    EXPECT_EQ(events[0].stage, ProgressEvent::Stage::Reading);
    EXPECT_EQ(events[1].stage, ProgressEvent::Stage::Compiling);
    std::vector<std::string> tasks;
    for (size_t i = 2; i < events.size(); ++i) {
        EXPECT_EQ(events[i].stage, ProgressEvent::Stage::Compiling);
        if (tasks.empty() || events[i].text != tasks.back()) {
            if (!tasks.empty() && events[i - 1].percent >= 0) {
                EXPECT_EQ(events[i - 1].percent, 100) << tasks.back();
            }
            tasks.push_back(events[i].text);
        } else {
            EXPECT_GE(events[i].percent, events[i - 1].percent) << events[i].text;
        }
    }
    const std::vector<std::string> expected = {"gridding 300 samples", "subdividing to depth 2 (45 x 33 nodes)",
                                               "writing small.pov (2816 triangles)"};
    EXPECT_EQ(tasks, expected);
    EXPECT_EQ(events.back().percent, 100);
    const std::string pov = readFile(dir / "small.pov");
    const std::string golden = readFile(kSource / "tests/golden/small/ref.pov");
    // The header names the scene as given; everything after it must match.
    EXPECT_EQ(pov.substr(pov.find("\n#")), golden.substr(golden.find("\n#")));
    const auto sidecar = nlohmann::json::parse(readFile(dir / "small.json"));
    const auto& c = *outcome.compiled;
    EXPECT_EQ(sidecar["refined"]["rows"], c.estimate.rows);
    EXPECT_EQ(sidecar["refined"]["triangles"], 2 * (c.estimate.rows - 1) * (c.estimate.cols - 1));
    EXPECT_EQ(sidecar["refined"]["pov_bytes"], pov.size());
    EXPECT_EQ(sidecar["outputs"]["pov"], (dir / "small.pov").string());
    EXPECT_FALSE(sidecar["outputs"].contains("png"));
    EXPECT_FALSE(fs::exists(dir / "small.png"));
}

// A bad scene: the diagnostics say why, and nothing is written.
TEST(Pipeline, BadSceneWritesNothing) {
    const fs::path dir = freshDir("bad");
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"missing.csv\"\n[render]\nwidth = 3\n";
    SceneJob job;
    job.scenePath = dir / "s.toml";
    job.output = dir / "out" / "s.png";
    job.templatesDir = kSource / "templates";
    Diagnostics diags;
    const JobOutcome outcome = runSceneJob(job, diags, nullptr);
    EXPECT_EQ(outcome.status, JobStatus::BadInput);
    EXPECT_EQ(diags.errorCount(), 2);  // every problem at once
    EXPECT_FALSE(fs::exists(dir / "out"));
}

// The surface: the refined grid keeps the net's frame and extent.
TEST(Pipeline, RefinedSurfaceKeepsTheNetsFrameAndExtent) {
    Diagnostics diags;
    const auto loaded = loadScene(kSource / "tests/golden/small/scene.toml", diags);
    ASSERT_TRUE(loaded);
    const auto s = buildSurface(*loaded, diags, 1);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->refined.frame.describe(), s->net.frame.describe());
    EXPECT_NEAR(s->refined.xMax(), s->net.xMax(), 1e-6);
    EXPECT_NEAR(s->refined.yMax(), s->net.yMax(), 1e-6);
    EXPECT_EQ(s->refined.rows(), s->estimate.rows);
    // The refined lattice's nodes sit where its origin and spacing say.
    const Vec3& corner = s->refined.grid.at(s->refined.rows() - 1, s->refined.cols() - 1);
    EXPECT_NEAR(corner.x, s->refined.xMax(), 1e-6);
    EXPECT_NEAR(corner.y, s->refined.yMax(), 1e-6);
}

}  // namespace
}  // namespace relief
