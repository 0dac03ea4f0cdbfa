// tev_listen PORT_FILE OUT.exr [DIE_AFTER_PACKETS]: the test tev server (tev_server.hpp) as
// a program for iris-render --tev. Listens on an ephemeral port of 127.0.0.1 and writes it to
// PORT_FILE; when the first connection closes, writes the one image it received to OUT.exr
// (its R, G, B channels) and exits 0, or 1 if a packet was malformed (the errors on stderr).
// With OUT ending in '/' (a directory), it writes every image it received, as OUT/NAME.exr.
// With DIE_AFTER_PACKETS it closes everything after that many packets and exits 3, as a
// viewer that is killed. Gives up after 60 s (exit 4).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include <iris/exr/exr.hpp>

#include "tev_server.hpp"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: tev_listen PORT_FILE OUT.exr [DIE_AFTER_PACKETS]\n");
        return 2;
    }
    const int die_after = argc > 3 ? std::atoi(argv[3]) : 0;
    iris::test::tev_server server;
    {
        const std::string tmp = std::string(argv[1]) + ".tmp";
        std::ofstream(tmp) << server.port() << "\n";
        std::filesystem::rename(tmp, argv[1]);
    }
    const auto start = std::chrono::steady_clock::now();
    while (server.closed_connections() == 0) {
        if (die_after > 0) {
            int total = 0;
            for (const auto& [type, n] : server.packet_counts()) total += n;
            if (total >= die_after) {
                server.stop();
                return 3;
            }
        }
        if (std::chrono::steady_clock::now() - start > std::chrono::seconds(60)) return 4;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    server.stop();
    for (const auto& e : server.errors()) std::fprintf(stderr, "tev_listen: %s\n", e.c_str());
    const auto images = server.images();
    const std::string out_path = argv[2];
    const bool many = !out_path.empty() && out_path.back() == '/';
    if (!server.errors().empty() || images.empty() || (!many && images.size() != 1)) return 1;
    for (const auto& [name, img] : images) {
        if (img.channels != std::vector<std::string>{"R", "G", "B"}) return 1;
        iris::image out(img.width, img.height);
        for (std::size_t i = 0; i < out.pixel_count(); ++i)
            out.pixels()[i] = {img.data[3 * i], img.data[3 * i + 1], img.data[3 * i + 2]};
        iris::exr::write(many ? out_path + name + ".exr" : out_path, out, {{"tev:updates", std::to_string(img.updates)}});
    }
    return 0;
}
