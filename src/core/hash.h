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
    /// Adds a file's bytes; false when it cannot be read.
    bool addFile(const std::filesystem::path& path);
    /// "sha256:" and 64 hex digits; the hash is finished (add no more).
    std::string hex();

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace relief
