// Raw terminal-set file written by `hexlod expand --out`: the in-memory batch as is,
// behind a magic and a version, so a reader can map it straight into a GPU buffer.
#pragma once

#include "hexlod/grammar/terminal_set.h"

#include <string>

namespace hexlod::apps {

// Layout (little-endian): "HXTS", uint32 version (1), TerminalSetHeader, uint32 shape count,
// uint32 counts[shape count], uint64 record count, TerminalRecord records[record count].
bool writeTerminalSetFile(const std::string& path, const grammar::TerminalSet& set, std::string& error);

} // namespace hexlod::apps
