#include "core/date_time.h"

#include <chrono>
#include <cstdlib>

#include <fmt/format.h>

namespace relief {

namespace {

// Exactly `n` decimal digits at text[pos]; advances pos.
std::optional<int> digits(std::string_view text, size_t& pos, int n) {
    if (pos + n > text.size()) return std::nullopt;
    int v = 0;
    for (int i = 0; i < n; ++i) {
        const char c = text[pos + i];
        if (c < '0' || c > '9') return std::nullopt;
        v = v * 10 + (c - '0');
    }
    pos += n;
    return v;
}

bool expect(std::string_view text, size_t& pos, char c) {
    if (pos >= text.size() || text[pos] != c) return false;
    ++pos;
    return true;
}

}  // namespace

std::optional<OffsetDateTime> parseOffsetDateTime(std::string_view text, std::string& why) {
    using namespace std::chrono;
    why = "it must be YYYY-MM-DDTHH:MM:SS with its UTC offset, e.g. 2026-06-21T09:00:00+12:00 or "
          "2026-06-20T21:00:00Z";
    size_t pos = 0;
    const auto y = digits(text, pos, 4);
    if (!y || !expect(text, pos, '-')) return std::nullopt;
    const auto mo = digits(text, pos, 2);
    if (!mo || !expect(text, pos, '-')) return std::nullopt;
    const auto d = digits(text, pos, 2);
    if (!d) return std::nullopt;
    if (pos >= text.size() || (text[pos] != 'T' && text[pos] != 't' && text[pos] != ' ')) return std::nullopt;
    ++pos;
    const auto h = digits(text, pos, 2);
    if (!h || !expect(text, pos, ':')) return std::nullopt;
    const auto mi = digits(text, pos, 2);
    if (!mi) return std::nullopt;
    int s = 0;
    if (pos < text.size() && text[pos] == ':') {
        ++pos;
        const auto sec = digits(text, pos, 2);
        if (!sec) return std::nullopt;
        s = *sec;
        if (pos < text.size() && text[pos] == '.') {
            ++pos;
            const size_t start = pos;
            while (pos < text.size() && text[pos] >= '0' && text[pos] <= '9') ++pos;
            if (pos == start) return std::nullopt;
        }
    }
    int offset = 0;
    if (pos >= text.size()) {
        why = "it has no UTC offset, so the instant depends on a time zone: add one, e.g. +12:00, -05:00 or Z";
        return std::nullopt;
    }
    if (text[pos] == 'Z' || text[pos] == 'z') {
        ++pos;
    } else if (text[pos] == '+' || text[pos] == '-') {
        const int sign = text[pos] == '-' ? -1 : 1;
        ++pos;
        const auto oh = digits(text, pos, 2);
        if (!oh || !expect(text, pos, ':')) return std::nullopt;
        const auto om = digits(text, pos, 2);
        if (!om || *oh > 14 || *om > 59) return std::nullopt;
        offset = sign * (*oh * 60 + *om);
    } else {
        return std::nullopt;
    }
    if (pos != text.size()) return std::nullopt;
    if (*y < 1800 || *y > 2200) {
        why = "the year must be within 1800 to 2200";
        return std::nullopt;
    }
    const year_month_day date{year{*y}, month{static_cast<unsigned>(*mo)}, day{static_cast<unsigned>(*d)}};
    if (!date.ok()) {
        why = fmt::format("{:04}-{:02}-{:02} is not a date", *y, *mo, *d);
        return std::nullopt;
    }
    if (*h > 23 || *mi > 59 || s > 60) {  // 60: a leap second, as RFC 3339 allows
        why = fmt::format("{:02}:{:02}:{:02} is not a time of day", *h, *mi, s);
        return std::nullopt;
    }
    OffsetDateTime out;
    out.offsetMinutes = offset;
    out.utcSeconds = sys_days(date).time_since_epoch().count() * 86400LL + *h * 3600LL + *mi * 60LL + s -
                     offset * 60LL;
    return out;
}

namespace {

// `YYYY-MM-DDTHH:MM:SS` of an instant shifted to a local time.
std::string calendarTime(std::int64_t seconds) {
    using namespace std::chrono;
    const std::int64_t dayIndex = seconds >= 0 ? seconds / 86400 : -((-seconds + 86399) / 86400);
    const std::int64_t rest = seconds - dayIndex * 86400;
    const year_month_day date{sys_days{days{dayIndex}}};
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", int(date.year()), unsigned(date.month()),
                       unsigned(date.day()), rest / 3600, rest / 60 % 60, rest % 60);
}

}  // namespace

std::string formatUtc(std::int64_t utcSeconds) {
    return calendarTime(utcSeconds) + "Z";
}

std::string formatOffsetDateTime(const OffsetDateTime& t) {
    const int m = t.offsetMinutes;
    if (m == 0) return formatUtc(t.utcSeconds);
    return calendarTime(t.utcSeconds + m * 60LL) +
           fmt::format("{}{:02}:{:02}", m < 0 ? '-' : '+', std::abs(m) / 60, std::abs(m) % 60);
}

}  // namespace relief
