// The studio's server: a thin layer of routes, limits and the page over one Workspace
// (cpp-httplib); nothing in the frame path knows it is there.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pleinair {

struct StudioOptions {
    std::string scene;                          // a scene name or file; empty with `preset`
    std::string preset;                         // a tree preset: the "tree" scene grows it, framed
    std::vector<std::string> set;               // "POINTER=VALUE" overrides to start from
    std::string host = "127.0.0.1";             // the interface; loopback unless asked otherwise
    int port = 8420;                            // 0: any free port
    std::filesystem::path save_to = "presets";  // where "keep" writes presets, and only there
    size_t max_request_bytes = 64 * 1024;       // a request's body; more is refused (413)
    int threads = 4;                            // connections served at once
};

// The Host values a request may carry: the loopback names (or the --host given) at the port.
std::vector<std::string> studio_allowed_hosts(const std::string& host, int port);
// Whether a request with these Host, Origin (empty: none sent) and Sec-Fetch-Site (empty:
// none) headers may be served: the Host one of `allowed` (a page of another site reaching
// the port through a name it resolves to 127.0.0.1 carries its own name), and an Origin, when
// a browser sends one, this page's.
bool studio_request_allowed(const std::vector<std::string>& allowed, const std::string& host,
                            const std::string& origin, const std::string& fetch_site);

class StudioServer {
  public:
    // Loads the scene (InputError on bad input, before anything listens).
    explicit StudioServer(const StudioOptions& options);
    ~StudioServer();
    StudioServer(const StudioServer&) = delete;
    StudioServer& operator=(const StudioServer&) = delete;

    // Binds the port (std::runtime_error if it cannot); returns it.
    int bind();
    // Serves until stop(); returns when every connection is closed.
    void listen();
    // From any thread (a signal watcher, a test).
    void stop();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace pleinair
