#pragma once
/// \file
/// \brief A preset's wavelength policy for one pass behind virtual calls, so that the
/// estimators' per-vertex code is compiled once per shape of the policy — C wavelengths,
/// the B term's bin count and whether it propagates (`core_config`) — instead of once per
/// preset (docs/performance.md, "One instantiation per core").
///
/// Everything a preset changes in a sample happens at its two ends: the C wavelengths drawn
/// from p_α, the B term's complement 1 − r_α at the bins (`propagation::start`), and the
/// weights r_α/p_α (÷ Z_α) the sample's values are summed with (`detail::restricted_weights`).
/// `sample_policy<C, Bins>` offers exactly these three; `preset_sample_policy` implements them
/// with a preset's own distribution and bias policy — the same code the preset's direct
/// instantiation runs, so images are bit-identical — and the estimators, instantiated with
/// `core_config<C, Bins, Propagates>` and given a `sample_policy`, read them through one
/// virtual call each per sample.

#include <array>
#include <cstddef>

#include "iris/render/bins.hpp"
#include "iris/render/propagation.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

namespace detail {
/// \brief The B term's bin count of a config: its bias policy's `bins` (80 — 5 nm on
/// 380–780 nm — for PropagateUnused; fewer for `propagate_coarse<B>`); 1 (unused) for
/// policies without a B term, so that they carry no 80-wide spectra.
template <class Config>
constexpr std::size_t bins_of() noexcept {
    if constexpr (requires { Config::bias_type::bins; }) return Config::bias_type::bins;
    else return 1;
}

/// \brief The C wavelengths' weights r_α(λ_j) / p_α(λ_j) (÷ Z_α for ScaledPdf) of one sample
/// drawn from `dist` (0 where p_α(λ_j) = 0): by Config's bias policy, or, for a policy behind
/// a virtual call (`sample_policy`, iris/render/sample_policy.hpp), by the policy itself.
template <class Config, std::size_t C, class Distribution>
std::array<double, C> restricted_weights(const Distribution& dist, const sampled_wavelengths<C>& wl) noexcept {
    if constexpr (requires { dist.weights(wl); }) {
        return dist.weights(wl);
    } else {
        std::array<double, C> w{};
        const float z = Config::bias_type::scales_pdf ? dist.normalisation() : 1.0f;
        for (std::size_t j = 0; j < C; ++j)
            if (wl.pdf(j) > 0.0f) w[j] = Config::bias_type::restricted_factor(dist.restriction(wl[j]), wl.pdf(j), z);
        return w;
    }
}
}  // namespace detail

/// \brief The wavelength policy of one pass: C wavelengths, their weights, the bins' complement.
template <std::size_t C, std::size_t Bins>
class sample_policy {
public:
    /// \brief C hero-rotated wavelengths for the sample's number u (as a restricted distribution's).
    template <std::size_t N>
    sampled_wavelengths<C> sample_wavelengths(float u) const noexcept {
        static_assert(N == C, "a sample_policy draws the C wavelengths it was made for");
        return sample(u);
    }
    virtual sampled_wavelengths<C> sample(float u) const noexcept = 0;
    /// \brief r_α(λ_j) / p_α(λ_j) (÷ Z_α), 0 where p_α(λ_j) = 0.
    virtual std::array<double, C> weights(const sampled_wavelengths<C>& wl) const noexcept = 0;
    /// \brief out ← 1 − r_α(λ_b) at the bins of jitter u on `lattice`; false if 0 everywhere.
    virtual bool complement(const bin_lattice<Bins>& lattice, float u, sampled_spectrum<Bins>& out) const noexcept = 0;

protected:
    sample_policy() = default;
    sample_policy(const sample_policy&) = default;
    sample_policy& operator=(const sample_policy&) = default;
    ~sample_policy() = default;
};

/// \brief The configuration the shared instantiations are compiled with: only the shape of
/// a policy (its restriction, relaxation and weights come from a `sample_policy`).
template <std::size_t C, std::size_t Bins, bool Propagates>
struct core_config {
    static constexpr std::size_t wavelength_count = C;
    struct bias_type {
        static constexpr bool propagates = Propagates;
        static constexpr bool scales_pdf = false;  ///< Z_α, where a preset has it, is in the policy's weights
        static constexpr std::size_t bins = Bins;
    };
};

/// \brief The core configuration of preset (or integrator config) P.
template <class P>
using core_of = core_config<P::wavelength_count, detail::bins_of<P>(), P::bias_type::propagates>;

/// \brief Preset P's policy at one α: `dist` is P's restricted distribution at that α
/// (referenced, not copied: it must outlive the pass).
template <class P>
class preset_sample_policy final : public sample_policy<P::wavelength_count, detail::bins_of<P>()> {
    static constexpr std::size_t C = P::wavelength_count;
    static constexpr std::size_t Bins = detail::bins_of<P>();

public:
    explicit preset_sample_policy(const typename P::distribution_type& dist) noexcept : m_dist(&dist) {}
    sampled_wavelengths<C> sample(float u) const noexcept override { return m_dist->template sample_wavelengths<C>(u); }
    std::array<double, C> weights(const sampled_wavelengths<C>& wl) const noexcept override {
        return detail::restricted_weights<P>(*m_dist, wl);
    }
    bool complement(const bin_lattice<Bins>& lattice, float u, sampled_spectrum<Bins>& out) const noexcept override {
        return propagation<Bins>::complement(*m_dist, lattice, u, out);
    }

private:
    const typename P::distribution_type* m_dist;
};

}  // namespace iris
