#include "core/text_escape.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include <fmt/format.h>

namespace relief {

namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// The length of the well-formed UTF-8 sequence at text[i], or 0 (RFC 3629:
// no overlong forms, no surrogates, nothing above U+10FFFF).
size_t utf8Length(std::string_view text, size_t i) {
    const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char b0 = byte(i);
    size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // the second byte's range
    if (b0 >= 0xC2 && b0 <= 0xDF) n = 2;
    else if (b0 >= 0xE0 && b0 <= 0xEF) n = 3, lo = b0 == 0xE0 ? 0xA0 : 0x80, hi = b0 == 0xED ? 0x9F : 0xBF;
    else if (b0 >= 0xF0 && b0 <= 0xF4) n = 4, lo = b0 == 0xF0 ? 0x90 : 0x80, hi = b0 == 0xF4 ? 0x8F : 0xBF;
    else return 0;
    if (i + n > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
    for (size_t k = 2; k < n; ++k)
        if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
    return n;
}

char32_t codePoint(std::string_view s) {  // of one well-formed UTF-8 sequence
    const auto b = [&](size_t k) { return static_cast<char32_t>(static_cast<unsigned char>(s[k])); };
    if (s.size() == 2) return ((b(0) & 0x1F) << 6) | (b(1) & 0x3F);
    if (s.size() == 3) return ((b(0) & 0x0F) << 12) | ((b(1) & 0x3F) << 6) | (b(2) & 0x3F);
    return ((b(0) & 0x07) << 18) | ((b(1) & 0x3F) << 12) | ((b(2) & 0x3F) << 6) | (b(3) & 0x3F);
}

// Characters a terminal acts on or that reorder what it shows: the C1
// controls (U+009B is an 8-bit CSI), line and paragraph separators, and the
// bidirectional marks and overrides (a path that reads backwards).
bool invisibleControl(char32_t cp) {
    return (cp >= 0x80 && cp <= 0x9F) || cp == 0x200E || cp == 0x200F || (cp >= 0x2028 && cp <= 0x202E) ||
           (cp >= 0x2066 && cp <= 0x2069);
}

}  // namespace

std::string terminalText(std::string_view text, std::size_t maxBytes, bool keepLines) {
    std::string out;
    size_t i = 0;
    while (i < text.size() && out.size() < maxBytes) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x80) {
            const size_t n = utf8Length(text, i);
            if (n == 0) {
                out += fmt::format("\\x{:02x}", c), ++i;
            } else if (const char32_t cp = codePoint(text.substr(i, n)); invisibleControl(cp)) {
                out += fmt::format("\\u{{{:04x}}}", static_cast<unsigned>(cp)), i += n;
            } else {
                out.append(text.substr(i, n)), i += n;
            }
        } else if ((c < 0x20 && !(keepLines && c == '\n') && c != '\t') || c == 0x7f) {
            out += fmt::format("\\x{:02x}", c), ++i;
        } else {
            out += static_cast<char>(c), ++i;
        }
    }
    if (i < text.size()) out += fmt::format("... ({} more bytes)", text.size() - i);
    return out;
}

std::string asciiLower(std::string text) {
    for (char& c : text)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return text;
}

std::string shellQuoted(std::string_view text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char ch) {
        const auto c = static_cast<unsigned char>(ch);
        return std::isalnum(c) || std::strchr("_-./=:,+@%", ch) != nullptr;
    });
    if (plain) return std::string(text);
    std::string out = "'";
    for (const char ch : text) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return out + "'";
}

bool isUtf8(std::string_view text) {
    for (size_t i = 0; i < text.size();) {
        if (static_cast<unsigned char>(text[i]) < 0x80) {
            ++i;
            continue;
        }
        const size_t n = utf8Length(text, i);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

std::string utf8Replaced(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        if (static_cast<unsigned char>(text[i]) < 0x80) {
            out += text[i++];
            continue;
        }
        const size_t n = utf8Length(text, i);
        if (n == 0) out += kReplacement, ++i;
        else out.append(text.substr(i, n)), i += n;
    }
    return out;
}

std::string latin1AsUtf8(std::string_view text) {
    std::string out;
    out.reserve(2 * text.size());
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x80) {
            out += ch;
        } else {  // U+0080 to U+00FF: two bytes, 110000xx 10xxxxxx
            out += static_cast<char>(0xC0 | (c >> 6));
            out += static_cast<char>(0x80 | (c & 0x3F));
        }
    }
    return out;
}

std::string markupText(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x80) {
            const size_t n = utf8Length(text, i);
            if (n == 0) out += kReplacement, ++i;
            else out.append(text.substr(i, n)), i += n;
            continue;
        }
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            case '\t': case '\n': case '\r': out += static_cast<char>(c); break;
            default:
                if (c < 0x20 || c == 0x7F) out += kReplacement;
                else out += static_cast<char>(c);
        }
        ++i;
    }
    return out;
}

std::string oneLineText(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x80) {
            const size_t n = utf8Length(text, i);
            if (n == 0)
                out += kReplacement, ++i;
            else
                out.append(text.substr(i, n)), i += n;
            continue;
        }
        if (c < 0x20 || c == 0x7f) out += fmt::format("\\x{:02x}", c);
        else
            out += static_cast<char>(c);
        ++i;
    }
    return out;
}

std::string drawnText(std::string_view text, std::size_t maxChars) {
    std::string out;
    size_t i = 0, chars = 0;
    for (; i < text.size() && chars < maxChars; ++chars) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) {
            out += c < 0x20 || c == 0x7f ? ' ' : static_cast<char>(c);
            ++i;
            continue;
        }
        const size_t n = utf8Length(text, i);
        if (n == 0) out += kReplacement, ++i;
        else if (invisibleControl(codePoint(text.substr(i, n)))) out += ' ', i += n;
        else out += text.substr(i, n), i += n;
    }
    if (i < text.size()) out += "\u2026";
    return out;
}

std::string printableExcerpt(std::string_view text, std::size_t maxChars) {
    std::string out;
    for (size_t i = 0; i < text.size() && i < maxChars; ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x20 && c < 0x7f) out += static_cast<char>(c);
        else out += fmt::format("\\x{:02x}", c);
    }
    if (text.size() > maxChars) out += "...";
    return out;
}

std::string hexBytes(std::string_view bytes) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out;
    out.reserve(bytes.size() * 2);
    for (const unsigned char c : bytes) {
        out += kDigits[c >> 4];
        out += kDigits[c & 15];
    }
    return out;
}

std::optional<std::string> bytesOfHex(std::string_view hex) {
    const auto digit = [](char c) {
        return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    };
    if (hex.size() % 2 != 0) return std::nullopt;
    std::string out;
    for (size_t i = 0; i < hex.size(); i += 2) {
        const int hi = digit(hex[i]), lo = digit(hex[i + 1]);
        if (hi < 0 || lo < 0) return std::nullopt;
        out += static_cast<char>(hi * 16 + lo);
    }
    return out;
}

}  // namespace relief
