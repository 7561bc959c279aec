#include "hexlod/server/server.h"

#include "http_session.h"
#include "server_context.h"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/asio/thread_pool.hpp>

#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

namespace hexlod::server {

namespace net = boost::asio;
using tcp = net::ip::tcp;

uint64_t ConnectionRegistry::add(std::weak_ptr<Connection> connection) {
    std::lock_guard lock(mutex_);
    const uint64_t id = next_++;
    connections_.emplace(id, std::move(connection));
    return id;
}

void ConnectionRegistry::remove(uint64_t id) {
    if (id == 0) return;
    std::lock_guard lock(mutex_);
    connections_.erase(id);
}

void ConnectionRegistry::shutdownAll() {
    std::vector<std::shared_ptr<Connection>> open;
    {
        std::lock_guard lock(mutex_);
        for (const auto& [id, weak] : connections_)
            if (auto c = weak.lock()) open.push_back(std::move(c));
    }
    for (const auto& c : open) c->shutdown();
}

size_t ConnectionRegistry::size() const {
    std::lock_guard lock(mutex_);
    return connections_.size();
}

bool isLoopbackAddress(const std::string& address) {
    if (address == "localhost") return true;
    boost::system::error_code ec;
    const net::ip::address ip = net::ip::make_address(address, ec);
    return !ec && ip.is_loopback();
}

bool checkBindPolicy(const ServerOptions& options, std::string& error) {
    if (isLoopbackAddress(options.bind) || !options.token.empty()) return true;
    error = "refusing to listen on " + options.bind +
            " without an edit token: anyone who can reach it could change the scene. Pass --token T (or set "
            "HEXLOD_TOKEN), or bind 127.0.0.1";
    return false;
}

namespace {

// Accepts connections; over the connection limit it answers 503 and closes at once.
class Listener : public std::enable_shared_from_this<Listener> {
public:
    Listener(net::io_context& ioc, ServerContext& context)
        : ioc_(ioc), context_(context), acceptor_(net::make_strand(ioc)), retry_(acceptor_.get_executor()) {}

    bool listen(const tcp::endpoint& endpoint, std::string& error) {
        boost::system::error_code ec;
        acceptor_.open(endpoint.protocol(), ec);
        if (!ec) acceptor_.set_option(net::socket_base::reuse_address(true), ec);
        if (!ec) acceptor_.bind(endpoint, ec);
        if (!ec) acceptor_.listen(net::socket_base::max_listen_connections, ec);
        if (ec) {
            error = "cannot listen on " + endpoint.address().to_string() + ":" +
                    std::to_string(endpoint.port()) + ": " + ec.message();
            return false;
        }
        return true;
    }
    uint16_t port() const { return acceptor_.local_endpoint().port(); }
    void start() { accept(); }
    void close() {
        net::post(acceptor_.get_executor(), [self = shared_from_this()] {
            boost::system::error_code ignored;
            self->acceptor_.close(ignored);
            self->retry_.cancel();
        });
    }

private:
    void accept() {
        acceptor_.async_accept(net::make_strand(ioc_),
                               [self = shared_from_this()](boost::system::error_code ec, tcp::socket socket) {
                                   self->onAccept(ec, std::move(socket));
                               });
    }

    void onAccept(boost::system::error_code ec, tcp::socket socket) {
        if (!acceptor_.is_open() || context_.stopping) return;
        if (ec) {
            // Out of descriptors, say: wait a moment instead of spinning on the error.
            retry_.expires_after(std::chrono::milliseconds(50));
            retry_.async_wait([self = shared_from_this()](boost::system::error_code e) {
                if (!e) self->accept();
            });
            return;
        }
        Metrics& metrics = context_.service.metrics();
        if (metrics.connectionsOpen.load() >= static_cast<int64_t>(context_.options.maxConnections)) {
            ++metrics.connectionsRefused;
            static const std::string kBody =
                "{\"status\":503,\"error\":\"too many connections; retry shortly\"}\n";
            static const std::string kRefusal =
                "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\n"
                "Retry-After: 1\r\nConnection: close\r\nContent-Length: " +
                std::to_string(kBody.size()) + "\r\n\r\n" + kBody;
            boost::system::error_code ignored;
            socket.non_blocking(true, ignored);
            socket.write_some(net::buffer(kRefusal), ignored);
            socket.shutdown(tcp::socket::shutdown_both, ignored);
            socket.close(ignored);
        } else {
            std::make_shared<HttpSession>(std::move(socket), context_)->start();
        }
        accept();
    }

    net::io_context& ioc_;
    ServerContext& context_;
    tcp::acceptor acceptor_;
    net::steady_timer retry_;
};

} // namespace

struct Server::Impl {
    Impl(SceneService& service, ServerOptions opts)
        : options(std::move(opts)), service(service),
          api(service,
              ApiOptions{options.token, options.webRoot,
                         [this](std::function<void()> job) { net::post(editThread, std::move(job)); }}),
          context{options, api, service, RateLimiter(options.rateLimit, options.rateBurst), {}, {}},
          ioc(static_cast<int>(std::max(1u, options.threads))) {}

    void log(const std::string& line) const {
        if (options.log) options.log(line);
    }

    ServerOptions options;
    SceneService& service;
    net::thread_pool editThread{1}; // edits run here, one at a time, off the I/O threads
    ServiceApi api;
    ServerContext context; // before ioc: handlers the io_context destroys still use it
    net::io_context ioc;
    std::shared_ptr<Listener> listener;
    std::optional<net::signal_set> signals;
    std::vector<std::thread> threads;
    uint16_t port = 0;

    std::mutex mutex;
    std::condition_variable stopRequested;
    bool stopWanted = false;
    std::once_flag stopOnce;
};

Server::Server(SceneService& service, ServerOptions options)
    : impl_(std::make_unique<Impl>(service, std::move(options))) {}

Server::~Server() {
    stop();
}

bool Server::start(std::string& error) {
    Impl& s = *impl_;
    if (!checkBindPolicy(s.options, error)) return false;
    boost::system::error_code ec;
    const std::string bind = s.options.bind == "localhost" ? "127.0.0.1" : s.options.bind;
    const net::ip::address address = net::ip::make_address(bind, ec);
    if (ec) {
        error = "--bind '" + s.options.bind + "' is not an IP address";
        return false;
    }
    s.listener = std::make_shared<Listener>(s.ioc, s.context);
    if (!s.listener->listen(tcp::endpoint(address, s.options.port), error)) return false;
    s.port = s.listener->port();
    s.listener->start();
    for (uint32_t i = 0; i < std::max(1u, s.options.threads); ++i)
        s.threads.emplace_back([&s] { s.ioc.run(); });
    return true;
}

uint16_t Server::port() const {
    return impl_->port;
}

std::string Server::url() const {
    const std::string& bind = impl_->options.bind;
    const bool v6 = bind.find(':') != std::string::npos;
    const std::string host = bind == "0.0.0.0" || bind == "::" ? "127.0.0.1" : (v6 ? "[" + bind + "]" : bind);
    return "http://" + host + ":" + std::to_string(impl_->port) + "/";
}

void Server::stopOnSignals() {
    Impl& s = *impl_;
    s.signals.emplace(s.ioc, SIGINT, SIGTERM);
    s.signals->async_wait([this](boost::system::error_code ec, int signal) {
        if (ec) return;
        impl_->log(std::string("received ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") + ": stopping");
        requestStop();
    });
}

void Server::requestStop() {
    {
        std::lock_guard lock(impl_->mutex);
        impl_->stopWanted = true;
    }
    impl_->stopRequested.notify_all();
}

void Server::waitForStop() {
    {
        std::unique_lock lock(impl_->mutex);
        impl_->stopRequested.wait(lock, [&] { return impl_->stopWanted; });
    }
    stop();
}

void Server::stop() {
    Impl& s = *impl_;
    std::call_once(s.stopOnce, [&s] {
        s.context.stopping = true;
        if (s.listener) s.listener->close();
        if (s.signals) net::post(s.ioc, [&s] { s.signals->cancel(); });
        s.service.events().closeAll();
        s.context.connections.shutdownAll();
        const auto deadline = std::chrono::steady_clock::now() + s.options.drainTimeout;
        while (s.service.metrics().connectionsOpen.load() > 0 && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        const int64_t left = s.service.metrics().connectionsOpen.load();
        if (left > 0) s.log("stopping with " + std::to_string(left) + " connections still open");
        s.editThread.join(); // queued edits finish and are answered
        s.service.stop();    // running generations finish; their replies go out first
        s.ioc.stop();
        for (std::thread& t : s.threads) t.join();
        s.threads.clear();
    });
}

} // namespace hexlod::server
