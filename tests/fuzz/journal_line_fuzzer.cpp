// libFuzzer target for the edit journal's line parser (server/edit_journal.h): arbitrary bytes
// as one journal line must be refused with a reason, or parse to an entry that formats back to
// a line parsing to the same entry, so replay after a restart sees exactly what was written.
#include "fuzz_check.h"

#include "hexlod/server/edit_journal.h"

using hexlod::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using hexlod::server::EditJournal;
    using hexlod::server::JournalEntry;
    const std::string_view line(reinterpret_cast<const char*>(data), size);
    JournalEntry entry;
    std::string error;
    if (!EditJournal::parseLine(line, entry, error)) {
        check(!error.empty());
        return 0;
    }
    const std::string again = EditJournal::formatLine(entry); // with its newline
    check(!again.empty() && again.back() == '\n');
    JournalEntry entry2;
    check(EditJournal::parseLine(std::string_view(again).substr(0, again.size() - 1), entry2, error));
    check(EditJournal::formatLine(entry2) == again);
    check(entry2.seq == entry.seq && entry2.op == entry.op);
    return 0;
}
