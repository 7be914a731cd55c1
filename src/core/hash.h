#pragma once
// SHA-256 (OpenSSL's libcrypto), fed bytes and files a piece at a time.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace relief {

class Sha256 {
public:
    Sha256();
    ~Sha256();
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;

    void add(std::string_view bytes);
    /// Adds a file's bytes; false when it cannot be read (a link, a FIFO, a
    /// device or a folder is not read: see fileSha256).
    bool addFile(const std::filesystem::path& path);
    /// "sha256:" and 64 hex digits; the hash is finished (add no more).
    std::string hex();

private:
    struct State;
    std::unique_ptr<State> state_;
};

/// The SHA-256 of a regular file ("sha256:..."), or "" with `problem` set
/// (as core/input_file.h words it: "it is a link ...", "it is a FIFO ...").
/// A link is never followed and a FIFO never blocks. Within one process a
/// file is read once: the hash is kept against its device, inode, size and
/// change time, which every write moves (a 100 MB mesh hard-linked into the
/// plan of every frame of a film is hashed once, however often its plans are
/// verified).
std::string fileSha256(const std::filesystem::path& path, std::string& problem);

}  // namespace relief
