// `pleinair studio`: the local page over a Workspace, until Ctrl-C.
#include <pthread.h>

#include <csignal>
#include <cstdio>
#include <thread>

#include "pipeline/cli/commands.h"
#include "pipeline/studio/server.h"

namespace pleinair {

int run_studio(const StudioCommand& cmd) {
    // Ctrl-C and SIGTERM are taken by one watcher thread that stops the server, so every
    // connection closes and nothing is cut half-written; the mask is set before any thread
    // starts, so all of them inherit it.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    StudioOptions o;
    o.scene = cmd.scene;
    o.preset = cmd.preset;
    o.set = cmd.set;
    o.host = cmd.host;
    o.port = cmd.port;
    o.save_to = cmd.save_to;
    StudioServer server(o);
    const int port = server.bind();
    if (cmd.host != "127.0.0.1" && cmd.host != "localhost" && cmd.host != "::1")
        std::fprintf(stderr,
                     "pleinair: warning: listening on %s: anyone who can reach this machine "
                     "there can use the studio (it reads presets and writes to %s)\n",
                     cmd.host.c_str(), cmd.save_to.c_str());
    const std::string shown_host = cmd.host == "::1" ? "[::1]" : cmd.host;
    std::printf("pleinair studio: open http://%s:%d/  (Ctrl-C stops it)\n", shown_host.c_str(),
                port);
    std::fflush(stdout);
    std::thread watcher([&] {
        int sig = 0;
        sigwait(&stop_signals, &sig);
        if (sig != 0) server.stop();
    });
    server.listen();
    // listen returned without a signal (it failed): wake the watcher with one of its own.
    pthread_kill(watcher.native_handle(), SIGTERM);
    watcher.join();
    std::printf("pleinair studio: stopped\n");
    return 0;
}

}  // namespace pleinair
