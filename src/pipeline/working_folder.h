#pragma once
// A working folder kept beside an output until the output is made (a render
// plan, a film's frames): made whole in a private folder, then named; a
// stale one a run left is replaced, anything else there is in the way.
#include <filesystem>
#include <optional>
#include <string_view>

#include "core/diagnostics.h"

namespace relief {

/// A working folder kept beside an output until the output is made: a render
/// plan, a film's frames. Which folders of that name a run may replace.
struct WorkingFolderKind {
    std::string_view what;   ///< "the render plan"
    std::string_view aKind;  ///< "a render plan"
    std::string_view fix;    ///< "give --plan"
    bool (*ours)(const std::filesystem::path& dir);  ///< a whole folder of this kind, relief's
};

/// Names `building` (made whole in a private folder) `asked`, or the next
/// free `asked`-N while a running relief holds that one; a folder of the kind
/// a run left (nobody's now) is replaced, anything else there is in the way.
/// The absolute name, or nullopt with the error at the name.
std::optional<std::filesystem::path> nameWorkingFolder(const std::filesystem::path& building,
                                                       const std::filesystem::path& asked,
                                                       const WorkingFolderKind& kind, Diagnostics& diags);

}  // namespace relief
