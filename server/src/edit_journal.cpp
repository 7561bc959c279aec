#include "hexlod/server/edit_journal.h"

#include "hexlod/cache/batch_key.h"
#include "hexlod/grammar/terminal_set_codec.h"
#include "hexlod/server/http_types.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace hexlod::server {
namespace {

using Json = nlohmann::json;
constexpr std::string_view kCrcMember = ",\"crc\":\"";
constexpr const char* kFormat = "hexlod-edit-journal";
constexpr int kFormatVersion = 1;

std::string systemError(const std::string& what, const std::string& path) {
    return what + " '" + path + "': " + std::strerror(errno);
}

uint64_t lineChecksum(std::string_view text) {
    return grammar::checksum64({reinterpret_cast<const uint8_t*>(text.data()), text.size()});
}

// `object` is a dumped JSON object; the crc member goes last, over the object without it.
std::string withCrc(const std::string& object) {
    std::string line = object.substr(0, object.size() - 1);
    line += kCrcMember;
    line += cache::hexDigest(lineChecksum(object));
    line += "\"}\n";
    return line;
}

// Checks the crc member and parses the rest.
bool verifiedJson(std::string_view line, Json& out, std::string& error) {
    const size_t at = line.rfind(kCrcMember);
    if (at == std::string_view::npos || line.size() != at + kCrcMember.size() + 16 + 2 ||
        line.substr(line.size() - 2) != "\"}")
        return error = "no crc member at the end of the line", false;
    const std::string object = std::string(line.substr(0, at)) + "}";
    const std::string_view hex = line.substr(at + kCrcMember.size(), 16);
    if (cache::hexDigest(lineChecksum(object)) != hex) return error = "checksum mismatch", false;
    out = Json::parse(object, nullptr, false);
    if (out.is_discarded() || !out.is_object()) return error = "not a JSON object", false;
    return true;
}

bool writeAll(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd, bytes.data(), bytes.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        bytes.remove_prefix(static_cast<size_t>(n));
    }
    return true;
}

bool syncFolderOf(const std::string& path, std::string& error) {
    std::string folder = std::filesystem::path(path).parent_path().string();
    if (folder.empty()) folder = ".";
    const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir < 0) return error = systemError("cannot open the journal's folder", folder), false;
    const bool ok = ::fsync(dir) == 0;
    if (!ok) error = systemError("cannot fsync the journal's folder", folder);
    ::close(dir);
    return ok;
}

bool readAll(int fd, std::string& out, std::string& error, const std::string& path) {
    out.clear();
    char buffer[1 << 16];
    off_t at = 0;
    while (true) {
        const ssize_t n = ::pread(fd, buffer, sizeof(buffer), at);
        if (n < 0) {
            if (errno == EINTR) continue;
            return error = systemError("cannot read edit journal", path), false;
        }
        if (n == 0) return true;
        out.append(buffer, static_cast<size_t>(n));
        at += n;
    }
}

std::string headerLine(const std::string& scene) {
    return withCrc(jsonText(Json{{"format", kFormat},
                                 {"version", kFormatVersion},
                                 {"scene", scene},
                                 {"seq", 0},
                                 {"created", utcNow()}}));
}

// Replaces the journal by `text` atomically: a temporary file, fsync, rename, folder fsync.
bool rewrite(const std::string& path, const std::string& text, std::string& error) {
    const std::string temporary = path + ".tmp";
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return error = systemError("cannot create", temporary), false;
    const bool ok = writeAll(fd, text) && ::fsync(fd) == 0;
    if (!ok) error = systemError("cannot write", temporary);
    ::close(fd);
    if (!ok) return false;
    if (::rename(temporary.c_str(), path.c_str()) != 0)
        return error = systemError("cannot replace", path), false;
    return syncFolderOf(path, error);
}

bool appendDurably(const std::string& path, const std::string& text, std::string& error) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) return error = systemError("cannot open", path), false;
    const bool ok = writeAll(fd, text) && ::fdatasync(fd) == 0;
    if (!ok) error = systemError("cannot write", path);
    ::close(fd);
    return ok;
}

bool entryFromJson(const Json& j, JournalEntry& e, std::string& error) {
    const auto it = j.find("seq");
    if (it == j.end() || !it->is_number_unsigned() || it->get<uint64_t>() == 0)
        return error = "no positive \"seq\"", false;
    e.seq = it->get<uint64_t>();
    const auto op = j.find("op");
    if (op == j.end() || !op->is_string()) return error = "no \"op\"", false;
    const auto time = j.find("time");
    e.time = time != j.end() && time->is_string() ? time->get<std::string>() : "";
    if (*op == "edit") {
        e.op = JournalEntry::Op::Edit;
        const auto selector = j.find("selector");
        const auto params = j.find("params");
        if (selector == j.end() || !selector->is_object() || params == j.end() || !params->is_object())
            return error = "an edit needs \"selector\" and \"params\" objects", false;
        e.selector = *selector;
        e.params = *params;
        const auto comment = j.find("comment");
        e.comment = comment != j.end() && comment->is_string() ? comment->get<std::string>() : "";
        return true;
    }
    if (*op == "undo") {
        e.op = JournalEntry::Op::Undo;
        const auto undoes = j.find("undoes");
        if (undoes == j.end() || !undoes->is_number_unsigned())
            return error = "an undo needs \"undoes\"", false;
        e.undoes = undoes->get<uint64_t>();
        return true;
    }
    return error = "unknown op " + op->dump(), false;
}

} // namespace

std::string utcNow() {
    const auto now = std::chrono::system_clock::now();
    const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
    const auto millis =
        std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
    std::tm tm{};
    gmtime_r(&seconds, &tm);
    char text[96];
    std::snprintf(text, sizeof(text), "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1,
                  tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(millis));
    return text;
}

std::string EditJournal::formatLine(const JournalEntry& e) {
    Json j = {{"seq", e.seq}, {"time", e.time}};
    if (e.op == JournalEntry::Op::Edit) {
        j["op"] = "edit";
        j["selector"] = e.selector;
        j["params"] = e.params;
        if (!e.comment.empty()) j["comment"] = e.comment;
    } else {
        j["op"] = "undo";
        j["undoes"] = e.undoes;
    }
    return withCrc(jsonText(j));
}

bool EditJournal::parseLine(std::string_view line, JournalEntry& entry, std::string& error) {
    Json j;
    return verifiedJson(line, j, error) && entryFromJson(j, entry, error);
}

EditJournal::EditJournal(std::string path, int fd, uint64_t size, uint64_t nextSeq)
    : path_(std::move(path)), fd_(fd), size_(size), nextSeq_(nextSeq) {}

EditJournal::~EditJournal() {
    if (fd_ >= 0) ::close(fd_);
}

std::unique_ptr<EditJournal> EditJournal::open(const std::string& path, const JournalOpenOptions& options,
                                               std::vector<JournalEntry>& entries,
                                               std::vector<std::string>& notes, std::string& error) {
    entries.clear();
    struct stat st {};
    const bool existed = ::stat(path.c_str(), &st) == 0;
    if (!existed && options.readOnly) {
        error = "no edit journal at '" + path + "'";
        return nullptr;
    }
    const int flags = options.readOnly ? O_RDONLY : O_RDWR | O_CREAT | O_APPEND;
    const int fd = ::open(path.c_str(), flags | O_CLOEXEC, 0644);
    if (fd < 0) {
        error = systemError(existed ? "cannot open edit journal" : "cannot create edit journal", path);
        return nullptr;
    }
    std::unique_ptr<EditJournal> journal(new EditJournal(path, fd, 0, 1));
    journal->readOnly_ = options.readOnly;
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        error = "edit journal '" + path + "' is not a regular file";
        return nullptr;
    }
    // Two servers appending to one journal would interleave their sequence numbers.
    if (!options.readOnly && ::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        error = "edit journal '" + path + "' is in use by another process";
        return nullptr;
    }
    if (!existed && !syncFolderOf(path, error)) return nullptr;

    std::string text;
    if (!readAll(fd, text, error, path)) return nullptr;
    const size_t complete = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
    if (complete < text.size()) {
        notes.push_back("journal " + path + ": " + std::to_string(text.size() - complete) +
                        " bytes after the last complete line (a write cut short, never acknowledged)" +
                        (options.readOnly ? ": ignored" : ": truncated"));
        if (!options.readOnly &&
            (::ftruncate(fd, static_cast<off_t>(complete)) != 0 || ::fdatasync(fd) != 0)) {
            error = systemError("cannot truncate the torn end of edit journal", path);
            return nullptr;
        }
        text.resize(complete);
    }

    std::string kept, rejected;
    uint64_t lastSeq = 0;
    size_t lineNumber = 0;
    bool sawHeader = false;
    for (size_t at = 0; at < text.size();) {
        const size_t end = text.find('\n', at);
        const std::string_view line(text.data() + at, end - at);
        ++lineNumber;
        at = end + 1;
        Json j;
        std::string why;
        JournalEntry entry;
        bool ok = verifiedJson(line, j, why);
        if (ok && lineNumber == 1 && j.value("format", "") == kFormat) {
            if (j.value("version", 0) != kFormatVersion) {
                error =
                    "edit journal '" + path + "': line 1: unsupported journal version " + j["version"].dump();
                return nullptr;
            }
            sawHeader = true;
            kept.append(line).push_back('\n');
            continue;
        }
        if (ok && entryFromJson(j, entry, why)) {
            if (entry.seq <= lastSeq) {
                why = "sequence number " + std::to_string(entry.seq) + " does not follow " +
                      std::to_string(lastSeq);
                ok = false;
            }
        } else {
            ok = false;
        }
        if (!ok) {
            if (!options.repair) {
                error = "edit journal '" + path + "': line " + std::to_string(lineNumber) + " is corrupt (" +
                        why + "); start with --journal-repair to move it aside and keep the rest";
                return nullptr;
            }
            notes.push_back("journal " + path + ": line " + std::to_string(lineNumber) + " is corrupt (" +
                            why + (options.readOnly ? "): skipped" : "): moved to " + path + ".rejected"));
            rejected.append(line).push_back('\n');
            continue;
        }
        lastSeq = entry.seq;
        kept.append(line).push_back('\n');
        entries.push_back(std::move(entry));
    }
    if (!sawHeader && !options.readOnly) {
        const std::string header = headerLine(options.scene);
        if (text.empty()) {
            if (!writeAll(fd, header) || ::fdatasync(fd) != 0) {
                error = systemError("cannot write edit journal", path);
                return nullptr;
            }
            kept = header;
        } else {
            notes.push_back("journal " + path + ": no header line (kept as it is)");
        }
    }
    if (!rejected.empty() && !options.readOnly) {
        if (!appendDurably(path + ".rejected", rejected, error) || !rewrite(path, kept, error))
            return nullptr;
        // The rename replaced the file: the descriptor (and its lock) must follow it.
        const int fresh = ::open(path.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
        if (fresh < 0 || ::flock(fresh, LOCK_EX | LOCK_NB) != 0) {
            error = systemError("cannot reopen repaired edit journal", path);
            if (fresh >= 0) ::close(fresh);
            return nullptr;
        }
        ::close(journal->fd_);
        journal->fd_ = fresh;
    }
    journal->size_ = kept.size();
    journal->nextSeq_ = lastSeq + 1;
    return journal;
}

bool EditJournal::append(const JournalEntry& entry, std::string& error) {
    if (broken_) return error = "edit journal '" + path_ + "' failed earlier and takes no more edits", false;
    if (readOnly_) return error = "edit journal '" + path_ + "' is open read-only", false;
    if (entry.seq != nextSeq_) return error = "journal entry out of sequence", false;
    const std::string line = formatLine(entry);
    if (!writeAll(fd_, line) || ::fdatasync(fd_) != 0) {
        error = systemError("cannot append to edit journal", path_);
        // Cut back what part of the line may have landed, so the next append starts clean.
        if (::ftruncate(fd_, static_cast<off_t>(size_)) != 0 || ::fdatasync(fd_) != 0) broken_ = true;
        return false;
    }
    size_ += line.size();
    ++nextSeq_;
    return true;
}

} // namespace hexlod::server

namespace hexlod::server {

std::string defaultJournalPath(const std::string& scenePath) {
    const std::filesystem::path scene(scenePath);
    return (scene.parent_path() / (scene.stem().string() + ".edits.jsonl")).string();
}

} // namespace hexlod::server
