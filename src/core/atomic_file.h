#pragma once
// Outputs are never half-written: everything goes to a temporary file in the
// destination's folder and is renamed into place only when complete.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace relief {

class AtomicFile {
public:
    /// Opens `<final>.tmp-<pid>` for writing. Throws std::runtime_error with the
    /// path and the system's reason when that fails (missing folder, no permission).
    explicit AtomicFile(std::filesystem::path finalPath);
    ~AtomicFile();  ///< removes the temporary file unless commit() succeeded
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::FILE* stream() { return file_; }
    void write(std::string_view bytes);
    const std::filesystem::path& tempPath() const { return temp_; }
    const std::filesystem::path& finalPath() const { return final_; }

    /// Flushes, closes and renames into place. Throws on any I/O error.
    void commit();

private:
    std::filesystem::path final_;
    std::filesystem::path temp_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

/// Writes `bytes` to `path` atomically.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

/// For writers that take a path rather than bytes (an image library's):
/// `write` writes the temporary file it is given (in the destination's folder,
/// with the destination's extension, so formats are told by it) and returns ""
/// or its error; the file is renamed into place only on success, and removed
/// otherwise. Returns "" or the error, naming `path`.
std::string writeThroughTemporary(const std::filesystem::path& path,
                                  const std::function<std::string(const std::filesystem::path&)>& write);

/// Creates the folder `file` goes in (and its parents). Throws
/// std::runtime_error naming the folder and the system's reason.
void createParentFolder(const std::filesystem::path& file);

/// Removes the temporary files a killed run left in `folder`: names that end
/// in ".tmp-<pid>" (optionally followed by an extension) whose process is no
/// longer running. Returns how many were removed.
int removeStaleTemporaries(const std::filesystem::path& folder);

/// Whether process `pid` is running (on this machine, in this PID namespace).
bool processRunning(long pid);

/// Reads a whole file; throws std::runtime_error naming the path on failure.
std::string readFile(const std::filesystem::path& path);

}  // namespace relief
