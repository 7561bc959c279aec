#include "serve_process.h"

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <poll.h>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace hexlod::test {

ServeProcess::ServeProcess(const std::vector<std::string>& arguments,
                           const std::vector<std::string>& environment) {
    char errPath[] = "/tmp/hexlod-serve-stderr-XXXXXX";
    const int errFd = mkstemp(errPath);
    stderrPath_ = errPath;
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe failed");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, errFd, STDERR_FILENO);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    std::vector<std::string> args = {HEXLOD_BINARY, "serve"};
    args.insert(args.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e) env.emplace_back(*e);
    env.insert(env.end(), environment.begin(), environment.end());
    std::vector<char*> envp;
    for (std::string& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    if (posix_spawn(&pid_, HEXLOD_BINARY, &actions, nullptr, argv.data(), envp.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
    close(out[1]);
    close(errFd);
    stdoutFd_ = out[0];
}

ServeProcess::~ServeProcess() {
    if (pid_ > 0 && status_ < 0) stop(SIGKILL);
    if (stdoutFd_ >= 0) close(stdoutFd_);
    std::remove(stderrPath_.c_str());
}

bool ServeProcess::waitUntilServing(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::string text;
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{stdoutFd_, POLLIN, 0};
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (poll(&p, 1, static_cast<int>(std::max<int64_t>(1, left.count()))) <= 0) continue;
        char buffer[512];
        const ssize_t n = read(stdoutFd_, buffer, sizeof(buffer));
        if (n <= 0) return false; // the process closed its output: it exited
        text.append(buffer, static_cast<size_t>(n));
        const size_t at = text.find("viewer at http://127.0.0.1:");
        if (at == std::string::npos) continue;
        const size_t end = text.find('/', at + 27);
        if (end == std::string::npos) continue;
        port_ = static_cast<uint16_t>(std::stoi(text.substr(at + 27, end - at - 27)));
        return true;
    }
    return false;
}

int ServeProcess::stop(int signal) {
    if (status_ >= 0) return status_;
    kill(pid_, signal);
    return wait();
}

int ServeProcess::wait() {
    if (status_ >= 0) return status_;
    int status = 0;
    waitpid(pid_, &status, 0);
    status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return status_;
}

std::string ServeProcess::stderrText() const {
    std::ifstream in(stderrPath_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

} // namespace hexlod::test
