// Runs `hexlod serve` as a separate process, as a user would, and finds its port from the
// "viewer at http://..." line it prints.
#pragma once

#include <chrono>
#include <string>
#include <sys/types.h>
#include <vector>

namespace hexlod::test {

class ServeProcess {
public:
    // Starts the binary with `arguments` (and `environment` entries "NAME=value" added).
    explicit ServeProcess(const std::vector<std::string>& arguments,
                          const std::vector<std::string>& environment = {});
    ~ServeProcess(); // kills it if still running

    // Waits for the URL line; false if the process exited or printed none within the time.
    bool waitUntilServing(std::chrono::milliseconds timeout = std::chrono::milliseconds(30000));
    uint16_t port() const { return port_; }
    // Sends `signal` and waits for the exit; returns the exit status (128 + signal if killed).
    int stop(int signal);
    // Waits for the process to end by itself.
    int wait();
    std::string stderrText() const;

private:
    pid_t pid_ = -1;
    int stdoutFd_ = -1;
    std::string stderrPath_;
    uint16_t port_ = 0;
    int status_ = -1;
};

} // namespace hexlod::test
