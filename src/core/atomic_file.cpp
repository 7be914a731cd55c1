#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/sendfile.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/file_descriptor.h"

namespace relief {

std::FILE* createNewFile(const std::filesystem::path& path, const std::filesystem::path& shown) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    std::FILE* file = fd >= 0 ? ::fdopen(fd, "wb") : nullptr;
    if (!file) {
        const int err = errno;
        if (fd >= 0) ::close(fd);
        throw OutputError::system(shown, err);
    }
    return file;
}

void closeWritten(std::FILE* file, const std::filesystem::path& shown) {
    // A writer that went through the stream left its errors in it (a full disk: ENOSPC).
    errno = 0;
    const bool ok = std::fflush(file) == 0 && !std::ferror(file) && ::fsync(::fileno(file)) == 0;
    const int err = errno != 0 ? errno : EIO;
    const bool closed = std::fclose(file) == 0;
    if (!ok || !closed) throw OutputError::system(shown, err);
}

AtomicFile::AtomicFile(std::filesystem::path finalPath) : final_(std::move(finalPath)), shown_(shownPath(final_)) {
    file_ = createNewFile(set_.add(final_, shown_.string()), shown_);
}

AtomicFile::~AtomicFile() {
    if (file_) std::fclose(file_);
}

void AtomicFile::write(std::string_view bytes) {
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
        throw OutputError::system(shown_, errno);
}

void AtomicFile::commit() {
    std::FILE* file = file_;
    file_ = nullptr;
    closeWritten(file, shown_);
    set_.commit();
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
    AtomicFile f(path);
    f.write(bytes);
    f.commit();
}

void writeThroughTemporary(const std::filesystem::path& path,
                           const std::function<std::string(const std::filesystem::path&)>& write) {
    OutputSet set;
    const std::filesystem::path shown = shownPath(path);
    const std::filesystem::path staged = set.add(path, shown.string());
    if (std::string error = write(staged); !error.empty()) throw OutputError(shown, "cannot be written: " + error);
    set.commit();
}

std::string copyFileContents(const std::filesystem::path& from, const std::filesystem::path& to) {
    const Fd in(::open(from.c_str(), O_RDONLY | O_CLOEXEC));
    struct stat st {};
    if (in.fd < 0 || ::fstat(in.fd, &st) != 0)
        return fmt::format("{} cannot be read: {}", from.string(), std::strerror(errno));
    const Fd out(::open(to.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, st.st_mode & 0777));
    if (out.fd < 0) return writeFailureReason(errno);
    for (off_t offset = 0; offset < st.st_size;) {
        // A short count (the disk filled mid-way) is followed by the call that says why.
        const ssize_t n = ::sendfile(out.fd, in.fd, &offset, static_cast<size_t>(st.st_size - offset));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return writeFailureReason(errno);
        if (n == 0) break;  // the file shrank while it was copied
    }
    return "";
}

void linkOrCopy(const std::filesystem::path& from, const std::filesystem::path& to) {
    std::error_code ec;
    std::filesystem::create_hard_link(from, to, ec);
    if (!ec) return;
    if (const std::string error = copyFileContents(from, to); !error.empty())
        throw OutputError(shownPath(to), "cannot be written: " + error);
}

void createParentFolder(const std::filesystem::path& file) {
    if (!file.has_parent_path()) return;
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec)
        throw OutputError(file.parent_path(), fmt::format("cannot be made as the folder of {}: {}",
                                                          file.filename().string(), ec.message()));
}

void makeOwnFolder(const std::filesystem::path& folder) {
    if (::mkdir(folder.c_str(), 0777) != 0 && errno != EEXIST) throw OutputError::system(folder, errno);
    struct stat st {};
    if (::lstat(folder.c_str(), &st) != 0) throw OutputError::system(folder, errno);
    if (S_ISLNK(st.st_mode))
        throw OutputError(folder, "is a link, and relief writes through none in its working folders (someone put it "
                                  "there): remove it");
    if (!S_ISDIR(st.st_mode)) throw OutputError(folder, "is in the way of a folder relief makes here: remove it");
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
