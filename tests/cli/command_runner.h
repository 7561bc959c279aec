// Runs the hexlod binary as a user would and captures its exit code, stdout and stderr.
#pragma once

#include <string>

namespace hexlod::test {

struct CommandResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

// `arguments` is appended to the binary path and run through /bin/sh.
CommandResult runHexlod(const std::string& arguments);

} // namespace hexlod::test
