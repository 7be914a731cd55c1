#pragma once
// Outputs are never half-written: everything is written in a private folder
// beside its final name and moved into place only when complete
// (core/output_set.h, which also commits several files as one set).
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "core/output_set.h"

namespace relief {

/// One output file, written whole or not at all.
class AtomicFile {
public:
    /// Creates the file in a private folder beside `finalPath` (a new name
    /// no one else can have made: never opened through a planted link).
    /// Throws OutputError at the path with the system's reason when that
    /// fails (missing folder, no permission).
    explicit AtomicFile(std::filesystem::path finalPath);
    ~AtomicFile();  ///< drops the file unless commit() succeeded
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::FILE* stream() { return file_; }
    void write(std::string_view bytes);
    const std::filesystem::path& finalPath() const { return final_; }

    /// Flushes, syncs, closes and moves into place. Throws on any I/O error.
    void commit();

private:
    std::filesystem::path final_, shown_;  ///< shown_: the name in messages (shownPath)
    OutputSet set_;
    std::FILE* file_ = nullptr;
};

/// Creates `path` for writing, exclusively (O_CREAT | O_EXCL | O_NOFOLLOW):
/// the file is new, never a link someone planted. Throws OutputError at
/// `shown` with the system's reason.
std::FILE* createNewFile(const std::filesystem::path& path, const std::filesystem::path& shown);

/// Flushes, syncs to disk and closes `file`; throws OutputError at `shown` on
/// any error (a full disk: ENOSPC).
void closeWritten(std::FILE* file, const std::filesystem::path& shown);

/// Writes `bytes` to `path` atomically.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

/// For writers that take a path rather than bytes (an image library's):
/// `write` writes the file it is given (in a private folder beside `path`,
/// with the same name, so formats are told by the extension) and returns ""
/// or its error; the file is moved into place only on success. Throws
/// OutputError at `path` when it cannot be.
void writeThroughTemporary(const std::filesystem::path& path,
                           const std::function<std::string(const std::filesystem::path&)>& write);

/// Copies the file `from` into the new file `to` (created exclusively, never
/// through a planted link); "" or why not, the system's reason worded as
/// writeFailureReason words it ("the disk is full (No space left on device);
/// ..."). std::filesystem::copy_file says "Input/output error" when the disk
/// fills: libstdc++ takes a short count from sendfile for EIO.
std::string copyFileContents(const std::filesystem::path& from, const std::filesystem::path& to);

/// `to` made the file `from` is: a hard link (no copy of a 100 MB mesh), else
/// copyFileContents. Throws OutputError at shownPath(to) when neither can be.
void linkOrCopy(const std::filesystem::path& from, const std::filesystem::path& to);

/// Creates the folder `file` goes in (and its parents). Throws OutputError at
/// the folder with the system's reason.
void createParentFolder(const std::filesystem::path& file);

/// Makes the folder `folder` (its parent must exist) unless it is there,
/// and checks that it is a folder and not a link: relief writes into the
/// folders of its own working folders (a render plan's tiles/, a film's
/// frames/) only when it can see they are real, so a link planted in their
/// place leads nowhere. Throws OutputError at `folder` ("is a link ...").
void makeOwnFolder(const std::filesystem::path& folder);

/// Reads a whole file; throws std::runtime_error naming the path on failure.
/// For relief's own files (tests, benchmarks); inputs go through
/// readInputFile (core/input_file.h).
std::string readFile(const std::filesystem::path& path);

}  // namespace relief
