// Records stay UTF-8: every string of a JSON record made valid, the first that
// was not named for the warning, and the warning said once a run.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/text_escape.h"
#include "core/utf8_record.h"

namespace relief {
namespace {

using nlohmann::ordered_json;

const std::string kFffd = "\xEF\xBF\xBD";

TEST(Utf8Record, EveryStringMadeValidAndTheFirstNamed) {
    ordered_json j = {{"inputs", {{"scene", "caf\xe9.tif"}, {"samples", "ok.tif"}}},
                      {"outputs", {{"pov", "out/caf\xe9.pov"}}},
                      {"labels", {"fine", "na\xefve"}},
                      {"count", 3}};
    EXPECT_EQ(replaceNotUtf8(j), "inputs.scene: caf\xe9.tif");
    EXPECT_EQ(j["inputs"]["scene"], "caf" + kFffd + ".tif");
    EXPECT_EQ(j["inputs"]["samples"], "ok.tif");
    EXPECT_EQ(j["outputs"]["pov"], "out/caf" + kFffd + ".pov");
    EXPECT_EQ(j["labels"][1], "na" + kFffd + "ve");
    EXPECT_EQ(j["count"], 3);
    EXPECT_NO_THROW((void)j.dump());  // nlohmann throws type_error.316 on a byte that is not UTF-8
    EXPECT_EQ(replaceNotUtf8(j), "");  // nothing left to replace
}

TEST(Utf8Record, KeysToo) {
    ordered_json j = {{"parameters", {{"a", 1}, {"override overlay.t\xe9tle", "x"}, {"z", 2}}}};
    EXPECT_EQ(replaceNotUtf8(j), "parameters.override overlay.t\xe9tle (a key)");
    const ordered_json& p = j["parameters"];
    ASSERT_EQ(p.size(), 3u);
    auto it = p.begin();
    EXPECT_EQ(it.key(), "a");
    EXPECT_EQ((++it).key(), "override overlay.t" + kFffd + "tle");  // in its place
    EXPECT_EQ((++it).key(), "z");
    EXPECT_TRUE(isUtf8(j.dump()));
}

TEST(Utf8Record, TheWarningIsSaidOnceARun) {
    Diagnostics diags;
    checkUtf8(diags, {"dem.tif", 0, 0}, "dem.tif", "the file's name");  // UTF-8: nothing said
    EXPECT_EQ(diags.warningCount(), 0);
    checkUtf8(diags, {"caf\xe9.tif", 0, 0}, "caf\xe9.tif", "the file's name");
    checkUtf8(diags, {"--set overlay.title", 0, 0}, "\xff", "the value");
    warnNotUtf8(diags, {"x.toml", 0, 0}, "the sidecar's outputs.pov: out/\xe9.pov");
    ASSERT_EQ(diags.warningCount(), 1);
    EXPECT_EQ(formatDiagnostic(diags.all()[0]),
              "caf\xe9.tif: warning: the file's name is not UTF-8: the sidecar, info --json and a PDF's or SVG's text "
              "write each byte that is not as U+FFFD, here and in any other such name or text (a UTF-8 name or text "
              "keeps it whole)");
    EXPECT_FALSE(diags.hasErrors());
}

// A name a record must give back (a plan's still): the same bytes, whatever they are.
TEST(Utf8Record, NamesComeBackByteForByte) {
    ordered_json j;
    putName(j, "still", "caf\xc3\xa9.png");  // UTF-8: as text
    EXPECT_EQ(j, ordered_json({{"still", "caf\xc3\xa9.png"}}));
    j = ordered_json::object();
    putName(j, "still", "caf\xe9.png");
    EXPECT_EQ(j, ordered_json({{"still", "caf\xef\xbf\xbd.png"}, {"still_bytes", "636166e92e706e67"}}));
    EXPECT_TRUE(isUtf8(j.dump()));
    for (const std::string name : {"caf\xe9.png", "a\nb\x01\xff\xfe", "x.png"}) {
        ordered_json k;
        putName(k, "name", name);
        EXPECT_EQ(nameAt(ordered_json::parse(k.dump()), "name"), name);
    }
    for (const char* damaged : {R"({"name": "x", "name_bytes": "6"})", R"({"name": "x", "name_bytes": "zz"})",
                                R"({"other": 1})", R"({"name": 3})"})
        EXPECT_THROW((void)nameAt(ordered_json::parse(damaged), "name"), nlohmann::json::exception) << damaged;
}

}  // namespace
}  // namespace relief
