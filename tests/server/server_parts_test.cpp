// The service's small parts on their own: target parsing, edit bodies, the payload LRU, the
// rate limiter, the event hub, the Prometheus text and the splice bases.
#include "hexlod/server/edit_request.h"
#include "hexlod/server/event_hub.h"
#include "hexlod/server/http_target.h"
#include "hexlod/server/metrics.h"
#include "hexlod/server/payload_cache.h"
#include "hexlod/server/rate_limiter.h"
#include "hexlod/server/splice_bases.h"
#include "hexlod/server/static_files.h"

#include <gtest/gtest.h>

namespace hexlod::server {
namespace {

TEST(HttpTarget, SplitsDecodesAndRejects) {
    ParsedTarget t;
    std::string error;
    ASSERT_TRUE(parseTarget("/api/v1/terminal-sets/3,-2/0/abc?since=4&x=%20y", t, error)) << error;
    ASSERT_EQ(t.segments.size(), 6u);
    EXPECT_EQ(t.segments[3], "3,-2");
    EXPECT_EQ(t.queryValue("since"), "4");
    EXPECT_EQ(t.queryValue("x"), " y");
    ASSERT_TRUE(parseTarget("/a%2Fb", t, error) == false);
    EXPECT_NE(error.find("slash"), std::string::npos);
    EXPECT_FALSE(parseTarget("/a%2", t, error));
    EXPECT_FALSE(parseTarget("/a%g0", t, error));
    EXPECT_FALSE(parseTarget("/a\\b", t, error));
    EXPECT_FALSE(parseTarget("*", t, error));
    EXPECT_FALSE(parseTarget("", t, error));
    EXPECT_FALSE(parseTarget("/" + std::string(kMaxTargetBytes, 'a'), t, error));
    ASSERT_TRUE(parseTarget("/%2e%2E/x", t, error));
    EXPECT_EQ(t.segments[0], ".."); // decoded, so the static handler sees the traversal
}

TEST(HttpTarget, NumbersAreWholeAndInRange) {
    EXPECT_EQ(parseInt32("-2147483648"), INT32_MIN);
    EXPECT_FALSE(parseInt32("2147483648"));
    EXPECT_FALSE(parseInt32("+1"));
    EXPECT_FALSE(parseInt32(" 1"));
    EXPECT_FALSE(parseInt32("1.5"));
    EXPECT_FALSE(parseInt32(""));
    EXPECT_FALSE(parseUint32("-0"));
    EXPECT_EQ(parseUint64("18446744073709551615"), UINT64_MAX);
    EXPECT_FALSE(parseUint64("18446744073709551616"));
    EXPECT_EQ(parseHexDigest("00000000000000fF"), 255u);
    EXPECT_FALSE(parseHexDigest("00000000000000f"));
    EXPECT_FALSE(parseHexDigest("0x000000000000ff"));
}

TEST(EditBody, ReadsEachSelectorFormAndNamesTheBadField) {
    EditSpec spec;
    EditError error;
    ASSERT_TRUE(
        parseEditBody(R"({"selector":{"cell":[-3,4]},"params":{"floor_h":3.25},"comment":"c"})", spec, error))
        << error.text();
    EXPECT_EQ(std::get<cells::HexCoord>(spec.selector).q, -3);
    EXPECT_EQ(spec.params.at("floor_h"), 3.25);
    EXPECT_EQ(spec.comment, "c");
    ASSERT_TRUE(parseEditBody(R"({"selector":{"grammar":2},"params":{"a":1}})", spec, error));
    EXPECT_EQ(std::get<cells::GrammarIndex>(spec.selector).index, 2u);
    ASSERT_TRUE(
        parseEditBody(R"({"selector":{"buildings":[0, 4294967295]},"params":{"a":-1e30}})", spec, error));
    EXPECT_EQ(std::get<cells::BuildingIds>(spec.selector).ids[1], 4294967295u);

    EXPECT_FALSE(parseEditBody(R"({"selector":{"buildings":[4294967296]},"params":{"a":1}})", spec, error));
    EXPECT_EQ(error.field, "selector.buildings[0]");
    EXPECT_FALSE(parseEditBody(R"({"selector":{"cell":[1, 2147483648]},"params":{"a":1}})", spec, error));
    EXPECT_EQ(error.field, "selector.cell[1]");
    EXPECT_FALSE(parseEditBody(R"({"selector":{"cell":[1.5, 2]},"params":{"a":1}})", spec, error));
    EXPECT_EQ(error.field, "selector.cell[0]");
    EXPECT_FALSE(parseEditBody(R"({"selector":{"grammar":""},"params":{"a":1}})", spec, error));
    EXPECT_EQ(error.field, "selector.grammar");
    EXPECT_FALSE(parseEditBody(R"({"selector":[],"params":{"a":1}})", spec, error));
    EXPECT_EQ(error.field, "selector");
    EXPECT_FALSE(parseEditBody(R"({"selector":{"grammar":"x"},"params":{"a":null}})", spec, error));
    EXPECT_EQ(error.text(), "params.a: expected a number, got null");
    EXPECT_FALSE(parseEditBody(R"({"selector":{"grammar":"x"},"params":{"a":1},"comment":5})", spec, error));
    EXPECT_EQ(error.field, "comment");
    EXPECT_FALSE(parseEditBody(R"({"selector":{"grammar":"x"},"params":{"a":1},"comment":")" +
                                   std::string(kMaxCommentBytes + 1, 'c') + "\"}",
                               spec, error));
    EXPECT_EQ(error.field, "comment");
    EXPECT_EQ(fieldOfCatalogError("parameter 'floor_h' = 99 is outside"), "params.floor_h");
    EXPECT_EQ(fieldOfCatalogError("no parameter values given"), "params");
    EXPECT_EQ(fieldOfCatalogError("the selection holds no building"), "selector");
    EXPECT_EQ(fieldOfCatalogError("grammar index 7 is not in the scene"), "selector");
}

TEST(PayloadCache, EvictsLeastRecentlyUsedWithinItsBudget) {
    PayloadCache cache(100);
    const auto bytes = [](size_t n) { return std::make_shared<const std::vector<uint8_t>>(n, 1); };
    cache::BatchKey a, b, c, big;
    a.parametersHash = 1;
    b.parametersHash = 2;
    c.parametersHash = 3;
    big.parametersHash = 4;
    cache.insert(a, bytes(40));
    cache.insert(b, bytes(40));
    EXPECT_TRUE(cache.find(a)); // a is now the most recent
    cache.insert(c, bytes(40)); // over budget: b goes
    EXPECT_TRUE(cache.peek(a));
    EXPECT_FALSE(cache.peek(b));
    EXPECT_TRUE(cache.peek(c));
    cache.insert(big, bytes(101)); // larger than the budget: not kept
    EXPECT_FALSE(cache.peek(big));
    const PayloadCacheStats s = cache.stats();
    EXPECT_EQ(s.bytes, 80u);
    EXPECT_EQ(s.entries, 2u);
    EXPECT_EQ(s.evictions, 1u);
    EXPECT_EQ(s.hits, 1u);
    EXPECT_EQ(s.misses, 0u);
    EXPECT_FALSE(cache.find(b));
    EXPECT_EQ(cache.stats().misses, 1u);
}

TEST(PayloadCache, SupersededPayloadsGoBeforeCurrentOnes) {
    PayloadCache cache(100);
    const auto bytes = [](size_t n) { return std::make_shared<const std::vector<uint8_t>>(n, 1); };
    cache::BatchKey keys[4];
    for (uint64_t i = 0; i < 4; ++i) keys[i].parametersHash = i + 1;
    for (int i = 0; i < 3; ++i) cache.insert(keys[i], bytes(30));
    cache.markSuperseded(keys[2]); // the most recent, but an old version now
    cache.insert(keys[3], bytes(30));
    EXPECT_FALSE(cache.peek(keys[2]));
    EXPECT_TRUE(cache.peek(keys[0]));
    cache.markSuperseded(keys[0]);
    cache.markCurrent(keys[0]); // an undo back to it
    cache.insert(keys[2], bytes(30));
    EXPECT_FALSE(cache.peek(keys[1])) << "now the least recently used";
    EXPECT_TRUE(cache.peek(keys[0]));
}

TEST(RateLimiter, ATokenBucketPerClient) {
    RateLimiter limiter(10.0, 3.0);
    const auto t0 = RateLimiter::Clock::now();
    for (int i = 0; i < 3; ++i) EXPECT_EQ(limiter.acquire("a", t0), 0u);
    EXPECT_EQ(limiter.acquire("a", t0), 1u); // empty: wait a second (rounded up)
    EXPECT_EQ(limiter.acquire("b", t0), 0u); // another client has its own bucket
    EXPECT_EQ(limiter.acquire("a", t0 + std::chrono::milliseconds(150)), 0u);
    RateLimiter off(0.0, 0.0);
    for (int i = 0; i < 1000; ++i) EXPECT_EQ(off.acquire("a", t0), 0u);
}

class RecordingSubscriber : public EventSubscriber {
public:
    explicit RecordingSubscriber(size_t capacity) : capacity_(capacity) {}
    bool deliver(EventFrame frame) override {
        if (frames.size() >= capacity_) return false;
        frames.push_back(*frame);
        return true;
    }
    void close() override { closed = true; }
    std::vector<std::string> frames;
    bool closed = false;

private:
    size_t capacity_;
};

TEST(EventHub, FansOutDropsTheOverflowingAndReplaysAfterLastEventId) {
    EventHub hub(2);
    hub.setBaseline(10);
    auto fast = std::make_shared<RecordingSubscriber>(100);
    auto slow = std::make_shared<RecordingSubscriber>(2);
    hub.subscribe(fast, std::nullopt, "{}");
    hub.subscribe(slow, std::nullopt, "{}");
    for (uint64_t id = 11; id <= 13; ++id) hub.publish(id, "edit", "{\"seq\":" + std::to_string(id) + "}");
    EXPECT_EQ(fast->frames.size(), 4u);
    EXPECT_EQ(fast->frames[0], "event: hello\ndata: {}\n\n");
    EXPECT_EQ(fast->frames[1], "id: 11\nevent: edit\ndata: {\"seq\":11}\n\n");
    EXPECT_TRUE(slow->closed);
    EXPECT_EQ(hub.stats().dropped, 1u);
    EXPECT_EQ(hub.stats().subscribers, 1u);

    auto resumed = std::make_shared<RecordingSubscriber>(100);
    hub.subscribe(resumed, 11, "{}"); // 12 and 13 are retained
    ASSERT_EQ(resumed->frames.size(), 3u);
    EXPECT_EQ(resumed->frames[1].rfind("id: 12\n", 0), 0u);
    auto late = std::make_shared<RecordingSubscriber>(100);
    hub.subscribe(late, 10, "{}"); // 11 is gone
    ASSERT_EQ(late->frames.size(), 2u);
    EXPECT_EQ(late->frames[1].rfind("event: reset\n", 0), 0u);
    auto current = std::make_shared<RecordingSubscriber>(100);
    hub.subscribe(current, 13, "{}");
    EXPECT_EQ(current->frames.size(), 1u);
    hub.closeAll();
    EXPECT_TRUE(fast->closed);
}

TEST(Metrics, PrometheusTextHasCumulativeBucketsAndEscapedLabels) {
    Histogram h;
    h.observe(0.0002);
    h.observe(0.003);
    h.observe(100.0);
    PrometheusText text;
    text.family("x_seconds", "histogram", "Help.");
    text.histogram("x_seconds", {{"route", "GET /a\"b"}}, h.snapshot());
    const std::string out = text.take();
    EXPECT_NE(out.find("# TYPE x_seconds histogram\n"), std::string::npos);
    EXPECT_NE(out.find("x_seconds_bucket{route=\"GET /a\\\"b\",le=\"0.00025\"} 1\n"), std::string::npos)
        << out;
    EXPECT_NE(out.find("x_seconds_bucket{route=\"GET /a\\\"b\",le=\"0.005\"} 2\n"), std::string::npos) << out;
    EXPECT_NE(out.find("x_seconds_bucket{route=\"GET /a\\\"b\",le=\"+Inf\"} 3\n"), std::string::npos) << out;
    EXPECT_NE(out.find("x_seconds_count{route=\"GET /a\\\"b\"} 3\n"), std::string::npos) << out;
}

std::vector<grammar::BuildingInput> tenBuildings() {
    std::vector<grammar::BuildingInput> out(10);
    for (uint32_t i = 0; i < 10; ++i) {
        out[i].id = 100 + 3 * i;
        out[i].footprint = {{0.0, 0.0}, {10.0, 0.0}, {10.0, 10.0}};
        out[i].parameters = {1.0f, float(i)};
    }
    return out;
}

cache::BatchKey keyOf(uint64_t parameters, uint64_t grammar = 9) {
    cache::BatchKey key;
    key.grammarHash = grammar;
    key.parametersHash = parameters;
    return key;
}

TEST(SpliceBases, APlanNamesExactlyTheBuildingsThatDiffer) {
    SpliceBases bases;
    std::vector<grammar::BuildingInput> inputs = tenBuildings();
    EXPECT_FALSE(bases.plan(4, keyOf(2), inputs, 0.5)) << "no base yet";
    bases.remember(4, keyOf(1), inputs);
    EXPECT_FALSE(bases.plan(4, keyOf(1), inputs, 0.5)) << "the base itself";
    std::reverse(inputs.begin(), inputs.end()); // the order of the inputs does not matter
    inputs[2].parameters[0] = 2.0f;             // id 121
    inputs[7].baseElevation = 0.5;              // id 106
    const auto plan = bases.plan(4, keyOf(2), inputs, 0.5);
    ASSERT_TRUE(plan);
    EXPECT_EQ(plan->base, keyOf(1));
    EXPECT_EQ(plan->ids, (std::vector<uint32_t>{106, 121}));
    EXPECT_EQ(plan->changed, (std::vector<uint32_t>{7, 2}));
    EXPECT_FALSE(bases.plan(5, keyOf(2), inputs, 0.5)) << "another batch";
    EXPECT_FALSE(bases.plan(4, keyOf(2, 8), inputs, 0.5)) << "another grammar";
    EXPECT_FALSE(bases.plan(4, keyOf(2), inputs, 0.1)) << "more than the share changed";
    EXPECT_FALSE(bases.plan(4, keyOf(2), tenBuildings(), 0.5)) << "nothing changed";
}

TEST(SpliceBases, OtherOrRepeatedBuildingIdsHaveNoPlan) {
    SpliceBases bases;
    std::vector<grammar::BuildingInput> inputs = tenBuildings();
    bases.remember(0, keyOf(1), inputs);
    std::vector<grammar::BuildingInput> other = inputs;
    other[3].id = 1;
    EXPECT_FALSE(bases.plan(0, keyOf(2), other, 0.5));
    other = inputs;
    other.pop_back();
    EXPECT_FALSE(bases.plan(0, keyOf(2), other, 0.5));
    std::vector<grammar::BuildingInput> repeated = inputs;
    repeated[4].id = repeated[5].id;
    bases.remember(0, keyOf(3), repeated);
    repeated[4].parameters[0] = 5.0f;
    EXPECT_FALSE(bases.plan(0, keyOf(4), repeated, 0.5));
    // A later base replaces the earlier one.
    bases.remember(0, keyOf(5), inputs);
    inputs[0].parameters[1] = 7.0f;
    const auto plan = bases.plan(0, keyOf(6), inputs, 0.5);
    ASSERT_TRUE(plan);
    EXPECT_EQ(plan->base, keyOf(5));
}

TEST(StaticFiles, ContentTypesAndEtagMatching) {
    EXPECT_EQ(StaticFiles::contentTypeFor("a/b/index.HTML"), "text/html; charset=utf-8");
    EXPECT_EQ(StaticFiles::contentTypeFor("x.wasm"), "application/wasm");
    EXPECT_EQ(StaticFiles::contentTypeFor("m.glb"), "model/gltf-binary");
    EXPECT_EQ(StaticFiles::contentTypeFor("noextension"), "application/octet-stream");
    EXPECT_TRUE(etagMatches("\"abc\"", "\"abc\""));
    EXPECT_TRUE(etagMatches("W/\"abc\"", "\"abc\""));
    EXPECT_TRUE(etagMatches("\"x\", W/\"abc\"", "W/\"abc\""));
    EXPECT_TRUE(etagMatches("*", "\"abc\""));
    EXPECT_FALSE(etagMatches("\"abcd\"", "\"abc\""));
    EXPECT_FALSE(etagMatches("", "\"abc\""));
}

} // namespace
} // namespace hexlod::server
