#include "live_server.h"

#include "hexlod/scene/scene_builder.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

namespace hexlod::test {

TemporaryFolder::TemporaryFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "hexlod-test-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
}

TemporaryFolder::~TemporaryFolder() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all, std::filesystem::perm_options::add,
                                 ec);
    std::filesystem::remove_all(path_, ec);
}

std::string writeSmallScene(const std::filesystem::path& folder, const SmallScene& scene) {
    const std::string configs = HEXLOD_CONFIGS_DIR;
    nlohmann::json config = {
        {"name", "small"},
        {"seed", 3},
        {"cell_size", scene.cellSize},
        {"grammars",
         {{"business", {{"file", configs + "/grammars/business.grammar"}}},
          {"residential", {{"file", configs + "/grammars/residential.grammar"}}}}},
        {"buildings",
         {{{"source", "procedural"},
           {"count", scene.buildings},
           {"block_size", 60},
           {"districts",
            {{{"grammar", "business"}, {"share", 0.3}, {"floors", {3, 6}}},
             {{"grammar", "residential"}, {"share", 0.7}, {"floors", {2, 4}}}}}}}},
        {"trees", {{"count", scene.trees}, {"species", configs + "/species.json"}}},
        {"cache", {{"memory_mb", 64}, {"disk_mb", 64}}},
    };
    if (!scene.overrides.empty()) config["overrides"] = scene.overrides;
    const std::string path = (folder / "small.json").string();
    std::ofstream(path) << config.dump(2);
    return path;
}

scene::BuiltScene buildSmallScene(const std::string& scenePath) {
    scene::SceneConfig config;
    std::string error;
    EXPECT_TRUE(scene::loadSceneConfig(scenePath, config, error)) << error;
    scene::BuiltScene built;
    EXPECT_TRUE(scene::buildScene(config, built, error)) << error;
    return built;
}

server::ServerOptions LiveServer::quietOptions() {
    server::ServerOptions options;
    options.port = 0;
    options.rateLimit = 0.0;
    options.heartbeat = std::chrono::milliseconds(200);
    options.drainTimeout = std::chrono::milliseconds(2000);
    return options;
}

LiveServer::LiveServer(SmallScene scene, server::ServerOptions serverOptions,
                       server::ServiceOptions serviceOptions)
    : scene_(scene), serverOptions_(std::move(serverOptions)), serviceOptions_(std::move(serviceOptions)) {
    scenePath_ = writeSmallScene(folder_.path(), scene_);
    journalPath_ =
        serviceOptions_.journalPath.empty() ? folder_.file("small.edits.jsonl") : serviceOptions_.journalPath;
    if (serverOptions_.webRoot == "web/dist") serverOptions_.webRoot = folder_.file("no-viewer");
    startService();
}

LiveServer::~LiveServer() {
    if (server_) server_->stop();
    server_.reset();
    service_.reset();
}

void LiveServer::startService() {
    server::ServiceOptions options = serviceOptions_;
    options.journalPath = journalPath_;
    std::vector<std::string> log;
    std::string error;
    cache::CacheOptions cacheOptions;
    cacheOptions.memoryBudgetBytes = uint64_t(64) << 20;
    service_ = server::SceneService::create(buildSmallScene(scenePath_), cacheOptions, options, log, error);
    if (!service_) throw std::runtime_error("service: " + error);
    server_ = std::make_unique<server::Server>(*service_, serverOptions_);
    if (!server_->start(error)) throw std::runtime_error("server: " + error);
}

void LiveServer::restart() {
    server_->stop();
    server_.reset();
    service_.reset();
    startService();
}

http_client::Response LiveServer::get(const std::string& target, const http_client::Headers& headers) const {
    return http_client::fetch("127.0.0.1", port(), "GET", target, {}, headers);
}

http_client::Response LiveServer::post(const std::string& target, const std::string& body,
                                       const http_client::Headers& headers) const {
    http_client::Connection connection("127.0.0.1", port());
    return connection.post(target, body, headers);
}

nlohmann::json LiveServer::getJson(const std::string& target) const {
    const http_client::Response response = get(target);
    EXPECT_EQ(response.status, 200) << target << ": " << response.body;
    return nlohmann::json::parse(response.body, nullptr, false);
}

} // namespace hexlod::test
