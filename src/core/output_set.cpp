#include "core/output_set.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/text_escape.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = ".relief-";
constexpr std::string_view kOwnerTag = "relief private folder";

// This machine's name as a file name can hold it: a run on another machine
// sharing the folder (a cluster's filesystem) is told apart by it.
std::string hostName() {
    char buf[256] = {};
    if (::gethostname(buf, sizeof buf - 1) != 0) return "host";
    std::string name;
    for (const char* c = buf; *c && name.size() < 40; ++c)
        name += std::isalnum(static_cast<unsigned char>(*c)) || *c == '-' ? *c : '_';
    return name.empty() ? "host" : name;
}

fs::path folderOf(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }

// An exclusive lock on a folder while a set is moved into it: two runs
// onto one name move their sets one after the other, never interleaved.
// Where the filesystem has no locks (some network filesystems), the moves
// go on without (each file is still whole).
class FolderLock {
public:
    explicit FolderLock(const fs::path& dir) : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
        if (fd_ >= 0)
            while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
            }
    }
    ~FolderLock() {
        if (fd_ >= 0) ::close(fd_);
    }
    FolderLock(FolderLock&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }
    FolderLock(const FolderLock&) = delete;

private:
    int fd_;
};

bool processRunning(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

// Whether the private folder `dir` was left by a run that is gone; `fd`
// keeps it locked for the caller (closed by the caller).
bool abandoned(const fs::path& dir, int& fd) {
    fd = ::open((dir / "owner").c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return false;
    char buf[128] = {};
    const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
    if (n < static_cast<ssize_t>(kOwnerTag.size()) || std::string_view(buf).substr(0, kOwnerTag.size()) != kOwnerTag)
        return false;  // not relief's
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return true;
    if (errno == EWOULDBLOCK) return false;  // its run holds it
    // No locks on this filesystem: a run of this machine whose process is gone.
    long pid = 0;
    char host[64] = {};
    return std::sscanf(buf + kOwnerTag.size(), " %ld %63s", &pid, host) == 2 && host == hostName() &&
           !processRunning(pid);
}

std::vector<std::string> journalNames(const fs::path& journal) {
    std::vector<std::string> names;
    std::string problem;
    const auto read = readInputFile(journal, 1u << 20, problem);
    if (!read) return names;
    const std::string& text = *read;
    size_t start = 0;
    for (size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1)
        names.push_back(text.substr(start, nl - start));
    // Whole only with its last line ".": one cut short was written when the kill came, before anything moved.
    if (names.empty() || names.back() != ".") return {};
    names.pop_back();
    return names;
}

void syncFolder(const fs::path& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

PrivateFolder::PrivateFolder(const fs::path& parent, std::string_view what) {
    const fs::path base = parent.empty() ? fs::path(".") : parent;
    std::string pattern = (base / fmt::format("{}{}-{}-{}-XXXXXX", kPrefix, what, hostName(), ::getpid())).string();
    if (!::mkdtemp(pattern.data()))
        throw std::runtime_error(fmt::format("cannot write in {}: {}", base.string(), std::strerror(errno)));
    dir_ = pattern;
    ownerFd_ = ::open((dir_ / "owner").c_str(), O_CREAT | O_EXCL | O_RDWR | O_NOFOLLOW | O_CLOEXEC, 0600);
    const std::string owner = fmt::format("{} {} {}\n", kOwnerTag, ::getpid(), hostName());
    if (ownerFd_ < 0 || ::write(ownerFd_, owner.data(), owner.size()) != static_cast<ssize_t>(owner.size())) {
        const int err = errno;
        std::error_code ec;
        fs::remove_all(dir_, ec);
        throw std::runtime_error(fmt::format("cannot write in {}: {}", base.string(), std::strerror(err)));
    }
    ::flock(ownerFd_, LOCK_EX | LOCK_NB);  // no locks here: abandoned() falls back to the process id
}

PrivateFolder::PrivateFolder(PrivateFolder&& o) noexcept : dir_(std::move(o.dir_)), ownerFd_(o.ownerFd_) {
    o.dir_.clear();
    o.ownerFd_ = -1;
}

PrivateFolder::~PrivateFolder() {
    if (dir_.empty()) return;
    std::error_code ec;
    for (auto it = fs::directory_iterator(dir_, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
        if (it->path().filename() != "owner") fs::remove_all(it->path(), ec);
    fs::remove(dir_ / "owner", ec);
    if (!fs::remove(dir_, ec) || ec) {
        // The folder cannot go (its parent was made read-only): an owner file, unlocked,
        // tells the next run it was abandoned.
        const int fd = ::open((dir_ / "owner").c_str(), O_CREAT | O_EXCL | O_WRONLY | O_NOFOLLOW | O_CLOEXEC, 0600);
        const std::string owner = fmt::format("{} {} {}\n", kOwnerTag, ::getpid(), hostName());
        if (fd >= 0) (void)!::write(fd, owner.data(), owner.size()), ::close(fd);
    }
    if (ownerFd_ >= 0) ::close(ownerFd_);
}

int removeAbandonedFolders(const fs::path& parent) {
    const fs::path dir = parent.empty() ? fs::path(".") : parent;
    int removed = 0;
    std::error_code ec;
    std::vector<fs::path> candidates;
    for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
        const std::string name = it->path().filename().string();
        std::error_code sec;
        if (name.starts_with(kPrefix) && it->symlink_status(sec).type() == fs::file_type::directory)
            candidates.push_back(it->path());
    }
    for (const fs::path& folder : candidates) {
        int fd = -1;
        if (abandoned(folder, fd)) {
            // Killed while moving its set into place: the rest of the set goes too.
            if (const auto names = journalNames(folder / "journal"); !names.empty()) {
                const FolderLock lock(dir);
                for (const auto& name : names)
                    if (fs::exists(folder / "new" / name, ec)) fs::rename(folder / "new" / name, dir / name, ec);
                syncFolder(dir);
            }
            fs::remove_all(folder, ec);
            if (!ec) ++removed;
        }
        if (fd >= 0) ::close(fd);
    }
    return removed;
}

fs::path shownPath(const fs::path& path) {
    const fs::path folder = path.parent_path();
    if (folder.filename() != "new" || !folder.parent_path().filename().string().starts_with(kPrefix)) return path;
    return shownPath(folder.parent_path().parent_path() / path.filename());  // a set within a set: the outer name
}

OutputSet::~OutputSet() = default;

fs::path OutputSet::add(const fs::path& finalPath, std::string_view role, bool seal) {
    std::error_code ec;
    const std::string name = finalPath.string();
    if (std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        throw std::runtime_error(fmt::format("{} ({}) holds a control character: give a plain file name", role,
                                             printableExcerpt(name, 200)));
    const fs::path key = fs::weakly_canonical(fs::absolute(finalPath, ec), ec);
    for (const auto& e : entries_)
        if (e.key == key)
            throw std::runtime_error(fmt::format("{} and {} are the same file, {}: give them different names", e.role,
                                                 role, finalPath.string()));
    if (key.filename().empty() || finalPath.filename() == "." || finalPath.filename() == "..")
        throw std::runtime_error(fmt::format("{} ({}) names a folder, not a file", role, finalPath.string()));
    createParentFolder(finalPath);
    const fs::path dir = folderOf(finalPath);
    const fs::path dirKey = fs::weakly_canonical(fs::absolute(dir, ec), ec);
    size_t folder = std::find(folderDirs_.begin(), folderDirs_.end(), dirKey) - folderDirs_.begin();
    if (folder == folderDirs_.size()) {
        removeAbandonedFolders(dir);  // what killed runs left, before this one writes there
        folders_.emplace_back(dir, "out");
        folderDirs_.push_back(dirKey);
        fs::create_directory(folders_.back().path() / "new");
        fs::create_directory(folders_.back().path() / "old");
    }
    entries_.push_back({finalPath, key, std::string(role), folder});
    if (seal) seal_ = finalPath;
    return staged(finalPath);
}

void OutputSet::drop(const fs::path& finalPath) {
    const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.finalPath == finalPath; });
    if (it == entries_.end()) return;
    std::error_code ec;
    fs::remove(staged(finalPath), ec);
    entries_.erase(it);
    if (seal_ == finalPath) seal_.clear();
}

fs::path OutputSet::staged(const fs::path& finalPath) const {
    for (const auto& e : entries_)
        if (e.finalPath == finalPath) return folders_[e.folder].path() / "new" / finalPath.filename();
    throw std::logic_error("OutputSet::staged: " + finalPath.string() + " was not declared");
}

void OutputSet::checkNotAnOutput(const fs::path& input, std::string_view role) const {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(fs::absolute(input, ec), ec);
    for (const auto& e : entries_)
        if (e.key == key)
            throw std::runtime_error(fmt::format("{} and {} are the same file, {}: an output must not overwrite "
                                                 "an input; give it another name",
                                                 role, e.role, e.finalPath.string()));
}

void OutputSet::commit() {
    if (committed_) throw std::logic_error("OutputSet::commit: committed twice");
    std::error_code ec;
    // The seal last.
    std::stable_partition(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.finalPath != seal_; });
    for (const auto& e : entries_)
        if (!fs::exists(staged(e.finalPath), ec))
            throw std::logic_error("OutputSet::commit: " + e.finalPath.string() + " was declared, never written");
    // Folders locked in one order (by path), so two runs never wait on each other.
    std::vector<size_t> order(folders_.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return folderDirs_[a] < folderDirs_[b]; });
    std::vector<FolderLock> locks;
    for (size_t f : order) locks.emplace_back(folderDirs_[f]);
    // The journal: what a later run moves the rest of the way if this one dies mid-way.
    for (size_t f = 0; f < folders_.size(); ++f) {
        std::string names;
        for (const auto& e : entries_)
            if (e.folder == f) names += e.finalPath.filename().string() + "\n";
        names += ".\n";
        const fs::path journal = folders_[f].path() / "journal";
        std::FILE* file = createNewFile(journal, journal);
        std::fwrite(names.data(), 1, names.size(), file);
        closeWritten(file, journal);
    }
    // The files replaced, kept (hard links) until the whole set is in place.
    const auto oldOf = [&](const Entry& e) { return folders_[e.folder].path() / "old" / e.finalPath.filename(); };
    for (const auto& e : entries_)
        if (fs::symlink_status(e.finalPath, ec).type() != fs::file_type::not_found)
            ::link(e.finalPath.c_str(), oldOf(e).c_str());
    // The seal goes first and comes back last: while the set is moved, no old sidecar vouches for new files.
    const bool sealed = !seal_.empty();
    if (sealed) fs::remove(seal_, ec);
    for (size_t i = 0; i < entries_.size(); ++i) {
        const Entry& e = entries_[i];
        fs::rename(staged(e.finalPath), e.finalPath, ec);
        if (!ec) continue;
        const std::string reason = ec.message();
        for (size_t j = 0; j <= i; ++j) {  // back as it was
            const Entry& done = entries_[j];
            std::error_code ignored;
            if (fs::exists(oldOf(done), ignored)) fs::rename(oldOf(done), done.finalPath, ignored);
            else if (j < i) fs::remove(done.finalPath, ignored);
        }
        if (const Entry& seal = entries_.back(); sealed && fs::exists(oldOf(seal), ec))
            fs::rename(oldOf(seal), seal.finalPath, ec);
        for (size_t f = 0; f < folders_.size(); ++f) fs::remove(folders_[f].path() / "journal", ec);
        throw std::runtime_error(fmt::format("cannot write {}: {}", e.finalPath.string(), reason));
    }
    for (const auto& dir : folderDirs_) syncFolder(dir);
    committed_ = true;
}

}  // namespace relief
