// The edit journal (ARCHITECTURE.md §4): one JSON line per edit or undo, appended and made
// durable (fdatasync; the folder is fsynced when the file is created) before the edit is
// acknowledged, and read back at start so that every acknowledged edit survives a kill -9.
//
// Line format (docs/protocol.md, "Edit journal"): a JSON object whose last member is
// "crc", the 16-hex-digit checksum64 of the line with that member removed, e.g.
//   {"op":"edit","params":{"floor_h":3.2},"selector":{"buildings":[12]},"seq":1,"time":"...","crc":"..."}
// The first line is a header ({"format":"hexlod-edit-journal","version":1,...}, seq 0).
//
// Reading, in order:
// - bytes after the last newline are a torn write: the process died inside an append, so
//   that edit was never acknowledged. They are truncated away (unless read-only) and reported;
// - a complete line that fails its checksum, is not JSON or does not hold a valid entry with
//   a sequence number above the previous one is corruption: open() fails naming the line,
//   unless `repair`, which moves such lines to "<path>.rejected" and rewrites the journal
//   without them (through a temporary file and a rename).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace hexlod::server {

struct JournalEntry {
    enum class Op { Edit, Undo };
    uint64_t seq = 0; // 1, 2, 3, ...; never reused
    Op op = Op::Edit;
    nlohmann::json selector; // Edit: as in the POST body, e.g. {"buildings": [12]}
    nlohmann::json params;   // Edit: {"name": number}
    uint64_t undoes = 0;     // Undo: the seq of the edit it reverts
    std::string comment;     // Edit: optional text from the client
    std::string time;        // UTC, ISO 8601, when it was written
};

struct JournalOpenOptions {
    bool repair = false;   // move corrupt lines aside instead of failing
    bool readOnly = false; // never create, truncate or rewrite (hexlod export)
    std::string scene;     // scene name for the header of a new journal
};

class EditJournal {
public:
    // Opens or creates `path` and reads it. On success `entries` holds every valid entry in
    // order and `notes` says what was repaired or truncated. On failure returns nullptr with
    // `error` naming the file (and line).
    static std::unique_ptr<EditJournal> open(const std::string& path, const JournalOpenOptions& options,
                                             std::vector<JournalEntry>& entries,
                                             std::vector<std::string>& notes, std::string& error);
    ~EditJournal();
    EditJournal(const EditJournal&) = delete;
    EditJournal& operator=(const EditJournal&) = delete;

    // Writes the entry (its seq must be nextSeq()) as one line and fdatasyncs it. On failure
    // the file is cut back to where it was and false is returned with `error`; if even that
    // fails the journal refuses every later append (broken()).
    bool append(const JournalEntry& entry, std::string& error);

    uint64_t nextSeq() const { return nextSeq_; }
    const std::string& path() const { return path_; }
    bool broken() const { return broken_; }

    // The line for an entry, newline included: what append() writes.
    static std::string formatLine(const JournalEntry& entry);
    // Parses and verifies one line (without its newline); false with `error` if it is not a
    // valid entry.
    static bool parseLine(std::string_view line, JournalEntry& entry, std::string& error);

private:
    EditJournal(std::string path, int fd, uint64_t size, uint64_t nextSeq);

    std::string path_;
    int fd_ = -1;
    uint64_t size_ = 0;
    uint64_t nextSeq_ = 1;
    bool broken_ = false;
    bool readOnly_ = false;
};

std::string utcNow(); // "2025-01-31T12:34:56.789Z"

} // namespace hexlod::server

namespace hexlod::server {

// Where a scene's journal lives unless told otherwise: beside its config, named after it
// ("configs/default.json" -> "configs/default.edits.jsonl").
std::string defaultJournalPath(const std::string& scenePath);

} // namespace hexlod::server
