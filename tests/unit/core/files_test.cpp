// Reading untrusted files and writing outputs whole, as sets.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/output_set.h"
#include "unit/test_dirs.h"

namespace relief {
namespace {

namespace fs = std::filesystem;
using testing::freshTestDir;

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }
std::string read(const fs::path& p) { return readFile(p); }

// The names in a folder (hidden ones too), sorted.
std::vector<std::string> names(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

TEST(InputFile, ReadsRegularFilesAndSaysWhatTheOthersAre) {
    const fs::path dir = freshTestDir("input-file");
    write(dir / "a.txt", "hello\n");
    std::string problem;
    EXPECT_EQ(readInputFile(dir / "a.txt", 100, problem).value_or("?"), "hello\n");
    EXPECT_EQ(problem, "");
    EXPECT_FALSE(readInputFile(dir / "none.txt", 100, problem));
    EXPECT_EQ(problem, "no such file");
    EXPECT_FALSE(readInputFile(dir, 100, problem));
    EXPECT_EQ(problem, "it is a folder, not a file");
    // A FIFO with no writer: refused at once, never opened to wait for one.
    ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
    EXPECT_FALSE(readInputFile(dir / "fifo", 100, problem));
    EXPECT_EQ(problem, "it is a FIFO (a named pipe), not a file");
    EXPECT_FALSE(readInputFile("/dev/zero", 100, problem));
    EXPECT_EQ(problem, "it is a device, not a file");
    fs::create_symlink("/dev/zero", dir / "zero.toml");  // a link to a device is the device
    EXPECT_EQ(inputFileProblem(dir / "zero.toml"), "it is a device, not a file");
    write(dir / "big.txt", std::string(2500, 'x'));
    EXPECT_FALSE(readInputFile(dir / "big.txt", 2000, problem));
    EXPECT_EQ(problem, "it is 2.5 kB, more than the 2 kB such a file may be");
    EXPECT_EQ(readInputHead(dir / "big.txt", 10, problem).value_or("?"), std::string(10, 'x'));
    EXPECT_EQ(readInputFile(dir / "big.txt", 0, problem).value_or("?").size(), 2500u);
}

TEST(AtomicFile, NeverWritesThroughALinkPlantedAtTheOutput) {
    const fs::path dir = freshTestDir("atomic-link");
    write(dir / "victim", "precious");
    fs::create_symlink(dir / "victim", dir / "out.pov");
    writeFileAtomically(dir / "out.pov", "scene");
    EXPECT_EQ(read(dir / "victim"), "precious");
    EXPECT_FALSE(fs::is_symlink(dir / "out.pov"));
    EXPECT_EQ(read(dir / "out.pov"), "scene");
    // A new file is created exclusively: a name taken (by a link or a file) is refused.
    fs::create_symlink(dir / "victim", dir / "planted");
    EXPECT_THROW(createNewFile(dir / "planted", "planted"), std::runtime_error);
    EXPECT_EQ(read(dir / "victim"), "precious");
    EXPECT_EQ(names(dir), (std::vector<std::string>{"out.pov", "planted", "victim"}));  // nothing else left
}

TEST(AtomicFile, AFileNotCommittedLeavesNothing) {
    const fs::path dir = freshTestDir("atomic-drop");
    write(dir / "x.json", "old");
    {
        AtomicFile f(dir / "x.json");
        f.write("half of a new");
    }
    EXPECT_EQ(read(dir / "x.json"), "old");
    EXPECT_EQ(names(dir), (std::vector<std::string>{"x.json"}));
}

TEST(AtomicFile, CopiesIntoANewFileAndWordsWhyNot) {
    const fs::path dir = freshTestDir("atomic-copy");
    const std::string bytes(300000, 'x');
    write(dir / "a.png", bytes);
    EXPECT_EQ(copyFileContents(dir / "a.png", dir / "b.png"), "");
    EXPECT_EQ(read(dir / "b.png"), bytes);
    // Never through a name taken, by a link or a file.
    fs::create_symlink(dir / "a.png", dir / "planted.png");
    EXPECT_EQ(copyFileContents(dir / "b.png", dir / "planted.png"), "File exists");
    EXPECT_EQ(copyFileContents(dir / "none.png", dir / "c.png"),
              (dir / "none.png").string() + " cannot be read: No such file or directory");
    EXPECT_EQ(writeFailureReason(ENOSPC),
              "the disk is full (No space left on device); make room on that disk or write elsewhere");
    EXPECT_EQ(writeFailureReason(EDQUOT),
              "your disk quota is used up (Disk quota exceeded); make room within it or write elsewhere");
}

TEST(OutputSet, RefusesTwoOutputsOfOneNameAndAnInputAsAnOutput) {
    const fs::path dir = freshTestDir("set-names");
    OutputSet set;
    set.add(dir / "x.pov", "-o");
    try {
        set.add(dir / "sub" / ".." / "x.pov", "--dump-net");
        FAIL() << "a second output of the same name";
    } catch (const OutputError& e) {  // reported at the file, as the user named it
        EXPECT_EQ(e.file(), dir / "sub/../x.pov");
        EXPECT_EQ(e.problem(), "-o and --dump-net are the same file: give them different names");
    }
    try {
        set.addInput(dir / "x.pov", "samples.path");
        FAIL() << "an input as an output";
    } catch (const OutputError& e) {
        EXPECT_EQ(e.file(), dir / "x.pov");
        EXPECT_EQ(e.problem().rfind("samples.path and -o are the same file: ", 0), 0u) << e.problem();
    }
    // An input declared first refuses an output declared later (a drape PNG named like the samples).
    set.addInput(dir / "dem.drape.png", "texture.image");
    EXPECT_THROW(set.add(dir / "dem.drape.png", "the drape PNG"), OutputError);
    EXPECT_THROW(set.add(dir / "a\nb.png", "-o"), OutputError);  // a line break in a name
}

TEST(OutputSet, MovesTheSetTogetherAndPutsItBackWhenAMoveFails) {
    const fs::path dir = freshTestDir("set-commit");
    write(dir / "s.png", "old png");
    write(dir / "s.json", "old sidecar");
    {
        OutputSet set;
        write(set.add(dir / "s.png", "the still"), "new png");
        write(set.add(dir / "s.json", "the sidecar", true), "new sidecar");
        // Staged, nothing has moved.
        EXPECT_EQ(read(dir / "s.png"), "old png");
        set.commit();
    }
    EXPECT_EQ(read(dir / "s.png"), "new png");
    EXPECT_EQ(read(dir / "s.json"), "new sidecar");
    EXPECT_EQ(names(dir), (std::vector<std::string>{"s.json", "s.png"}));
    // The third output's name is a folder, so its move fails: the first two
    // come back as they were, the sidecar too, and the error names the file.
    fs::create_directories(dir / "s.pov" / "in-the-way");
    OutputSet set;
    write(set.add(dir / "s.png", "the still"), "newer png");
    write(set.add(dir / "s.json", "the sidecar", true), "newer sidecar");
    write(set.add(dir / "s.pov", "the .pov"), "newer pov");
    try {
        set.commit();
        FAIL() << "a move onto a folder";
    } catch (const OutputError& e) {
        EXPECT_EQ(e.file(), dir / "s.pov");
        EXPECT_EQ(e.problem().rfind("cannot be moved into place: ", 0), 0u) << e.problem();
    }
    EXPECT_EQ(read(dir / "s.png"), "new png");
    EXPECT_EQ(read(dir / "s.json"), "new sidecar");
}

// A run killed while it had a private folder leaves it; the next run removes
// it, and nothing else: not a live run's folder, not a user's files.
TEST(OutputSet, RemovesOnlyFoldersOfRunsThatAreGone) {
    const fs::path dir = freshTestDir("set-sweep");
    const pid_t child = ::fork();
    if (child == 0) {  // a run killed with its folder made: _exit runs no destructor
        PrivateFolder killed(dir, "out");
        write(killed.path() / "half.png", "half");
        ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    PrivateFolder live(dir, "out");
    fs::create_directories(dir / ".relief-mine");  // a user's folder with relief's prefix but no owner file
    write(dir / "notes.tmp-123", "a user's file");
    write(dir / "data.tmp-999999.csv", "another");
    EXPECT_EQ(names(dir).size(), 5u);
    EXPECT_EQ(removeAbandonedFolders(dir), 1);
    const auto left = names(dir);
    EXPECT_EQ(left.size(), 4u);
    EXPECT_TRUE(fs::exists(live.path()));
    EXPECT_TRUE(fs::exists(dir / ".relief-mine"));
    EXPECT_EQ(read(dir / "notes.tmp-123"), "a user's file");
    EXPECT_EQ(read(dir / "data.tmp-999999.csv"), "another");
}

// Killed in the middle of moving a set into place: the journal lists the
// set, and the next run moves the rest of it (or, if it was being put back,
// puts the rest back); a journal cut short (written when the kill came) moves
// nothing; a planted journal moves nothing out of its folder.
TEST(OutputSet, FinishesASetWhoseMoveWasCutShort) {
    const fs::path dir = freshTestDir("set-journal");
    auto abandonedSet = [&](const std::string& folder, const std::string& journal) {
        const fs::path f = dir / folder;
        fs::create_directories(f / "new");
        fs::create_directories(f / "old");
        write(f / "owner", "relief private folder 999999 elsewhere\n");
        write(f / "journal", journal);
        return f;
    };
    write(dir / "a.png", "new png");  // moved before the kill
    write(abandonedSet(".relief-out-elsewhere-999999-AAAAAA", "forward\na.png\nb.json\n.\n") / "new" / "b.json",
          "new sidecar");
    EXPECT_EQ(removeAbandonedFolders(dir), 1);
    EXPECT_EQ(read(dir / "b.json"), "new sidecar");
    EXPECT_EQ(names(dir), (std::vector<std::string>{"a.png", "b.json"}));
    // Cut short: nothing moves, the folder goes.
    write(abandonedSet(".relief-out-elsewhere-999999-BBBBBB", "forward\nc.png\nd.js") / "new" / "d.js", "x");
    EXPECT_EQ(removeAbandonedFolders(dir), 1);
    EXPECT_EQ(names(dir), (std::vector<std::string>{"a.png", "b.json"}));
    // Being put back: a.png had replaced a file kept in old/, b.json was new: a.png comes back, b.json goes.
    const fs::path back = abandonedSet(".relief-out-elsewhere-999999-CCCCCC", "back\na.png\nb.json\n.\n");
    write(back / "old" / "a.png", "old png");
    EXPECT_EQ(removeAbandonedFolders(dir), 1);
    EXPECT_EQ(read(dir / "a.png"), "old png");
    EXPECT_EQ(names(dir), (std::vector<std::string>{"a.png"}));
    // A planted journal naming a path outside: nothing is moved there.
    fs::create_directories(dir / "elsewhere");
    write(dir / "elsewhere" / "victim", "precious");
    write(abandonedSet(".relief-out-elsewhere-999999-DDDDDD", "forward\n../elsewhere/victim\n.\n") / "new" / "x",
          "evil");
    removeAbandonedFolders(dir);
    EXPECT_EQ(read(dir / "elsewhere" / "victim"), "precious");
    // Another user's folder is not this user's to sweep.
    if (::geteuid() == 0) {
        const fs::path theirs = abandonedSet(".relief-out-elsewhere-999999-EEEEEE", "forward\n.\n");
        ASSERT_EQ(::chown(theirs.c_str(), 65534, 65534), 0);
        EXPECT_EQ(removeAbandonedFolders(dir), 0);
        EXPECT_TRUE(fs::exists(theirs));
    }
}

TEST(OutputSet, MessagesNameTheFinalPath) {
    EXPECT_EQ(shownPath("out/.relief-out-h-1-AbCdEf/new/x.pov"), "out/x.pov");
    EXPECT_EQ(shownPath("out/.relief-out-h-1-AbCdEf/new/.relief-out-h-1-XyZ123/new/x.png"), "out/x.png");
    EXPECT_EQ(shownPath("out/new/x.pov"), "out/new/x.pov");
}

}  // namespace
}  // namespace relief
