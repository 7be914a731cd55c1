#pragma once
// An instant written as ISO 8601 / RFC 3339 with its UTC offset
// ("2026-06-21T09:00:00+12:00", "2026-06-21T21:00Z"): what [lighting]
// datetime takes. A time without an offset is refused: which instant it
// means depends on a time zone the scene does not name.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace relief {

struct OffsetDateTime {
    std::int64_t utcSeconds = 0;  ///< since 1970-01-01T00:00:00Z (fractions of a second dropped)
    int offsetMinutes = 0;        ///< the local time's offset from UTC, as written
};

/// `YYYY-MM-DD[T ]HH:MM[:SS[.fraction]](Z|±HH:MM)`, the calendar checked
/// (no 31 April, 29 February only in leap years), years 1800 to 2200 (the
/// span the solar ephemeris is accurate over). On failure: nullopt and
/// `why`, a phrase saying what is wrong.
std::optional<OffsetDateTime> parseOffsetDateTime(std::string_view text, std::string& why);

/// The instant as UTC, `YYYY-MM-DDTHH:MM:SSZ`.
std::string formatUtc(std::int64_t utcSeconds);

/// The instant in its own offset's local time, `YYYY-MM-DDTHH:MM:SS+HH:MM`
/// (`Z` for UTC): what parseOffsetDateTime reads back.
std::string formatOffsetDateTime(const OffsetDateTime& t);

}  // namespace relief
