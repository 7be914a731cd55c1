#include <gtest/gtest.h>

#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <locale>
#include <sstream>
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
}

// A C locale with a decimal comma changes nothing. The build compiles
// de_DE.UTF-8 into the build tree (tests/CMakeLists.txt) and the test points
// glibc at it (LOCPATH), so this runs everywhere; the locale's comma is checked
// first, so the test cannot pass vacuously.
TEST(NumberFormat, LocaleFreeUnderADecimalCommaCLocale) {
    ::setenv("LOCPATH", RELIEF_TEST_LOCPATH, 1);
    ASSERT_NE(std::setlocale(LC_ALL, "de_DE.UTF-8"), nullptr) << "no de_DE.UTF-8 in " << RELIEF_TEST_LOCPATH;
    ASSERT_STREQ(std::localeconv()->decimal_point, ",");
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f", 1.25);
    EXPECT_STREQ(buf, "1,25");  // what printf would have written into a .pov
    EXPECT_EQ(fixed(1.25, 2), "1.25");
    EXPECT_EQ(formatShortest(0.5), "0.5");
    EXPECT_EQ(formatShortest(-1234.5678), "-1234.5678");
    std::setlocale(LC_ALL, "C");
    ::unsetenv("LOCPATH");
}

// The same for the C++ global locale, with a numpunct of its own.
TEST(NumberFormat, LocaleFreeUnderADecimalCommaCxxLocale) {
    struct Comma : std::numpunct<char> {
        char do_decimal_point() const override { return ','; }
        char do_thousands_sep() const override { return '.'; }
        std::string do_grouping() const override { return "\3"; }
    };
    const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new Comma));
    std::ostringstream probe;
    probe << 1234.5;
    EXPECT_EQ(probe.str(), "1.234,5");  // the locale is in force
    EXPECT_EQ(fixed(1234.5, 1), "1234.5");
    EXPECT_EQ(formatShortest(1234.5), "1234.5");
    std::locale::global(previous);
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
