#pragma once
/// \file
/// \brief The renderer's random stream: the numbers of one sample of one pixel, from one of
/// three samplers. Every number is a pure function of (sampler, seed, pixel, sample index,
/// dimension) — and for `zsobol` of the image size and spp as well — so no pixel depends on
/// tiling, thread count or instruction set.
///
/// | sampler | a pixel's numbers |
/// |---|---|
/// | `independent` | `counter_rng` (sampling/random.hpp): a hash of (seed, pixel, sample, dimension) |
/// | `sobol` | Owen-scrambled Sobol' points (Joe & Kuo's direction numbers, sampling/sobol.hpp): the sample index shuffled once per (seed, pixel), each slot one Sobol' dimension (a 2-D slot: the dimension and its (0, 2) partner), each coordinate scrambled with its own key (Burley 2020) |
/// | `zsobol` | the same points indexed in Morton order over the image, index = (Morton(x, y) ≪ ⌈log₂ spp⌉) + sample, shuffled and scrambled per seed only, so that neighbouring pixels share one net and their errors are distributed as blue noise (Ahmed & Wonka 2020; pbrt-v4's ZSobolSampler) |
///
/// One index shuffle for all slots keeps the Sobol' points' joint structure: a pixel's
/// samples are stratified across slots (pixel footprint × wavelength × light point), not
/// only within each, which is what makes the error fall faster than 1/N (docs/results.md).
/// Padded samplers (a shuffle per slot, as pbrt-v4's PaddedSobol and ZSobol) pair the slots
/// at random and fall as 1/N; iris pads only the slots past its table (bounce 50 on).
///
/// **Dimension layout.** The path tracer asks for its numbers in *slots*, each a 1-D or a
/// 2-D point; for the low-discrepancy samplers a slot is one Sobol' dimension, chosen by
/// scripts/gen_sobol_slots.py (data/sobol_slots.hpp) so that no two coordinates of the
/// camera and of neighbouring bounces are nearly the same digits (the worst t-value of
/// their 2-D projections is 4 at m ≤ 10; taking dimension slot + 1 gives t = 9 between
/// the pixel's y and the light point's y, and a floor in the error):
///
/// | slot | what | kind |
/// |---|---|---|
/// | 0 | pixel jitter | 2-D |
/// | 1 | the hero wavelength's u | 1-D |
/// | 2 | the B term's bin jitter (only while it runs) | 1-D |
/// | 3 + 5k | bounce k: light point | 2-D |
/// | 4 + 5k | bounce k: light choice | 1-D |
/// | 5 + 5k | bounce k: lobe choice (reflect or refract) | 1-D |
/// | 6 + 5k | bounce k: BSDF direction | 2-D |
/// | 7 + 5k | bounce k: Russian roulette | 1-D |
///
/// `start_bounce(k)` moves to slot 3 + 5k, so a slot skipped (no B term, no next-event
/// estimation at a delta vertex) never shifts the slots after it. A bounce (or the camera
/// part, slots 0–2) that draws more than its slots does not read the next bounce's: its
/// extra draws come from slots of its own past the table (`overflow_slot`), padded as the
/// slots past bounce 50 are — never a number another draw of the sample reads, at the cost
/// of their stratification (`overflows()` counts the bounces that overflowed; the path
/// tracer never does, tests/render/sampler_test.cpp). A free flight through a scattering
/// medium reads one padded slot of its bounce's own (`next_medium`), outside this layout: the
/// distance is not stratified across samples (docs/method.md §10). The `independent`
/// sampler ignores the layout and numbers its draws consecutively, as iris always did: its
/// images are the ones of the releases before the samplers.
///
/// A pixel's first 2^m samples are a (0, m, 2)-net in every 2-D slot and one point per
/// stratum of width 2^-m in every 1-D slot, for both Sobol' samplers (tests/render/sampler_test.cpp).
///
/// **Relaxation and stratification.** Slot 1 stratifies the hero's u over a pixel's samples,
/// but sample i maps its u through the inverse CDF of p_α with α = curve(i / N_thold), which
/// changes with i. The wavelengths are therefore stratified exactly only once α has reached 1
/// (or for `hwss`, whose p_α does not change); while α grows, 2^m consecutive samples see 2^m
/// slightly different maps, and the strata in λ overlap by how much the CDF moves over them
/// (for the linear curve and 512 samples, at most 2^m / 512 of the way from p_0 to p_1). The
/// B term's jitter (slot 2) is stratified the same way over the bins. docs/results.md measures
/// what this costs: `paper`'s error with a Sobol' sampler relative to independent sampling,
/// against the same ratio for `hwss`.
/// Any spp works; `zsobol` supports images up to 65 536 pixels on a side and 2³² spp.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <optional>
#include <string_view>

#include <glm/vec2.hpp>

#include "iris/sampling/data/sobol_slots.hpp"
#include "iris/sampling/random.hpp"
#include "iris/sampling/sobol.hpp"

namespace iris {

enum class sampler_kind : std::uint8_t { independent, sobol, zsobol };

/// \brief The CLI name of a sampler.
constexpr std::string_view sampler_name(sampler_kind k) noexcept {
    switch (k) {
        case sampler_kind::sobol: return "sobol";
        case sampler_kind::zsobol: return "zsobol";
        default: return "independent";
    }
}

/// \brief The sampler called `name`, if any.
constexpr std::optional<sampler_kind> parse_sampler(std::string_view name) noexcept {
    for (auto k : {sampler_kind::independent, sampler_kind::sobol, sampler_kind::zsobol})
        if (name == sampler_name(k)) return k;
    return std::nullopt;
}

/// \brief What a render's streams share: the sampler, the seed and, for `zsobol`, the
/// sizes of its Morton-ordered index.
struct sampler_setup {
    sampler_kind kind = sampler_kind::independent;
    std::uint64_t seed = 0;
    int log2_spp = 0;  ///< ⌈log₂ spp⌉ (zsobol)

    static constexpr sampler_setup make(sampler_kind kind, std::uint64_t seed, std::uint64_t spp) noexcept {
        return {kind, seed, spp > 1 ? static_cast<int>(std::bit_width(spp - 1)) : 0};
    }
};

class sample_stream {
public:
    static constexpr std::uint32_t pixel_slot = 0, hero_slot = 1, bterm_slot = 2;
    static constexpr std::uint32_t first_bounce_slot = 3, slots_per_bounce = 5;

    /// \brief The `independent` stream of (seed, pixel, sample).
    constexpr sample_stream(std::uint64_t seed, std::uint64_t pixel = 0, std::uint64_t sample = 0) noexcept
        : m_rng(seed, pixel, sample) {}

    /// \brief The stream of sample `sample` of pixel (x, y), `pixel` = y · width + x.
    constexpr sample_stream(const sampler_setup& s, std::uint32_t x, std::uint32_t y, std::uint64_t pixel,
                            std::uint64_t sample) noexcept
        : m_rng(s.kind == sampler_kind::independent ? counter_rng(s.seed, pixel, sample) : counter_rng(0)),
          m_kind(s.kind),
          m_sample(sample) {  // (counter_rng(0) folds to a constant: the Sobol' streams skip its hashes)
        if (m_kind == sampler_kind::sobol) {
            m_key = detail::counter_hash(detail::counter_hash(s.seed ^ 0x50b01ull) ^ pixel);
            const auto shuffle = static_cast<std::uint32_t>(m_key >> 32);
            m_index = sobol::shuffle_index(static_cast<std::uint32_t>(sample), shuffle) ^ sobol::shuffle_index(0, shuffle);
        } else if (m_kind == sampler_kind::zsobol) {
            m_sample = (static_cast<std::uint64_t>(sobol::morton2(x, y)) << s.log2_spp) + sample;
            const std::uint64_t key = detail::counter_hash(s.seed ^ 0x25b01ull);
            m_index = sobol::shuffle_index64(m_sample, key) ^ sobol::shuffle_index64(0, key);
            // bits of the Morton index past 32 do not reach a 32-bit point: they key the
            // scrambling instead, so far-apart image blocks do not repeat one pattern
            m_key = detail::counter_hash(key ^ (m_index >> 32));
        }
    }

    /// \brief Where the extra draws of bounce k (k = −1: the camera's slots) go: 2¹⁶ slots
    /// of its own, far past every bounce's (bounce k's first slot is 3 + 5k < 2³¹ for any
    /// path length a render allows), read as padded slots.
    static constexpr std::uint32_t overflow_slot(int k) noexcept {
        return 0x80000000u + (static_cast<std::uint32_t>(k + 1) << 16);
    }

    /// \brief The next 1-D slot, in [0, 1).
    constexpr float next() noexcept {
        if (m_kind == sampler_kind::independent) return m_rng.next();
        const point p = at(take(), false);
        return p.x;
    }

    /// \brief The next 2-D slot, in [0, 1)².
    constexpr glm::vec2 next2() noexcept {
        if (m_kind == sampler_kind::independent) {
            const float a = m_rng.next();
            return {a, m_rng.next()};
        }
        const point p = at(take(), true);
        return {p.x, p.y};
    }

    /// \brief The number of the current bounce's free flight through a scattering medium
    /// (iris/render/medium.hpp): one padded slot per bounce (`medium_slot`), read without
    /// moving the bounce's own slots, so scenes without media keep every number they had; the
    /// next number for `independent`. A bounce flies at most once (a scattering in the
    /// medium is the next bounce).
    constexpr float next_medium() noexcept {
        if (m_kind == sampler_kind::independent) return m_rng.next();
        return at(medium_slot(m_bounce), false).x;
    }
    /// \brief Bounce k's free-flight slot: past the table and every bounce's slots, below the
    /// overflow slots (`overflow_slot`).
    static constexpr std::uint32_t medium_slot(int k) noexcept {
        return 0x40000000u + static_cast<std::uint32_t>(k + 1);
    }

    /// \brief Move to bounce k's first slot (a no-op for `independent`).
    constexpr void start_bounce(int k) noexcept {
        if (m_kind != sampler_kind::independent) {
            m_slot = first_bounce_slot + slots_per_bounce * static_cast<std::uint32_t>(k);
            m_end = m_slot + slots_per_bounce;
            m_bounce = k;
        }
    }

    /// \brief The slot the next draw reads (low-discrepancy samplers).
    constexpr std::uint32_t slot() const noexcept { return m_slot; }
    /// \brief How many bounces (or the camera part) drew past their slots (low-discrepancy samplers).
    constexpr std::uint32_t overflows() const noexcept { return m_overflows; }

private:
    struct point {
        float x, y;
    };
    /// \brief The slot of the next draw: the next of the bounce's own, or past them its
    /// overflow slots.
    constexpr std::uint32_t take() noexcept {
        if (m_slot == m_end) [[unlikely]] {
            m_slot = overflow_slot(m_bounce);
            m_end = m_slot + 0x10000u;
            ++m_overflows;
        }
        return m_slot++;
    }
    /// \brief Slot `slot`'s point: the slot's Sobol' dimension d (data/sobol_slots.hpp; the
    /// pixel slot: d = 0) of the stream's shuffled index, with its (0, 2) partner for a 2-D slot (sobol::paired), each
    /// coordinate Owen-scrambled with its own seed. Past the table of dimensions, `padded`.
    constexpr point at(std::uint32_t slot, bool two) const noexcept {
        const auto& table = data::sobol_slots::dimension;
        if (slot >= table.size()) return padded(slot, two);
        const std::uint32_t d = table[slot];
        const std::uint64_t h = detail::counter_hash(m_key + slot);
        const std::uint32_t x = sobol::point(static_cast<std::uint32_t>(m_index), d);
        const float a = sobol::to_unit(sobol::owen_scramble(x, static_cast<std::uint32_t>(h)));
        if (!two) return {a, 0.0f};
        return {a, sobol::to_unit(sobol::owen_scramble(sobol::paired(x), static_cast<std::uint32_t>(h >> 32)))};
    }

    /// \brief A slot past the table: dimensions 0 and 1 of the sample index shuffled for this
    /// slot alone (padding), Owen-scrambled for the slot.
    constexpr point padded(std::uint32_t slot, bool two) const noexcept {
        const std::uint64_t h = detail::counter_hash(m_key + slot + 0x9adull);
        const std::uint32_t i = m_kind == sampler_kind::sobol
                                    ? sobol::shuffle_index(static_cast<std::uint32_t>(m_sample), static_cast<std::uint32_t>(h))
                                    : static_cast<std::uint32_t>(sobol::shuffle_index64(m_sample, h));
        const auto seeds = detail::counter_hash(h);
        const float a = sobol::to_unit(sobol::owen_scramble(sobol::dimension0(i), static_cast<std::uint32_t>(seeds)));
        if (!two) return {a, 0.0f};
        return {a, sobol::to_unit(sobol::owen_scramble(sobol::dimension1(i), static_cast<std::uint32_t>(seeds >> 32)))};
    }

    counter_rng m_rng;
    sampler_kind m_kind = sampler_kind::independent;
    std::uint32_t m_slot = 0;
    std::uint32_t m_end = first_bounce_slot;  ///< one past the current bounce's last slot
    int m_bounce = -1;                        ///< -1: the camera's slots
    std::uint32_t m_overflows = 0;
    std::uint64_t m_sample = 0;  ///< sobol: the sample index; zsobol: the Morton-ordered index
    std::uint64_t m_index = 0;   ///< the index shuffled once for all slots (zsobol: 64 bits)
    std::uint64_t m_key = 0;
};

}  // namespace iris
