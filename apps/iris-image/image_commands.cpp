#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include <iris/exr/exr.hpp>
#include <iris/metrics/flip.hpp>
#include <iris/metrics/metrics.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "error_ramp.hpp"

namespace iris::app {
namespace {

namespace fs = std::filesystem;

/// \brief Messages from OpenEXR may span lines; the exit-status policy promises one.
std::string one_line(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

std::string size_of(const image& img) { return fmt::format("{}x{}", img.width(), img.height()); }

/// \brief Read an EXR, turning every way it can fail into a usage_error naming the file.
exr::loaded load(const std::string& path) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status)) throw usage_error(fmt::format("cannot read '{}': no such file", path));
    if (fs::is_directory(status)) throw usage_error(fmt::format("cannot read '{}': it is a directory", path));
    exr::loaded out;
    try {
        out = exr::read(path);
    } catch (const exr::error& e) {
        throw usage_error(one_line(e.what()));
    }
    if (out.pixels.empty()) throw usage_error(fmt::format("'{}' has no pixels", path));
    // The metrics refuse NaN/Inf too; checking here lets the message name the file.
    for (int y = 0; y < out.pixels.height(); ++y)
        for (int x = 0; x < out.pixels.width(); ++x) {
            const rgb_pixel& p = out.pixels(x, y);
            if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b))
                throw usage_error(fmt::format("'{}' has a non-finite value (NaN or Inf) at pixel ({}, {})", path, x, y));
        }
    return out;
}

/// \brief Two images of the same size (the one check every two-image command needs first).
struct image_pair {
    exr::loaded test, reference;
};

image_pair load_pair(const std::string& image_path, const std::string& reference_path) {
    image_pair p{load(image_path), load(reference_path)};
    if (p.test.pixels.width() != p.reference.pixels.width() ||
        p.test.pixels.height() != p.reference.pixels.height())
        throw usage_error(fmt::format("'{}' is {} but '{}' is {}: the images must have the same size", image_path,
                                      size_of(p.test.pixels), reference_path, size_of(p.reference.pixels)));
    return p;
}

/// \brief Refuse an output name whose extension says another format (e.g. PNG bytes in
/// a file called out.exr), before any work is done.
void require_extension(const std::string& path, std::string_view ext, std::string_view option) {
    std::string e = fs::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (e != ext) throw usage_error(fmt::format("{} '{}' must end in {}", option, path, ext));
}

/// \brief Run a writer of the exr module; its failures (unwritable directory, …) are the
/// user's path, so they exit with status 2 like any other bad input.
template <class Write>
void write_output(const std::string& path, Write&& write) {
    try {
        write();
    } catch (const exr::error& e) {
        throw usage_error(one_line(e.what()));
    }
    fmt::print("wrote {}\n", path);
}

// ---- diff -----------------------------------------------------------------------------

void diff(const std::string& image_path, const std::string& reference_path, bool json) {
    const image_pair p = load_pair(image_path, reference_path);
    const image_metrics m = compare(p.test.pixels, p.reference.pixels);
    if (json) {
        // fmt's "{}" is the shortest round-trip form, a valid JSON number for finite values;
        // SSIM is undefined (NaN) below 11 × 11 and becomes null.
        const std::string ssim = std::isnan(m.ssim) ? std::string("null") : fmt::format("{}", m.ssim);
        fmt::print(
            "{{\"mse\": {}, \"relmse\": {}, \"ssim\": {}, \"max_abs\": {}, \"pixels\": {}, \"width\": {}, "
            "\"height\": {}}}\n",
            m.mse, m.relmse, ssim, m.max_abs, m.pixels, p.test.pixels.width(), p.test.pixels.height());
    } else {
        fmt::print("mse={:.6g} relmse={:.6g} ssim={:.6f} max_abs={:.6g} pixels={}\n", m.mse, m.relmse, m.ssim,
                   m.max_abs, m.pixels);
    }
}

// ---- bias -----------------------------------------------------------------------------

void bias(const std::vector<std::string>& run_paths, const std::string& reference_path, bool json) {
    if (run_paths.size() < 2)
        throw usage_error(fmt::format("bias needs at least 2 runs (renders with other seeds), got {}", run_paths.size()));
    const exr::loaded ref = load(reference_path);
    std::vector<image> runs;
    for (const auto& path : run_paths) {
        exr::loaded r = load(path);
        if (r.pixels.width() != ref.pixels.width() || r.pixels.height() != ref.pixels.height())
            throw usage_error(fmt::format("'{}' is {} but '{}' is {}: the images must have the same size", path,
                                          size_of(r.pixels), reference_path, size_of(ref.pixels)));
        runs.push_back(std::move(r.pixels));
    }
    const bias_variance_split b = bias_variance(runs, ref.pixels);
    if (json)
        fmt::print("{{\"runs\": {}, \"mse\": {}, \"variance\": {}, \"bias_sq\": {}, \"bias_sq_se\": {}}}\n", b.runs, b.mse,
                   b.variance, b.bias_sq, b.bias_sq_se);
    else
        fmt::print("runs={} mse={:.6g} variance={:.6g} bias_sq={:.6g} bias_sq_se={:.3g}\n", b.runs, b.mse, b.variance,
                   b.bias_sq, b.bias_sq_se);
}

// ---- regions --------------------------------------------------------------------------

/// Per N×N block (whole blocks only, from the top-left), the mean of each channel of both
/// images and their relative difference (IMAGE − REFERENCE) / REFERENCE; blocks whose
/// reference luminance is below `floor` × the image's mean are not compared (a relative
/// difference of near-black means nothing). For comparing two renderers region by region.
void regions(const std::string& image_path, const std::string& reference_path, int size, double floor, bool json) {
    const image_pair p = load_pair(image_path, reference_path);
    const int w = p.test.pixels.width(), h = p.test.pixels.height();
    if (size < 1 || size > w || size > h)
        throw usage_error(fmt::format("--size {} does not fit a {} image", size, size_of(p.test.pixels)));
    const auto lum = [](const rgb_pixel& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
    double mean = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) mean += lum(p.reference.pixels(x, y));
    mean /= static_cast<double>(w) * h;
    int blocks = 0, compared = 0, worst_x = -1, worst_y = -1;
    double max_rel = 0.0, sum_abs = 0.0, sum_signed = 0.0;
    for (int by = 0; by + size <= h; by += size)
        for (int bx = 0; bx + size <= w; bx += size) {
            ++blocks;
            double a[3] = {}, b[3] = {};
            for (int y = by; y < by + size; ++y)
                for (int x = bx; x < bx + size; ++x) {
                    const rgb_pixel &t = p.test.pixels(x, y), &r = p.reference.pixels(x, y);
                    a[0] += t.r, a[1] += t.g, a[2] += t.b;
                    b[0] += r.r, b[1] += r.g, b[2] += r.b;
                }
            const double n = static_cast<double>(size) * size;
            if (0.2126 * b[0] / n + 0.7152 * b[1] / n + 0.0722 * b[2] / n < floor * mean) continue;
            ++compared;
            for (int c = 0; c < 3; ++c) {
                // a channel that is itself near black (a saturated colour) is measured against the
                // block's luminance instead
                const double den = std::max(b[c], 0.2126 * b[0] + 0.7152 * b[1] + 0.0722 * b[2]);
                const double rel = den > 0.0 ? (a[c] - b[c]) / den : 0.0;
                sum_abs += std::fabs(rel) / 3.0;
                sum_signed += rel / 3.0;
                if (std::fabs(rel) > max_rel) {
                    max_rel = std::fabs(rel);
                    worst_x = bx;
                    worst_y = by;
                }
            }
        }
    const double k = compared > 0 ? 1.0 / compared : 0.0;
    if (json)
        fmt::print("{{\"regions\": {}, \"compared\": {}, \"max_rel\": {}, \"mean_abs_rel\": {}, \"mean_rel\": {}, "
                   "\"worst_x\": {}, \"worst_y\": {}}}\n",
                   blocks, compared, max_rel, sum_abs * k, sum_signed * k, worst_x, worst_y);
    else
        fmt::print("regions={} compared={} max_rel={:.4f} mean_abs_rel={:.4f} mean_rel={:+.4f} worst={},{}\n", blocks,
                   compared, max_rel, sum_abs * k, sum_signed * k, worst_x, worst_y);
}

// ---- convert --------------------------------------------------------------------------

void convert(const std::string& in, const std::string& out, const std::string& exposure_text) {
    require_extension(out, ".png", "output");
    const double exposure = parse_number(exposure_text, "--exposure (stops)");
    const exr::loaded img = load(in);
    write_output(out, [&] { exr::write_png(out, img.pixels, exposure); });
}

// ---- crop -----------------------------------------------------------------------------

struct rect {
    long long x = 0, y = 0, w = 0, h = 0;
};

rect parse_rect(const std::string& text) {
    std::vector<long long> v;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::string_view part =
            std::string_view(text).substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        long long n = 0;
        const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), n);
        if (part.empty() || ec != std::errc() || end != part.data() + part.size())
            throw usage_error(fmt::format("--rect must be X,Y,W,H (four integers), got '{}'", text));
        v.push_back(n);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (v.size() != 4) throw usage_error(fmt::format("--rect must be X,Y,W,H (four integers), got '{}'", text));
    const rect r{v[0], v[1], v[2], v[3]};
    if (r.x < 0 || r.y < 0 || r.w < 1 || r.h < 1)
        throw usage_error(fmt::format("--rect {}: X and Y must be >= 0, W and H >= 1", text));
    return r;
}

void crop(const std::string& in, const std::string& rect_text, const std::string& out) {
    require_extension(out, ".exr", "output");
    const rect r = parse_rect(rect_text);
    const exr::loaded src = load(in);
    const long long w = src.pixels.width(), h = src.pixels.height();
    // r.w and r.h are ≥ 1 and compared before adding, so the sums cannot overflow.
    if (r.x >= w || r.y >= h || r.w > w - r.x || r.h > h - r.y)
        throw usage_error(fmt::format("--rect {} (x {}..{}, y {}..{}) does not fit inside '{}', which is {}", rect_text,
                                      r.x, r.x + r.w - 1, r.y, r.y + r.h - 1, in, size_of(src.pixels)));
    image dst(static_cast<int>(r.w), static_cast<int>(r.h));
    for (int y = 0; y < dst.height(); ++y)
        for (int x = 0; x < dst.width(); ++x)
            dst(x, y) = src.pixels(static_cast<int>(r.x) + x, static_cast<int>(r.y) + y);
    // the spectral channels too, if any (the layout's attributes are in the metadata)
    exr::spectral_image spectral;
    const std::size_t n = src.spectral.count();
    spectral.wavelengths = src.spectral.wavelengths;
    for (int y = 0; y < dst.height(); ++y)
        for (int x = 0; x < dst.width(); ++x) {
            const auto i = static_cast<std::size_t>(r.y + y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(r.x + x);
            spectral.values.insert(spectral.values.end(), src.spectral.values.begin() + static_cast<std::ptrdiff_t>(i * n),
                                   src.spectral.values.begin() + static_cast<std::ptrdiff_t>((i + 1) * n));
        }
    write_output(out, [&] { exr::write(out, dst, src.meta, exr::pixel_type::float32, n > 0 ? &spectral : nullptr); });
}

// ---- spectrum ---------------------------------------------------------------------------

/// \brief The spectral channels of pixel (X, Y) — or the mean over the (2R + 1)² pixels
/// around it, clipped to the image — one `wavelength_nm value` line per channel.
void spectrum(const std::string& in, long long px, long long py, int radius, bool json) {
    const exr::loaded src = load(in);
    const std::size_t n = src.spectral.count();
    if (n == 0)
        throw usage_error(fmt::format("'{}' has no spectral channels (S0.<wavelength>nm; iris-render --spectral B writes them)", in));
    const long long w = src.pixels.width(), h = src.pixels.height();
    if (px < 0 || py < 0 || px >= w || py >= h)
        throw usage_error(fmt::format("pixel ({}, {}) is outside '{}', which is {}", px, py, in, size_of(src.pixels)));
    if (radius < 0) throw usage_error(fmt::format("--radius must be >= 0, got {}", radius));
    std::vector<double> sum(n, 0.0);
    long long count = 0;
    for (long long y = std::max(0LL, py - radius); y <= std::min(h - 1, py + radius); ++y)
        for (long long x = std::max(0LL, px - radius); x <= std::min(w - 1, px + radius); ++x) {
            const auto i = static_cast<std::size_t>(y * w + x);
            for (std::size_t b = 0; b < n; ++b) {
                const float v = src.spectral.values[i * n + b];
                if (!std::isfinite(v))
                    throw usage_error(fmt::format("'{}' has a non-finite spectral value at pixel ({}, {}), {} nm", in, x, y,
                                                  src.spectral.wavelengths[b]));
                sum[b] += static_cast<double>(v);
            }
            ++count;
        }
    if (json) {
        std::string nm, values;
        for (std::size_t b = 0; b < n; ++b) {
            nm += fmt::format("{}{}", b ? "," : "", src.spectral.wavelengths[b]);
            values += fmt::format("{}{:.9g}", b ? "," : "", sum[b] / static_cast<double>(count));
        }
        fmt::print("{{\"x\": {}, \"y\": {}, \"pixels\": {}, \"wavelength_nm\": [{}], \"value\": [{}]}}\n", px, py, count, nm,
                   values);
        return;
    }
    fmt::print("# pixel ({}, {}), mean over {} pixels, units: {}\n", px, py, count,
               src.meta.count("emissiveUnits") ? src.meta.at("emissiveUnits") : std::string("not given"));
    for (std::size_t b = 0; b < n; ++b)
        fmt::print("{} {:.9g}\n", src.spectral.wavelengths[b], sum[b] / static_cast<double>(count));
}

// ---- error-map ------------------------------------------------------------------------

/// \brief Luminance (Rec. 709 / sRGB Y weights) of the per-channel absolute difference.
std::vector<double> error_luminance(const image& a, const image& b) {
    std::vector<double> e(a.pixel_count());
    for (std::size_t i = 0; i < e.size(); ++i) {
        const rgb_pixel& p = a.pixels()[i];
        const rgb_pixel& q = b.pixels()[i];
        auto d = [](float u, float v) { return std::abs(static_cast<double>(u) - static_cast<double>(v)); };
        e[i] = 0.2126 * d(p.r, q.r) + 0.7152 * d(p.g, q.g) + 0.0722 * d(p.b, q.b);
    }
    return e;
}

/// \brief Default scale: the nearest-rank 99th percentile (the ⌈0.99 N⌉-th smallest error),
/// so a few fireflies do not flatten the rest of the map; the maximum if that is 0 (sparse
/// errors), and 1 for equal images, so the map is defined (all dark) instead of 0/0.
double default_scale(std::vector<double> e) {
    const auto rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(e.size())));
    const auto nth = e.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(rank, 1) - 1);
    std::nth_element(e.begin(), nth, e.end());
    if (*nth > 0.0) return *nth;
    const double max = *std::max_element(e.begin(), e.end());
    return max > 0.0 ? max : 1.0;
}

void error_map(const std::string& image_path, const std::string& reference_path, const std::string& out,
               const std::string& scale_text) {
    require_extension(out, ".png", "output");
    double scale = 0.0;
    if (!scale_text.empty()) {
        scale = parse_number(scale_text, "--scale");
        if (!(scale > 0.0)) throw usage_error(fmt::format("--scale must be > 0, got '{}'", scale_text));
    }
    const image_pair p = load_pair(image_path, reference_path);
    const std::vector<double> e = error_luminance(p.test.pixels, p.reference.pixels);
    const bool by_percentile = scale_text.empty();
    if (by_percentile) scale = default_scale(e);
    image map(p.test.pixels.width(), p.test.pixels.height());
    for (std::size_t i = 0; i < e.size(); ++i) {
        const rgb c = error_ramp(e[i] / scale);
        map.pixels()[i] = {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
    }
    fmt::print("scale={:.6g} ({})\n", scale, by_percentile ? "99th percentile of the error" : "--scale");
    write_output(out, [&] { exr::write_png(out, map, 0.0); });
}

// ---- flip -----------------------------------------------------------------------------

void flip_command(const std::string& image_path, const std::string& reference_path, bool ldr, const std::string& ppd_text,
                  const std::string& out, bool json) {
    if (!out.empty()) require_extension(out, ".png", "--output");
    double ppd = flip_default_ppd;
    if (!ppd_text.empty()) {
        ppd = parse_number(ppd_text, "--ppd");
        if (!(ppd > 0.0 && ppd <= 1e4)) throw usage_error(fmt::format("--ppd must be in (0, 10000], got '{}'", ppd_text));
    }
    const image_pair p = load_pair(image_path, reference_path);
    std::vector<float> map;
    flip_exposures e;
    if (ldr) {
        map = flip_map(p.test.pixels, p.reference.pixels, ppd);
    } else {
        try {
            e = flip_exposure_range(p.reference.pixels);
        } catch (const std::invalid_argument& err) {
            throw usage_error(fmt::format("'{}': {} (--ldr)", reference_path, err.what()));
        }
        map = flip_hdr_map(p.test.pixels, p.reference.pixels, ppd);
    }
    const double mean = flip_mean(map);
    if (json) {
        if (ldr)
            fmt::print("{{\"flip\": {}, \"mode\": \"ldr\", \"ppd\": {}}}\n", mean, ppd);
        else
            fmt::print("{{\"flip\": {}, \"mode\": \"hdr\", \"ppd\": {}, \"start_exposure\": {}, \"stop_exposure\": {}, "
                       "\"exposures\": {}}}\n",
                       mean, ppd, e.start, e.stop, e.count);
    } else if (ldr) {
        fmt::print("flip={:.6f} mode=ldr ppd={:.4g}\n", mean, ppd);
    } else {
        fmt::print("flip={:.6f} mode=hdr ppd={:.4g} exposures={:.4g}..{:.4g} ({})\n", mean, ppd, e.start, e.stop, e.count);
    }
    if (out.empty()) return;
    image img(p.test.pixels.width(), p.test.pixels.height());
    for (std::size_t i = 0; i < map.size(); ++i) {
        const rgb c = error_ramp(map[i]);  // ꟻLIP's errors lie in [0, 1]: the ramp's whole range
        img.pixels()[i] = {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
    }
    write_output(out, [&] { exr::write_png(out, img, 0.0); });
}

// ---- info -----------------------------------------------------------------------------

void info(const std::string& in) {
    const exr::loaded img = load(in);
    fmt::print("width={} height={}\n", img.pixels.width(), img.pixels.height());
    if (const std::size_t n = img.spectral.count(); n > 0)
        fmt::print("spectral_channels={} ({}..{} nm)\n", n, img.spectral.wavelengths.front(), img.spectral.wavelengths.back());
    for (const auto& [key, value] : img.meta) fmt::print("{}={}\n", key, one_line(value));
}

}  // namespace

void add_image_commands(CLI::App& app) {
    // Option storage lives as long as the callbacks that read it (shared ownership).
    struct options {
        std::string image, reference, out, rect, exposure = "0", scale;
        bool json = false;
    };
    auto o = std::make_shared<options>();

    auto* diff_cmd = app.add_subcommand("diff", "Print mse, relmse, ssim, max_abs and the pixel count of IMAGE "
                                                "against REFERENCE (docs/metrics.md)");
    diff_cmd->add_option("IMAGE", o->image, "EXR to measure")->required();
    diff_cmd->add_option("REFERENCE", o->reference, "reference EXR (relmse divides by it)")->required();
    diff_cmd->add_flag("--json", o->json, "print one JSON object (keys mse relmse ssim max_abs pixels width height)");
    diff_cmd->callback([o] { diff(o->image, o->reference, o->json); });

    auto region = std::make_shared<std::pair<int, double>>(20, 0.01);
    auto* regions_cmd = app.add_subcommand(
        "regions", "Compare IMAGE with REFERENCE block by block: the relative difference of each block's mean, per "
                   "channel (max, mean of its magnitude, mean with its sign) over the blocks bright enough to compare");
    regions_cmd->add_option("IMAGE", o->image, "EXR to measure")->required();
    regions_cmd->add_option("REFERENCE", o->reference, "reference EXR (the denominator)")->required();
    regions_cmd->add_option("--size", region->first, "block side in pixels")->capture_default_str();
    regions_cmd->add_option("--floor", region->second,
                            "blocks whose reference luminance is below this fraction of the image's mean are skipped")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    regions_cmd->add_flag("--json", o->json, "print one JSON object (keys regions compared max_rel mean_abs_rel mean_rel worst_x worst_y)");
    regions_cmd->callback([o, region] { regions(o->image, o->reference, region->first, region->second, o->json); });

    auto runs = std::make_shared<std::vector<std::string>>();
    auto* bias_cmd = app.add_subcommand("bias", "Split the MSE of independent runs (2 or more seeds) against "
                                                "REFERENCE into variance and squared bias (docs/metrics.md)");
    bias_cmd->add_option("RUNS", *runs, "EXRs of the same render with other seeds")->required();
    bias_cmd->add_option("-r,--reference", o->reference, "reference EXR")->required();
    bias_cmd->add_flag("--json", o->json, "print one JSON object (keys runs mse variance bias_sq bias_sq_se)");
    bias_cmd->callback([o, runs] { bias(*runs, o->reference, o->json); });

    auto* convert_cmd = app.add_subcommand("convert", "Write an 8-bit sRGB PNG of an EXR");
    convert_cmd->add_option("IMAGE", o->image, "input EXR")->required();
    convert_cmd->add_option("-o,--output", o->out, "output PNG")->required();
    convert_cmd->add_option("--exposure", o->exposure, "exposure in stops: pixels are scaled by 2^E")
        ->capture_default_str();
    convert_cmd->callback([o] { convert(o->image, o->out, o->exposure); });

    auto* crop_cmd = app.add_subcommand("crop", "Write a rectangle of an EXR as an EXR, keeping its metadata");
    crop_cmd->add_option("IMAGE", o->image, "input EXR")->required();
    crop_cmd->add_option("--rect", o->rect, "X,Y,W,H in pixels; (X, Y) is the top-left corner, y = 0 the top row")
        ->required();
    crop_cmd->add_option("-o,--output", o->out, "output EXR")->required();
    crop_cmd->callback([o] { crop(o->image, o->rect, o->out); });

    auto* map_cmd = app.add_subcommand("error-map", "Write a false-colour PNG of the per-pixel error luminance "
                                                    "|IMAGE - REFERENCE|");
    map_cmd->add_option("IMAGE", o->image, "EXR to measure")->required();
    map_cmd->add_option("REFERENCE", o->reference, "reference EXR")->required();
    map_cmd->add_option("-o,--output", o->out, "output PNG")->required();
    map_cmd->add_option("--scale", o->scale,
                        "error at the top of the colour ramp (default: the 99th percentile of the error)");
    map_cmd->callback([o] { error_map(o->image, o->reference, o->out, o->scale); });

    auto flip_opts = std::make_shared<std::pair<bool, std::string>>(false, "");
    auto* flip_cmd = app.add_subcommand("flip", "Print the mean FLIP perceptual error of IMAGE against REFERENCE "
                                                "(Andersson et al. 2020, 2021; docs/metrics.md): HDR-FLIP, or LDR-FLIP "
                                                "with --ldr");
    flip_cmd->add_option("IMAGE", o->image, "EXR to measure")->required();
    flip_cmd->add_option("REFERENCE", o->reference, "reference EXR (HDR-FLIP takes its exposures from it)")->required();
    flip_cmd->add_flag("--ldr", flip_opts->first, "LDR-FLIP of the images clamped to [0, 1] (default: HDR-FLIP)");
    flip_cmd->add_option("--ppd", flip_opts->second,
                         "pixels per degree of the viewing condition (default 67.02: 3840 pixels across 0.7 m seen from 0.7 m)");
    flip_cmd->add_option("-o,--output", o->out, "also write the per-pixel error as a false-colour PNG (0 to 1)");
    flip_cmd->add_flag("--json", o->json, "print one JSON object (keys flip mode ppd [start_exposure stop_exposure exposures])");
    flip_cmd->callback([o, flip_opts] { flip_command(o->image, o->reference, flip_opts->first, flip_opts->second, o->out, o->json); });

    auto pixel = std::make_shared<std::pair<long long, long long>>(0, 0);
    auto spectrum_radius = std::make_shared<int>(0);
    auto* spectrum_cmd = app.add_subcommand("spectrum", "Print the spectral channels (S0.<wavelength>nm) of one pixel, "
                                                        "or their mean around it, as 'wavelength_nm value' lines");
    spectrum_cmd->add_option("IMAGE", o->image, "spectral EXR (iris-render --spectral B)")->required();
    spectrum_cmd->add_option("X", pixel->first, "column (0 is the left)")->required();
    spectrum_cmd->add_option("Y", pixel->second, "row (0 is the top)")->required();
    spectrum_cmd->add_option("--radius", *spectrum_radius, "mean over the (2R+1)^2 pixels around (X, Y), clipped to the image")
        ->capture_default_str();
    spectrum_cmd->add_flag("--json", o->json, "print one JSON object (keys x y pixels wavelength_nm value)");
    spectrum_cmd->callback(
        [o, pixel, spectrum_radius] { spectrum(o->image, pixel->first, pixel->second, *spectrum_radius, o->json); });

    auto* info_cmd = app.add_subcommand("info", "Print the size and string metadata of an EXR");
    info_cmd->add_option("IMAGE", o->image, "input EXR")->required();
    info_cmd->callback([o] { info(o->image); });
}

}  // namespace iris::app
