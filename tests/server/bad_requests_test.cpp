// Malformed and hostile requests, sent as raw bytes: each gets its 4xx (or 505) with a
// reason, none crashes the service or costs an edit.
#include "live_server.h"

#include <gtest/gtest.h>

#include <thread>

namespace hexlod::test {
namespace {

struct BadRequest {
    std::string name;
    std::string bytes;
    int status;
    std::string reason; // a substring of the reply body
};

std::string get(const std::string& target) {
    return "GET " + target + " HTTP/1.1\r\nHost: test\r\n\r\n";
}

std::string postJson(const std::string& target, const std::string& body,
                     const std::string& type = "application/json") {
    return "POST " + target + " HTTP/1.1\r\nHost: test\r\nContent-Type: " + type +
           "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

std::string edit(const std::string& body) {
    return postJson("/api/v1/edits", body);
}

TEST(BadRequests, EveryOneGetsItsStatusAndAReasonAndNothingIsLost) {
    LiveServer live;
    const nlohmann::json index = live.getJson("/api/v1/cells");
    const nlohmann::json& cell = index["cells"][0];
    const std::string where = std::to_string(cell["q"].get<int>()) + "," +
                              std::to_string(cell["r"].get<int>()) + "/" +
                              std::to_string(cell["batches"][0]["grammar"].get<int>());
    const std::string longTarget = "/" + std::string(5000, 'a');
    const std::string bigHeader =
        "GET / HTTP/1.1\r\nHost: test\r\nX-Big: " + std::string(20000, 'x') + "\r\n\r\n";
    const std::string bigBody =
        "POST /api/v1/edits HTTP/1.1\r\nHost: test\r\nContent-Type: application/json\r\n"
        "Content-Length: 100000\r\n\r\n" +
        std::string(100000, ' ');

    const std::vector<BadRequest> cases = {
        {"unknown method", "BREW / HTTP/1.1\r\nHost: test\r\n\r\n", 405, "not allowed"},
        {"method not allowed on an API route", "DELETE /api/v1/edits HTTP/1.1\r\nHost: test\r\n\r\n", 405,
         "use GET, HEAD, POST"},
        {"POST to a read-only route", postJson("/api/v1/scene", "{}"), 405, "not allowed"},
        {"cell out of range and not a number", get("/api/v1/terminal-sets/9999999999,x/0/0123456789abcdef"),
         400, "cell must be 'q,r'"},
        {"cell without a comma", get("/api/v1/extruded-sets/12/0/0123456789abcdef"), 400,
         "cell must be 'q,r'"},
        {"grammar not a number", get("/api/v1/terminal-sets/1,2/x/0123456789abcdef"), 400, "grammar must be"},
        {"negative grammar", get("/api/v1/terminal-sets/1,2/-1/0123456789abcdef"), 400, "grammar must be"},
        {"key too short", get("/api/v1/terminal-sets/0,0/0/abc"), 400, "key must be 16 hex digits"},
        {"key not hex", get("/api/v1/terminal-sets/0,0/0/0123456789abcdeg"), 400,
         "key must be 16 hex digits"},
        {"cell without buildings", get("/api/v1/terminal-sets/12345,12345/0/0123456789abcdef"), 404,
         "no batch"},
        {"grammar not in the scene",
         get("/api/v1/terminal-sets/" + std::to_string(cell["q"].get<int>()) + "," +
             std::to_string(cell["r"].get<int>()) + "/99/0123456789abcdef"),
         404, "no batch"},
        {"stale or wrong key", get("/api/v1/terminal-sets/" + where + "/0123456789abcdef"), 404,
         "not this batch's current key"},
        {"building id negative", get("/api/v1/buildings/-1"), 400, "whole number"},
        {"building id too large", get("/api/v1/buildings/99999999999999999999"), 400, "whole number"},
        {"target not a path", get("nothing"), 400, "absolute path"},
        {"absolute-form target", get("http://example.com/api/v1/scene"), 400, "absolute path"},
        {"bad percent escape", get("/api/v1/scene%zz"), 400, "percent escape"},
        {"encoded NUL", get("/a%00b"), 400, "control byte"},
        {"target too long", get(longTarget), 414, "longer than"},
        {"header too large", bigHeader, 431, "header larger than"},
        {"body too large", bigBody, 413, "body larger than"},
        {"edit: not JSON", edit("{\"selector\": "), 400, "not valid JSON"},
        {"edit: wrong content type", postJson("/api/v1/edits", "{}", "text/plain"), 415, "application/json"},
        {"edit: JSON array", edit("[1, 2]"), 400, "expected a JSON object"},
        {"edit: unknown parameter", edit(R"({"selector":{"buildings":[1]},"params":{"window_q":1}})"), 400,
         "params.window_q"},
        {"edit: out of range", edit(R"({"selector":{"grammar":"residential"},"params":{"floor_h":99}})"), 400,
         "outside"},
        {"edit: string value", edit(R"({"selector":{"buildings":[1]},"params":{"floor_h":"3"}})"), 400,
         "params.floor_h: expected a number"},
        {"edit: boolean value", edit(R"({"selector":{"buildings":[1]},"params":{"floor_h":true}})"), 400,
         "expected a number"},
        {"edit: infinite value", edit(R"({"selector":{"buildings":[1]},"params":{"floor_h":1e999}})"), 400,
         "number overflow"},
        {"edit: NaN literal", edit(R"({"selector":{"buildings":[1]},"params":{"floor_h":NaN}})"), 400,
         "not valid JSON"},
        {"edit: empty params", edit(R"({"selector":{"buildings":[1]},"params":{}})"), 400,
         "no parameter values"},
        {"edit: unknown building", edit(R"({"selector":{"buildings":[1, 9999]},"params":{"floor_h":3}})"),
         400, "selector.buildings[1]"},
        {"edit: negative building id", edit(R"({"selector":{"buildings":[-4]},"params":{"floor_h":3}})"), 400,
         "selector.buildings[0]"},
        {"edit: empty cell", edit(R"({"selector":{"cell":[500,500]},"params":{"floor_h":3}})"), 400,
         "holds no building"},
        {"edit: cell not a pair", edit(R"({"selector":{"cell":[1]},"params":{"floor_h":3}})"), 400, "[q, r]"},
        {"edit: unknown grammar", edit(R"({"selector":{"grammar":"castle"},"params":{"floor_h":3}})"), 400,
         "'castle' is not in the scene"},
        {"edit: two selectors",
         edit(R"({"selector":{"grammar":"business","cell":[0,0]},"params":{"floor_h":3}})"), 400,
         "exactly one"},
        {"edit: unknown selector", edit(R"({"selector":{"street":"main"},"params":{"floor_h":3}})"), 400,
         "selector.street"},
        {"edit: no selector", edit(R"({"params":{"floor_h":3}})"), 400, "selector: is required"},
        {"edit: unknown member", edit(R"({"selector":{"buildings":[1]},"params":{"floor_h":3},"when":1})"),
         400, "when: unknown member"},
        {"undo with a body", postJson("/api/v1/edits/undo", "[1]"), 400, "takes no parameters"},
        {"history: since not a number", get("/api/v1/edits?since=abc"), 400, "since"},
        {"history: limit zero", get("/api/v1/edits?limit=0"), 400, "limit"},
        {"events: bad Last-Event-ID",
         "GET /api/v1/events HTTP/1.1\r\nHost: test\r\nLast-Event-ID: yesterday\r\n\r\n", 400,
         "Last-Event-ID"},
        {"HTTP/1.0 without Host", "GET /api/v1/scene HTTP/1.0\r\n\r\n", 400, "missing Host"},
        {"HTTP/1.1 without Host", "GET /api/v1/scene HTTP/1.1\r\n\r\n", 400, "missing Host"},
        {"HTTP/2.0 request line", "GET / HTTP/2.0\r\nHost: test\r\n\r\n", 505, "HTTP/1.0 and HTTP/1.1"},
        {"bad Content-Length", "POST /api/v1/edits HTTP/1.1\r\nHost: test\r\nContent-Length: abc\r\n\r\n",
         400, "malformed request"},
        {"binary garbage", std::string("\x01\x02\x03 hello\r\n\r\n"), 400, "malformed request"},
        {"invalid UTF-8 in a path parameter", get("/api/v1/terminal-sets/%ff%fe,1/0/0123456789abcdef"), 400,
         "cell must be 'q,r'"},
        {"edit: invalid UTF-8 in the body", edit("{\"selector\":{\"build\xff\":[1]},\"params\":{\"a\":1}}"),
         400, "not valid JSON"},
        {"bad chunk",
         "POST /api/v1/edits HTTP/1.1\r\nHost: test\r\nTransfer-Encoding: chunked\r\n\r\nZZZ\r\n", 400,
         "malformed request"},
    };
    ASSERT_GE(cases.size(), 20u);
    for (const BadRequest& c : cases) {
        http_client::Connection connection("127.0.0.1", live.port());
        const http_client::Response response = connection.raw(c.bytes);
        EXPECT_EQ(response.status, c.status) << c.name << ": " << response.body;
        EXPECT_NE(response.body.find(c.reason), std::string::npos) << c.name << ": " << response.body;
        if (response.status >= 400) {
            EXPECT_EQ(response.header("cache-control"), "no-store") << c.name;
        }
    }
    // Still serving, and not one edit came of it.
    EXPECT_EQ(live.getJson("/healthz")["status"], "ok");
    EXPECT_EQ(live.getJson("/api/v1/edits")["total"], 0);
    EXPECT_EQ(live.service().lastSeq(), 0u);
}

TEST(BadRequests, PipelinedGarbageAfterAGoodRequestGetsTheGoodReplyThenA400) {
    LiveServer live;
    http_client::Connection connection("127.0.0.1", live.port());
    const http_client::Response first = connection.raw(get("/healthz") + "\x7f\x7f garbage\r\n\r\n");
    EXPECT_EQ(first.status, 200);
    const http_client::Response second = connection.readResponse();
    EXPECT_EQ(second.status, 400);
    EXPECT_NE(second.body.find("malformed request"), std::string::npos) << second.body;
    EXPECT_EQ(second.header("connection"), "close");
}

TEST(BadRequests, KeepAliveServesManyRequestsOnOneConnectionAndPipelinesInOrder) {
    LiveServer live;
    http_client::Connection connection("127.0.0.1", live.port());
    for (int i = 0; i < 20; ++i) EXPECT_EQ(connection.get("/healthz").status, 200);
    const http_client::Response a =
        connection.raw(get("/healthz") + get("/api/v1/nothing") + get("/healthz"));
    EXPECT_EQ(a.status, 200);
    EXPECT_EQ(connection.readResponse().status, 404);
    EXPECT_EQ(connection.readResponse().status, 200);
    EXPECT_TRUE(connection.isOpen());
}

TEST(Limits, ARequestRateAboveTheLimitGets429WithRetryAfter) {
    server::ServerOptions options = LiveServer::quietOptions();
    options.rateLimit = 1.0;
    options.rateBurst = 5.0;
    LiveServer live({}, options);
    http_client::Connection connection("127.0.0.1", live.port());
    for (int i = 0; i < 5; ++i) EXPECT_EQ(connection.get("/healthz").status, 200) << i;
    const http_client::Response limited = connection.get("/healthz");
    EXPECT_EQ(limited.status, 429);
    EXPECT_EQ(limited.header("retry-after"), "1");
    EXPECT_NE(limited.body.find("too many requests"), std::string::npos) << limited.body;
    EXPECT_TRUE(connection.isOpen()); // refused, not disconnected
}

TEST(Limits, ARequestThatDoesNotArriveInTimeGets408AndAnIdleConnectionIsClosed) {
    server::ServerOptions options = LiveServer::quietOptions();
    options.requestTimeout = std::chrono::milliseconds(300);
    LiveServer live({}, options);
    http_client::Connection slow("127.0.0.1", live.port());
    const http_client::Response timedOut =
        slow.raw("GET /api/v1/scene HTTP/1.1\r\nHost: te"); // never finished
    EXPECT_EQ(timedOut.status, 408);
    EXPECT_NE(timedOut.body.find("did not arrive within 0.3 s"), std::string::npos) << timedOut.body;
    http_client::Connection idle("127.0.0.1", live.port());
    EXPECT_EQ(idle.get("/healthz").status, 200);
    std::this_thread::sleep_for(std::chrono::milliseconds(600));
    EXPECT_EQ(idle.get("/healthz").status, 0); // closed by the server meanwhile
}

TEST(Limits, ConnectionsBeyondTheLimitAreTurnedAwayWith503) {
    server::ServerOptions options = LiveServer::quietOptions();
    options.maxConnections = 2;
    LiveServer live({}, options);
    http_client::Connection first("127.0.0.1", live.port()), second("127.0.0.1", live.port());
    EXPECT_EQ(first.get("/healthz").status, 200);
    EXPECT_EQ(second.get("/healthz").status, 200);
    http_client::Connection third("127.0.0.1", live.port());
    const http_client::Response refused = third.readResponse();
    EXPECT_EQ(refused.status, 503);
    EXPECT_EQ(refused.header("retry-after"), "1");
    EXPECT_EQ(first.get("/healthz").status, 200); // the others keep being served
}

} // namespace
} // namespace hexlod::test
