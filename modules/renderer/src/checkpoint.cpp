// Checkpoint files (format in iris/renderer/checkpoint.hpp).
#include "iris/renderer/checkpoint.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <span>
#include <map>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "iris/exr/exr.hpp"
#include "iris/hash.hpp"
#include "iris/renderer/renderer.hpp"

namespace iris::renderer {
namespace {

static_assert(std::endian::native == std::endian::little, "checkpoints are little-endian");
static_assert(sizeof(exact_xyz) == 48);
/// A square sum is stored as its 128-bit low part and 64-bit high part (24 bytes, no padding).
constexpr std::size_t square_bytes = sizeof(fade::exact_uint) + sizeof(std::uint64_t);
/// A fade layer's bytes per pixel in the file: early sums, early count, 6 square sums.
constexpr std::size_t fade_file_bytes = sizeof(exact_xyz) + sizeof(std::uint32_t) + 6 * square_bytes;

constexpr char magic[8] = {'I', 'R', 'I', 'S', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t format_version = 3;  // 1: no fade layer, no fade_split; 2: no spectral layer (both still read)
constexpr int max_side = 16384;

/// \brief The key's fields as (name, value) in a fixed order: the header and the mismatch
/// message both use it.
std::vector<std::pair<std::string, std::string>> fields(const checkpoint_key& k) {
    return {{"version", k.version},
            {"scene", k.scene},
            {"scene_fingerprint", fmt::format("{:016x}", k.scene_fingerprint)},
            {"preset", k.preset},
            {"estimator", k.estimator},
            {"sampler", k.sampler},
            {"seed", std::to_string(k.seed)},
            {"nthold", std::to_string(k.nthold)},
            {"max_depth", std::to_string(k.max_depth)},
            {"spp", std::to_string(k.spp)},
            {"width", std::to_string(k.width)},
            {"height", std::to_string(k.height)},
            {"spectral_bins", std::to_string(k.spectral_bins)}};
}

template <class T>
void put(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void put_all(std::string& out, std::span<const T> v) {
    out.append(reinterpret_cast<const char*>(v.data()), v.size_bytes());
}

/// \brief Reads the file's bytes in order; every read is bounds-checked.
class reader {
public:
    reader(std::string_view bytes, std::string name) : m_bytes(bytes), m_name(std::move(name)) {}
    [[noreturn]] void fail(const std::string& why) const {
        throw checkpoint_error(fmt::format("checkpoint '{}' is corrupt or not a checkpoint: {}", m_name, why));
    }
    std::string_view take(std::size_t n, const char* what) {
        if (n > m_bytes.size() - m_pos) fail(fmt::format("truncated in {} ({} bytes)", what, m_bytes.size()));
        const std::string_view v(m_bytes.data() + m_pos, n);
        m_pos += n;
        return v;
    }
    template <class T>
    T get(const char* what) {
        T v;
        std::memcpy(&v, take(sizeof v, what).data(), sizeof v);
        return v;
    }
    template <class T>
    std::vector<T> get_all(std::size_t n, const char* what) {
        std::vector<T> v(n);
        const auto b = take(n * sizeof(T), what);
        std::memcpy(v.data(), b.data(), b.size());
        return v;
    }
    std::size_t position() const noexcept { return m_pos; }

private:
    std::string_view m_bytes;
    std::string m_name;
    std::size_t m_pos = 0;
};

template <class T>
T parse_number(const reader& r, const std::map<std::string, std::string>& h, const std::string& name, T lo, T hi) {
    const auto it = h.find(name);
    if (it == h.end()) r.fail(fmt::format("the header has no '{}'", name));
    T v{};
    const auto& s = it->second;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || v < lo || v > hi)
        r.fail(fmt::format("header field {}='{}' is not a number in {}..{}", name, s, lo, hi));
    return v;
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const checkpoint& c) {
    const film& f = c.image;
    std::string header;
    for (const auto& [k, v] : fields(c.key)) header += k + "=" + v + "\n";
    const film::fade_parts* fade = f.fade_state();
    header += fmt::format("spp_done={}\nsamples={}\nrays={}\nseconds={}\nfade_split={}\n", c.spp_done, c.samples, c.rays,
                          c.seconds, fade ? fade->split : 0);
    const film::spectral_parts* spectral = f.spectral_state();
    if ((spectral ? spectral->bands.count : 0) != c.key.spectral_bins)
        throw checkpoint_error(fmt::format("cannot write checkpoint '{}': its key has {} spectral bins, its film {}", path.string(),
                                           c.key.spectral_bins, spectral ? spectral->bands.count : 0));
    if (spectral)
        header += fmt::format("spectral_range={},{}\nspectral_dropped={}\n", spectral->bands.lambda_min,
                              spectral->bands.lambda_max, spectral->dropped);
    std::string out;
    const std::size_t pixels = f.sums().size();
    out.reserve(24 + header.size() + pixels * (film::bytes_per_pixel + (fade ? fade_file_bytes : 0)) + 8);
    out.append(magic, sizeof magic);
    put(out, format_version);
    put(out, static_cast<std::uint32_t>(header.size()));
    out += header;
    put_all(out, f.sums());
    put_all(out, f.counts());
    put_all(out, f.dropped_counts());
    if (fade) {
        put_all(out, std::span<const exact_xyz>(fade->early_sum));
        put_all(out, std::span<const std::uint32_t>(fade->early_count));
        for (const auto* side : {&fade->early_sq, &fade->late_sq})
            for (const auto& pixel : *side)
                for (const auto& q : pixel) {
                    put(out, q.low);
                    put(out, q.high);
                }
    }
    if (spectral) put_all(out, std::span<const exact_int>(spectral->sums));
    put(out, fnv1a_of(out.data(), out.size()));
    try {
        exr::write_atomically(path, [&](const std::filesystem::path& tmp) {
            std::ofstream o(tmp, std::ios::binary);
            o.write(out.data(), static_cast<std::streamsize>(out.size()));
            o.flush();
            if (!o) throw checkpoint_error(fmt::format("cannot write checkpoint '{}'", path.string()));
        });
    } catch (const checkpoint_error&) {
        throw;
    } catch (const std::exception& e) {
        throw checkpoint_error(fmt::format("cannot write checkpoint '{}': {}", path.string(), e.what()));
    }
}

checkpoint read_checkpoint(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (!in || ec) throw checkpoint_error(fmt::format("cannot read checkpoint '{}': no such file or not readable", path.string()));
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
        throw checkpoint_error(fmt::format("cannot read checkpoint '{}'", path.string()));
    return parse_checkpoint(bytes, path.string());
}

checkpoint parse_checkpoint(std::string_view bytes, const std::string& name) {
    reader r(bytes, name);

    if (r.take(sizeof magic, "the magic") != std::string_view(magic, sizeof magic)) r.fail("it does not start with IRISCKPT");
    const auto version = r.get<std::uint32_t>("the format version");
    if (version < 1 || version > format_version)
        r.fail(fmt::format("format version {}, this iris reads 1 to {}", version, format_version));
    const auto header_length = r.get<std::uint32_t>("the header length");
    if (header_length > (1u << 16)) r.fail(fmt::format("a header of {} bytes", header_length));
    std::map<std::string, std::string> h;
    {
        std::string_view text = r.take(header_length, "the header");
        while (!text.empty()) {
            const auto nl = text.find('\n');
            if (nl == std::string_view::npos) r.fail("the header's last line has no newline");
            const std::string_view line = text.substr(0, nl);
            text.remove_prefix(nl + 1);
            const auto eq = line.find('=');
            if (eq == std::string_view::npos) r.fail(fmt::format("header line '{}' is not key=value", line));
            h[std::string(line.substr(0, eq))] = std::string(line.substr(eq + 1));
        }
    }
    checkpoint c;
    auto text = [&](const std::string& field) {
        const auto it = h.find(field);
        if (it == h.end()) r.fail(fmt::format("the header has no '{}'", field));
        return it->second;
    };
    c.key.version = text("version");
    c.key.scene = text("scene");
    {
        const std::string s = text("scene_fingerprint");
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), c.key.scene_fingerprint, 16);
        if (ec != std::errc() || end != s.data() + s.size() || s.size() != 16)
            r.fail(fmt::format("header field scene_fingerprint='{}' is not 16 hex digits", s));
    }
    c.key.preset = text("preset");
    c.key.estimator = text("estimator");
    c.key.sampler = text("sampler");
    c.key.seed = parse_number<std::uint64_t>(r, h, "seed", 0, UINT64_MAX);
    c.key.nthold = parse_number<int>(r, h, "nthold", 1, INT32_MAX);
    c.key.max_depth = parse_number<int>(r, h, "max_depth", 1, INT32_MAX);
    c.key.spp = parse_number<int>(r, h, "spp", 1, INT32_MAX);
    c.key.width = parse_number<int>(r, h, "width", 1, max_side);
    c.key.height = parse_number<int>(r, h, "height", 1, max_side);
    c.spp_done = parse_number<int>(r, h, "spp_done", 0, c.key.spp);
    c.samples = parse_number<std::uint64_t>(r, h, "samples", 0, UINT64_MAX);
    c.rays = parse_number<std::uint64_t>(r, h, "rays", 0, UINT64_MAX);
    c.seconds = parse_number<double>(r, h, "seconds", 0.0, 1e12);
    const auto fade_split = version == 1 ? 0u : parse_number<std::uint32_t>(r, h, "fade_split", 0, UINT32_MAX);
    c.key.spectral_bins = version < 3 ? 0 : parse_number<int>(r, h, "spectral_bins", 0, max_spectral_bins);
    std::optional<film::spectral_parts> spectral;
    if (c.key.spectral_bins > 0) {
        spectral.emplace();
        spectral->bands.count = c.key.spectral_bins;
        const std::string range = text("spectral_range");
        const auto comma = range.find(',');
        const auto number = [&](std::string_view t, double& v) {
            const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
            return ec == std::errc() && end == t.data() + t.size() && std::isfinite(v);
        };
        if (comma == std::string::npos ||
            !number(std::string_view(range).substr(0, comma), spectral->bands.lambda_min) ||
            !number(std::string_view(range).substr(comma + 1), spectral->bands.lambda_max) ||
            !(spectral->bands.lambda_max > spectral->bands.lambda_min))
            r.fail(fmt::format("header field spectral_range='{}' is not two increasing wavelengths 'min,max'", range));
        spectral->dropped = parse_number<std::uint64_t>(r, h, "spectral_dropped", 0, UINT64_MAX);
    }

    const std::size_t pixels = static_cast<std::size_t>(c.key.width) * static_cast<std::size_t>(c.key.height);
    const std::size_t per_pixel = film::bytes_per_pixel + (fade_split > 0 ? fade_file_bytes : 0) +
                                  film::spectral_bytes_per_band * static_cast<std::size_t>(c.key.spectral_bins);
    const std::size_t expected = r.position() + pixels * per_pixel + 8;
    if (bytes.size() != expected)
        r.fail(fmt::format("{} bytes, a {}x{} checkpoint has {}", bytes.size(), c.key.width, c.key.height, expected));
    auto sums = r.get_all<exact_xyz>(pixels, "the sums");
    auto counts = r.get_all<std::uint32_t>(pixels, "the sample counts");
    auto dropped = r.get_all<std::uint32_t>(pixels, "the dropped counts");
    std::optional<film::fade_parts> fade;
    if (fade_split > 0) {
        fade.emplace();
        fade->split = fade_split;
        fade->early_sum = r.get_all<exact_xyz>(pixels, "the fade layer's early sums");
        fade->early_count = r.get_all<std::uint32_t>(pixels, "the fade layer's early counts");
        for (auto* side : {&fade->early_sq, &fade->late_sq}) {
            side->resize(pixels);
            for (auto& pixel : *side)
                for (auto& q : pixel) {
                    q.low = r.get<fade::exact_uint>("the fade layer's squares");
                    q.high = r.get<std::uint64_t>("the fade layer's squares");
                }
        }
    }
    if (spectral) spectral->sums = r.get_all<exact_int>(pixels * static_cast<std::size_t>(c.key.spectral_bins), "the spectral layer");
    const std::size_t body = r.position();
    if (r.get<std::uint64_t>("the checksum") != fnv1a_of(bytes.data(), body)) r.fail("checksum mismatch");
    for (std::size_t i = 0; i < pixels; ++i) {
        if (counts[i] != static_cast<std::uint32_t>(c.spp_done))
            r.fail(fmt::format("pixel {} has {} samples, spp_done is {}", i, counts[i], c.spp_done));
        if (dropped[i] > counts[i]) r.fail(fmt::format("pixel {} has more dropped samples than samples", i));
        // every pixel took samples 0 .. spp_done − 1, so min(spp_done, split) of them early
        if (fade && fade->early_count[i] != std::min(counts[i], fade_split))
            r.fail(fmt::format("pixel {} has {} early samples in the fade layer, {} with spp_done {} and fade_split {}", i,
                               fade->early_count[i], std::min(counts[i], fade_split), c.spp_done, fade_split));
    }
    c.image = film::from_parts(c.key.width, c.key.height, std::move(sums), std::move(counts), std::move(dropped),
                               std::move(fade), std::move(spectral));
    return c;
}

std::optional<std::string> key_mismatch(const checkpoint_key& stored, const checkpoint_key& wanted) {
    const auto a = fields(stored), b = fields(wanted);
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].second != b[i].second)
            return fmt::format("its {} is {}, this render's is {}", a[i].first, a[i].second, b[i].second);
    return std::nullopt;
}

}  // namespace iris::renderer
