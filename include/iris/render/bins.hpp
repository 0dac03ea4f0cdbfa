#pragma once
/// \file
/// \brief Spectra tabulated on the lattice of the B term's bins (SPEC §3), so that one
/// spectrum at all bins of a sample costs two contiguous rows blended — a vectorisable
/// loop, with no per-wavelength table search, division or Sellmeier evaluation.
///
/// The bins of one sample share a jitter u: λ_b = λmin + (b + u)Δ. On a lattice of K
/// sub-steps per bin (h = Δ/K) every bin therefore sits at the same place between two
/// lattice nodes: λ_b = λmin + (bK + q + t)h with q = ⌊uK⌋, t = uK − q. Row q of a
/// `binned_spectrum` holds the spectrum at the nodes bK + q of every bin, and the value
/// at all bins is (1 − t)·row_q + t·row_{q+1}.
///
/// Linear interpolation on the lattice equals the spectrum's own linear interpolation
/// wherever the spectrum's knots lie on the lattice: the 1 nm and 5 nm CIE tables on the
/// default 380–780 nm domain with 80 bins and K = 5 (h = 1 nm). Elsewhere (a 400–700 nm
/// domain, h = 0.75 nm; smooth models such as Sellmeier) the two differ by the
/// interpolation error O(h²·S″), about 1e-8 in η for glass — far below the noise of a term
/// that is itself biased and vanishes at α = 1.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "iris/render/scene.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/sampled.hpp"
#include "iris/spectrum/spectrum.hpp"
#include "iris/spectrum/tabulated.hpp"

namespace iris {

/// \brief Where one sample's bins fall on the lattice: row q and the fraction t.
struct bin_position {
    std::size_t row = 0;
    float t = 0.0f;
};

/// \brief `Bins` bins of width Δ over [λmin, λmax], each split into `K` lattice steps.
template <std::size_t Bins, std::size_t K = 5>
class bin_lattice {
    static_assert(Bins > 0 && K > 0, "a bin lattice needs at least one bin and one step per bin");

public:
    static constexpr std::size_t bins = Bins;
    static constexpr std::size_t steps = K;

    constexpr bin_lattice() noexcept = default;
    constexpr bin_lattice(float lambda_min, float lambda_max) noexcept
        : m_min(lambda_min), m_width((lambda_max - lambda_min) / static_cast<float>(Bins)) {}

    constexpr float lambda_min() const noexcept { return m_min; }
    constexpr float bin_width() const noexcept { return m_width; }

    /// \brief λ_b = λmin + (b + u)Δ.
    constexpr float lambda(std::size_t b, float u) const noexcept {
        return m_min + (static_cast<float>(b) + u) * m_width;
    }

    /// \brief The lattice position of jitter u ∈ [0, 1). (u·K may round up to K in float
    /// for u just below 1: that is the last row's far end, t = 1.)
    constexpr bin_position position(float u) const noexcept {
        const float x = std::clamp(u, 0.0f, 1.0f) * static_cast<float>(K);
        const auto q = std::min(static_cast<std::size_t>(x), K - 1);
        return {q, x - static_cast<float>(q)};
    }

    /// \brief The wavelength of node q (0 ≤ q ≤ K) of bin b, in double.
    constexpr double node(std::size_t b, std::size_t q) const noexcept {
        const double h = static_cast<double>(m_width) / static_cast<double>(K);
        return static_cast<double>(m_min) + static_cast<double>(b * K + q) * h;
    }

private:
    float m_min = 380.0f;
    float m_width = 5.0f;
};

/// \brief A function of wavelength sampled at the nodes of a `bin_lattice`, row by row.
template <std::size_t Bins, std::size_t K = 5>
class binned_spectrum {
public:
    binned_spectrum() = default;

    /// \brief Tabulate `f(λ)` (λ in nm, double) at every node.
    template <class F>
    binned_spectrum(const bin_lattice<Bins, K>& lattice, F&& f) {
        for (std::size_t q = 0; q <= K; ++q)
            for (std::size_t b = 0; b < Bins; ++b) m_rows[q][b] = static_cast<float>(f(lattice.node(b, q)));
    }

    /// \brief The spectrum at every bin of a sample whose jitter sits at `p`.
    sampled_spectrum<Bins> operator()(bin_position p) const noexcept {
        const auto& lo = m_rows[p.row];
        const auto& hi = m_rows[p.row + 1];
        const float s = 1.0f - p.t;
        sampled_spectrum<Bins> out;
        for (std::size_t b = 0; b < Bins; ++b) out[b] = s * lo[b] + p.t * hi[b];
        return out;
    }

private:
    std::array<std::array<float, Bins>, K + 1> m_rows{};
};

/// \brief A tabulated spectrum re-tabulated in float on a 1 nm lattice over the domain,
/// for the C hero-rotated wavelengths (any λ in the domain): one multiply, one truncation
/// and one blend per wavelength instead of the double-precision table walk. Used only
/// where it is exact — the table covers the domain and every knot inside it lies on the
/// lattice (all of iris's 1 nm and 5 nm tables on an integer-nm domain); otherwise it
/// evaluates the original table, so the hero path never sees an approximation.
class lattice_spectrum {
public:
    lattice_spectrum() = default;
    lattice_spectrum(const tabulated_spectrum& s, float lambda_min, float lambda_max) : m_source(&s), m_min(lambda_min) {
        const double lo = lambda_min, hi = lambda_max;
        const auto knots = s.wavelengths();
        if (knots.empty() || !(hi > lo) || knots.front() > lo || knots.back() < hi) return;
        if (std::fabs((hi - lo) - std::round(hi - lo)) > 1e-9) return;  // λmax must be a node
        for (double k : knots)
            if (k > lo && k < hi && std::fabs(k - std::round(k - lo) - lo) > 1e-9) return;
        const auto n = static_cast<std::size_t>(std::ceil(hi - lo)) + 1;
        m_values.resize(n + 1);  // one spare node past λmax: the blend at λmax reads it with weight 0
        for (std::size_t i = 0; i <= n; ++i) m_values[i] = static_cast<float>(s(std::min(hi, lo + static_cast<double>(i))));
    }

    /// \brief The spectrum at N wavelengths inside the domain.
    template <std::size_t N>
    sampled_spectrum<N> operator()(const sampled_wavelengths<N>& wl) const noexcept {
        if (m_values.empty()) return m_source ? sample(*m_source, wl) : sampled_spectrum<N>{};
        sampled_spectrum<N> out;
        const float last = static_cast<float>(m_values.size() - 2);
        const float* v = m_values.data();
        for (std::size_t k = 0; k < N; ++k) {
            const float x = std::min(std::max(wl[k] - m_min, 0.0f), last);  // minss/maxss, no branches
            const int i = static_cast<int>(x);  // to int, not size_t: one instruction on x86-64
            const float t = x - static_cast<float>(i);
            out[k] = (1.0f - t) * v[i] + t * v[i + 1];
        }
        return out;
    }

    bool exact_lattice() const noexcept { return !m_values.empty(); }

private:
    const tabulated_spectrum* m_source = nullptr;
    float m_min = 0.0f;
    std::vector<float> m_values;
};

/// \brief The spectra the hero wavelengths read at every vertex, as `lattice_spectrum`s:
/// per material its reflectance (diffuse, conductor; none for dielectrics), per emitter its
/// radiance, and the environment.
struct hero_tables {
    std::vector<lattice_spectrum> albedo;
    std::vector<lattice_spectrum> emission;
    lattice_spectrum environment;

    hero_tables() = default;
    explicit hero_tables(const scene_desc& scene) {
        const float lo = scene.lambda_min, hi = scene.lambda_max;
        for (const material_desc& m : scene.materials) {
            if (const auto* d = std::get_if<material::diffuse>(&m)) albedo.emplace_back(d->reflectance, lo, hi);
            else if (const auto* c = std::get_if<material::conductor>(&m)) albedo.emplace_back(c->reflectance, lo, hi);
            else albedo.emplace_back();
        }
        for (const emitter_desc& e : scene.emitters) emission.emplace_back(e.radiance, lo, hi);
        if (scene.environment) environment = lattice_spectrum(scene.environment->radiance, lo, hi);
    }
};

/// \brief Every spectrum the B term reads, tabulated once per render: per material its
/// reflectance (diffuse, conductor) or index of refraction (dielectric), per emitter its
/// radiance, the environment, and the CIE 1931 matching functions.
template <std::size_t Bins, std::size_t K = 5>
struct bin_tables {
    using spectrum = binned_spectrum<Bins, K>;

    bin_lattice<Bins, K> lattice;
    std::vector<spectrum> albedo;  ///< per material; zero for dielectrics
    std::vector<spectrum> eta;     ///< per material; zero unless a dielectric
    std::vector<spectrum> emission;
    spectrum environment;
    spectrum x_bar, y_bar, z_bar;

    bin_tables() = default;
    explicit bin_tables(const scene_desc& scene)
        : lattice(scene.lambda_min, scene.lambda_max),
          x_bar(lattice, [](double l) { return cie::x_bar(l); }),
          y_bar(lattice, [](double l) { return cie::y_bar(l); }),
          z_bar(lattice, [](double l) { return cie::z_bar(l); }) {
        for (const material_desc& m : scene.materials) {
            if (const auto* d = std::get_if<material::diffuse>(&m)) {
                albedo.emplace_back(lattice, d->reflectance);
                eta.emplace_back();
            } else if (const auto* c = std::get_if<material::conductor>(&m)) {
                albedo.emplace_back(lattice, c->reflectance);
                eta.emplace_back();
            } else {
                const auto& g = std::get<material::dielectric>(m);
                albedo.emplace_back();
                eta.emplace_back(lattice, [&](double l) { return refractive_index(g.ior, l); });
            }
        }
        for (const emitter_desc& e : scene.emitters) emission.emplace_back(lattice, e.radiance);
        if (scene.environment) environment = spectrum(lattice, scene.environment->radiance);
    }
};

}  // namespace iris
