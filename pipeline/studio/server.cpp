// The studio's routes over one Workspace: the page, the key catalogue, changes, frames.
#include "pipeline/studio/server.h"

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "pipeline/frame/frame_plan.h"
#include "pipeline/input/error.h"
#include "pipeline/input/presets.h"
#include "pipeline/output/image_io.h"
#include "pipeline/studio/studio_request.h"
#include "pipeline/studio/workspace.h"

#ifndef PLEINAIR_STUDIO_WEB_DIR
#error "PLEINAIR_STUDIO_WEB_DIR names the folder of the studio's page"
#endif

namespace pleinair {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::vector<std::string> studio_allowed_hosts(const std::string& host, int port) {
    const std::string p = ":" + std::to_string(port);
    std::vector<std::string> out = {"127.0.0.1" + p, "localhost" + p, "[::1]" + p};
    if (host != "127.0.0.1" && host != "localhost" && host != "::1" && !host.empty())
        out.push_back((host.find(':') != std::string::npos ? "[" + host + "]" : host) + p);
    return out;
}

bool studio_request_allowed(const std::vector<std::string>& allowed, const std::string& host,
                            const std::string& origin, const std::string& fetch_site) {
    auto lower = [](std::string s) {
        for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    const std::string h = lower(host);
    if (std::find(allowed.begin(), allowed.end(), h) == allowed.end()) return false;
    if (!origin.empty() && lower(origin) != "http://" + h) return false;
    // A browser that says the request comes from another site (a link or a form elsewhere).
    if (fetch_site == "cross-site" || fetch_site == "same-site") return false;
    return true;
}

namespace {

// The page's files: a fixed map, so no request names a path on disk.
const std::map<std::string, std::pair<std::string, std::string>>& page_files() {
    static const std::map<std::string, std::pair<std::string, std::string>> files = {
        {"/", {"index.html", "text/html; charset=utf-8"}},
        {"/studio.js", {"studio.js", "text/javascript; charset=utf-8"}},
        {"/studio.css", {"studio.css", "text/css; charset=utf-8"}},
    };
    return files;
}

std::string read_page_file(const std::string& name) {
    std::ifstream in(fs::path(PLEINAIR_STUDIO_WEB_DIR) / name, std::ios::binary);
    if (!in) throw std::runtime_error("the studio's page file " + name + " is missing");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// A header value holds printable ASCII only: the rest percent-encoded (the page decodes it).
std::string header_safe(const std::string& s) {
    std::string out;
    for (unsigned char c : s) {
        if (c >= 0x20 && c < 0x7f && c != '%') {
            out += static_cast<char>(c);
        } else {
            char buf[4];
            std::snprintf(buf, sizeof buf, "%%%02X", c);
            out += buf;
        }
    }
    return out;
}

void send_json(httplib::Response& res, int status, const json& body) {
    res.status = status;
    res.set_content(body.dump(), "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message,
                const std::string& pointer = "") {
    send_json(res, status, {{"error", message}, {"pointer", pointer}});
}

}  // namespace

struct StudioServer::Impl {
    StudioOptions options;
    std::unique_ptr<Workspace> workspace;
    std::mutex mutex;                 // one change or frame at a time
    std::atomic<uint64_t> latest{0};  // the newest change or frame request
    std::string last_explain;         // the last painted frame's plan and passes
    std::vector<fs::path> readable;   // the folders a change may name files in
    httplib::Server http;
    int port = 0;

    void routes();
    void frame(const httplib::Request& req, httplib::Response& res);
    void change(const httplib::Request& req, httplib::Response& res);
};

namespace {

std::optional<int> frame_param(const httplib::Request& req, const Workspace& ws) {
    if (!req.has_param("frame") || !ws.animated()) return std::nullopt;
    const std::string v = req.get_param_value("frame");
    char* end = nullptr;
    const long f = std::strtol(v.c_str(), &end, 10);
    const FrameRange r = animation_frames(ws.scene());
    if (v.empty() || *end != '\0' || f < r.first || f > r.last)
        throw InputError("frame", "",
                         "expected a frame from " + std::to_string(r.first) + " to " +
                             std::to_string(r.last) + ", got \"" + v + "\"");
    return static_cast<int>(f);
}

std::string explain_text(const StudioFrame& f) {
    std::string out = f.built.empty()
                          ? ""
                          : "shot rebuilt (" + std::string(change_level_name(f.rebuilt)) + "):\n";
    char line[512];
    for (const auto* list : {&f.built, &f.report.decisions, &f.report.passes})
        for (const PassReport& p : *list) {
            std::snprintf(line, sizeof line, "%-20s %s %9.1f ms  %s%s%s\n", p.name.c_str(),
                          p.ran ? "ran " : "skip", p.ms, p.why.c_str(),
                          p.counts.empty() ? "" : "; ", p.counts.c_str());
            out += line;
        }
    return out;
}

}  // namespace

void StudioServer::Impl::change(const httplib::Request& req, httplib::Response& res) {
    // A change supersedes the frame being painted: it will be painted again.
    ++latest;
    StudioChange change;
    try {
        change = parse_studio_change(req.body, readable, workspace->scene_file().parent_path());
    } catch (const RequestRefused& e) {
        return send_error(res, 400, e.what(), e.pointer);
    }
    const std::lock_guard<std::mutex> lock(mutex);
    try {
        ChangeLevel level = ChangeLevel::kFrame;
        for (const std::string& p : change.unset) level = std::max(level, workspace->unset(p));
        if (!change.set.empty()) level = std::max(level, workspace->set_all(change.set));
        send_json(res, 200,
                  {{"level", change_level_name(level)},
                   {"catalog", json::parse(workspace->catalog_json())}});
    } catch (const InputError& e) {
        std::string msg = format_problems(e.source(), e.problems());
        while (!msg.empty() && msg.back() == '\n') msg.pop_back();
        const std::string pointer = e.problems().empty() ? "" : e.problems()[0].pointer;
        send_error(res, 400, msg, pointer);
    }
}

void StudioServer::Impl::frame(const httplib::Request& req, httplib::Response& res) {
    const uint64_t id = ++latest;
    const bool preview = req.get_param_value("preview") == "1";
    const bool draft = req.get_param_value("draft") == "1";
    const std::lock_guard<std::mutex> lock(mutex);
    // Superseded: 204, nothing to show (the page asks again; not an error to log).
    if (latest.load() != id) {
        res.status = 204;
        return;
    }
    try {
        const std::optional<int> f = frame_param(req, *workspace);
        StudioFrame painted = workspace->paint(
            f, preview, [this, id] { return latest.load() != id; }, draft);
        // Previews travel as JPEG: a 480x270 frame encodes in about a millisecond and a tenth of
        // the PNG's bytes. At rest, PNG: the exact pixels the shown command writes.
        const bool jpeg = preview || req.get_param_value("format") == "jpeg";
        const std::string bytes = encode_frame(painted.frame, jpeg ? ".jpg" : ".png", 88);
        last_explain = explain_text(painted);
        res.set_header("X-Pleinair-Exact", painted.exact ? "1" : "0");
        res.set_header("X-Pleinair-Rebuilt",
                       painted.rebuilt_any ? change_level_name(painted.rebuilt) : "none");
        char ms[64];
        std::snprintf(ms, sizeof ms, "%.1f %.1f", painted.build_ms, painted.paint_ms);
        res.set_header("X-Pleinair-Ms", ms);
        res.set_header("X-Pleinair-Command",
                       header_safe(workspace->command_line(f, preview, "still.png", draft)));
        res.set_header("Cache-Control", "no-store");
        res.set_content(bytes, jpeg ? "image/jpeg" : "image/png");
    } catch (const FrameAbandoned&) {
        res.status = 204;
    } catch (const InputError& e) {
        std::string msg = format_problems(e.source(), e.problems());
        while (!msg.empty() && msg.back() == '\n') msg.pop_back();
        send_error(res, 400, msg);
    }
}

void StudioServer::Impl::routes() {
    for (const auto& [route, file] : page_files()) {
        const std::string name = file.first, type = file.second;
        http.Get(route, [name, type](const httplib::Request&, httplib::Response& res) {
            res.set_header("Cache-Control", "no-store");
            res.set_content(read_page_file(name), type.c_str());
        });
    }
    http.Get("/api/catalog", [this](const httplib::Request&, httplib::Response& res) {
        const std::lock_guard<std::mutex> lock(mutex);
        res.set_content(workspace->catalog_json(), "application/json");
    });
    http.Post("/api/change",
              [this](const httplib::Request& req, httplib::Response& res) { change(req, res); });
    http.Get("/api/frame",
             [this](const httplib::Request& req, httplib::Response& res) { frame(req, res); });
    http.Get("/api/explain", [this](const httplib::Request&, httplib::Response& res) {
        const std::lock_guard<std::mutex> lock(mutex);
        res.set_content(last_explain, "text/plain; charset=utf-8");
    });
    http.Get("/api/circles", [this](const httplib::Request& req, httplib::Response& res) {
        const std::lock_guard<std::mutex> lock(mutex);
        try {
            res.set_content(workspace->circles_json(frame_param(req, *workspace),
                                                    req.get_param_value("preview") == "1"),
                            "application/json");
        } catch (const InputError& e) {
            send_error(res, 400, format_problems(e.source(), e.problems()));
        }
    });
    http.Post("/api/keep", [this](const httplib::Request& req, httplib::Response& res) {
        json body = json::parse(req.body, nullptr, false);
        if (body.is_discarded() || !body.is_object() || !body.contains("family") ||
            !body["family"].is_string())
            return send_error(res, 400, "expected {\"family\": NAME}");
        const std::lock_guard<std::mutex> lock(mutex);
        try {
            const fs::path file = workspace->keep(body["family"], options.save_to);
            send_json(res, 200, {{"file", file.string()}});
        } catch (const InputError& e) {
            send_error(res, 400, format_problems(e.source(), e.problems()));
        }
    });
    http.Get("/api/contact", [this](const httplib::Request& req, httplib::Response& res) {
        const std::string family = req.get_param_value("family");
        const std::lock_guard<std::mutex> lock(mutex);
        try {
            const Frame sheet = workspace->contact_sheet(family, 6, 960, 540);
            res.set_content(encode_frame(sheet, ".jpg", 90), "image/jpeg");
        } catch (const InputError& e) {
            send_error(res, 400, format_problems(e.source(), e.problems()));
        }
    });
}

StudioServer::StudioServer(const StudioOptions& options) : impl_(std::make_unique<Impl>()) {
    impl_->options = options;
    std::vector<std::string> sets;
    std::string scene = options.scene;
    impl_->readable = {preset_root(), options.save_to};
    if (!options.preset.empty()) {
        scene = "tree";
        // A preset file named on the command line is read from where the user stands.
        std::string preset = options.preset;
        std::error_code ec;
        if (fs::path(preset).has_parent_path() && fs::is_regular_file(preset, ec)) {
            preset = fs::absolute(preset).string();
            impl_->readable.push_back(fs::path(preset).parent_path());
        }
        sets.push_back("/families/tree/preset=" + preset);
    }
    sets.insert(sets.end(), options.set.begin(), options.set.end());
    impl_->workspace = std::make_unique<Workspace>(scene, sets);
    impl_->readable.push_back(impl_->workspace->scene_file().parent_path());
    if (!options.preset.empty()) impl_->workspace->set_all(impl_->workspace->framing());
}

StudioServer::~StudioServer() = default;

int StudioServer::bind() {
    Impl& s = *impl_;
    s.http.set_payload_max_length(s.options.max_request_bytes);
    s.http.set_read_timeout(std::chrono::seconds(10));
    const int threads = std::max(2, s.options.threads);
    s.http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
    s.http.set_pre_routing_handler([&s](const httplib::Request& req, httplib::Response& res) {
        static const std::vector<std::string> none;
        const auto allowed = studio_allowed_hosts(s.options.host, s.port);
        if (!studio_request_allowed(allowed, req.get_header_value("Host"),
                                    req.get_header_value("Origin"),
                                    req.get_header_value("Sec-Fetch-Site"))) {
            send_error(res, 403,
                       "refused: the studio answers only its own page on " + allowed.front());
            return httplib::Server::HandlerResponse::Handled;
        }
        return httplib::Server::HandlerResponse::Unhandled;
    });
    s.http.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
            std::string what = "internal error";
            try {
                std::rethrow_exception(ep);
            } catch (const std::exception& e) {
                what = e.what();
            } catch (...) {
            }
            send_error(res, 500, what);
        });
    s.routes();
    if (s.options.port == 0) {
        s.port = s.http.bind_to_any_port(s.options.host);
        if (s.port < 0) throw std::runtime_error("cannot listen on " + s.options.host);
    } else {
        if (!s.http.bind_to_port(s.options.host, s.options.port))
            throw std::runtime_error("cannot listen on " + s.options.host + ":" +
                                     std::to_string(s.options.port) +
                                     " (in use? try --port 0 for any free port)");
        s.port = s.options.port;
    }
    return s.port;
}

void StudioServer::listen() { impl_->http.listen_after_bind(); }

void StudioServer::stop() { impl_->http.stop(); }

}  // namespace pleinair
