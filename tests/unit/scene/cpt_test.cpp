// GMT colour palettes: the slices become stops (steps where two slices meet
// in different colours), every colour notation GMT writes for RGB is read,
// and each malformed line is an error at its line and column.
#include "scene/cpt_palette.h"

#include <gtest/gtest.h>

#include <string>

#include <cmath>

#include "scene/color_ramp.h"

namespace relief::scene {
namespace {

double lin(double v) { return srgbToLinear(v / 255); }

TEST(Cpt, SlicesBecomeStops) {
    Diagnostics diags;
    const auto stops = parseCpt("# COLOR_MODEL = RGB\n"
                                "0 0/0/255 10 0/255/0\n"          // R/G/B
                                "10 0 255 0 20 255 255 255 L\n"   // R G B, a flag
                                "20\t#ff0000\t30\t128 ; a label\n" // hex, a grey level, a label
                                "B 0/0/0\nF 255/255/255\nN 128\n",
                                "p.cpt", diags);
    ASSERT_TRUE(stops) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    ASSERT_EQ(stops->size(), 5u);  // 0, 10 (shared), 20, 20 (a step to red), 30
    EXPECT_EQ((*stops)[0].elevM, 0);
    EXPECT_DOUBLE_EQ((*stops)[0].rgb.b, 1);
    EXPECT_EQ((*stops)[1].elevM, 10);
    EXPECT_EQ((*stops)[2].elevM, 20);
    EXPECT_DOUBLE_EQ((*stops)[2].rgb.r, 1);
    EXPECT_EQ((*stops)[3].elevM, 20);
    EXPECT_DOUBLE_EQ((*stops)[3].rgb.r, 1);
    EXPECT_DOUBLE_EQ((*stops)[3].rgb.g, 0);
    EXPECT_DOUBLE_EQ((*stops)[4].rgb.g, lin(128));
    // Between slices' stops, linear; at a step, the upper slice's colour.
    EXPECT_NEAR(sampleRamp(*stops, 5).g, 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(sampleRamp(*stops, 20).g, 0);
    EXPECT_NEAR(sampleRamp(*stops, 19.999).r, 0.9999, 1e-9);  // the second slice, green to white
    EXPECT_DOUBLE_EQ(sampleRamp(*stops, 19.999).g, 1);
}

// Every palette shipped in scenes/palettes/ reads, over the range its header gives.
TEST(Cpt, ShippedPalettesRead) {
    const struct {
        const char* file;
        size_t stops;
        double lo, hi;
    } shipped[] = {{"relief-hypsometric.cpt", 6, 0, 1000},
                   {"gmt-dem2.cpt", 8, 0, 4900},
                   {"gmt-etopo1.cpt", 0, -11000, 8500},
                   {"cpt-city-elevation.cpt", 0, 0, 7000}};
    for (const auto& p : shipped) {
        Diagnostics diags;
        std::string text;
        {
            FILE* f = std::fopen((std::string(RELIEF_SOURCE_DIR "/scenes/palettes/") + p.file).c_str(), "rb");
            ASSERT_TRUE(f) << p.file;
            char buf[8192];
            text.assign(buf, std::fread(buf, 1, sizeof buf, f));
            std::fclose(f);
        }
        const auto stops = parseCpt(text, p.file, diags);
        ASSERT_TRUE(stops) << p.file;
        EXPECT_EQ(diags.errorCount(), 0) << p.file;
        if (p.stops > 0) {
            EXPECT_EQ(stops->size(), p.stops) << p.file;
        }
        EXPECT_NEAR(stops->front().elevM, p.lo, 1) << p.file;
        EXPECT_NEAR(stops->back().elevM, p.hi, 1) << p.file;
    }
}

// fuzz_cpt's finding: "#-88e0d" was read as a colour with negative components.
TEST(Cpt, ASignedHexColourIsAnError) {
    Diagnostics diags;
    EXPECT_FALSE(parseCpt(".5\t#-88e0d 5\t#-88d0d\n", "signed.cpt", diags));
    EXPECT_GE(diags.errorCount(), 1);
}

TEST(Cpt, BadPalettesAreErrorsAtTheirLines) {
    const struct {
        const char* text;
        const char* message;
    } cases[] = {
        {"0 0/0/255 10 0/255/0\nten 0/0/0 20 0/0/0\n",
         "p.cpt:2:1: error: \"ten\" is not a number: each line is z_low colour z_high colour (e.g. 0 0/97/71 500 16/122/47)"},
        {"0 red 10 blue\n",
         "p.cpt:1:3: error: expected a colour (R/G/B, R G B, #rrggbb or a grey level, 0-255) after z_low; named colours and HSV are not read"},
        {"0 0/0/300 10 0/0/0\n",
         "p.cpt:1:3: error: expected a colour (R/G/B, R G B, #rrggbb or a grey level, 0-255) after z_low; named colours and HSV are not read"},
        {"# COLOR_MODEL = HSV\n0 0-1-1 10 120-1-1\n",
         "p.cpt:1:1: error: # COLOR_MODEL = HSV: relief reads RGB palettes only; convert it with GMT's gmt makecpt or give the colours as R/G/B"},
        {"1 0/0/0 ; category\n",
         "p.cpt:1:9: error: expected z_high after the first colour: a categorical palette (one value a line) cannot colour elevations"},
        {"10 0/0/0 5 1/1/1\n", "p.cpt:1:10: error: z_high 5 must be above z_low 10"},
        {"0 0/0/0 10 1/1/1\n5 0/0/0 20 1/1/1\n",
         "p.cpt:2:1: error: slice from 5 overlaps the one before (to 10): list slices bottom to top"},
        {"0 0/0/0 10 1/1/1 X\n", "p.cpt:1:18: error: unexpected \"X\" after the slice's colours"},
        {"# only comments\n\n", "p.cpt: error: no colour slices: a .cpt needs lines z_low colour z_high colour"},
        {"0 0/0/0 10 1/1/1\n\x7f" "ELF\0\0", "p.cpt:2:1: error: not a colour palette (a NUL byte): a .cpt file is text"},
    };
    for (const auto& c : cases) {
        Diagnostics diags;
        const std::string text(c.text, std::string_view(c.text).size() + (std::string_view(c.text).find("ELF") != std::string_view::npos ? 2 : 0));
        EXPECT_FALSE(parseCpt(text, "p.cpt", diags)) << c.text;
        ASSERT_GE(diags.errorCount(), 1) << c.text;
        EXPECT_EQ(formatDiagnostic(diags.all()[0]), c.message);
    }
}

}  // namespace
}  // namespace relief::scene
