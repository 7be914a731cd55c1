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
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/file_descriptor.h"
#include "core/input_file.h"
#include "core/text_escape.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = ".relief-";
constexpr std::string_view kOwnerTag = "relief private folder";

}  // namespace

std::string writeFailureReason(int err) {
    std::string text = std::strerror(err);
    switch (err) {
        case ENOSPC:
            return "the disk is full (" + text + "); make room on that disk or write elsewhere";
        case EDQUOT:
            return "your disk quota is used up (" + text + "); make room within it or write elsewhere";
        case EFBIG:
            return text + "; the file system or the file size limit (ulimit -f) refuses a file this big";
        case EACCES:
        case EPERM:
        case EROFS:
            return text + "; write it in a folder you may write in";
        case ENOENT:
        case ENOTDIR:
            return text + "; its folder is missing or is not a folder";
        default:
            return text;
    }
}

namespace {

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

std::string ownerLine() { return fmt::format("{} {} {}\n", kOwnerTag, ::getpid(), hostName()); }

fs::path folderOf(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }

bool processRunning(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

// An open file description's own write lock (OFD: unlike flock, it holds
// over NFS, and unlike a POSIX lock, a second open in the same process
// conflicts with it). Released when the file is closed, or its process dies.
bool lockFile(int fd, bool wait) {
    struct flock l {};
    l.l_type = F_WRLCK;
    l.l_whence = SEEK_SET;
    while (::fcntl(fd, wait ? F_OFD_SETLKW : F_OFD_SETLK, &l) != 0)
        if (errno != EINTR) return false;
    return true;
}

// An exclusive lock on a folder while a set is moved into it: two runs
// onto one name move their sets one after the other, never interleaved.
// Where the filesystem has no locks on folders (a network filesystem), the
// moves go on without (each file is still whole).
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

// A folder owned by this user, a real folder (not a link), holding relief's owner file.
bool ownFolder(const fs::path& dir) {
    struct stat st {};
    return ::lstat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == ::geteuid();
}

// The owner file of a private folder its run left, locked by the caller; none
// while the run lives (its lock held, or its process running here) or when
// the folder is not relief's, or not this user's.
std::optional<Fd> abandoned(const fs::path& dir) {
    if (!ownFolder(dir)) return std::nullopt;
    Fd owner(::open((dir / "owner").c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK));
    struct stat st {};
    if (owner.fd < 0 || ::fstat(owner.fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::geteuid())
        return std::nullopt;
    char buf[128] = {};
    const ssize_t n = ::pread(owner.fd, buf, sizeof buf - 1, 0);
    if (n < static_cast<ssize_t>(kOwnerTag.size()) || std::string_view(buf).substr(0, kOwnerTag.size()) != kOwnerTag)
        return std::nullopt;  // not relief's
    long pid = 0;
    char host[64] = {};
    const bool parsed = std::sscanf(buf + kOwnerTag.size(), " %ld %63s", &pid, host) == 2;
    if (parsed && host == hostName() && processRunning(pid) && pid != ::getpid()) return std::nullopt;
    if (lockFile(owner.fd, false)) return owner;
    return std::nullopt;  // its run holds the lock (or the filesystem has none, and it may be alive elsewhere)
}

// A set's journal: which way it was moving ("forward", "back") and its file
// names in order, ended by a line ".". A journal without its end was cut
// short by a kill before anything moved.
struct Journal {
    bool forward = true;
    std::vector<std::string> names;
};

bool plainName(const std::string& n) {
    return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos &&
           std::none_of(n.begin(), n.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
}

std::optional<Journal> readJournal(const fs::path& file) {
    std::string problem;
    const auto text = readInputFile(file, 1'000'000, problem);
    if (!text) return std::nullopt;
    std::vector<std::string> lines;
    size_t start = 0;
    for (size_t nl; (nl = text->find('\n', start)) != std::string::npos; start = nl + 1)
        lines.push_back(text->substr(start, nl - start));
    if (lines.size() < 2 || lines.back() != "." || (lines[0] != "forward" && lines[0] != "back")) return std::nullopt;
    Journal j{lines[0] == "forward", {lines.begin() + 1, lines.end() - 1}};
    // Names only, never paths: a planted journal cannot move a file anywhere but into this folder.
    if (!std::all_of(j.names.begin(), j.names.end(), plainName)) return std::nullopt;
    return j;
}

void writeJournal(const fs::path& folder, const Journal& j) {
    std::string text = j.forward ? "forward\n" : "back\n";
    for (const auto& n : j.names) text += n + "\n";
    text += ".\n";
    const fs::path next = folder / "journal.next";
    std::FILE* file = createNewFile(next, next);
    std::fwrite(text.data(), 1, text.size(), file);
    closeWritten(file, next);
    std::error_code ec;
    fs::rename(next, folder / "journal", ec);  // whole, or not there
    if (ec) throw OutputError::system(folder, ec.value());
}

void syncFolder(const fs::path& dir) {
    Fd fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (fd.fd >= 0) ::fsync(fd.fd);
}

bool isThere(const fs::path& p) {
    struct stat st {};
    return ::lstat(p.c_str(), &st) == 0;
}

// Moves a set the way its journal says, file by file: forward, the new files
// still in new/ into place; back, the kept files in old/ into place, and the
// new files already moved (no longer in new/, with nothing kept) away.
// Returns false when a file could not be put where it belongs.
bool finishMove(const fs::path& dir, const fs::path& folder, const Journal& j) {
    bool ok = true;
    std::error_code ec;
    for (const auto& name : j.names) {
        const fs::path fresh = folder / "new" / name, kept = folder / "old" / name, target = dir / name;
        ec.clear();
        if (j.forward && isThere(fresh)) fs::rename(fresh, target, ec);
        else if (!j.forward && isThere(kept)) fs::rename(kept, target, ec);
        else if (!j.forward && !isThere(fresh)) fs::remove(target, ec);  // moved, and nothing was there before
        if (ec) ok = false;
    }
    syncFolder(dir);
    return ok;
}

// The private folders of `dir`, to sweep; `locked`: the caller holds dir's FolderLock.
int sweep(const fs::path& dir, bool locked) {
    int removed = 0;
    std::error_code ec;
    std::vector<fs::path> candidates;
    for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
        if (it->path().filename().string().starts_with(kPrefix)) candidates.push_back(it->path());
    for (const fs::path& folder : candidates) {
        const auto owner = abandoned(folder);
        if (!owner) continue;
        if (const auto journal = readJournal(folder / "journal")) {
            std::optional<FolderLock> lock;
            if (!locked) lock.emplace(dir);
            if (!finishMove(dir, folder, *journal)) continue;  // kept, with its journal, for a later run
        }
        fs::remove_all(folder, ec);
        if (!ec) ++removed;
    }
    return removed;
}

}  // namespace

PrivateFolder::PrivateFolder(const fs::path& parent, std::string_view what) {
    const fs::path base = parent.empty() ? fs::path(".") : parent;
    std::string pattern = (base / fmt::format("{}{}-{}-{}-XXXXXX", kPrefix, what, hostName(), ::getpid())).string();
    if (!::mkdtemp(pattern.data())) throw OutputError::system(base, errno);
    dir_ = pattern;
    ownerFd_ = ::open((dir_ / "owner").c_str(), O_CREAT | O_EXCL | O_RDWR | O_NOFOLLOW | O_CLOEXEC, 0600);
    // Locked before it says whose it is: a sweep never finds it tagged and free.
    if (ownerFd_ >= 0) lockFile(ownerFd_, false);
    const std::string owner = ownerLine();
    if (ownerFd_ < 0 || ::write(ownerFd_, owner.data(), owner.size()) != static_cast<ssize_t>(owner.size())) {
        const int err = errno;
        std::error_code ec;
        fs::remove_all(dir_, ec);
        throw OutputError::system(base, err);
    }
}

PrivateFolder::PrivateFolder(PrivateFolder&& o) noexcept
    : dir_(std::move(o.dir_)), ownerFd_(o.ownerFd_), keep_(o.keep_) {
    o.dir_.clear();
    o.ownerFd_ = -1;
}

PrivateFolder::~PrivateFolder() {
    if (dir_.empty()) return;
    if (!keep_) {
        std::error_code ec;
        for (auto it = fs::directory_iterator(dir_, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
            if (it->path().filename() != "owner") fs::remove_all(it->path(), ec);
        fs::remove(dir_ / "owner", ec);
        if (fs::remove(dir_, ec) && !ec) {
            if (ownerFd_ >= 0) ::close(ownerFd_);
            return;
        }
        // The folder cannot go (its parent was made read-only): an owner file,
        // unlocked once this run ends, tells the next run it was abandoned.
        Fd fd(::open((dir_ / "owner").c_str(), O_CREAT | O_EXCL | O_WRONLY | O_NOFOLLOW | O_CLOEXEC, 0600));
        const std::string owner = ownerLine();
        if (fd.fd >= 0 && ::write(fd.fd, owner.data(), owner.size()) < 0) {
            // nothing more to try: the folder stays until someone removes it
        }
    }
    if (ownerFd_ >= 0) ::close(ownerFd_);
}

int removeAbandonedFolders(const fs::path& parent) { return sweep(parent.empty() ? fs::path(".") : parent, false); }

fs::path shownPath(const fs::path& path) {
    const fs::path folder = path.parent_path();
    if (folder.filename() != "new" || !folder.parent_path().filename().string().starts_with(kPrefix)) return path;
    return shownPath(folder.parent_path().parent_path() / path.filename());  // a set within a set: the outer name
}

namespace {

// What two names of a file have in common: the folder, links resolved, and the
// name as written (a link at the final name is replaced, not followed).
fs::path fileKey(const fs::path& p) {
    std::error_code ec;
    return fs::weakly_canonical(fs::absolute(folderOf(p), ec), ec) / p.filename();
}

}  // namespace

OutputError::OutputError(fs::path file, std::string problem)
    : std::runtime_error(file.string() + ": " + problem), file_(std::move(file)), problem_(std::move(problem)) {}

OutputError OutputError::system(const fs::path& file, int err) {
    return OutputError(file, "cannot be written: " + writeFailureReason(err));
}

OutputSet::~OutputSet() = default;

fs::path OutputSet::add(const fs::path& finalPath, std::string_view role, bool seal) {
    const std::string name = finalPath.string();
    if (std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        throw OutputError(printableExcerpt(name, 200),
                          fmt::format("{} holds a control character: give a plain file name", role));
    if (finalPath.filename().empty() || finalPath.filename() == "." || finalPath.filename() == "..")
        throw OutputError(name, fmt::format("{} names a folder, not a file: give a file name", role));
    const fs::path key = fileKey(finalPath);
    for (const auto& e : entries_)
        if (e.key == key)
            throw OutputError(name,
                              fmt::format("{} and {} are the same file: give them different names", e.role, role));
    for (const auto& [input, inputRole] : inputs_)
        if (fileKey(input) == key)
            throw OutputError(name, fmt::format("{} and {} are the same file: an output must not overwrite an input; "
                                                "give it another name",
                                                inputRole, role));
    createParentFolder(finalPath);
    const fs::path dir = folderOf(finalPath);
    std::error_code ec;
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

void OutputSet::addInput(const fs::path& input, std::string_view role) {
    const fs::path key = fileKey(input);
    for (const auto& e : entries_)
        if (e.key == key)
            throw OutputError(e.finalPath, fmt::format("{} and {} are the same file: an output must not overwrite an "
                                                       "input; give it another name",
                                                       role, e.role));
    inputs_.emplace_back(input, std::string(role));
}

void OutputSet::drop(const fs::path& finalPath) {
    const fs::path key = fileKey(finalPath);
    const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == key; });
    if (it == entries_.end()) return;
    std::error_code ec;
    fs::remove(staged(finalPath), ec);
    if (fileKey(seal_) == key) seal_.clear();
    entries_.erase(it);
}

bool OutputSet::contains(const fs::path& finalPath) const {
    const fs::path key = fileKey(finalPath);
    return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == key; });
}

fs::path OutputSet::staged(const fs::path& finalPath) const {
    const fs::path key = fileKey(finalPath);
    for (const auto& e : entries_)
        if (e.finalPath == finalPath || e.key == key) return folders_[e.folder].path() / "new" / finalPath.filename();
    throw std::logic_error("OutputSet::staged: " + finalPath.string() + " was not declared");
}

void OutputSet::keepPrevious() {
    for (const auto& e : entries_) {
        struct stat st {};
        // Nothing there, or a folder in the way (the move will fail and say so): nothing to keep.
        if (::lstat(e.finalPath.c_str(), &st) != 0 || S_ISDIR(st.st_mode)) continue;
        const fs::path kept = folders_[e.folder].path() / "old" / e.finalPath.filename();
        // A hard link costs nothing; where there are none (or the kernel
        // refuses one of another user's file), a copy.
        if (::link(e.finalPath.c_str(), kept.c_str()) == 0) continue;
        if (const std::string problem = copyFileContents(e.finalPath, kept); !problem.empty())
            throw OutputError(e.finalPath, fmt::format("cannot be written: the file it replaces cannot be kept until "
                                                       "the new one is in place ({})",
                                                       problem));
    }
}

void OutputSet::commit() {
    if (committed_) throw std::logic_error("OutputSet::commit: committed twice");
    std::error_code ec;
    std::stable_partition(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.finalPath != seal_; });
    for (const auto& e : entries_)
        if (!fs::exists(staged(e.finalPath), ec))
            throw std::logic_error("OutputSet::commit: " + e.finalPath.string() + " was declared, never written");
    // Folders locked in one order (by path), so two runs never wait on each other;
    // under the locks, a set a killed run was moving is finished before this one moves.
    std::vector<size_t> order(folders_.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return folderDirs_[a] < folderDirs_[b]; });
    std::vector<FolderLock> locks;
    for (size_t f : order) {
        locks.emplace_back(folderDirs_[f]);
        sweep(folderDirs_[f], true);
    }
    for (size_t f = 0; f < folders_.size(); ++f) writeJournal(folders_[f].path(), {true, namesIn(f)});
    keepPrevious();
    // The seal goes first and comes back last: while the set moves, no old sidecar vouches for new files.
    if (!seal_.empty()) fs::remove(seal_, ec);
    for (const auto& e : entries_) {
        fs::rename(staged(e.finalPath), e.finalPath, ec);
        if (ec) moveBack(e, writeFailureReason(ec.value()));
    }
    for (const auto& dir : folderDirs_) syncFolder(dir);
    committed_ = true;
}

std::vector<std::string> OutputSet::namesIn(size_t folder) const {
    std::vector<std::string> names;
    for (const auto& e : entries_)
        if (e.folder == folder) names.push_back(e.finalPath.filename().string());
    return names;
}

void OutputSet::moveBack(const Entry& failed, const std::string& reason) {
    // The journal turned round first: were this run killed while putting the
    // files back, the next run would go on putting them back.
    bool restored = true;
    for (size_t f = 0; f < folders_.size(); ++f) {
        const Journal back{false, namesIn(f)};
        try {
            writeJournal(folders_[f].path(), back);
        } catch (const std::runtime_error&) {
            restored = false;
        }
        restored = finishMove(folderDirs_[f], folders_[f].path(), back) && restored;
    }
    if (restored) throw OutputError(failed.finalPath, "cannot be moved into place: " + reason);
    for (auto& folder : folders_) folder.keep();  // the only copies of the replaced files may be in old/
    throw OutputError(failed.finalPath, fmt::format("cannot be moved into place: {}; the files it replaced could not "
                                                    "all be put back: they are in {}/old (the next run there puts "
                                                    "them back)",
                                                    reason, folders_[failed.folder].path().string()));
}

}  // namespace relief
