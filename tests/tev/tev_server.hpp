#pragma once
// A test tev server: listens on 127.0.0.1 (an ephemeral port unless one is given), accepts
// one connection at a time and decodes tev's IPC packets (iris/tev/tev.hpp) into images,
// checking the framing and every field on the way. Written from the protocol, independently
// of the client's encoder.
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace iris::test {

class tev_server {
public:
    struct image {
        int width = 0, height = 0;
        std::vector<std::string> channels;
        std::vector<float> data;  ///< interleaved, as created (zeros until updated)
        int updates = 0;          ///< UpdateImageV3 packets received
    };

    /// \brief `read` false: accept connections but never read from them (a stuck viewer).
    explicit tev_server(std::uint16_t port = 0, bool read = true) : m_read(read) {
        m_listen = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        const int one = 1;
        ::setsockopt(m_listen, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        if (!read) {  // a small receive buffer fills quickly
            const int small = 4096;
            ::setsockopt(m_listen, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
        }
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        a.sin_port = htons(port);
        if (::bind(m_listen, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(m_listen, 4) != 0)
            throw std::runtime_error("tev_server: cannot listen");
        socklen_t len = sizeof a;
        ::getsockname(m_listen, reinterpret_cast<sockaddr*>(&a), &len);
        m_port = ntohs(a.sin_port);
        m_thread = std::thread([this] { serve(); });
    }
    ~tev_server() { stop(); }

    std::uint16_t port() const { return m_port; }

    /// \brief Close everything, as a viewer that is killed.
    void stop() {
        if (m_stopped.exchange(true)) return;
        ::shutdown(m_listen, SHUT_RDWR);
        ::close(m_listen);
        if (const int c = m_conn.exchange(-1); c >= 0) {
            ::shutdown(c, SHUT_RDWR);
        }
        m_thread.join();
    }

    std::map<std::string, image> images() const {
        std::lock_guard lk(m_mutex);
        return m_images;
    }
    std::vector<std::string> errors() const {
        std::lock_guard lk(m_mutex);
        return m_errors;
    }
    std::map<int, int> packet_counts() const {
        std::lock_guard lk(m_mutex);
        return m_types;
    }
    int connections() const { return m_connections.load(); }
    int closed_connections() const { return m_closed.load(); }

private:
    void serve() {
        while (!m_stopped.load()) {
            const int c = ::accept4(m_listen, nullptr, nullptr, SOCK_CLOEXEC);
            if (c < 0) return;
            ++m_connections;
            m_conn.store(c);
            if (!m_read) {
                while (!m_stopped.load()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
            } else {
                connection(c);
            }
            if (const int cc = m_conn.exchange(-1); cc >= 0) ::close(cc);
            else ::close(c);
            ++m_closed;
        }
    }
    bool read_exact(int c, char* p, std::size_t n) {
        while (n > 0) {
            const ssize_t r = ::recv(c, p, n, 0);
            if (r <= 0) return false;
            p += r;
            n -= static_cast<std::size_t>(r);
        }
        return true;
    }
    void error(const std::string& e) {
        std::lock_guard lk(m_mutex);
        m_errors.push_back(e);
    }
    void connection(int c) {
        while (true) {
            std::uint32_t length = 0;
            if (!read_exact(c, reinterpret_cast<char*>(&length), 4)) return;  // closed between packets: fine
            if (length < 5 || length > (1u << 28)) return error("bad packet length " + std::to_string(length));
            std::string body(length - 4, '\0');
            if (!read_exact(c, body.data(), body.size())) return error("connection closed inside a packet");
            decode(body);
        }
    }
    // a cursor over one packet's payload; every read checks the bounds
    struct cursor {
        const std::string& b;
        std::size_t at = 0;
        bool ok = true;
        template <class T>
        T get() {
            T v{};
            if (at + sizeof v > b.size()) {
                ok = false;
                return v;
            }
            std::memcpy(&v, b.data() + at, sizeof v);
            at += sizeof v;
            return v;
        }
        std::string str() {
            const auto end = b.find('\0', at);
            if (end == std::string::npos) {
                ok = false;
                return {};
            }
            std::string s = b.substr(at, end - at);
            at = end + 1;
            return s;
        }
    };
    void decode(const std::string& body) {
        cursor k{body};
        const int type = k.get<std::uint8_t>();
        {
            std::lock_guard lk(m_mutex);
            ++m_types[type];
        }
        if (type == 2) {  // CloseImage
            const std::string name = k.str();
            std::lock_guard lk(m_mutex);
            m_images.erase(name);
        } else if (type == 4) {  // CreateImage
            const auto grab = k.get<std::uint8_t>();
            image img;
            const std::string name = k.str();
            img.width = k.get<std::int32_t>();
            img.height = k.get<std::int32_t>();
            const int n = k.get<std::int32_t>();
            for (int i = 0; i < n && k.ok; ++i) img.channels.push_back(k.str());
            if (!k.ok || k.at != body.size() || grab > 1 || img.width <= 0 || img.height <= 0 || n <= 0)
                return error("malformed CreateImage");
            img.data.assign(static_cast<std::size_t>(img.width) * img.height * n, 0.0f);
            std::lock_guard lk(m_mutex);
            m_images[name] = std::move(img);
        } else if (type == 6) {  // UpdateImageV3
            const auto grab = k.get<std::uint8_t>();
            const std::string name = k.str();
            const int n = k.get<std::int32_t>();
            std::vector<std::string> channels;
            for (int i = 0; i < n && k.ok; ++i) channels.push_back(k.str());
            const int x = k.get<std::int32_t>(), y = k.get<std::int32_t>();
            const int w = k.get<std::int32_t>(), h = k.get<std::int32_t>();
            std::vector<std::int64_t> offsets, strides;
            for (int i = 0; i < n; ++i) offsets.push_back(k.get<std::int64_t>());
            for (int i = 0; i < n; ++i) strides.push_back(k.get<std::int64_t>());
            const std::size_t floats = (body.size() - std::min(body.size(), k.at)) / sizeof(float);
            if (!k.ok || grab > 1 || w <= 0 || h <= 0 || w > 128 || h > 128 || n <= 0 ||
                (body.size() - k.at) % sizeof(float) != 0)
                return error("malformed UpdateImageV3 header");
            std::vector<float> data(floats);
            std::memcpy(data.data(), body.data() + k.at, floats * sizeof(float));
            std::lock_guard lk(m_mutex);
            auto it = m_images.find(name);
            if (it == m_images.end()) return m_errors.push_back("update of an image never created: " + name);
            image& img = it->second;
            if (channels != img.channels) return m_errors.push_back("update with other channels");
            if (x < 0 || y < 0 || x + w > img.width || y + h > img.height) return m_errors.push_back("update outside the image");
            const auto nc = static_cast<std::size_t>(n);
            for (int p = 0; p < w * h; ++p)
                for (std::size_t ch = 0; ch < nc; ++ch) {
                    const auto at = offsets[ch] + static_cast<std::int64_t>(p) * strides[ch];
                    if (at < 0 || static_cast<std::size_t>(at) >= data.size()) return m_errors.push_back("data index out of range");
                    const std::size_t px = static_cast<std::size_t>(y + p / w) * img.width + static_cast<std::size_t>(x + p % w);
                    img.data[px * nc + ch] = data[static_cast<std::size_t>(at)];
                }
            ++img.updates;
        } else {
            error("unexpected packet type " + std::to_string(type));
        }
    }

    bool m_read;
    int m_listen = -1;
    std::uint16_t m_port = 0;
    std::atomic<int> m_conn{-1};
    std::atomic<bool> m_stopped{false};
    std::atomic<int> m_connections{0}, m_closed{0};
    mutable std::mutex m_mutex;
    std::map<std::string, image> m_images;
    std::vector<std::string> m_errors;
    std::map<int, int> m_types;
    std::thread m_thread;
};

}  // namespace iris::test
