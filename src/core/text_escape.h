#pragma once
// Untrusted text where it lands: in markup (SVG, HTML, XML), on one line (an
// SDL comment, a diagnostic), or as an excerpt of a file in a message.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace relief {

/// For SVG, HTML and XML, in element content and in attribute values alike:
/// the characters markup gives meaning to (& < > " ') become entities;
/// characters XML 1.0 does not allow (C0 controls other than tab, line feed
/// and carriage return, DEL) and bytes that are not UTF-8 become U+FFFD, so
/// the file stays well-formed whatever the input.
std::string markupText(std::string_view text);

/// One line of UTF-8: control characters (line breaks included) and DEL as
/// \xNN, bytes that are not UTF-8 as U+FFFD (a TOML file or a JSON sidecar
/// must be UTF-8), the rest as it is. An SDL `//` comment ends at a line
/// break, so a path holding one can never start a directive.
std::string oneLineText(std::string_view text);

/// For a terminal: what an input put in a message shown as text, never as
/// commands (an ESC sequence, a line break, a NUL): control characters and
/// bytes that are not UTF-8 as \xNN, line feeds too unless `keepLines`, and
/// at most about `maxBytes` of it, cut at a character with
/// "... (N more bytes)".
std::string terminalText(std::string_view text, std::size_t maxBytes = 2000, bool keepLines = false);

/// A word for a POSIX shell command line that a user copies: as it is when
/// it holds only letters, digits and _-./=:,+@%, else in single quotes (a '
/// inside as '\'').
std::string shellQuoted(std::string_view text);

/// `text` with the letters A-Z in lower case (the rest as it is): names
/// compared in any case, as GDAL compares file names and units.
std::string asciiLower(std::string text);

/// A string drawn on a still (a vector file's label, from any format): valid
/// UTF-8 (bytes that are not as U+FFFD), on one line (control characters and
/// invisible marks as spaces), at most `maxChars` characters, cut with "…".
/// Drawn as text, never as markup.
std::string drawnText(std::string_view text, std::size_t maxChars = 80);

/// Bytes as lower-case hex digits, two a byte: a name that is not UTF-8 kept
/// whole in a JSON record.
std::string hexBytes(std::string_view bytes);
/// The bytes of hexBytes' digits; nullopt when `hex` is not such digits.
std::optional<std::string> bytesOfHex(std::string_view hex);

/// Whether `text` is well-formed UTF-8 (RFC 3629).
bool isUtf8(std::string_view text);

/// `text` as valid UTF-8 for a record (a JSON sidecar, a PDF's metadata, a
/// text Pango lays out): each byte that is not part of a well-formed UTF-8
/// sequence as U+FFFD, everything else (control characters too) as it is.
std::string utf8Replaced(std::string_view text);

/// `text` read as ISO-8859-1 (Latin-1, where every byte is the character of
/// that number) and written as UTF-8: how relief reads a file's metadata that
/// is not UTF-8, as old GeoTIFFs' often is not.
std::string latin1AsUtf8(std::string_view text);

/// An excerpt of a file for a message: at most `maxChars` characters,
/// control and non-ASCII bytes as \xNN (a binary file must not fill the
/// screen), "..." when cut.
std::string printableExcerpt(std::string_view text, std::size_t maxChars = 60);

}  // namespace relief
