#include "core/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/std.h>

namespace relief {

AtomicFile::AtomicFile(std::filesystem::path finalPath) : final_(std::move(finalPath)) {
    temp_ = final_;
    temp_ += fmt::format(".tmp-{}", ::getpid());
    file_ = std::fopen(temp_.c_str(), "wb");
    if (!file_)
        throw std::runtime_error(fmt::format("cannot write {}: {}", final_.string(),
                                             std::strerror(errno)));
}

AtomicFile::~AtomicFile() {
    if (file_) std::fclose(file_);
    if (!committed_) {
        std::error_code ec;
        std::filesystem::remove(temp_, ec);
    }
}

void AtomicFile::write(std::string_view bytes) {
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
        throw std::runtime_error(
            fmt::format("cannot write {}: {}", final_.string(), std::strerror(errno)));
}

void AtomicFile::commit() {
    // A writer that went through stream() left its errors in the stream (a full disk: ENOSPC).
    const bool ok = std::fflush(file_) == 0 && !std::ferror(file_) && ::fsync(::fileno(file_)) == 0;
    const int err = errno != 0 ? errno : EIO;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!ok || !closed)
        throw std::runtime_error(
            fmt::format("cannot write {}: {}", final_.string(), std::strerror(err)));
    std::error_code ec;
    std::filesystem::rename(temp_, final_, ec);
    if (ec)
        throw std::runtime_error(
            fmt::format("cannot rename into {}: {}", final_.string(), ec.message()));
    committed_ = true;
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
    AtomicFile f(path);
    f.write(bytes);
    f.commit();
}

std::string writeThroughTemporary(const std::filesystem::path& path,
                                  const std::function<std::string(const std::filesystem::path&)>& write) {
    std::filesystem::path temp = path;
    temp += fmt::format(".tmp-{}{}", ::getpid(), path.extension().string());
    std::string error = write(temp);
    std::error_code ec;
    if (error.empty()) {
        std::filesystem::rename(temp, path, ec);
        if (ec) error = fmt::format("cannot rename into {}: {}", path.string(), ec.message());
    } else {
        error = fmt::format("cannot write {}: {}", path.string(), error);
    }
    if (!error.empty()) std::filesystem::remove(temp, ec);
    return error;
}

void createParentFolder(const std::filesystem::path& file) {
    if (!file.has_parent_path()) return;
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec)
        throw std::runtime_error(fmt::format("cannot create the folder {} for {}: {}", file.parent_path().string(),
                                             file.filename().string(), ec.message()));
}

bool processRunning(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

int removeStaleTemporaries(const std::filesystem::path& folder) {
    static const std::regex temporary(R"(.*\.tmp-([0-9]+)(\.[A-Za-z0-9]+)?)");
    int removed = 0;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder.empty() ? "." : folder, ec)) {
        std::smatch m;
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file(ec) || !std::regex_match(name, m, temporary)) continue;
        if (processRunning(std::stol(m[1].str()))) continue;
        if (std::filesystem::remove(entry.path(), ec)) ++removed;
    }
    return removed;
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(fmt::format("cannot read {}: {}", path.string(),
                                                  std::strerror(errno)));
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace relief
