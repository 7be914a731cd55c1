#include "core/diagnostics.h"

#include <fmt/format.h>

namespace relief {

void Diagnostics::error(SourceLoc loc, std::string message) {
    items_.push_back({Severity::Error, std::move(loc), std::move(message)});
    ++errors_;
}

void Diagnostics::warning(SourceLoc loc, std::string message) {
    items_.push_back({Severity::Warning, std::move(loc), std::move(message)});
    ++warnings_;
}

void Diagnostics::note(SourceLoc loc, std::string message) {
    items_.push_back({Severity::Note, std::move(loc), std::move(message)});
}

void Diagnostics::warningOnce(std::string_view topic, SourceLoc loc, std::string message) {
    if (topicsWarned_.emplace(topic).second) warning(std::move(loc), std::move(message));
}

void Diagnostics::append(const Diagnostics& other) {
    if (&other == this) return;
    items_.insert(items_.end(), other.items_.begin(), other.items_.end());
    errors_ += other.errors_;
    warnings_ += other.warnings_;
    topicsWarned_.insert(other.topicsWarned_.begin(), other.topicsWarned_.end());
}

std::string formatDiagnostic(const Diagnostic& d) {
    std::string where;
    if (!d.loc.file.empty()) {
        where = d.loc.file;
        if (d.loc.line > 0) {
            where += fmt::format(":{}", d.loc.line);
            if (d.loc.column > 0) where += fmt::format(":{}", d.loc.column);
        }
        where += ": ";
    }
    const char* sev = d.severity == Severity::Error     ? "error"
                      : d.severity == Severity::Warning ? "warning"
                                                        : "note";
    return fmt::format("{}{}: {}", where, sev, d.message);
}

}  // namespace relief
