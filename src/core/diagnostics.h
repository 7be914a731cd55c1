#pragma once
// Diagnostics are recorded by the library and printed by the CLI. Each one
// reads `file:line:col: severity: message`, giving the bad value, the valid
// range and the unit. Stages report everything they find, and the pipeline
// stops between stages when there are errors.
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/source_loc.h"

namespace relief {

enum class Severity { Note, Warning, Error };

struct Diagnostic {
    Severity severity;
    SourceLoc loc;
    std::string message;
};

class Diagnostics {
public:
    void error(SourceLoc loc, std::string message);
    void warning(SourceLoc loc, std::string message);
    void note(SourceLoc loc, std::string message);
    /// A warning said once a run however often its cause recurs (every name
    /// that is not UTF-8): the first call for `topic` adds it, the rest nothing.
    void warningOnce(std::string_view topic, SourceLoc loc, std::string message);
    /// Every diagnostic of `other` after these (a pass whose findings are kept only when it stops).
    void append(const Diagnostics& other);

    bool hasErrors() const { return errors_ > 0; }
    int errorCount() const { return errors_; }
    int warningCount() const { return warnings_; }
    const std::vector<Diagnostic>& all() const { return items_; }

private:
    std::vector<Diagnostic> items_;
    int errors_ = 0;
    int warnings_ = 0;
    std::set<std::string, std::less<>> topicsWarned_;
};

/// `file:line:col: error: message` (parts that are unknown are left out).
std::string formatDiagnostic(const Diagnostic& d);

}  // namespace relief
