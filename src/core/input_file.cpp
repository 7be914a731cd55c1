#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "core/file_descriptor.h"

namespace relief {

namespace {

std::string kindProblem(mode_t mode) {
    if (S_ISDIR(mode)) return "it is a folder, not a file";
    if (S_ISFIFO(mode)) return "it is a FIFO (a named pipe), not a file";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "it is a device, not a file";
    if (S_ISSOCK(mode)) return "it is a socket, not a file";
    if (!S_ISREG(mode)) return "it is not a regular file";
    return "";
}

std::string sizeProblem(std::uintmax_t size, std::uintmax_t maxBytes) {
    if (maxBytes == 0 || size <= maxBytes) return "";
    return fmt::format("it is {}, more than the {} such a file may be", byteSize(size), byteSize(maxBytes));
}

std::string openProblem(int err) {
    if (err == ENOENT) return "no such file";
    return fmt::format("it cannot be opened: {}", std::strerror(err));
}

}  // namespace

std::string byteSize(std::uintmax_t bytes) {
    if (bytes >= 1000000000) return fmt::format("{:.3g} GB", double(bytes) / 1e9);
    if (bytes >= 1000000) return fmt::format("{:.3g} MB", double(bytes) / 1e6);
    if (bytes >= 1000) return fmt::format("{:.3g} kB", double(bytes) / 1e3);
    return fmt::format("{} bytes", bytes);
}

bool pathInside(const std::filesystem::path& path, const std::filesystem::path& folder) {
    std::error_code ec;
    const auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
    const auto f = std::filesystem::weakly_canonical(
        std::filesystem::absolute(folder.empty() ? std::filesystem::path(".") : folder, ec), ec);
    auto pi = p.begin();
    for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
        if (fi->empty() && std::next(fi) == f.end()) break;  // a folder written with a trailing slash
        if (pi == p.end() || *fi != *pi) return false;
    }
    return true;
}

std::string inputFileProblem(const std::filesystem::path& path, std::uintmax_t maxBytes) {
    // stat() first: it tells a FIFO or a device without opening it (an open
    // could block, or start a device).
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return openProblem(errno);
    if (std::string kind = kindProblem(st.st_mode); !kind.empty()) return kind;
    if (::access(path.c_str(), R_OK) != 0) return openProblem(errno);
    return sizeProblem(static_cast<std::uintmax_t>(st.st_size), maxBytes);
}

std::string plainFileProblem(const std::filesystem::path& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return openProblem(errno);
    if (S_ISLNK(st.st_mode)) return "it is a link, and relief follows none out of its own folders";
    return kindProblem(st.st_mode);
}

namespace {

// Reads regular files only, at most `cap` bytes (0: all); `wholeOrRefuse`:
// a file longer than `cap` is refused rather than cut.
std::optional<std::string> readRegular(const std::filesystem::path& path, std::uintmax_t cap, bool wholeOrRefuse,
                                       std::string& problem) {
    const std::uintmax_t maxBytes = wholeOrRefuse ? cap : 0;
    problem = inputFileProblem(path, maxBytes);
    if (!problem.empty()) return std::nullopt;
    // O_NONBLOCK: were the file swapped for a FIFO since the stat, the open
    // still returns at once, and fstat below refuses it.
    Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)};
    if (f.fd < 0) {
        problem = openProblem(errno);
        return std::nullopt;
    }
    struct stat st {};
    if (::fstat(f.fd, &st) != 0) {
        problem = openProblem(errno);
        return std::nullopt;
    }
    problem = kindProblem(st.st_mode);
    if (problem.empty()) problem = sizeProblem(static_cast<std::uintmax_t>(st.st_size), maxBytes);
    if (!problem.empty()) return std::nullopt;
    const std::uintmax_t limit = cap > 0 ? cap + (wholeOrRefuse ? 1 : 0) : 0;  // one byte over tells "too long"
    std::string text(static_cast<size_t>(limit > 0 ? std::min<std::uintmax_t>(st.st_size, limit) : st.st_size), '\0');
    size_t got = 0;
    // A file that grows while read is cut at the cap, and said to be too long.
    while (true) {
        if (got == text.size()) {
            if (limit > 0 && got >= limit) break;
            text.resize(limit > 0 ? std::min<std::uintmax_t>(got + 65536, limit) : got + 65536);
        }
        const ssize_t n = ::read(f.fd, text.data() + got, text.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            problem = fmt::format("it cannot be read: {}", std::strerror(errno));
            return std::nullopt;
        }
        if (n == 0) break;
        got += static_cast<size_t>(n);
    }
    if (maxBytes > 0 && got > maxBytes) {
        problem = sizeProblem(got, maxBytes);
        return std::nullopt;
    }
    text.resize(got);
    return text;
}

}  // namespace

std::optional<std::string> readInputFile(const std::filesystem::path& path, std::uintmax_t maxBytes,
                                         std::string& problem) {
    return readRegular(path, maxBytes, true, problem);
}

std::optional<std::string> readInputHead(const std::filesystem::path& path, std::uintmax_t maxBytes,
                                         std::string& problem) {
    return readRegular(path, maxBytes, false, problem);
}

}  // namespace relief
