#include <gtest/gtest.h>

#include <clocale>
#include <string>

#include "core/diagnostics.h"
#include "core/number_format.h"
#include "core/text_distance.h"

namespace relief {
namespace {

std::string fixed(double v, int d) {
    char buf[40];
    return std::string(buf, writeFixed(buf, v, d));
}

TEST(NumberFormat, FixedDecimals) {
    EXPECT_EQ(fixed(0, 5), "0");
    EXPECT_EQ(fixed(-0.0, 5), "0");
    EXPECT_EQ(fixed(-0.000001, 5), "0");
    EXPECT_EQ(fixed(1.5, 0), "2");
    EXPECT_EQ(fixed(3.14159265, 5), "3.14159");
    EXPECT_EQ(fixed(-2.0000051, 5), "-2.00001");
    EXPECT_EQ(fixed(2.0000049, 5), "2.00000");
    EXPECT_EQ(fixed(0.05, 3), "0.050");
    EXPECT_EQ(fixed(-12345.678901, 6), "-12345.678901");
    EXPECT_EQ(fixed(99.999996, 5), "100.00000");
    EXPECT_EQ(fixed(0.00042, 6), "0.000420");
}

TEST(NumberFormat, UnsignedAndLocaleFree) {
    char buf[24];
    EXPECT_EQ(std::string(buf, writeUnsigned(buf, 0)), "0");
    EXPECT_EQ(std::string(buf, writeUnsigned(buf, 18446744073709551615ull)),
              "18446744073709551615");
    // A locale with a decimal comma, if installed, changes nothing.
    if (std::setlocale(LC_ALL, "de_DE.UTF-8")) {
        EXPECT_EQ(fixed(1.25, 2), "1.25");
        EXPECT_EQ(formatShortest(0.5), "0.5");
        std::setlocale(LC_ALL, "C");
    }
}

TEST(Diagnostics, FormatsLocation) {
    Diagnostics d;
    d.error({"a.toml", 3, 7}, "bad");
    d.warning({"a.toml", 0, 0}, "meh");
    d.error({}, "no file");
    EXPECT_EQ(formatDiagnostic(d.all()[0]), "a.toml:3:7: error: bad");
    EXPECT_EQ(formatDiagnostic(d.all()[1]), "a.toml: warning: meh");
    EXPECT_EQ(formatDiagnostic(d.all()[2]), "error: no file");
    EXPECT_EQ(d.errorCount(), 2);
    EXPECT_EQ(d.warningCount(), 1);
}

TEST(TextDistance, Suggestions) {
    EXPECT_EQ(editDistance("subdivison", "subdivision"), 1);
    EXPECT_EQ(closestMatch("subdivison", {"samples", "subdivision", "camera"}), "subdivision");
    EXPECT_EQ(closestMatch("zzzz", {"samples", "camera"}), "");
}

}  // namespace
}  // namespace relief
