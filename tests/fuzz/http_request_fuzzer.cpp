// libFuzzer target for the HTTP front of the service, in process: every input is fed to
// Boost.Beast's request parser with the server's limits, and a request that parses goes
// through the same pre-routing checks and the same ServiceApi as on the network, against a
// small scene (12 buildings, journal in a temporary folder). No socket is involved, so each
// input costs microseconds unless it asks for content that must be generated.
//
// Invariants (abort on violation, so libFuzzer keeps the input): the handler answers exactly
// once and within 10 s; the status is a real one; every error reply is a JSON object with
// a reason; a JSON 200 reply parses as JSON.
#include "../scratch_folder.h"
#include "fuzz_check.h"

#include "hexlod/scene/scene_builder.h"
#include "hexlod/server/beast_request.h"
#include "hexlod/server/service_api.h"

#include <boost/asio/buffer.hpp>
#include <boost/beast/http/parser.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>

namespace {

namespace http = boost::beast::http;
using namespace hexlod;

using hexlod::fuzz::check;

// Small stand-ins for the meshes and impostors `hexlod serve` builds, so the shape routes'
// parsing and lookups are reached (their real content is tested in tests/cli).
server::ShapeAssets shapeAssets() {
    const auto bytes = std::make_shared<const std::vector<uint8_t>>(std::vector<uint8_t>{'g', 'l', 'T', 'F'});
    server::ShapeAssets assets;
    assets.meshes = {{server::MeshAsset{0x0123456789abcdef, bytes, {1.0f, 1.0f, 0.1f}, {}}, std::nullopt}};
    server::ImpostorAsset impostor;
    impostor.key = 0x0123456789abcdef;
    impostor.albedoPng = impostor.normalPng = bytes;
    assets.impostors = {{impostor}};
    assets.meshesServed = assets.impostorsServed = true;
    return assets;
}

struct Fixture {
    Fixture() {
        check(!scratch.path().empty());
        const std::string folder = scratch.path().string();
        const std::string configs = HEXLOD_CONFIGS_DIR;
        const nlohmann::json config = {
            {"name", "fuzz"},
            {"cell_size", 40},
            {"grammars", {{"residential", {{"file", configs + "/grammars/residential.grammar"}}}}},
            {"buildings",
             {{{"source", "procedural"},
               {"count", 12},
               {"districts", {{{"grammar", "residential"}, {"floors", {2, 3}}}}}}}},
        };
        const std::string path = folder + "/fuzz.json";
        std::ofstream(path) << config.dump();
        scene::SceneConfig sceneConfig;
        scene::BuiltScene built;
        std::string error;
        check(scene::loadSceneConfig(path, sceneConfig, error) &&
              scene::buildScene(sceneConfig, built, error));
        server::ServiceOptions options;
        options.journalPath = folder + "/fuzz.edits.jsonl";
        std::vector<std::string> log;
        service = server::SceneService::create(std::move(built), cache::CacheOptions{}, options, log, error);
        check(service != nullptr);
        service->attachShapeAssets(shapeAssets());
        api = std::make_unique<server::ServiceApi>(
            *service,
            server::ApiOptions{"", folder + "/no-viewer", [](std::function<void()> job) { job(); }});
    }
    // First, so that it goes last: after the service has closed its journal in it.
    testing::ScratchFolder scratch{"hexlod-fuzz"};
    std::unique_ptr<server::SceneService> service;
    std::unique_ptr<server::ServiceApi> api;
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

void checkReply(const server::Reply& reply) {
    check(reply.status >= 200 && reply.status <= 599);
    if (reply.status >= 400) {
        const nlohmann::json body = nlohmann::json::parse(reply.body, nullptr, false);
        check(body.is_object() && body.contains("error") && !body["error"].get<std::string>().empty());
    }
    if (reply.status == 200 && reply.contentType == "application/json")
        check(!nlohmann::json::parse(reply.body, nullptr, false).is_discarded());
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Fixture& f = fixture();
    http::request_parser<http::string_body> parser;
    parser.header_limit(16 * 1024);
    parser.body_limit(64 * 1024);
    parser.eager(true);
    boost::beast::error_code ec;
    size_t used = 0;
    while (used < size && !parser.is_done()) {
        const size_t n = parser.put(boost::asio::buffer(data + used, size - used), ec);
        used += n;
        if (ec == http::error::need_more) {
            ec = {};
            if (n == 0) break;
            continue;
        }
        if (ec) return 0; // the session answers these 400/413/431 without routing
    }
    if (!parser.is_done()) {
        parser.put_eof(ec);
        if (ec || !parser.is_done()) return 0;
    }
    server::BeastRequest message = parser.release();
    if (const auto rejected = server::rejectBeforeRouting(message)) {
        checkReply(*rejected);
        return 0;
    }
    const server::Request request = server::toRequest(std::move(message), "127.0.0.1");
    auto answered = std::make_shared<std::promise<server::Reply>>();
    auto calls = std::make_shared<std::atomic<int>>(0);
    f.api->handle(request, [answered, calls](server::Reply reply) {
        check(calls->fetch_add(1) == 0);
        answered->set_value(std::move(reply));
    });
    std::future<server::Reply> reply = answered->get_future();
    check(reply.wait_for(std::chrono::seconds(10)) == std::future_status::ready);
    checkReply(reply.get());
    return 0;
}
