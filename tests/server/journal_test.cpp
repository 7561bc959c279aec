// The edit journal: lines that carry their checksum, a torn last line truncated, a corrupt
// line refused by line number (or moved aside with repair), append failures that leave the
// file as it was, and replay through the service (undo included, stale entries skipped).
#include "live_server.h"

#include "hexlod/server/edit_journal.h"

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>

namespace hexlod::test {
namespace {

using server::EditJournal;
using server::JournalEntry;
using Json = nlohmann::json;

JournalEntry editEntry(uint64_t seq, double floorHeight) {
    JournalEntry e;
    e.seq = seq;
    e.op = JournalEntry::Op::Edit;
    e.selector = {{"buildings", {seq % 40}}};
    e.params = {{"floor_h", floorHeight}};
    e.time = "2025-01-01T00:00:00.000Z";
    return e;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

struct Opened {
    std::unique_ptr<EditJournal> journal;
    std::vector<JournalEntry> entries;
    std::vector<std::string> notes;
    std::string error;
};

Opened openJournal(const std::string& path, server::JournalOpenOptions options = {}) {
    Opened o;
    o.journal = EditJournal::open(path, options, o.entries, o.notes, o.error);
    return o;
}

// A journal with a header and `n` edits, closed again.
std::string journalWith(const TemporaryFolder& folder, int n) {
    const std::string path = folder.file("j.jsonl");
    Opened o = openJournal(path);
    EXPECT_TRUE(o.journal) << o.error;
    for (int i = 1; i <= n; ++i) {
        std::string error;
        EXPECT_TRUE(o.journal->append(editEntry(i, 3.0 + 0.1 * i), error)) << error;
    }
    return path;
}

TEST(EditJournal, WritesAHeaderAndReadsEveryEntryBack) {
    TemporaryFolder folder;
    const std::string path = journalWith(folder, 3);
    const std::string text = readText(path);
    EXPECT_EQ(text.rfind("{\"created\":", 0), 0u) << text;
    EXPECT_NE(text.find("\"format\":\"hexlod-edit-journal\""), std::string::npos);
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 4);
    Opened o = openJournal(path);
    ASSERT_TRUE(o.journal) << o.error;
    ASSERT_EQ(o.entries.size(), 3u);
    EXPECT_EQ(o.entries[2].seq, 3u);
    EXPECT_EQ(o.entries[2].params["floor_h"], 3.3);
    EXPECT_EQ(o.entries[1].selector, Json({{"buildings", {2}}}));
    EXPECT_EQ(o.journal->nextSeq(), 4u);
    EXPECT_TRUE(o.notes.empty());
    std::string error;
    EXPECT_FALSE(o.journal->append(editEntry(9, 3.0), error)); // out of sequence
}

TEST(EditJournal, ALineRoundTripsAndAnyChangedByteFailsItsChecksum) {
    JournalEntry undo;
    undo.seq = 12;
    undo.op = JournalEntry::Op::Undo;
    undo.undoes = 11;
    const std::string line = EditJournal::formatLine(undo);
    ASSERT_EQ(line.back(), '\n');
    JournalEntry back;
    std::string error;
    ASSERT_TRUE(EditJournal::parseLine(std::string_view(line).substr(0, line.size() - 1), back, error))
        << error;
    EXPECT_EQ(back.op, JournalEntry::Op::Undo);
    EXPECT_EQ(back.undoes, 11u);
    EXPECT_TRUE(Json::parse(line).is_object()); // still one JSON object per line
    for (size_t i = 0; i + 1 < line.size(); ++i) {
        std::string changed = line.substr(0, line.size() - 1);
        changed[i] = changed[i] == '1' ? '2' : '1';
        EXPECT_FALSE(EditJournal::parseLine(changed, back, error)) << "byte " << i;
    }
}

TEST(EditJournal, ATornLastLineIsTruncatedAway) {
    TemporaryFolder folder;
    const std::string path = journalWith(folder, 2);
    const std::string good = readText(path);
    for (const std::string& torn : {std::string("{\"op\":\"edit\",\"par"), std::string(7, '\0')}) {
        writeText(path, good + torn);
        Opened o = openJournal(path);
        ASSERT_TRUE(o.journal) << o.error;
        EXPECT_EQ(o.entries.size(), 2u);
        ASSERT_EQ(o.notes.size(), 1u);
        EXPECT_NE(o.notes[0].find(std::to_string(torn.size()) + " bytes after the last complete line"),
                  std::string::npos)
            << o.notes[0];
        EXPECT_EQ(readText(path), good);
        std::string error;
        EXPECT_TRUE(o.journal->append(editEntry(3, 3.5), error)) << error; // appends after the cut
    }
}

TEST(EditJournal, ReadOnlyOpeningLeavesATornLineInPlace) {
    TemporaryFolder folder;
    const std::string path = journalWith(folder, 1);
    const std::string text = readText(path) + "{\"torn";
    writeText(path, text);
    server::JournalOpenOptions options;
    options.readOnly = true;
    Opened o = openJournal(path, options);
    ASSERT_TRUE(o.journal) << o.error;
    EXPECT_EQ(o.entries.size(), 1u);
    EXPECT_EQ(readText(path), text);
    std::string error;
    EXPECT_FALSE(o.journal->append(editEntry(2, 3.0), error));
    EXPECT_NE(error.find("read-only"), std::string::npos);
}

TEST(EditJournal, ACorruptLineInTheMiddleRefusesToOpenNamingTheLine) {
    TemporaryFolder folder;
    const std::string path = journalWith(folder, 3);
    std::string text = readText(path);
    const size_t line3 = text.find("\"seq\":2");
    ASSERT_NE(line3, std::string::npos);
    text[line3 + 6] = '7'; // seq 2 becomes 7: valid JSON, wrong checksum
    writeText(path, text);
    Opened o = openJournal(path);
    EXPECT_FALSE(o.journal);
    EXPECT_NE(o.error.find("line 3 is corrupt (checksum mismatch)"), std::string::npos) << o.error;
    EXPECT_NE(o.error.find("--journal-repair"), std::string::npos) << o.error;
    EXPECT_EQ(readText(path), text); // nothing touched

    server::JournalOpenOptions repair;
    repair.repair = true;
    Opened repaired = openJournal(path, repair);
    ASSERT_TRUE(repaired.journal) << repaired.error;
    ASSERT_EQ(repaired.entries.size(), 2u);
    EXPECT_EQ(repaired.entries[1].seq, 3u);
    ASSERT_EQ(repaired.notes.size(), 1u);
    EXPECT_NE(repaired.notes[0].find("moved to"), std::string::npos);
    EXPECT_NE(readText(path + ".rejected").find("\"seq\":7"), std::string::npos);
    std::string error;
    EXPECT_TRUE(repaired.journal->append(editEntry(4, 3.9), error)) << error;
    repaired.journal.reset();
    Opened again = openJournal(path);
    ASSERT_TRUE(again.journal) << again.error;
    EXPECT_EQ(again.entries.size(), 3u);
}

TEST(EditJournal, ACompleteButBrokenLastLineIsCorruptionNotATornWrite) {
    TemporaryFolder folder;
    const std::string path = journalWith(folder, 1);
    writeText(path, readText(path) + "{\"op\":\"edit\"}\n");
    Opened o = openJournal(path);
    EXPECT_FALSE(o.journal);
    EXPECT_NE(o.error.find("line 3 is corrupt (no crc member"), std::string::npos) << o.error;
}

TEST(EditJournal, SequenceNumbersMustGrow) {
    TemporaryFolder folder;
    const std::string path = journalWith(folder, 2);
    writeText(path, readText(path) + EditJournal::formatLine(editEntry(2, 3.0)));
    Opened o = openJournal(path);
    EXPECT_FALSE(o.journal);
    EXPECT_NE(o.error.find("sequence number 2 does not follow 2"), std::string::npos) << o.error;
}

TEST(EditJournal, OneProcessAtATime) {
    TemporaryFolder folder;
    const std::string path = folder.file("j.jsonl");
    Opened first = openJournal(path);
    ASSERT_TRUE(first.journal) << first.error;
    Opened second = openJournal(path);
    EXPECT_FALSE(second.journal);
    EXPECT_NE(second.error.find("in use by another process"), std::string::npos) << second.error;
}

TEST(EditJournal, PathErrorsSayWhatIsWrong) {
    TemporaryFolder folder;
    writeText(folder.file("plain"), "x");
    Opened underFile = openJournal(folder.file("plain") + "/j.jsonl");
    EXPECT_FALSE(underFile.journal);
    EXPECT_NE(underFile.error.find("cannot create edit journal"), std::string::npos) << underFile.error;
    EXPECT_NE(underFile.error.find("Not a directory"), std::string::npos) << underFile.error;

    std::filesystem::create_directory(folder.path() / "dir");
    Opened directory = openJournal(folder.file("dir"));
    EXPECT_FALSE(directory.journal);
    EXPECT_NE(directory.error.find("Is a directory"), std::string::npos) << directory.error;

    server::JournalOpenOptions readOnly;
    readOnly.readOnly = true;
    Opened missing = openJournal(folder.file("none.jsonl"), readOnly);
    EXPECT_FALSE(missing.journal);
    EXPECT_NE(missing.error.find("no edit journal at"), std::string::npos);
}

TEST(EditJournal, AReadOnlyFolderSaysPermissionDenied) {
    TemporaryFolder folder;
    if (geteuid() == 0) GTEST_SKIP() << "running as root: a read-only folder does not stop root";
    std::filesystem::create_directory(folder.path() / "locked");
    std::filesystem::permissions(folder.path() / "locked",
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    Opened locked = openJournal(folder.file("locked") + "/j.jsonl");
    EXPECT_FALSE(locked.journal);
    EXPECT_NE(locked.error.find("Permission denied"), std::string::npos) << locked.error;
}

// Caps the process's file size so the next write fails with EFBIG, as a full disk would.
class FileSizeCap {
public:
    explicit FileSizeCap(rlim_t bytes) {
        std::signal(SIGXFSZ, SIG_IGN);
        getrlimit(RLIMIT_FSIZE, &saved_);
        rlimit cap = saved_;
        cap.rlim_cur = bytes;
        setrlimit(RLIMIT_FSIZE, &cap);
    }
    ~FileSizeCap() {
        setrlimit(RLIMIT_FSIZE, &saved_);
        std::signal(SIGXFSZ, SIG_DFL);
    }

private:
    rlimit saved_{};
};

TEST(EditJournal, AFailedAppendLeavesTheFileAsItWas) {
    TemporaryFolder folder;
    const std::string path = journalWith(folder, 0);
    Opened o = openJournal(path);
    ASSERT_TRUE(o.journal) << o.error;
    const std::string before = readText(path);
    std::string error;
    {
        FileSizeCap cap(before.size() + 20); // room for part of the line only
        EXPECT_FALSE(o.journal->append(editEntry(1, 3.0), error));
    }
    EXPECT_NE(error.find("cannot append to edit journal"), std::string::npos) << error;
    EXPECT_EQ(readText(path), before);
    EXPECT_FALSE(o.journal->broken());
    EXPECT_TRUE(o.journal->append(editEntry(1, 3.0), error)) << error;
}

TEST(JournalReplay, AnEditThatCouldNotBeJournaledIsNotApplied) {
    LiveServer live;
    const Json before = live.getJson("/api/v1/buildings/2");
    const size_t size = std::filesystem::file_size(live.journalPath());
    http_client::Response response;
    {
        FileSizeCap cap(size + 10);
        response = live.post("/api/v1/edits", R"({"selector":{"buildings":[2]},"params":{"floor_h":3.4}})");
    }
    EXPECT_EQ(response.status, 503);
    EXPECT_NE(response.body.find("the edit was not applied"), std::string::npos) << response.body;
    EXPECT_EQ(live.getJson("/api/v1/buildings/2"), before);
    EXPECT_EQ(live.getJson("/api/v1/scene")["edits"], 0);
    EXPECT_EQ(std::filesystem::file_size(live.journalPath()), size);
    const auto retry =
        live.post("/api/v1/edits", R"({"selector":{"buildings":[2]},"params":{"floor_h":3.4}})");
    ASSERT_EQ(retry.status, 200) << retry.body;
    EXPECT_EQ(Json::parse(retry.body)["seq"], 1);
}

TEST(JournalReplay, UndoReplaysAndEntriesThatNoLongerApplyAreSkipped) {
    LiveServer live;
    ASSERT_EQ(live.post("/api/v1/edits", R"({"selector":{"buildings":[4]},"params":{"floor_h":3.1}})").status,
              200);
    ASSERT_EQ(live.post("/api/v1/edits", R"({"selector":{"buildings":[4]},"params":{"floor_h":3.9}})").status,
              200);
    ASSERT_EQ(live.post("/api/v1/edits/undo", "").status, 200);
    const Json building = live.getJson("/api/v1/buildings/4");
    EXPECT_EQ(building["params"]["floor_h"], 3.1);

    // Entries the scene no longer accepts (a parameter a grammar change removed) and the undo
    // of such an entry are skipped; the rest replays.
    const std::string path = live.journalPath();
    JournalEntry stale = editEntry(4, 3.0);
    stale.params = {{"removed_param", 1.0}};
    JournalEntry undoStale;
    undoStale.seq = 5;
    undoStale.op = JournalEntry::Op::Undo;
    undoStale.undoes = 4;
    JournalEntry fresh = editEntry(6, 3.7);
    fresh.selector = {{"buildings", {8}}};
    std::ofstream(path, std::ios::app) << EditJournal::formatLine(stale) << EditJournal::formatLine(undoStale)
                                       << EditJournal::formatLine(fresh);
    live.restart();
    EXPECT_EQ(live.getJson("/api/v1/buildings/4")["params"]["floor_h"], 3.1);
    EXPECT_EQ(live.getJson("/api/v1/buildings/8")["params"]["floor_h"], 3.7);
    const Json history = live.getJson("/api/v1/edits");
    ASSERT_EQ(history["entries"].size(), 6u);
    EXPECT_EQ(history["entries"][0]["status"], "applied");
    EXPECT_EQ(history["entries"][1]["status"], "undone");
    EXPECT_EQ(history["entries"][3]["status"], "skipped");
    EXPECT_NE(history["entries"][3]["reason"].get<std::string>().find("removed_param"), std::string::npos);
    EXPECT_EQ(history["entries"][5]["status"], "applied");
    bool noted = false;
    const Json scene = live.getJson("/api/v1/scene");
    for (const Json& note : scene["notes"])
        noted = noted || note.get<std::string>().find("edit 4 no longer applies") != std::string::npos;
    EXPECT_TRUE(noted);
    // The next live undo reverts edit 6, then the skipped 4 is gone already, then edit 1.
    ASSERT_EQ(live.post("/api/v1/edits/undo", "").status, 200);
    EXPECT_EQ(live.getJson("/api/v1/edits")["undo_next"], 1);
}

} // namespace
} // namespace hexlod::test
