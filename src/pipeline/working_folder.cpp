// A working folder named when whole: the next free name, a stale one of
// relief's replaced, anything else in the way refused.
#include "pipeline/working_folder.h"

#include <fmt/format.h>

#include "plan/plan.h"

namespace relief {

namespace fs = std::filesystem;

std::optional<fs::path> nameWorkingFolder(const fs::path& building, const fs::path& asked,
                                         const WorkingFolderKind& kind, Diagnostics& diags) {
    std::error_code ec;
    for (int attempt = 0; attempt < 10; ++attempt) {
        std::optional<fs::path> dir;
        for (int n = 1; n < 100 && !dir; ++n) {
            const fs::path at = n == 1 ? asked : fs::path(asked.string() + "-" + std::to_string(n));
            if (!fs::exists(fs::symlink_status(at, ec))) {
                dir = at;
                break;
            }
            // Only a folder that reads as a whole one of this relief's is ever removed: a folder
            // of the user's that happens to hold a plan.json is in the way, never deleted.
            if (!fs::is_directory(fs::symlink_status(at, ec)) || !kind.ours(at)) {
                diags.error({at.string(), 0, 0}, fmt::format("in the way of {}: it is not {} of this relief's; "
                                                             "remove it or {}",
                                                             kind.what, kind.aKind, kind.fix));
                return std::nullopt;
            }
            if (auto lock = plan::PlanLock::take(at)) {
                fs::remove_all(at, ec);
                if (!ec) dir = at;
            }
        }
        if (!dir) {
            diags.error({asked.string(), 0, 0}, fmt::format("no folder for {} is free here or beside it (-2 to -99 "
                                                            "tried): let the renders using them end, or {}",
                                                            kind.what, kind.fix));
            return std::nullopt;
        }
        fs::rename(building, *dir, ec);
        if (!ec) return fs::absolute(*dir);
        if (ec != std::errc::directory_not_empty && ec != std::errc::file_exists) {
            diags.error({dir->string(), 0, 0}, fmt::format("{} cannot be written here: {}", kind.what, ec.message()));
            return std::nullopt;
        }
    }
    diags.error({asked.string(), 0, 0}, fmt::format("{} cannot be named here: other renders keep taking the name; "
                                                    "{}", kind.what, kind.fix));
    return std::nullopt;
}

}  // namespace relief
