// The tev client (iris/tev/tev.hpp) against the test server of tev_server.hpp: addresses,
// the packets' framing and fields, images arriving intact in 128x128 tiles, a viewer that
// stops reading (post never blocks; stale frames are dropped), and one that dies and comes
// back (one warning each way; the image is created again).
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include <iris/tev/tev.hpp>

#include "tev_server.hpp"

namespace {

using namespace std::chrono_literals;

iris::tev::frame test_frame(const std::string& name, int w, int h, float base) {
    iris::tev::frame f{name, w, h, {"R", "G", "B"}, {}};
    for (int i = 0; i < w * h * 3; ++i) f.data.push_back(base + static_cast<float>(i) * 0.25f);
    return f;
}

/// \brief Collects the client's warnings.
struct warnings {
    std::mutex m;
    std::vector<std::string> list;
    std::function<void(const std::string&)> sink() {
        return [this](const std::string& s) {
            std::lock_guard lk(m);
            list.push_back(s);
        };
    }
    std::vector<std::string> get() {
        std::lock_guard lk(m);
        return list;
    }
};

TEST(TevAddress, ParsesTheAcceptedFormsAndRefusesTheRest) {
    using iris::tev::parse_address;
    EXPECT_EQ(parse_address("").host, "127.0.0.1");
    EXPECT_EQ(parse_address("").port, 14158);
    EXPECT_EQ(parse_address("viewer:9000").host, "viewer");
    EXPECT_EQ(parse_address("viewer:9000").port, 9000);
    EXPECT_EQ(parse_address(":1").port, 1);
    EXPECT_EQ(parse_address(":1").host, "127.0.0.1");
    EXPECT_EQ(parse_address("somehost").port, 14158);
    EXPECT_EQ(parse_address("[::1]:65535").host, "::1");
    EXPECT_EQ(parse_address("[::1]:65535").port, 65535);
    for (const char* bad : {"h:0", "h:65536", "h:", "h:12x", "h:-1", "::1:80", "[::1", "[::1]80", "a b:1", "h:99999999999"})
        EXPECT_THROW((void)parse_address(bad), std::invalid_argument) << bad;
    try {
        (void)parse_address("h:70000");
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "tev address 'h:70000': port 70000 is not in 1..65535 (expected HOST:PORT, HOST or :PORT)");
    }
}

// The bytes of each packet, field by field, as the protocol lays them out (little-endian,
// the length counting itself, NUL-terminated strings).
TEST(TevPackets, FieldsAreInTheProtocolsOrder) {
    const std::vector<std::string> ch{"R", "G"};
    const std::string c = iris::tev::create_image_packet("im", 3, 2, ch, true);
    const std::string expect_c = std::string("\x19\0\0\0", 4) + '\x04' + '\x01' + std::string("im\0", 3) +
                                 std::string("\x03\0\0\0\x02\0\0\0\x02\0\0\0", 12) + std::string("R\0G\0", 4);
    EXPECT_EQ(c, expect_c);
    EXPECT_EQ(iris::tev::close_image_packet("im"), std::string("\x08\0\0\0\x02im\0", 8));
    const std::vector<float> data{1.0f, 2.0f};
    const std::string u = iris::tev::update_image_packet("im", ch, 5, 6, 1, 1, data, false);
    std::string expect_u = std::string(4, '\0') + '\x06' + '\0' + std::string("im\0", 3) + std::string("\x02\0\0\0", 4) +
                           std::string("R\0G\0", 4) + std::string("\x05\0\0\0\x06\0\0\0\x01\0\0\0\x01\0\0\0", 16) +
                           std::string("\0\0\0\0\0\0\0\0\x01\0\0\0\0\0\0\0", 16) +  // offsets 0, 1
                           std::string("\x02\0\0\0\0\0\0\0\x02\0\0\0\0\0\0\0", 16);   // strides 2, 2
    expect_u.append(reinterpret_cast<const char*>(data.data()), 8);
    const auto n = static_cast<std::uint32_t>(expect_u.size());
    std::memcpy(expect_u.data(), &n, 4);
    EXPECT_EQ(u, expect_u);
    EXPECT_THROW((void)iris::tev::update_image_packet("im", ch, 0, 0, 2, 1, data, false), std::invalid_argument);
}

// A 300x200 frame (3x2 tiles, the last ones partial) arrives bit for bit, then a second
// frame replaces it without a second CreateImage; a frame of another size closes and
// recreates the image.
TEST(TevClient, FramesArriveIntactInTiles) {
    iris::test::tev_server server;
    warnings w;
    iris::tev::client c({"127.0.0.1", server.port()}, w.sink());
    auto f = test_frame("a.exr", 300, 200, 0.5f);
    c.post(f);
    ASSERT_TRUE(c.flush(10.0));
    // flush: sent; the server may still be decoding: wait for its count (at most 5 s)
    const auto wait_updates = [&](int n) {
        for (int i = 0; i < 500 && server.images()["a.exr"].updates < n; ++i) std::this_thread::sleep_for(10ms);
    };
    wait_updates(6);
    auto f2 = test_frame("a.exr", 300, 200, 7.0f);
    c.post(f2);
    ASSERT_TRUE(c.flush(10.0));
    wait_updates(12);
    auto images = server.images();
    ASSERT_EQ(images.count("a.exr"), 1u);
    EXPECT_EQ(images["a.exr"].data, f2.data);
    EXPECT_EQ(images["a.exr"].updates, 12);  // 2 frames x 6 tiles
    c.post(test_frame("a.exr", 10, 20, 1.0f));
    ASSERT_TRUE(c.flush(10.0));
    for (int i = 0; i < 500 && (server.images()["a.exr"].width != 10 || server.images()["a.exr"].updates < 1); ++i)
        std::this_thread::sleep_for(10ms);
    EXPECT_EQ(server.images()["a.exr"].data, test_frame("a.exr", 10, 20, 1.0f).data);
    const auto counts = server.packet_counts();
    EXPECT_EQ(counts.at(4), 2);  // created twice: first size, then the new one
    EXPECT_EQ(counts.at(2), 1);  // closed once, before the second create
    EXPECT_TRUE(server.errors().empty());
    EXPECT_TRUE(w.get().empty());
}

// A viewer that accepts but never reads: the sender blocks in send(), but post() returns at
// once every time (bound: 50 ms, against the microseconds it takes) and the frames not yet
// sent are replaced, not queued. The client's destructor returns promptly.
TEST(TevClient, AViewerThatStopsReadingNeverBlocksPost) {
    iris::test::tev_server server(0, /*read=*/false);
    warnings w;
    auto start = std::chrono::steady_clock::now();
    {
        iris::tev::client c({"127.0.0.1", server.port()}, w.sink());
        double worst = 0.0;
        for (int i = 0; i < 40; ++i) {
            auto f = test_frame("stuck", 512, 512, static_cast<float>(i));  // 3 MB a frame, made outside the timing
            const auto t0 = std::chrono::steady_clock::now();
            c.post(std::move(f));
            worst = std::max(worst, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            std::this_thread::sleep_for(5ms);
        }
        EXPECT_LT(worst, 0.05);
        const auto s = c.stats();
        EXPECT_EQ(s.posted, 40u);
        EXPECT_GT(s.dropped, 30u);  // at most a frame or two got into the socket
        start = std::chrono::steady_clock::now();
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
}

// No viewer, then one that appears, dies, and comes back on the same port: one warning
// when it cannot be reached, one when it is back, and the newest frame is what arrives each
// time (created anew on each connection).
TEST(TevClient, AViewerThatDiesAndComesBackGetsTheNewestFrame) {
    std::uint16_t port = 0;
    {
        iris::test::tev_server probe;  // find a free port, then free it
        port = probe.port();
    }
    warnings w;
    iris::tev::client c({"127.0.0.1", port}, w.sink());
    c.post(test_frame("x", 4, 4, 1.0f));
    EXPECT_FALSE(c.flush(0.5));  // nobody listens
    ASSERT_EQ(w.get().size(), 1u);
    EXPECT_NE(w.get()[0].find("not reachable"), std::string::npos);
    c.post(test_frame("x", 4, 4, 2.0f));  // replaces the unsent one
    {
        iris::test::tev_server server(port);
        // flush gives up at once while tev is known unreachable: wait for the retry instead
        for (int i = 0; i < 500 && c.stats().sent == 0; ++i) std::this_thread::sleep_for(10ms);
        ASSERT_EQ(c.stats().sent, 1u);
        for (int i = 0; i < 100 && server.images()["x"].updates == 0; ++i) std::this_thread::sleep_for(10ms);
        EXPECT_EQ(server.images()["x"].data, test_frame("x", 4, 4, 2.0f).data);
        ASSERT_EQ(w.get().size(), 2u);
        EXPECT_NE(w.get()[1].find("reachable again"), std::string::npos);
        server.stop();  // killed
    }
    // the next frames find the connection gone (perhaps only at the second send)
    for (int i = 0; i < 50 && c.stats().failures < 2; ++i) {
        c.post(test_frame("x", 4, 4, 3.0f));
        std::this_thread::sleep_for(20ms);
    }
    iris::test::tev_server again(port);
    const auto sent = c.stats().sent;
    c.post(test_frame("x", 4, 4, 4.0f));
    for (int i = 0; i < 500 && c.stats().sent == sent; ++i) std::this_thread::sleep_for(10ms);
    for (int i = 0; i < 200 && again.images()["x"].data != test_frame("x", 4, 4, 4.0f).data; ++i)
        std::this_thread::sleep_for(10ms);
    EXPECT_EQ(again.images()["x"].data, test_frame("x", 4, 4, 4.0f).data);
    EXPECT_GE(c.stats().connects, 2u);
    EXPECT_TRUE(again.errors().empty());
}

}  // namespace
