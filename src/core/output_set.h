#pragma once
// A run's outputs appear together or not at all. Each is written in a
// private folder beside its final name; when the run has made all of them,
// they are moved into place at once (under a lock of their folder, so two
// runs onto one name never leave a mixed set), the sidecar last.
//
// What "nothing written" then means: no file under any output's final name
// was created, replaced or removed. A run killed at any moment leaves at most
// its private folder (hidden: .relief-...), which the next run into that
// folder removes, or, if the kill came in the middle of moving a set into
// place, finishes moving.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/source_loc.h"

namespace relief {

/// An output that cannot be made, reported at its file: the file as the user
/// knows it (shownPath) and the problem, with the fix where there is one.
/// what() is "<file>: <problem>", for channels that carry text only.
/// The system's reason a file cannot be written (errno `err`), and what the
/// user can do about it: "the disk is full (No space left on device); make
/// room on that disk or write elsewhere".
std::string writeFailureReason(int err);

class OutputError : public std::runtime_error {
public:
    OutputError(std::filesystem::path file, std::string problem);
    /// "cannot be written: <the system's reason>; <what to do about it>".
    static OutputError system(const std::filesystem::path& file, int err);

    const std::filesystem::path& file() const { return file_; }
    const std::string& problem() const { return problem_; }
    SourceLoc at() const { return {file_.string(), 0, 0}; }

private:
    std::filesystem::path file_;
    std::string problem_;
};

/// A folder only this run writes in: `<parent>/.relief-<what>-<host>-<pid>-XXXXXX`
/// (mode 0700, a name no other process can take), holding an `owner` file
/// this process keeps locked while it lives. The kernel drops a dead
/// process's locks, so a later run that can lock the owner file knows the
/// folder was abandoned. Removed (with what is in it) by the destructor.
class PrivateFolder {
public:
    /// Throws OutputError at `parent` with the system's reason.
    PrivateFolder(const std::filesystem::path& parent, std::string_view what);
    ~PrivateFolder();
    PrivateFolder(PrivateFolder&& other) noexcept;
    PrivateFolder& operator=(PrivateFolder&&) = delete;
    PrivateFolder(const PrivateFolder&) = delete;

    const std::filesystem::path& path() const { return dir_; }
    /// Leaves the folder when this run ends (its lock then free): it holds
    /// what a later run must put back.
    void keep() { keep_ = true; }

private:
    std::filesystem::path dir_;
    int ownerFd_ = -1;
    bool keep_ = false;
};

/// Removes the private folders in `parent` whose run is gone, and only those:
/// this user's hidden folders named .relief-... holding relief's `owner` file,
/// which no live run holds locked (a user's own files are never touched). A
/// set that was being moved into place when its run died is moved the rest of
/// the way first (or, if it was being put back, put back). Returns how many
/// folders were removed.
int removeAbandonedFolders(const std::filesystem::path& parent);

/// The name a user knows a file by: for a path in a set's private folder
/// (<folder>/.relief-.../new/<name>), its final path <folder>/<name>;
/// any other path as it is. For messages.
std::filesystem::path shownPath(const std::filesystem::path& path);

/// The outputs of one run.
class OutputSet {
public:
    OutputSet() = default;
    ~OutputSet();  ///< drops whatever was not committed
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;

    /// Declares an output and returns where to write it (a path in the
    /// private folder beside `finalPath`, with the same file name). Creates
    /// the folder `finalPath` goes in. Throws OutputError when it is
    /// the same file as an output declared before (naming both `role`s: "-o",
    /// "--dump-net", "the sidecar"), its name holds a control character, or
    /// the folder cannot be made. The `seal` (the sidecar) is moved into
    /// place after all the others, and its old file taken away before them.
    std::filesystem::path add(const std::filesystem::path& finalPath, std::string_view role, bool seal = false);
    /// Whether `finalPath` is declared.
    bool contains(const std::filesystem::path& finalPath) const;
    /// Takes back an output declared before: it is not moved into place.
    void drop(const std::filesystem::path& finalPath);
    /// Where the output declared as `finalPath` is written.
    std::filesystem::path staged(const std::filesystem::path& finalPath) const;
    /// Declares an input (the scene, the samples, a drape): an output declared
    /// before or after with its name is refused, naming both.
    void addInput(const std::filesystem::path& input, std::string_view role);

    /// Moves every output into place, in the order declared, the seal last
    /// (a set with its sidecar is whole), the files it replaces kept until all
    /// are in place. Throws OutputError at the file when one cannot
    /// be moved, after putting back the files it had replaced (or, when even
    /// that fails, saying where they are kept).
    void commit();

private:
    struct Entry {
        std::filesystem::path finalPath, key;  ///< key: the final path's folder resolved, and its name
        std::string role;
        size_t folder;
    };
    std::vector<std::string> namesIn(size_t folder) const;
    void keepPrevious();
    [[noreturn]] void moveBack(const Entry& failed, const std::string& reason);
    std::vector<std::pair<std::filesystem::path, std::string>> inputs_;
    std::vector<PrivateFolder> folders_;
    std::vector<std::filesystem::path> folderDirs_;  ///< the destination folder of each
    std::vector<Entry> entries_;
    std::filesystem::path seal_;
    bool committed_ = false;
};

}  // namespace relief
