#include "command_runner.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace hexlod::test {

CommandResult runHexlod(const std::string& arguments) {
    char errPath[] = "/tmp/hexlod-cli-stderr-XXXXXX";
    const int fd = mkstemp(errPath);
    close(fd);
    const std::string command = std::string(HEXLOD_BINARY) + " " + arguments + " 2>" + errPath;
    CommandResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    size_t n;
    while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) result.out.append(buffer, n);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream err(errPath);
    std::ostringstream text;
    text << err.rdbuf();
    result.err = text.str();
    std::remove(errPath);
    return result;
}

} // namespace hexlod::test
