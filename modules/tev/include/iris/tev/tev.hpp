#pragma once
/// \file
/// \brief iris::tev — a client of the tev image viewer's IPC protocol, for watching a render
/// converge live.
///
/// **The protocol** (as tev speaks it; every integer little-endian): a packet is a uint32
/// length (of the whole packet, these 4 bytes included), a uint8 type and a payload; strings
/// are UTF-8 and NUL-terminated.
///
/// | type | packet | payload |
/// |---|---|---|
/// | 2 | CloseImage | name |
/// | 4 | CreateImage | grab_focus (uint8), name, width, height, channel count (int32), channel names |
/// | 6 | UpdateImageV3 | grab_focus, name, channel count, channel names, x, y, width, height (int32), one int64 offset per channel, one int64 stride per channel, float32 data |
///
/// In an update, channel c of the rectangle's pixel p (row-major) is the float at
/// offset_c + p · stride_c of the data. iris sends interleaved channels (offset c, stride =
/// channel count) in tiles of at most 128 × 128 pixels (`max_tile`).
///
/// **The client** never stalls the caller: `post` hands an image to a sender thread through
/// a one-image mailbox, replacing an image not yet sent (a stale update is dropped, never
/// queued). If tev is not running, or goes away, the client warns once, keeps the newest
/// image, and tries to connect again at most once a second; on reconnecting it creates the
/// images again.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace iris::tev {

inline constexpr std::uint16_t default_port = 14158;
inline constexpr int max_tile = 128;

/// \brief Where tev listens.
struct address {
    std::string host = "127.0.0.1";
    std::uint16_t port = default_port;
};

/// \brief "HOST:PORT", "HOST", ":PORT" or "" (127.0.0.1:14158 for what is left out); an
/// IPv6 host in brackets, "[::1]:PORT". \throws std::invalid_argument naming the text and
/// what was expected (a port outside 1..65535, not a number, an empty host with a colon…).
address parse_address(std::string_view text);

// ---- packets (pure functions; the test server decodes them) --------------------------
std::string close_image_packet(std::string_view name);
std::string create_image_packet(std::string_view name, int width, int height, std::span<const std::string> channels,
                                bool grab_focus);
/// \brief One UpdateImageV3 packet: the rectangle [x, x + width) × [y, y + height), its
/// pixels' channels interleaved in `data` (width · height · channels floats, row-major).
std::string update_image_packet(std::string_view name, std::span<const std::string> channels, int x, int y, int width,
                                int height, std::span<const float> data, bool grab_focus);

/// \brief An image to show: width × height pixels, `channels.size()` interleaved floats each.
struct frame {
    std::string name;
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::vector<float> data;
};

/// \brief What the client did so far.
struct client_stats {
    std::uint64_t posted = 0;     ///< frames handed to `post`
    std::uint64_t sent = 0;       ///< frames sent completely
    std::uint64_t dropped = 0;    ///< frames replaced by a newer one before they were sent
    std::uint64_t connects = 0;   ///< successful connections
    std::uint64_t failures = 0;   ///< failed connections or sends
};

/// \brief Streams frames to tev from a background thread (see the file comment).
class client {
public:
    /// \brief `warn` is called (from the sender thread) once when tev cannot be reached or
    /// goes away, and once when it is back; it must be thread-safe.
    client(address where, std::function<void(const std::string&)> warn);
    ~client();  ///< sends nothing more; closes the connection; never blocks for long
    client(const client&) = delete;
    client& operator=(const client&) = delete;

    /// \brief Show `f` (replacing a frame of the same name not yet sent). Never blocks on
    /// the network.
    void post(frame f);
    /// \brief Wait until every posted frame was sent or `seconds` passed (not at all while tev
    /// is known to be unreachable); true if all were sent.
    bool flush(double seconds);
    client_stats stats() const;

private:
    void run();
    bool send_all(const std::string& bytes);
    void disconnect();

    address m_where;
    std::function<void(const std::string&)> m_warn;
    mutable std::mutex m_mutex;
    std::condition_variable m_wake, m_idle;
    std::map<std::string, frame> m_pending;  ///< the mailbox: the newest frame per name
    std::map<std::string, std::pair<int, int>> m_created;  ///< images created on this connection
    client_stats m_stats;
    bool m_busy = false;
    bool m_stop = false;
    std::atomic<int> m_fd{-1};
    bool m_warned = false;
    std::thread m_thread;
};

}  // namespace iris::tev
