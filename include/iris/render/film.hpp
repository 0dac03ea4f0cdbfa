#pragma once
/// \file
/// \brief The film: a per-pixel mean of XYZ over every sample (the paper's accumulation),
/// summed exactly, with non-finite and out-of-range samples dropped and counted, never
/// accumulated.
///
/// **Exact accumulation.** Each sample's X, Y and Z are added as 128-bit fixed-point
/// integers with 56 fractional bits (`fraction_bits`): v · 2^56 rounded toward zero, so a
/// sample loses less than 2^-56 ≈ 1.4·10^-17 in absolute terms (relative 1.8·10^-13 at
/// 7.8·10^-5, 10^-15 at 0.01). Integer sums are associative: a pixel's sums, and so its
/// image, do not depend on the order its samples were added in — by one thread or several,
/// in one run or split over runs (resume) or processes (MPI) — only on which samples.
/// **Range:** a sample with |X|, |Y| or |Z| ≥ 2^39 ≈ 5.5·10^11 (`max_sample`) is dropped and
/// counted like a NaN; below it, 2^32 − 1 samples per pixel (the counter's limit) cannot
/// overflow the sums: 2^39 · 2^56 · 2^32 = 2^127. The mean is the sum converted to double
/// once (rounded to nearest) and divided by the sample count.
///
/// **The fade layer** (accumulation::fade, iris/render/fade.hpp), off unless `enable_fade`
/// switches it on: the sums of the samples with index < split (taken while α < 1) kept
/// apart, and the exact second moments of both sides. `mean` stays the running mean over
/// every sample; `to_image` shows the fade's blend. The layer's state (`fade_state`, and
/// `from_parts` with it) is exact like the sums, so checkpoints and the ranks' reduction
/// carry it, and a fading render resumed or distributed gives the same image bit for bit.
///
/// **Splats** (`add_pass`): an estimator that adds light to pixels other than its sample's
/// own (light tracing, bidirectional connections to the camera) hands the film a whole pass
/// of splats; each pixel takes one sample per pass, the exact sum of what landed on it. The
/// state above stays what it is, so all of it holds for such renders too.
///
/// **The spectral layer** (`enable_spectral`, off unless switched on): per pixel, the
/// exact sums of each sample's point contributions per band (iris/render/spectral_bands.hpp),
/// in the same fixed point as XYZ — 16 bytes per band per pixel (`spectral_bytes_per_band`).
/// A sample's row is summed where its XYZ is; a row with a band out of range while its XYZ
/// is summable adds nothing and is counted (`spectral_dropped`). Checkpoints and the ranks'
/// reduction carry it, so it is as exact and deterministic as the XYZ sums. Splatting
/// estimators (add_pass) have no spectral layer.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "iris/image.hpp"
#include "iris/render/fade.hpp"
#include "iris/render/spectral_bands.hpp"
#include "iris/spectrum/color.hpp"

namespace iris {

__extension__ typedef __int128 exact_int;  ///< GCC and Clang; the film's only non-standard type

/// \brief A pixel's exact sums: X, Y, Z in fixed point (film::fraction_bits fractional bits).
struct exact_xyz {
    exact_int x = 0, y = 0, z = 0;
    friend bool operator==(const exact_xyz&, const exact_xyz&) = default;
};

/// \brief A contribution to one pixel from anywhere in a pass: a light path's vertex
/// connected to the camera lands on the pixel it projects to, not on the pixel whose
/// sample made it (`film::add_pass`).
struct splat {
    std::uint32_t pixel = 0;  ///< row-major index
    xyz value;
};

class film {
public:
    static constexpr int fraction_bits = 56;
    static constexpr double max_sample = 0x1p39;

    film(int width, int height)
        : m_width(width), m_height(height), m_sum(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
          m_count(m_sum.size(), 0), m_dropped(m_sum.size(), 0) {}

    /// \brief Memory per pixel: the exact XYZ sums (3 × 16 bytes) and two 32-bit counters.
    static constexpr std::size_t bytes_per_pixel = sizeof(exact_xyz) + 2 * sizeof(std::uint32_t);

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }

    /// \brief Whether a sample's value can be summed: finite and |v| < max_sample.
    static constexpr bool summable(double v) noexcept { return std::fabs(v) < max_sample; }  // false for NaN

    /// \brief v in fixed point, rounded toward zero (exact for |v| < max_sample): the same as
    /// static_cast<exact_int>(v · 2^56), without the library call that conversion is (≈ 20 ns
    /// for three). w = v · 2^56 is exact; its high part h = trunc(w · 2^-40) and the rest
    /// w − h · 2^40 (exact: it is w's low mantissa bits, |·| < 2^40) have the sign of w, so
    /// trunc(w) = h · 2^40 + trunc(rest), each part a 64-bit conversion.
    static exact_int to_fixed(double v) noexcept {
        const double w = v * 0x1p56;
        const auto h = static_cast<std::int64_t>(w * 0x1p-40);
        const auto rest = static_cast<std::int64_t>(w - static_cast<double>(h) * 0x1p40);
        return static_cast<exact_int>(h) * (std::int64_t{1} << 40) + rest;
    }

    /// \brief Add one sample to pixel `i`; a NaN/Inf or out-of-range sample still counts as
    /// a sample taken (so the mean is not biased upwards) but contributes 0, and is counted.
    /// `sample` is its 0-based index in the pixel: the fade layer's side (ignored without it).
    void add(std::size_t i, const xyz& v, std::uint64_t sample = 0) noexcept {
        ++m_count[i];
        const bool ok = summable(v.x) && summable(v.y) && summable(v.z);
        if (ok) {
            m_sum[i].x += to_fixed(v.x);
            m_sum[i].y += to_fixed(v.y);
            m_sum[i].z += to_fixed(v.z);
        } else {
            ++m_dropped[i];
        }
        if (m_fade) m_fade->add(i, ok ? v : xyz{}, sample);
    }

    /// \brief `add` with the sample's spectral row (`spectral_bands().count` values, which
    /// are read and set to 0): summed into the spectral layer where the XYZ value is summed.
    /// Only with the spectral layer.
    void add(std::size_t i, const xyz& v, std::uint64_t sample, double* row) noexcept {
        add(i, v, sample);
        spectral_parts& sp = *m_spectral;
        const auto n = static_cast<std::size_t>(sp.bands.count);
        const bool xyz_ok = summable(v.x) && summable(v.y) && summable(v.z);
        bool ok = xyz_ok;
        for (std::size_t o = 0; o < n; ++o) ok = ok && summable(row[o]);
        if (ok) {
            exact_int* s = &sp.sums[i * n];
            for (std::size_t o = 0; o < n; ++o) s[o] += to_fixed(row[o]);
        } else if (xyz_ok) {
            ++sp.dropped;
        }
        for (std::size_t o = 0; o < n; ++o) row[o] = 0.0;
    }

    /// \brief The spectral layer's state: its bands, per pixel (row-major) the exact sums of
    /// every band's contributions, and the rows dropped while their XYZ was summed.
    struct spectral_parts {
        spectral_bands bands;
        std::vector<exact_int> sums;  ///< pixel i's band o at i · bands.count + o
        std::uint64_t dropped = 0;
    };
    /// \brief Switch the spectral layer on (a film without samples). Memory:
    /// spectral_bytes_per_band · bands.count more per pixel.
    /// \throws std::logic_error if the film has samples, std::invalid_argument for no bands
    /// or an empty range.
    void enable_spectral(const spectral_bands& bands) {
        for (auto c : m_count)
            if (c != 0) throw std::logic_error("film::enable_spectral: the film already has samples");
        if (bands.count < 1 || !(bands.lambda_max > bands.lambda_min))
            throw std::invalid_argument("film::enable_spectral: no bands, or an empty wavelength range");
        m_spectral.emplace(spectral_parts{bands, std::vector<exact_int>(m_sum.size() * static_cast<std::size_t>(bands.count)), 0});
    }
    static constexpr std::size_t spectral_bytes_per_band = sizeof(exact_int);
    /// \brief The spectral layer (nullptr without one).
    const spectral_parts* spectral_state() const noexcept { return m_spectral ? &*m_spectral : nullptr; }
    /// \brief Pixel i's mean spectral radiance per band (`out` has bands.count entries): the
    /// band's sum ÷ (samples · band width) — 0 before the first sample. Only with the layer.
    void spectral_mean(std::size_t i, double* out) const noexcept {
        const spectral_parts& sp = *m_spectral;
        const auto n = static_cast<std::size_t>(sp.bands.count);
        const double d = static_cast<double>(m_count[i]) * sp.bands.width();
        for (std::size_t o = 0; o < n; ++o) out[o] = m_count[i] == 0 ? 0.0 : static_cast<double>(sp.sums[i * n + o]) * 0x1p-56 / d;
    }

    /// \brief Add one pass of an estimator that splats (light tracing, bidirectional
    /// connections to the camera): every pixel takes **one sample**, the sum of the splats
    /// that landed on it in this pass — 0 where none did. `lists` is a range of ranges of
    /// `splat` (one list per thread, in any order); `sample` is the pass's index (the fade
    /// layer's side).
    ///
    /// A pass is a sample, so everything the film keeps per sample keeps its meaning: counts
    /// (one per pixel per pass), the running mean, the fade layer's early and late sides and
    /// their variances (of per-pass totals), checkpoints (taken between passes) and the ranks'
    /// reduction (ranks render whole passes). Splats are summed exactly like samples, so the
    /// pass does not depend on how they were split into lists or ordered: threads and tiles
    /// change nothing. A splat that is not finite or out of range (|v| ≥ max_sample) makes
    /// its pixel's pass sample a dropped one (0, counted once), as a non-finite sample is;
    /// so does a pass total out of range. The sum of a pixel's splats cannot overflow: fewer
    /// than 2^32 splats (checked) of |v| < 2^39 stay below 2^127.
    /// Scratch memory while the film is used this way: pass_bytes_per_pixel.
    /// \throws std::out_of_range for a splat's pixel outside the film, std::length_error
    /// for 2^32 or more splats in one pass.
    template <class Lists>
    void add_pass(const Lists& lists, std::uint64_t sample) {
        begin_pass();
        for (const auto& list : lists) add_splats(list);
        end_pass(sample);
    }

    /// \name A pass of splats in pieces
    /// `add_pass` as three steps, so that an estimator can hand over its splats in chunks
    /// while it renders and keep its lists short (the renderer's splatting loops flush a
    /// thread's list every `splat_chunk` splats): `begin_pass`, any number of `add_splats`
    /// (one caller at a time), `end_pass`. The pass's sums are exact, so how the splats were
    /// chunked changes nothing.
    /// @{
    void begin_pass() {
        if (m_spectral) throw std::logic_error("film: a pass of splats cannot fill a spectral layer");
        const std::size_t n = m_sum.size();
        m_pass.assign(n, exact_xyz{});
        m_pass_bad.assign(n, 0);
        m_pass_splats = 0;
    }
    template <class List>
    void add_splats(const List& list) {
        const std::size_t n = m_pass.size();
        for (const splat& s : list) {
            if (s.pixel >= n) throw std::out_of_range("film::add_pass: a splat outside the film");
            if (++m_pass_splats > UINT32_MAX) throw std::length_error("film::add_pass: 2^32 or more splats in one pass");
            if (!(summable(s.value.x) && summable(s.value.y) && summable(s.value.z))) {
                m_pass_bad[s.pixel] = 1;
                continue;
            }
            exact_xyz& p = m_pass[s.pixel];
            p.x += to_fixed(s.value.x);
            p.y += to_fixed(s.value.y);
            p.z += to_fixed(s.value.z);
        }
    }
    void end_pass(std::uint64_t sample) {
        const std::size_t n = m_sum.size();
        for (std::size_t i = 0; i < n; ++i) {
            ++m_count[i];
            const exact_xyz& t = m_pass[i];
            const xyz v{static_cast<double>(t.x) * 0x1p-56, static_cast<double>(t.y) * 0x1p-56,
                        static_cast<double>(t.z) * 0x1p-56};
            const bool ok = !m_pass_bad[i] && summable(v.x) && summable(v.y) && summable(v.z);
            if (ok) {
                m_sum[i].x += t.x;
                m_sum[i].y += t.y;
                m_sum[i].z += t.z;
            } else {
                ++m_dropped[i];
            }
            if (m_fade) m_fade->add_fixed(i, ok ? t : exact_xyz{}, ok ? v : xyz{}, sample);
        }
    }
    /// @}
    /// \brief Splats a splatting loop gathers per thread before it hands them to the pass
    /// (32 bytes each: 2 MiB per thread at most, whatever the image size).
    static constexpr std::size_t splat_chunk = std::size_t{1} << 16;
    /// \brief Scratch bytes per pixel of `add_pass`: a pass's exact sums and a flag.
    static constexpr std::size_t pass_bytes_per_pixel = sizeof(exact_xyz) + 1;

    /// \brief Switch the fade layer on (a film without samples): samples with index < `split`
    /// (N_thold) are the early side. Memory: fade_bytes_per_pixel more per pixel.
    /// \throws std::logic_error if the film has samples.
    void enable_fade(std::uint32_t split) {
        for (auto c : m_count)
            if (c != 0) throw std::logic_error("film::enable_fade: the film already has samples");
        m_fade.emplace(m_sum.size(), split);
    }
    bool fades() const noexcept { return m_fade.has_value(); }
    static constexpr std::size_t fade_bytes_per_pixel =
        sizeof(exact_xyz) + sizeof(std::uint32_t) + 6 * sizeof(fade::square_sum);

    /// \brief Pixel `i`'s early (index < split) and late samples per channel (X, Y, Z): count,
    /// mean, variance of the mean. Only with the fade layer.
    std::array<std::pair<fade::side, fade::side>, 3> fade_sides(std::size_t i) const noexcept {
        const auto& l = *m_fade;
        const double n = m_count[i], nb = l.early_count[i], nu = n - nb;
        const exact_int early[3] = {l.early_sum[i].x, l.early_sum[i].y, l.early_sum[i].z};
        const exact_int all[3] = {m_sum[i].x, m_sum[i].y, m_sum[i].z};
        std::array<std::pair<fade::side, fade::side>, 3> out;
        for (std::size_t c = 0; c < 3; ++c)
            out[c] = {fade::make_side(nb, static_cast<double>(early[c]) * 0x1p-56, l.early_sq[i][c].value()),
                      fade::make_side(nu, static_cast<double>(all[c] - early[c]) * 0x1p-56, l.late_sq[i][c].value())};
        return out;
    }

    /// \brief The fade's blend of every pixel (fade.hpp), row-major: each pixel's weight from
    /// the sums over its (2·radius + 1)² neighbourhood clipped to the image (pixels with fewer
    /// than 2 samples on a side left out); the running mean where the pixel itself has fewer
    /// than 2 samples on a side. Only with the fade layer. Works through the film row by row,
    /// keeping the statistics of the 2·radius + 1 rows a neighbourhood spans: O(width)
    /// memory beside the result (`to_image` writes straight into the image). Cost:
    /// bench/fade_bench.cpp.
    std::vector<xyz> faded(int radius = fade_radius) const {
        std::vector<xyz> out(m_sum.size());
        for_each_faded(radius, [&](std::size_t i, const xyz& v) { out[i] = v; });
        return out;
    }
    /// \brief `faded`'s values, handed to `f(i, value)` pixel by pixel (row-major) instead of
    /// stored.
    template <class F>
    void for_each_faded(int radius, F&& f) const {
        const std::size_t w = static_cast<std::size_t>(m_width);
        const int rows = 2 * radius + 1;
        struct pixel_stats {
            std::array<std::pair<fade::side, fade::side>, 3> sides;
            fade::weight_sums own;  // zero unless usable
            bool usable = false;
        };
        std::vector<pixel_stats> ring(static_cast<std::size_t>(rows) * w);
        const auto slot = [&](int y) { return static_cast<std::size_t>(y % rows) * w; };
        const auto load_row = [&](int y) {
            for (std::size_t x = 0; x < w; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * w + x;
                pixel_stats& p = ring[slot(y) + x];
                p.sides = fade_sides(i);
                p.usable = p.sides[0].first.n >= 2 && p.sides[0].second.n >= 2;
                p.own = {};
                if (p.usable)
                    for (const auto& [early, late] : p.sides) p.own.add(early, late);
            }
        };
        for (int y = 0; y < std::min(radius, m_height); ++y) load_row(y);
        for (int y = 0; y < m_height; ++y) {
            if (y + radius < m_height) load_row(y + radius);
            for (int x = 0; x < m_width; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
                const pixel_stats& p = ring[slot(y) + static_cast<std::size_t>(x)];
                if (!p.usable) {
                    f(i, mean(i));
                    continue;
                }
                fade::weight_sums sums;
                for (int yy = std::max(0, y - radius); yy <= std::min(m_height - 1, y + radius); ++yy)
                    for (int xx = std::max(0, x - radius); xx <= std::min(m_width - 1, x + radius); ++xx) {
                        const auto& o = ring[slot(yy) + static_cast<std::size_t>(xx)].own;
                        sums.var_late += o.var_late;
                        sums.var_both += o.var_both;
                        sums.diff_sq += o.diff_sq;
                    }
                const double nb = p.sides[0].first.n, nu = p.sides[0].second.n;
                const double wt = fade::weight(sums, nb / (nb + nu));
                const auto blend = [&](std::size_t c) { return wt * p.sides[c].first.mean + (1 - wt) * p.sides[c].second.mean; };
                f(i, xyz{blend(0), blend(1), blend(2)});
            }
        }
    }
    /// \brief The neighbourhood radius of the fade's weights: 5 × 5 pixels.
    static constexpr int fade_radius = 2;

    /// \brief The fade layer's state (enable_fade): the split, and per pixel (row-major) the
    /// early samples' exact XYZ sums and count, and both sides' exact sums of squares (X, Y, Z).
    struct fade_parts {
        std::uint32_t split = 0;
        std::vector<exact_xyz> early_sum;
        std::vector<std::uint32_t> early_count;
        std::vector<std::array<fade::square_sum, 3>> early_sq, late_sq;
        fade_parts() = default;
        fade_parts(std::size_t pixels, std::uint32_t split_at)
            : split(split_at), early_sum(pixels), early_count(pixels, 0), early_sq(pixels), late_sq(pixels) {}
        void add(std::size_t i, const xyz& v, std::uint64_t sample) noexcept {
            add_fixed(i, {to_fixed(v.x), to_fixed(v.y), to_fixed(v.z)}, v, sample);
        }
        /// A sample whose fixed-point value `t` (what the film's sums took) is known;
        /// `v` is its value for the squares.
        void add_fixed(std::size_t i, const exact_xyz& t, const xyz& v, std::uint64_t sample) noexcept {
            const bool early = sample < split;
            auto& sq = early ? early_sq[i] : late_sq[i];
            sq[0].add(fade::to_fixed_square(v.x));
            sq[1].add(fade::to_fixed_square(v.y));
            sq[2].add(fade::to_fixed_square(v.z));
            if (!early) return;
            ++early_count[i];
            early_sum[i].x += t.x;
            early_sum[i].y += t.y;
            early_sum[i].z += t.z;
        }
        void merge(const fade_parts& o) noexcept {
            for (std::size_t i = 0; i < early_sum.size(); ++i) {
                early_sum[i].x += o.early_sum[i].x;
                early_sum[i].y += o.early_sum[i].y;
                early_sum[i].z += o.early_sum[i].z;
                early_count[i] += o.early_count[i];
                for (std::size_t c = 0; c < 3; ++c) {
                    early_sq[i][c].add(o.early_sq[i][c]);
                    late_sq[i][c].add(o.late_sq[i][c]);
                }
            }
        }
    };

    /// \brief The fade layer (nullptr without one): what checkpoints store and ranks sum.
    const fade_parts* fade_state() const noexcept { return m_fade ? &*m_fade : nullptr; }

    /// \brief Mean XYZ of pixel `i` (0 before its first sample).
    xyz mean(std::size_t i) const noexcept {
        const double n = static_cast<double>(m_count[i]);
        if (n == 0) return {};
        const auto v = [&](exact_int s) { return static_cast<double>(s) * 0x1p-56 / n; };
        return {v(m_sum[i].x), v(m_sum[i].y), v(m_sum[i].z)};
    }

    /// \brief Samples dropped so far (non-finite or out of range), over all pixels.
    std::uint64_t dropped() const noexcept {
        std::uint64_t n = 0;
        for (auto d : m_dropped) n += d;
        return n;
    }
    std::uint32_t samples(std::size_t i) const noexcept { return m_count[i]; }

    /// \brief Pixel `i`'s exact sums.
    const exact_xyz& sum(std::size_t i) const noexcept { return m_sum[i]; }

    /// \brief The whole state, pixel by pixel (row-major): what a checkpoint stores and
    /// what ranks exchange. `from_parts` rebuilds a film from it.
    std::span<const exact_xyz> sums() const noexcept { return m_sum; }
    std::span<const std::uint32_t> counts() const noexcept { return m_count; }
    std::span<const std::uint32_t> dropped_counts() const noexcept { return m_dropped; }

    /// \brief A film with the given state, with a fade layer if `fade` is given.
    /// \throws std::invalid_argument if a part does not have width · height entries, a pixel
    /// has more dropped samples than samples, or (fade layer) the split is 0 or a pixel has
    /// more early samples than samples or than the split.
    static film from_parts(int width, int height, std::vector<exact_xyz> sums, std::vector<std::uint32_t> counts,
                           std::vector<std::uint32_t> dropped, std::optional<fade_parts> fade = std::nullopt,
                           std::optional<spectral_parts> spectral = std::nullopt) {
        film f(0, 0);
        const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
        if (width < 0 || height < 0 || sums.size() != n || counts.size() != n || dropped.size() != n)
            throw std::invalid_argument("film::from_parts: the parts do not have width x height entries");
        for (std::size_t i = 0; i < n; ++i)
            if (dropped[i] > counts[i]) throw std::invalid_argument("film::from_parts: more dropped samples than samples");
        if (fade) {
            if (fade->split == 0) throw std::invalid_argument("film::from_parts: a fade layer that splits at sample 0");
            if (fade->early_sum.size() != n || fade->early_count.size() != n || fade->early_sq.size() != n ||
                fade->late_sq.size() != n)
                throw std::invalid_argument("film::from_parts: the fade layer does not have width x height entries");
            for (std::size_t i = 0; i < n; ++i)
                if (fade->early_count[i] > counts[i] || fade->early_count[i] > fade->split)
                    throw std::invalid_argument("film::from_parts: a pixel has more early samples than samples or than the split");
        }
        if (spectral && (spectral->bands.count < 1 || !(spectral->bands.lambda_max > spectral->bands.lambda_min) ||
                         spectral->sums.size() != n * static_cast<std::size_t>(spectral->bands.count)))
            throw std::invalid_argument("film::from_parts: the spectral layer has no bands or not width x height x bands sums");
        f.m_fade = std::move(fade);
        f.m_spectral = std::move(spectral);
        f.m_width = width;
        f.m_height = height;
        f.m_sum = std::move(sums);
        f.m_count = std::move(counts);
        f.m_dropped = std::move(dropped);
        return f;
    }

    /// \brief Add another film's samples to this one's, exactly: the result is the film
    /// that took both films' samples (in any order). \throws std::invalid_argument for
    /// another size, std::overflow_error if a pixel's sample count would pass 2^32 − 1.
    void merge(const film& other) {
        if (other.m_width != m_width || other.m_height != m_height)
            throw std::invalid_argument("film::merge: the films differ in size");
        if (fades() != other.fades() || (fades() && m_fade->split != other.m_fade->split))
            throw std::invalid_argument("film::merge: one film fades and the other does not, or they split at different samples");
        if (m_spectral.has_value() != other.m_spectral.has_value() ||
            (m_spectral && m_spectral->bands != other.m_spectral->bands))
            throw std::invalid_argument("film::merge: the films' spectral layers differ (one has none, or other bands)");
        for (std::size_t i = 0; i < m_sum.size(); ++i)
            if (other.m_count[i] > UINT32_MAX - m_count[i]) throw std::overflow_error("film::merge: more than 2^32 - 1 samples in a pixel");
        if (m_fade) m_fade->merge(*other.m_fade);
        if (m_spectral) {
            for (std::size_t k = 0; k < m_spectral->sums.size(); ++k) m_spectral->sums[k] += other.m_spectral->sums[k];
            m_spectral->dropped += other.m_spectral->dropped;
        }
        for (std::size_t i = 0; i < m_sum.size(); ++i) {
            m_sum[i].x += other.m_sum[i].x;
            m_sum[i].y += other.m_sum[i].y;
            m_sum[i].z += other.m_sum[i].z;
            m_count[i] += other.m_count[i];
            m_dropped[i] += other.m_dropped[i];
        }
    }

    /// \brief The image as linear sRGB: the running mean, or with the fade layer the fade's blend.
    image to_image() const {
        image img(m_width, m_height);
        for_each_shown([&](std::size_t i, const xyz& v) {
            const rgb c = xyz_to_linear_srgb(v);
            img.pixels()[i] = {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
        });
        return img;
    }

    /// \brief f(i, v) for every pixel i with the XYZ value `to_image` shows: the running
    /// mean, or with the fade layer the fade's blend (for callers that write the image
    /// straight into a buffer of their own, e.g. the Python module's numpy arrays).
    template <class F>
    void for_each_shown(F&& f) const {
        if (m_fade)
            for_each_faded(fade_radius, f);
        else
            for (std::size_t i = 0; i < m_sum.size(); ++i) f(i, mean(i));
    }

private:
    int m_width, m_height;
    std::vector<exact_xyz> m_sum;
    std::vector<std::uint32_t> m_count;
    std::vector<std::uint32_t> m_dropped;
    std::optional<fade_parts> m_fade;
    std::optional<spectral_parts> m_spectral;
    std::vector<exact_xyz> m_pass;           ///< add_pass's scratch: this pass's sums
    std::vector<unsigned char> m_pass_bad;   ///< add_pass's scratch: a pixel took a bad splat
    std::uint64_t m_pass_splats = 0;         ///< splats added to the current pass
};

}  // namespace iris
