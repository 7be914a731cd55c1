#include "scene/edit_scene.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace relief::scene {
namespace {

// What "Use this view" writes: three keys, the orbit's retired.
const std::vector<TomlKeyValue> kView = {{"position", "[174.5, -36.9, 500]"}, {"look_at", "[174.6, -36.8, 100]"},
                                         {"fov_deg", "35"}};
const std::vector<std::string> kOrbit = {"azimuth_deg", "elevation_deg", "distance_m"};

struct EditCase {
    const char* name;
    std::string before, after;
};

// Each case: a scene's text, and exactly the text relief must make of it.
const std::vector<EditCase> kCases = {
    {"keys replaced in place, their comments kept, the orbit's commented out",
     "# my scene\n[camera]\nazimuth_deg = 200   # from the south\nelevation_deg = 35\nfov_deg = 40  # wide\n\n"
     "[render]\nwidth = 640\n",
     "# my scene\n[camera]\n# azimuth_deg = 200   # from the south\n# elevation_deg = 35\nfov_deg = 35  # wide\n"
     "position = [174.5, -36.9, 500]\nlook_at = [174.6, -36.8, 100]\n\n[render]\nwidth = 640\n"},
    {"a value over several lines becomes one",
     "[camera]\nposition = [\n  1,\n  2,\n  3,\n] # eye\nlook_at = [1, 2, 0]\n",
     "[camera]\nposition = [174.5, -36.9, 500] # eye\nlook_at = [174.6, -36.8, 100]\nfov_deg = 35\n"},
    {"no [camera]: the table appended",
     "[samples]\npath = \"a.csv\"",
     "[samples]\npath = \"a.csv\"\n\n[camera]\nposition = [174.5, -36.9, 500]\nlook_at = [174.6, -36.8, 100]\nfov_deg = 35\n"},
    {"an empty [camera]: keys under its header, before the next table",
     "[camera]\n\n# next\n[render]\nwidth = 64\n",
     "[camera]\nposition = [174.5, -36.9, 500]\nlook_at = [174.6, -36.8, 100]\nfov_deg = 35\n\n# next\n[render]\nwidth = 64\n"},
    {"CRLF line endings kept, new lines too",
     "[camera]\r\nfov_deg = 40\r\n[render]\r\nwidth = 64\r\n",
     "[camera]\r\nfov_deg = 35\r\nposition = [174.5, -36.9, 500]\r\nlook_at = [174.6, -36.8, 100]\r\n[render]\r\nwidth = 64\r\n"},
    {"the last key's value over several lines, replaced: new keys after it",
     "[camera]\nfov_deg = 40\nposition = [\n  1,\n  2,\n  3]\n",
     "[camera]\nfov_deg = 35\nposition = [174.5, -36.9, 500]\nlook_at = [174.6, -36.8, 100]\n"},
    {"a sub-table after the table: new keys before its header",
     "[camera]\nfov_deg = 40\n\n[camera.extra]\nx = 1\n",
     "[camera]\nfov_deg = 35\nposition = [174.5, -36.9, 500]\nlook_at = [174.6, -36.8, 100]\n\n[camera.extra]\nx = 1\n"},
    {"a header with spaces and a comment",
     "[ camera ]  # the view\ndistance_m = 900\n",
     "[ camera ]  # the view\n# distance_m = 900\nposition = [174.5, -36.9, 500]\nlook_at = [174.6, -36.8, 100]\nfov_deg = 35\n"},
};

TEST(EditScene, WritesExactlyTheKeysAndKeepsEveryOtherLine) {
    for (const EditCase& c : kCases) {
        SCOPED_TRACE(c.name);
        Diagnostics diags;
        const auto out = withTableKeys(c.before, "scene.toml", "camera", kView, kOrbit, diags);
        ASSERT_TRUE(out) << (diags.all().empty() ? "" : diags.all()[0].message);
        EXPECT_EQ(*out, c.after);
        // What must hold of every case: the text parses, [camera] has the values written, and
        // every comment of the file before is still there.
        const toml::table t = toml::parse(*out);
        EXPECT_EQ(t["camera"]["fov_deg"].value<double>(), 35.0);
        EXPECT_EQ(t["camera"]["position"][2].value<double>(), 500.0);
        EXPECT_EQ(t["camera"]["look_at"][0].value<double>(), 174.6);
        for (const std::string& key : kOrbit) EXPECT_FALSE(t["camera"][key]) << key;
        std::istringstream lines(c.before);
        for (std::string line; std::getline(lines, line);) {
            const size_t hash = line.find('#');
            if (hash == std::string::npos) continue;
            EXPECT_NE(out->find(line.substr(hash)), std::string::npos) << "lost comment: " << line;
        }
    }
}

TEST(EditScene, DefaultsOnlyWhereTheTableLacksThem) {
    Diagnostics diags;
    const std::vector<TomlKeyValue> path = {{"path", "\"flyover\""}};
    const auto kept = withTableKeys("[animation]\nframes = 240\npath = \"orbit\"\n", "s.toml", "animation", path, {},
                                    diags, {{"frames", "48"}});
    ASSERT_TRUE(kept);
    EXPECT_EQ(*kept, "[animation]\nframes = 240\npath = \"flyover\"\n");
    const auto added = withTableKeys("[animation]\npath = \"orbit\"\n", "s.toml", "animation", path, {}, diags,
                                     {{"frames", "48"}});
    ASSERT_TRUE(added);
    EXPECT_EQ(*added, "[animation]\npath = \"flyover\"\nframes = 48\n");
}

TEST(EditScene, AKeyBothSetAndRetiredIsSet) {
    Diagnostics diags;
    const std::vector<std::string> retired = {"look_at", "azimuth_from_deg"};
    const auto out = withTableKeys("[animation]\nazimuth_from_deg = 0\nlook_at = [1, 2, 3]\n", "s.toml", "animation",
                                   {{"look_at", "[4, 5, 6]"}}, retired, diags);
    ASSERT_TRUE(out);
    EXPECT_EQ(*out, "[animation]\n# azimuth_from_deg = 0\nlook_at = [4, 5, 6]\n");
}

TEST(EditScene, RefusesWhatItCannotEditWithTheFix) {
    const std::vector<std::pair<std::string, std::string>> refused = {
        {"camera = { fov_deg = 40 }\n", "written inline or as dotted keys"},
        {"camera.fov_deg = 40\n", "written inline or as dotted keys"},
        {"[camera]\nfov_deg = \n", "fix the file"},
    };
    for (const auto& [text, why] : refused) {
        SCOPED_TRACE(text);
        Diagnostics diags;
        EXPECT_FALSE(withTableKeys(text, "scene.toml", "camera", kView, kOrbit, diags));
        ASSERT_EQ(diags.errorCount(), 1);
        EXPECT_NE(diags.all()[0].message.find(why), std::string::npos) << diags.all()[0].message;
        EXPECT_EQ(diags.all()[0].loc.file, "scene.toml");
        EXPECT_GT(diags.all()[0].loc.line, 0);
    }
}

}  // namespace
}  // namespace relief::scene
