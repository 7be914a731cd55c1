#include "execute/command.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>

#include "core/text_escape.h"

extern char** environ;

namespace relief::execute {

namespace {

// The command's output until it closes its end, or until `deadline` (then false).
bool readUntil(int fd, std::chrono::steady_clock::time_point deadline, bool limited, std::string& output) {
    char buf[4096];
    while (true) {
        if (limited) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline -
                                                                                    std::chrono::steady_clock::now());
            if (left.count() <= 0) return false;
            pollfd p{fd, POLLIN, 0};
            const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
            if (ready < 0 && errno != EINTR) return true;
            if (ready <= 0) continue;
        }
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return true;
        if (output.size() < (1u << 20)) output.append(buf, static_cast<size_t>(n));
    }
}

}  // namespace

CommandOutput runCommand(const std::vector<std::string>& argv, const CommandOptions& options) {
    CommandOutput out;
    int fd[2];
    if (argv.empty() || ::pipe2(fd, O_CLOEXEC) != 0) return out;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fd[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, fd[1], STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    if (!options.workingDir.empty()) posix_spawn_file_actions_addchdir_np(&actions, options.workingDir.c_str());
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    // The child starts with no signal blocked and SIGINT and SIGTERM at their defaults, whatever
    // this thread has (relief preview blocks them in every thread, to wait for them in one): so
    // that Ctrl-C and a kill reach what relief started.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    pid_t pid = 0;
    const int err = ::posix_spawnp(&pid, args[0], &actions, &attributes, args.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fd[1]);
    if (err != 0) {
        ::close(fd[0]);
        out.output = argv[0] + ": not found";
        return out;
    }
    const bool limited = options.timeoutSeconds > 0;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::milliseconds(static_cast<long long>(options.timeoutSeconds * 1000));
    if (!readUntil(fd[0], deadline, limited, out.output)) {
        ::kill(pid, SIGKILL);
        out.timedOut = true;
    }
    ::close(fd[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    out.status = WIFEXITED(status) && !out.timedOut ? WEXITSTATUS(status) : -1;
    return out;
}

std::string firstLine(const std::string& text) {
    size_t start = 0;
    while (start < text.size()) {
        const size_t end = text.find('\n', start);
        const std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (line.find_first_not_of(" \t\r") != std::string::npos) return terminalText(line, 300);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return "";
}

}  // namespace relief::execute
