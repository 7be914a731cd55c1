#pragma once
// Untrusted text where it lands: in markup (SVG, HTML, XML), on one line (an
// SDL comment, a diagnostic), or as an excerpt of a file in a message.
#include <cstddef>
#include <string>
#include <string_view>

namespace relief {

/// For SVG, HTML and XML, in element content and in attribute values alike:
/// the characters markup gives meaning to (& < > " ') become entities;
/// characters XML 1.0 does not allow (C0 controls other than tab, line feed
/// and carriage return, DEL) and bytes that are not UTF-8 become U+FFFD, so
/// the file stays well-formed whatever the input.
std::string markupText(std::string_view text);

/// One line: control characters (line breaks included) and DEL as \xNN,
/// the rest as it is. An SDL `//` comment ends at a line break, so a path
/// holding one can never start a directive.
std::string oneLineText(std::string_view text);

/// An excerpt of a file for a message: at most `maxChars` characters,
/// control and non-ASCII bytes as \xNN (a binary file must not fill the
/// screen), "..." when cut.
std::string printableExcerpt(std::string_view text, std::size_t maxChars = 60);

}  // namespace relief
