// Test support: a small scene written to a fresh temporary folder, and a real service on a
// free loopback port built from it, talked to through the Beast client.
#pragma once

#include "hexlod/http_client/http_client.h"
#include "hexlod/server/server.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <string>

namespace hexlod::test {

// A fresh folder under the system's temporary directory, removed with its contents.
class TemporaryFolder {
public:
    TemporaryFolder();
    ~TemporaryFolder();
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

struct SmallScene {
    uint32_t buildings = 40;
    uint32_t trees = 30;
    double cellSize = 60.0;
    nlohmann::json overrides = nlohmann::json::array(); // the config's "overrides"
};

// Writes a scene config (two building grammars, the shipped tree species) into `folder`
// and returns its path.
std::string writeSmallScene(const std::filesystem::path& folder, const SmallScene& scene = {});

// Builds `scenePath` or fails the test.
scene::BuiltScene buildSmallScene(const std::string& scenePath);

class LiveServer {
public:
    explicit LiveServer(SmallScene scene = {}, server::ServerOptions serverOptions = quietOptions(),
                        server::ServiceOptions serviceOptions = {});
    ~LiveServer();

    static server::ServerOptions quietOptions(); // port 0, no rate limit, short timeouts

    uint16_t port() const { return server_->port(); }
    server::SceneService& service() { return *service_; }
    server::Server& server() { return *server_; }
    const std::string& scenePath() const { return scenePath_; }
    const std::string& journalPath() const { return journalPath_; }
    const TemporaryFolder& folder() const { return folder_; }

    http_client::Response get(const std::string& target, const http_client::Headers& headers = {}) const;
    http_client::Response post(const std::string& target, const std::string& body,
                               const http_client::Headers& headers = {}) const;
    nlohmann::json getJson(const std::string& target) const; // asserts 200
    // Restarts the service and server on the same scene and journal.
    void restart();

private:
    void startService();

    TemporaryFolder folder_;
    SmallScene scene_;
    server::ServerOptions serverOptions_;
    server::ServiceOptions serviceOptions_;
    std::string scenePath_, journalPath_;
    std::unique_ptr<server::SceneService> service_;
    std::unique_ptr<server::Server> server_;
};

} // namespace hexlod::test
