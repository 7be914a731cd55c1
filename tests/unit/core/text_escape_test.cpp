// Hostile strings in every sink that takes untrusted text: markup (SVG, the
// HTML report, JUnit XML), one-line SDL comments and messages. Markup outputs
// are parsed back with GDAL's XML parser: well-formed, and the text reads as
// it was written (with U+FFFD for what XML cannot hold).
#include <gtest/gtest.h>

#include <cpl_minixml.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "core/text_escape.h"
#include "plot/svg.h"
#include "regress/regress.h"
#include "unit/test_dirs.h"

namespace relief {
namespace {

namespace fs = std::filesystem;

// Titles a user might write, and ones an attacker would.
const std::string kHostile[] = {
    "<b>bold</b> &amp; \"quoted\" 'single'",
    "</text></svg><script>alert(1)</script>",
    "#fopen F \"/tmp/x\" write {{terrain}} %s %n",
    std::string("nul\0inside", 10) + "\x01\x1f\x7f",
    "line\nbreak\r\n\ttab",
    "\xff\xfe not UTF-8 \xc3\x28 \xed\xa0\x80",
    "Maungawhau \xe2\x80\x94 M\xc4\x81ori \xf0\x9f\x8c\x8b",
    std::string(100000, '<'),
};

// What XML can hold of `s`: U+FFFD for controls and bytes that are not UTF-8
// (one per byte), the rest as it is.
std::string expectedText(const std::string& s) {
    std::string out;
    const std::string r = "\xEF\xBF\xBD";
    for (size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c == '\t' || c == '\n' || c == '\r') out += s[i];
        else if (c < 0x20 || c == 0x7f) out += r;
        else if (c < 0x80) out += s[i];
        else if (s.compare(i, 3, "\xe2\x80\x94") == 0 || s.compare(i, 2, "\xc4\x81") == 0 ||
                 s.compare(i, 4, "\xf0\x9f\x8c\x8b") == 0) {
            const size_t n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : 2;
            out += s.substr(i, n), i += n - 1;
        } else {
            out += r;
        }
    }
    return out;
}

struct XmlTree {
    CPLXMLNode* root = nullptr;
    explicit XmlTree(const std::string& text) : root(CPLParseXMLString(text.c_str())) {}
    ~XmlTree() {
        if (root) CPLDestroyXMLNode(root);
    }
};

// The concatenated text of every <text> element (in order).
void collectText(const CPLXMLNode* n, const char* element, std::string& out) {
    for (; n; n = n->psNext) {
        if (n->eType == CXT_Element && std::string(n->pszValue) == element)
            for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
                if (c->eType == CXT_Text) out += c->pszValue;
        if (n->eType == CXT_Element) collectText(n->psChild, element, out);
    }
}

TEST(TextEscape, MarkupTextIsEntitiesAndValidUtf8) {
    EXPECT_EQ(markupText("<b>&amp;\"'"), "&lt;b&gt;&amp;amp;&quot;&#39;");
    EXPECT_EQ(markupText(std::string("a\0b", 3)), "a\xEF\xBF\xBD" "b");
    EXPECT_EQ(markupText("\xc3\xa9t\xc3\xa9"), "\xc3\xa9t\xc3\xa9");    // UTF-8 kept
    EXPECT_EQ(markupText("\xc0\xaf"), "\xEF\xBF\xBD\xEF\xBF\xBD");      // overlong '/': two bad bytes
    EXPECT_EQ(markupText("\xed\xa0\x80"), "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");  // a surrogate
    for (const std::string& s : kHostile) {
        const std::string m = markupText(s);
        EXPECT_EQ(m.find('<'), std::string::npos);
        EXPECT_EQ(m.find('"'), std::string::npos);
        EXPECT_EQ(m.find('\0'), std::string::npos);
    }
}

TEST(TextEscape, OneLineAndExcerpts) {
    EXPECT_EQ(oneLineText("a\n#fopen F \"/tmp/x\" write\r\x7f"), "a\\x0a#fopen F \"/tmp/x\" write\\x0d\\x7f");
    EXPECT_EQ(oneLineText(std::string("\0", 1)), "\\x00");
    for (const std::string& s : kHostile) EXPECT_EQ(oneLineText(s).find('\n'), std::string::npos);
    // A CRS name in Latin-1 (a file's own bytes) becomes UTF-8 a TOML file and a JSON sidecar can hold.
    EXPECT_EQ(oneLineText("Lamb\xe9rt 93 / \xc3\xa9"), "Lamb\xEF\xBF\xBDrt 93 / \xc3\xa9");
    for (const std::string& s : kHostile) EXPECT_TRUE(isUtf8(oneLineText(s))) << s;
    EXPECT_EQ(printableExcerpt(std::string("II*\x00\x10", 5), 60), "II*\\x00\\x10");
    EXPECT_EQ(printableExcerpt(std::string(100, 'x'), 60), std::string(60, 'x') + "...");
}

// A record's text: every byte that is not UTF-8 one U+FFFD, the rest (controls too) as it was.
TEST(TextEscape, Utf8ReplacedKeepsWhatIsUtf8) {
    const std::string r = "\xEF\xBF\xBD";
    EXPECT_EQ(utf8Replaced("caf\xe9.tif"), "caf" + r + ".tif");                 // a Latin-1 file name
    EXPECT_EQ(utf8Replaced("\xc0\xaf"), r + r);                                 // overlong '/'
    EXPECT_EQ(utf8Replaced("\xe2\x80"), r + r);                                 // cut short
    EXPECT_EQ(utf8Replaced("\xed\xa0\x80"), r + r + r);                         // a surrogate
    EXPECT_EQ(utf8Replaced("a\n\x01\x7f\xc3\xa9"), "a\n\x01\x7f\xc3\xa9");      // controls are the record's to escape
    for (const std::string& s : kHostile) {
        EXPECT_TRUE(isUtf8(utf8Replaced(s))) << s;
        EXPECT_EQ(utf8Replaced(s) == s, isUtf8(s)) << s;
    }
}

// Metadata in Latin-1: every byte the character of its number, written as UTF-8.
TEST(TextEscape, Latin1AsUtf8) {
    EXPECT_EQ(latin1AsUtf8("Monta\xf1" "a"), "Monta\xc3\xb1" "a");
    EXPECT_EQ(latin1AsUtf8("\xa9 IGN"), "\xc2\xa9 IGN");
    EXPECT_EQ(latin1AsUtf8("\x80\xff"), "\xc2\x80\xc3\xbf");
    EXPECT_EQ(latin1AsUtf8("plain ASCII\n"), "plain ASCII\n");
    std::string every;
    for (int c = 1; c < 256; ++c) every += static_cast<char>(c);
    const std::string utf8 = latin1AsUtf8(every);
    EXPECT_TRUE(isUtf8(utf8));
    EXPECT_EQ(utf8.size(), 127u + 2 * 128u);
}

// Every hostile title and label comes out of the SVG as the text it was.
TEST(TextEscape, SvgTextStaysText) {
    for (const std::string& s : kHostile) {
        plot::SvgLayer layer{s, {{s, {{0, 0}, {1, 1}}}}, "", false, false};
        plot::SvgAxes axes;
        axes.show = true;
        axes.xLabel = s;
        axes.yLabel = s;
        const std::string svg = plot::plotSvg(s, {layer}, {{{0, 0}, {1, 1}, s}}, axes);
        XmlTree xml(svg);
        ASSERT_TRUE(xml.root) << "not well-formed XML: " << svg.substr(0, 300);
        std::string text;
        collectText(xml.root, "text", text);
        const std::string e = expectedText(s);
        // Title, the axis labels, the marker and the legend: five times.
        size_t count = 0;
        for (size_t at = text.find(e); at != std::string::npos; at = text.find(e, at + e.size())) ++count;
        EXPECT_EQ(count, 5u) << s.substr(0, 60);
        EXPECT_EQ(svg.find("<script"), std::string::npos);
    }
}

// The HTML report and the JUnit XML of `relief test`: a failing case's message
// (which holds a path, hence anything) stays text in both.
TEST(TextEscape, TestReportTextStaysText) {
    const fs::path dir = relief::testing::freshTestDir("relief-report-hostile");
    fs::create_directories(dir / "report");
    regress::Manifest m;
    m.file = dir / "manifest.toml";
    m.cases.resize(std::size(kHostile));
    std::vector<regress::CaseResult> results(std::size(kHostile));
    for (size_t i = 0; i < std::size(kHostile); ++i) {
        m.cases[i].name = "case-" + std::to_string(i);
        m.cases[i].scene = dir / "scene.toml";
        results[i].testCase = &m.cases[i];
        results[i].status = regress::CaseStatus::Error;
        results[i].message = kHostile[i];
    }
    regress::RunOptions o;
    o.reportDir = dir / "report";
    o.manifestArgument = "manifest.toml";
    regress::writeReport(m, results, o, 1.0);

    std::stringstream junit;
    junit << std::ifstream(o.reportDir / "junit.xml").rdbuf();
    XmlTree xml(junit.str());
    ASSERT_TRUE(xml.root) << "junit.xml is not well-formed";
    std::string failures;
    collectText(xml.root, "failure", failures);
    std::stringstream html;
    html << std::ifstream(o.reportDir / "index.html").rdbuf();
    for (const std::string& s : kHostile) {
        EXPECT_NE(failures.find(expectedText(s)), std::string::npos) << s.substr(0, 60);
        EXPECT_NE(html.str().find(markupText(s)), std::string::npos) << s.substr(0, 60);
    }
    EXPECT_EQ(html.str().find("<script"), std::string::npos);
    EXPECT_EQ(html.str().find("<b>"), std::string::npos);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace relief

namespace relief {
namespace {

TEST(TextEscape, TerminalTextShowsControlsAsText) {
    EXPECT_EQ(terminalText(std::string("a\x1b[2Jb\nc\0d", 10), 100), "a\\x1b[2Jb\\x0ac\\x00d");
    EXPECT_EQ(terminalText("keep\nlines", 100, true), "keep\nlines");
    // C1 controls (an 8-bit CSI) and a right-to-left override, as valid UTF-8.
    EXPECT_EQ(terminalText("x\xc2\x9b" "2Jy", 100), "x\\u{009b}2Jy");
    EXPECT_EQ(terminalText("gnp.\xe2\x80\xae" "exe", 100), "gnp.\\u{202e}exe");
    EXPECT_EQ(terminalText("caf\xc3\xa9 \xff", 100), "caf\xc3\xa9 \\xff");
    EXPECT_EQ(terminalText(std::string(50, 'z'), 10), "zzzzzzzzzz... (40 more bytes)");
}

TEST(TextEscape, ShellQuotedForCopying) {
    EXPECT_EQ(shellQuoted("tests/golden/manifest.toml"), "tests/golden/manifest.toml");
    EXPECT_EQ(shellQuoted("it's $(here)"), "'it'\\''s $(here)'");
    EXPECT_EQ(shellQuoted(""), "''");
}

}  // namespace
}  // namespace relief
