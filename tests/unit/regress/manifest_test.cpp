#include "regress/regress.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include "unit/test_dirs.h"

namespace relief::regress {
namespace {

namespace fs = std::filesystem;

// Defaults apply to every case, a case overrides them, and every problem is
// reported at its line.
TEST(Manifest, DefaultsOverridesAndErrorsAtTheirLines) {
    const fs::path dir = relief::testing::freshTestDir("relief-manifest-test");
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"x.csv\"\n";
    std::ofstream(dir / "m.toml") << "[defaults]\nwidth = 200\nfail = 0.01\n"
                                     "[[case]]\nname = \"a\"\nscene = \"s.toml\"\nreferences = \"ref\"\n"
                                     "[[case]]\nname = \"b\"\nscene = \"s.toml\"\nreferences = \"ref\"\nwidth = 64\n";
    Diagnostics diags;
    const auto m = readManifest(dir / "m.toml", diags);
    ASSERT_TRUE(m) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    ASSERT_EQ(m->cases.size(), 2u);
    EXPECT_EQ(m->cases[0].width, 200);
    EXPECT_EQ(m->cases[1].width, 64);
    EXPECT_DOUBLE_EQ(m->cases[1].thresholds.fail, 0.01);
    EXPECT_EQ(m->cases[0].scene, dir / "s.toml");

    std::ofstream(dir / "bad.toml") << "[[case]]\nname = \"a\"\nscene = \"s.toml\"\nreferences = \"ref\"\n"
                                       "[[case]]\nname = \"a\"\nscene = \"missing.toml\"\nreferences = \"ref\"\n";
    Diagnostics bad;
    EXPECT_FALSE(readManifest(dir / "bad.toml", bad));
    ASSERT_EQ(bad.errorCount(), 2);  // the duplicate name and the missing scene
    for (const auto& d : bad.all()) EXPECT_GE(d.loc.line, 5) << d.message;
    fs::remove_all(dir);
}

// A case's name names its files in the report: no path, no markup, no control characters.
TEST(Manifest, CaseNamesAreFileNames) {
    const fs::path dir = relief::testing::freshTestDir("relief-manifest-names");
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"x.csv\"\n";
    for (const std::string name : {"../../escape", "a/b", ".hidden", "<b>x</b>", "tab\\there", ""}) {
        std::ofstream(dir / "m.toml") << "[[case]]\nname = \"" << name << "\"\nscene = \"s.toml\"\nreferences = \"ref\"\n";
        Diagnostics diags;
        EXPECT_FALSE(readManifest(dir / "m.toml", diags)) << name;
        ASSERT_EQ(diags.errorCount(), 1) << name;
        EXPECT_EQ(diags.all()[0].loc.line, 2);
        EXPECT_NE(diags.all()[0].message.find("must be 1 to 100 letters, digits, '-', '_' or '.'"), std::string::npos);
    }
    std::ofstream(dir / "m.toml") << "[[case]]\nname = \"mt-eden_2.5m\"\nscene = \"s.toml\"\nreferences = \"ref\"\n";
    Diagnostics diags;
    EXPECT_TRUE(readManifest(dir / "m.toml", diags));
    fs::remove_all(dir);
}

// A profile is "LON,LAT:LON,LAT" in degrees, read the same in any locale:
// spaces after the separators are allowed; nan, inf, a far latitude or text
// after the fourth number are errors at the line.
TEST(Manifest, ProfilesAreFourFiniteDegrees) {
    const fs::path dir = relief::testing::freshTestDir("relief-manifest-profiles");
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"x.csv\"\n";
    auto read = [&](const std::string& profile, Diagnostics& diags) {
        std::ofstream(dir / "m.toml") << "[[case]]\nname = \"a\"\nscene = \"s.toml\"\nreferences = \"ref\"\n"
                                      << "profile = \"" << profile << "\"\n";
        return readManifest(dir / "m.toml", diags);
    };
    Diagnostics good;
    const auto m = read("-3.17, 55.94: -3.15,55.95", good);
    ASSERT_TRUE(m) << (good.all().empty() ? "" : formatDiagnostic(good.all()[0]));
    ASSERT_EQ(m->cases.front().geometry.profiles.size(), 1u);
    EXPECT_DOUBLE_EQ(m->cases.front().geometry.profiles[0].from.latDeg, 55.94);
    EXPECT_DOUBLE_EQ(m->cases.front().geometry.profiles[0].to.lonDeg, -3.15);
    for (const std::string bad : {"nan,55:-3,55", "-3,inf:-3,55", "-3,95:-3,55", "-3,55:-3,55x", "-3,55,-3,55",
                                  "-3,55:-3", ""}) {
        Diagnostics diags;
        EXPECT_FALSE(read(bad, diags)) << bad;
        ASSERT_EQ(diags.errorCount(), 1) << bad;
        EXPECT_EQ(diags.all()[0].loc.line, 5) << bad;
        EXPECT_NE(diags.all()[0].message.find("is not \"LON,LAT:LON,LAT\""), std::string::npos) << bad;
    }
    fs::remove_all(dir);
}

// Found by fuzz_manifest: a scene path the system refuses (here too long for
// it) made std::filesystem throw out of the reader; it is a missing scene.
TEST(Manifest, AScenePathTheSystemRefusesIsAnError) {
    const fs::path dir = relief::testing::freshTestDir("relief-manifest-long-path");
    std::ofstream(dir / "m.toml") << "[[case]]\nname = \"a\"\nscene = \"/" << std::string(5000, 'j')
                                  << ".toml\"\nreferences = \"ref\"\n";
    Diagnostics diags;
    EXPECT_FALSE(readManifest(dir / "m.toml", diags));
    ASSERT_EQ(diags.errorCount(), 1);
    EXPECT_EQ(diags.all()[0].loc.line, 3);
    EXPECT_NE(diags.all()[0].message.find("not found (relative to the manifest): File name too long"),
              std::string::npos)
        << diags.all()[0].message;
    fs::remove_all(dir);
}

TEST(Manifest, StatusNames) {
    EXPECT_STREQ(statusName(CaseStatus::Pass), "PASS");
    EXPECT_STREQ(statusName(CaseStatus::Fail), "FAIL");
}

}  // namespace
}  // namespace relief::regress
