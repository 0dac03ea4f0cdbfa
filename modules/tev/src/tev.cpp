// iris::tev: packets and the sender thread (protocol in iris/tev/tev.hpp).
#include "iris/tev/tev.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <utility>

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <fmt/core.h>

namespace iris::tev {
namespace {

static_assert(std::endian::native == std::endian::little, "tev's protocol is little-endian, as this host");

enum : std::uint8_t { type_close = 2, type_create = 4, type_update_v3 = 6 };

/// \brief A packet under construction: the length is patched in by `finish`.
class packet {
public:
    explicit packet(std::uint8_t type) {
        m_bytes.assign(4, '\0');
        m_bytes.push_back(static_cast<char>(type));
    }
    template <class T>
    packet& put(T v) {
        m_bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
        return *this;
    }
    packet& put(std::string_view s) {
        if (s.find('\0') != std::string_view::npos) throw std::invalid_argument("tev: a name with a NUL character");
        m_bytes.append(s);
        m_bytes.push_back('\0');
        return *this;
    }
    packet& put_floats(std::span<const float> v) {
        m_bytes.append(reinterpret_cast<const char*>(v.data()), v.size_bytes());
        return *this;
    }
    std::string finish() {
        if (m_bytes.size() > UINT32_MAX) throw std::length_error("tev: packet over 4 GiB");
        const auto n = static_cast<std::uint32_t>(m_bytes.size());
        std::memcpy(m_bytes.data(), &n, sizeof n);
        return std::move(m_bytes);
    }

private:
    std::string m_bytes;
};

using clock = std::chrono::steady_clock;

/// \brief A TCP connection to `a`, or -1. Waits at most `timeout_ms` for the connection.
int connect_to(const address& a, int timeout_ms) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (::getaddrinfo(a.host.c_str(), std::to_string(a.port).c_str(), &hints, &found) != 0) return -1;
    int fd = -1;
    for (addrinfo* ai = found; ai != nullptr && fd < 0; ai = ai->ai_next) {
        fd = ::socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC | SOCK_NONBLOCK, ai->ai_protocol);
        if (fd < 0) continue;
        bool ok = ::connect(fd, ai->ai_addr, ai->ai_addrlen) == 0;
        if (!ok && errno == EINPROGRESS) {
            pollfd p{fd, POLLOUT, 0};
            int err = 0;
            socklen_t len = sizeof err;
            ok = ::poll(&p, 1, timeout_ms) == 1 && ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) == 0 && err == 0;
        }
        if (!ok) {
            ::close(fd);
            fd = -1;
        }
    }
    ::freeaddrinfo(found);
    if (fd < 0) return -1;
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    timeval tv{5, 0};  // a tev that stops reading for 5 s is treated as gone
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    return fd;
}

}  // namespace

address parse_address(std::string_view text) {
    address a;
    const auto bad = [&](const std::string& why) {
        return std::invalid_argument(fmt::format("tev address '{}': {} (expected HOST:PORT, HOST or :PORT)", text, why));
    };
    std::string_view host = text, port;
    if (!text.empty() && text.front() == '[') {  // [IPv6]:PORT
        const auto close = text.find(']');
        if (close == std::string_view::npos) throw bad("'[' without ']'");
        host = text.substr(1, close - 1);
        const std::string_view rest = text.substr(close + 1);
        if (!rest.empty()) {
            if (rest.front() != ':') throw bad("expected ':' after ']'");
            port = rest.substr(1);
            if (port.empty()) throw bad("no port after ':'");
        }
    } else if (const auto colon = text.rfind(':'); colon != std::string_view::npos) {
        if (text.find(':') != colon) throw bad("an IPv6 host must be in brackets");
        host = text.substr(0, colon);
        port = text.substr(colon + 1);
        if (port.empty()) throw bad("no port after ':'");
    }
    if (!host.empty()) a.host = std::string(host);
    if (a.host.find_first_of(" \t") != std::string::npos) throw bad("a space in the host");
    if (!port.empty()) {
        unsigned v = 0;
        const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), v);
        if (ec != std::errc() || end != port.data() + port.size()) throw bad(fmt::format("port '{}' is not a number", port));
        if (v < 1 || v > 65535) throw bad(fmt::format("port {} is not in 1..65535", port));
        a.port = static_cast<std::uint16_t>(v);
    }
    return a;
}

std::string close_image_packet(std::string_view name) { return packet(type_close).put(name).finish(); }

std::string create_image_packet(std::string_view name, int width, int height, std::span<const std::string> channels,
                                bool grab_focus) {
    packet p(type_create);
    p.put(static_cast<std::uint8_t>(grab_focus)).put(name).put(std::int32_t{width}).put(std::int32_t{height});
    p.put(static_cast<std::int32_t>(channels.size()));
    for (const auto& c : channels) p.put(std::string_view(c));
    return p.finish();
}

std::string update_image_packet(std::string_view name, std::span<const std::string> channels, int x, int y, int width,
                                int height, std::span<const float> data, bool grab_focus) {
    const std::size_t n = channels.size();
    if (data.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * n)
        throw std::invalid_argument("tev: update data is not width x height x channels floats");
    packet p(type_update_v3);
    p.put(static_cast<std::uint8_t>(grab_focus)).put(name).put(static_cast<std::int32_t>(n));
    for (const auto& c : channels) p.put(std::string_view(c));
    p.put(std::int32_t{x}).put(std::int32_t{y}).put(std::int32_t{width}).put(std::int32_t{height});
    for (std::size_t c = 0; c < n; ++c) p.put(static_cast<std::int64_t>(c));  // offsets
    for (std::size_t c = 0; c < n; ++c) p.put(static_cast<std::int64_t>(n));  // strides
    p.put_floats(data);
    return p.finish();
}

client::client(address where, std::function<void(const std::string&)> warn)
    : m_where(std::move(where)), m_warn(std::move(warn)), m_thread([this] { run(); }) {}

client::~client() {
    {
        std::lock_guard lk(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    if (const int fd = m_fd.load(); fd >= 0) ::shutdown(fd, SHUT_RDWR);  // unblocks a send
    m_thread.join();
    disconnect();
}

void client::post(frame f) {
    {
        std::lock_guard lk(m_mutex);
        ++m_stats.posted;
        auto& slot = m_pending[f.name];
        if (!slot.name.empty()) ++m_stats.dropped;
        slot = std::move(f);
    }
    m_wake.notify_one();
}

bool client::flush(double seconds) {
    std::unique_lock lk(m_mutex);
    // gives up at once while tev is known to be unreachable (nothing would arrive)
    m_idle.wait_for(lk, std::chrono::duration<double>(seconds),
                    [&] { return (m_pending.empty() && !m_busy) || (m_warned && m_fd.load() < 0); });
    return m_pending.empty() && !m_busy;
}

client_stats client::stats() const {
    std::lock_guard lk(m_mutex);
    return m_stats;
}

bool client::send_all(const std::string& bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::send(m_fd.load(), bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
        } else if (n < 0 && errno == EINTR) {
            continue;
        } else {
            return false;
        }
    }
    return true;
}

void client::disconnect() {
    const int fd = m_fd.exchange(-1);
    if (fd >= 0) ::close(fd);
}

void client::run() {
    clock::time_point last_attempt{};
    bool attempted = false;
    std::unique_lock lk(m_mutex);
    while (true) {
        m_wake.wait(lk, [&] { return m_stop || !m_pending.empty(); });
        if (m_stop) break;
        if (m_fd.load() < 0) {
            const auto now = clock::now();
            if (attempted && now - last_attempt < std::chrono::seconds(1)) {
                m_wake.wait_until(lk, last_attempt + std::chrono::seconds(1), [&] { return m_stop; });
                continue;
            }
            attempted = true;
            last_attempt = now;
            lk.unlock();
            const int fd = connect_to(m_where, 1000);
            lk.lock();
            if (fd < 0) {
                ++m_stats.failures;
                if (!m_warned) {  // warned first, then marked: flush() returns after the warning
                    lk.unlock();
                    m_warn(fmt::format("tev is not reachable at {}:{}; rendering goes on, retrying every second",
                                       m_where.host, m_where.port));
                    lk.lock();
                    m_warned = true;
                }
                m_idle.notify_all();
                continue;
            }
            m_fd.store(fd);
            ++m_stats.connects;
            m_created.clear();
            if (m_warned) {
                m_warned = false;
                lk.unlock();
                m_warn(fmt::format("tev is reachable again at {}:{}", m_where.host, m_where.port));
                lk.lock();
            }
        }
        auto node = m_pending.extract(m_pending.begin());
        frame f = std::move(node.mapped());
        const auto created = m_created.find(f.name);
        const bool create = created == m_created.end() || created->second != std::pair{f.width, f.height};
        m_busy = true;
        lk.unlock();

        bool ok = true;
        if (create) {
            if (created != m_created.end()) ok = send_all(close_image_packet(f.name));
            ok = ok && send_all(create_image_packet(f.name, f.width, f.height, f.channels, false));
        }
        const std::size_t nc = f.channels.size();
        std::vector<float> tile;
        for (int y0 = 0; ok && y0 < f.height; y0 += max_tile)
            for (int x0 = 0; ok && x0 < f.width; x0 += max_tile) {
                const int w = std::min(max_tile, f.width - x0), h = std::min(max_tile, f.height - y0);
                tile.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * nc);
                for (int y = 0; y < h; ++y)
                    std::copy_n(f.data.begin() + static_cast<std::ptrdiff_t>(((static_cast<std::size_t>(y0 + y) * f.width) + x0) * nc),
                                static_cast<std::size_t>(w) * nc, tile.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * w * nc));
                ok = send_all(update_image_packet(f.name, f.channels, x0, y0, w, h, tile, false));
            }

        lk.lock();
        m_busy = false;
        if (ok) {
            ++m_stats.sent;
            m_created[f.name] = {f.width, f.height};
        } else {
            ++m_stats.failures;
            disconnect();
            m_created.clear();
            if (!m_pending.contains(f.name) && !m_stop) m_pending[f.name] = std::move(f);  // send it after reconnecting
            if (!m_warned) {
                m_warned = true;
                lk.unlock();
                m_warn(fmt::format("lost the connection to tev at {}:{}; rendering goes on, retrying every second",
                                   m_where.host, m_where.port));
                lk.lock();
            }
        }
        m_idle.notify_all();
    }
}

}  // namespace iris::tev
