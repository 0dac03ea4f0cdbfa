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
/// | `sobol` | Owen-scrambled Sobol' (0, 2)-sequence points, padded: each dimension of the path has its own index shuffle and scrambling, keyed by (seed, pixel, dimension) (sampling/sobol.hpp) |
/// | `zsobol` | the same points indexed in Morton order over the image, index = (Morton(x, y) ≪ ⌈log₂ spp⌉) + sample, shuffled and scrambled per (seed, dimension) only, so that neighbouring pixels share one net and their errors are distributed as blue noise (Ahmed & Wonka 2020; pbrt-v4's ZSobolSampler) |
///
/// **Dimension layout.** The path tracer asks for its numbers in *slots*, each a 1-D or a
/// 2-D point; for the low-discrepancy samplers a slot is one padded dimension:
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
/// estimation at a delta vertex) never shifts the slots after it. The `independent`
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
        : m_rng(s.seed, pixel, sample), m_kind(s.kind) {
        if (m_kind == sampler_kind::sobol) {
            m_index = sobol::reverse_bits(static_cast<std::uint32_t>(sample));  // reversed once (at())
            m_key = detail::counter_hash(detail::counter_hash(s.seed ^ 0x50b01ull) ^ pixel);
        } else if (m_kind == sampler_kind::zsobol) {
            m_index = (static_cast<std::uint64_t>(sobol::morton2(x, y)) << s.log2_spp) + sample;
            m_key = detail::counter_hash(s.seed ^ 0x25b01ull);
        }
    }

    constexpr sampler_kind kind() const noexcept { return m_kind; }

    /// \brief The next 1-D slot, in [0, 1).
    constexpr float next() noexcept {
        if (m_kind == sampler_kind::independent) return m_rng.next();
        const point p = at(m_slot++, false);
        return p.x;
    }

    /// \brief The next 2-D slot, in [0, 1)².
    constexpr glm::vec2 next2() noexcept {
        if (m_kind == sampler_kind::independent) {
            const float a = m_rng.next();
            return {a, m_rng.next()};
        }
        const point p = at(m_slot++, true);
        return {p.x, p.y};
    }

    /// \brief Move to bounce k's first slot (a no-op for `independent`).
    constexpr void start_bounce(int k) noexcept {
        if (m_kind != sampler_kind::independent)
            m_slot = first_bounce_slot + slots_per_bounce * static_cast<std::uint32_t>(k);
    }

    /// \brief The slot the next draw reads (low-discrepancy samplers).
    constexpr std::uint32_t slot() const noexcept { return m_slot; }

private:
    struct point {
        float x, y;
    };
    /// \brief Slot `slot`'s point: this sample's index shuffled for the slot, its Sobol'
    /// dimensions 0 (and 1) Owen-scrambled for the slot — for `sobol`,
    /// owen_scramble(dimension0(shuffle_index(sample, a)), b), computed from the sample
    /// index the stream reversed once (`sobol::shuffled_dimension0`: the reversals in
    /// between cancel).
    constexpr point at(std::uint32_t slot, bool two) const noexcept {
        const std::uint64_t h = detail::counter_hash(m_key + slot);
        std::uint32_t i, x;
        std::uint64_t scramble;
        if (m_kind == sampler_kind::sobol) {
            scramble = h >> 32;
            const auto p = sobol::shuffled_dimension0(static_cast<std::uint32_t>(m_index), static_cast<std::uint32_t>(h),
                                                      static_cast<std::uint32_t>(scramble));
            i = p.index;
            x = p.value;
        } else {
            // bits of the Morton index past 32 do not reach a 32-bit point: they key the
            // scrambling instead, so far-apart image blocks do not repeat one pattern
            const std::uint64_t z = sobol::shuffle_index64(m_index, h);
            i = static_cast<std::uint32_t>(z);
            scramble = detail::counter_hash(h ^ (z >> 32));
            x = sobol::owen_scramble(sobol::dimension0(i), static_cast<std::uint32_t>(scramble));
        }
        const float a = sobol::to_unit(x);
        if (!two) return {a, 0.0f};
        const auto seed_b = static_cast<std::uint32_t>(detail::counter_hash(scramble));
        return {a, sobol::to_unit(sobol::scrambled_dimension1(i, seed_b))};
    }

    counter_rng m_rng;
    sampler_kind m_kind = sampler_kind::independent;
    std::uint32_t m_slot = 0;
    std::uint64_t m_index = 0;  ///< sobol: the sample index bit-reversed; zsobol: the Morton-ordered index
    std::uint64_t m_key = 0;
};

}  // namespace iris
