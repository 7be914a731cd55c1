#include "core/hash.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <map>
#include <mutex>
#include <tuple>

#include <openssl/evp.h>
#include <fmt/format.h>

#include "core/file_descriptor.h"
#include "core/input_file.h"

namespace relief {

struct Sha256::State {
    EVP_MD_CTX* ctx = EVP_MD_CTX_new();
    ~State() { EVP_MD_CTX_free(ctx); }
};

Sha256::Sha256() : state_(std::make_unique<State>()) { EVP_DigestInit_ex(state_->ctx, EVP_sha256(), nullptr); }
Sha256::~Sha256() = default;

void Sha256::add(std::string_view bytes) { EVP_DigestUpdate(state_->ctx, bytes.data(), bytes.size()); }

namespace {

// A regular file opened without following a link or blocking on a FIFO; -1 with `problem`.
int openRegular(const std::filesystem::path& path, struct stat& st, std::string& problem) {
    problem = plainFileProblem(path);
    if (!problem.empty()) return -1;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY);
    if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        // Swapped since the check: told as what it is now.
        problem = plainFileProblem(path);
        if (problem.empty()) problem = "it cannot be opened";
        if (fd >= 0) ::close(fd);
        return -1;
    }
    return fd;
}

bool addOpenFile(Sha256& h, int fd) {
    char buf[1 << 16];
    ssize_t n;
    while ((n = ::read(fd, buf, sizeof buf)) > 0) h.add({buf, static_cast<size_t>(n)});
    return n == 0;
}

}  // namespace

bool Sha256::addFile(const std::filesystem::path& path) {
    struct stat st {};
    std::string problem;
    const Fd f{openRegular(path, st, problem)};
    return f.fd >= 0 && addOpenFile(*this, f.fd);
}

std::string Sha256::hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    EVP_DigestFinal_ex(state_->ctx, digest, &size);
    std::string out = "sha256:";
    for (unsigned int i = 0; i < size; ++i) out += fmt::format("{:02x}", digest[i]);
    return out;
}

std::string fileSha256(const std::filesystem::path& path, std::string& problem) {
    using Key = std::tuple<dev_t, ino_t, off_t, long, long, long, long>;
    static std::mutex mutex;
    static std::map<Key, std::string> known;
    struct stat st {};
    const Fd f{openRegular(path, st, problem)};
    if (f.fd < 0) return {};
    const Key key{st.st_dev, st.st_ino, st.st_size, st.st_mtim.tv_sec, st.st_mtim.tv_nsec, st.st_ctim.tv_sec,
                  st.st_ctim.tv_nsec};
    {
        const std::lock_guard lock(mutex);
        if (const auto it = known.find(key); it != known.end()) return it->second;
    }
    Sha256 h;
    if (!addOpenFile(h, f.fd)) {
        problem = "it cannot be read";
        return {};
    }
    std::string hash = h.hex();
    // A file written while it was read is not remembered: its next read sees the change.
    struct stat after {};
    if (::fstat(f.fd, &after) == 0 && after.st_ctim.tv_sec == st.st_ctim.tv_sec &&
        after.st_ctim.tv_nsec == st.st_ctim.tv_nsec && after.st_size == st.st_size) {
        const std::lock_guard lock(mutex);
        known[key] = hash;
    }
    return hash;
}

}  // namespace relief
