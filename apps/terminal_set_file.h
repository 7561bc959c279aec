// The terminal-set file written by `hexlod expand --out`: the terminal-set codec's bytes
// (docs/protocol.md, "Terminal set"), written atomically so a reader never sees half a file.
#pragma once

#include "hexlod/grammar/terminal_set.h"

#include <string>

namespace hexlod::apps {

bool writeTerminalSetFile(const std::string& path, const grammar::TerminalSet& set, std::string& error);

} // namespace hexlod::apps
