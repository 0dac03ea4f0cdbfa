#pragma once
/// \file
/// \brief Spectra tabulated on the lattice of the B term's bins (docs/method.md §2, Bias policies), so that one
/// spectrum at all bins of a sample costs two contiguous rows blended — a vectorisable
/// loop, with no per-wavelength table search, division or Sellmeier evaluation.
///
/// The bins of one sample share a jitter u: λ_b = λmin + (b + u)Δ. On a lattice of K
/// steps per bin (h = Δ/K) every bin therefore sits at the same place between two lattice
/// nodes: λ_b = λmin + (bK + q + t)h with q = ⌊uK⌋, t = uK − q. Row q of a
/// `binned_spectrum` holds the spectrum at the nodes bK + q of every bin, and the value at
/// all bins is (1 − t)·row_q + t·row_{q+1}.
///
/// K is chosen per domain so that h = 1/m nm (m = 1…8) with λmin on a multiple of h
/// whenever that is possible (380–780 nm, 80 bins: h = 1 nm, K = 5; 400–700 nm: h = 0.25 nm,
/// K = 15; 8 bins: K = 50). Linear interpolation on the lattice then equals a table's own
/// linear interpolation for every table whose knots lie on whole nm (all of iris's data,
/// sRGB-upsampled reflectances, and any 1 nm or 5 nm table) — the B term stays exactly the
/// estimator of docs/method.md §3. A tabulated spectrum that the lattice would not reproduce (knots off
/// the lattice, a step inside the domain) is evaluated directly at the bins' wavelengths
/// instead: slower, exact. The one approximation left is the refractive index of dispersive
/// glass (Cauchy, Sellmeier: smooth curves, not tables), and η² and 1/η² for Fresnel,
/// each interpolated on the lattice with error ≤ h²/8·|f″| ≈ 1e-8 for glass at h = 1 nm.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "iris/render/lights/light.hpp"
#include "iris/render/materials/materials.hpp"
#include "iris/render/absorption.hpp"
#include "iris/render/medium.hpp"
#include "iris/render/scene.hpp"
#include "iris/render/texture.hpp"
#include "iris/sampling/bias/bin_layout.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/data/cie1931.hpp"
#include "iris/spectrum/sampled.hpp"
#include "iris/spectrum/spectrum.hpp"
#include "iris/spectrum/tabulated.hpp"

namespace iris {

/// \brief Where one sample's bins fall on the lattice: row q, the fraction t, and the
/// jitter u itself (for spectra evaluated directly).
struct bin_position {
    std::size_t row = 0;
    float t = 0.0f;
    float u = 0.0f;
};

/// \brief `Bins` equal bins of width Δ over [λmin, λmax] — the sampling layer's
/// `bias::bin_layout::with_count(domain, Bins)` — each split into K lattice steps.
template <std::size_t Bins>
class bin_lattice {
    static_assert(Bins > 0, "a bin lattice needs at least one bin");

public:
    static constexpr std::size_t bins = Bins;

    bin_lattice() : bin_lattice(380.0f, 780.0f) {}
    bin_lattice(float lambda_min, float lambda_max)
        : m_lo(lambda_min), m_hi(lambda_max), m_min(lambda_min),
          m_width((lambda_max - lambda_min) / static_cast<float>(Bins)) {
        const auto layout = bias::bin_layout::with_count({lambda_min, lambda_max}, Bins);
        for (std::size_t b = 0; b < Bins; ++b) {
            const auto e = layout.edges(b);
            m_edge_lo[b] = e.lo;
            m_edge_hi[b] = e.hi;
        }
        const double delta = (m_hi - m_lo) / static_cast<double>(Bins);
        auto whole = [](double x) { return std::fabs(x - std::round(x)) < 1e-6; };
        for (int m = 1; m <= 8 && !m_whole_nm; ++m)
            if (whole(delta * m) && whole(m_lo * m) && delta * m >= 1.0) {
                m_steps = static_cast<std::size_t>(std::lround(delta * m));
                m_per_nm = m;
                m_whole_nm = true;
            }
        if (!m_whole_nm) m_steps = static_cast<std::size_t>(std::max(1L, std::lround(delta)));  // ≈ 1 nm
    }

    float lambda_min() const noexcept { return m_min; }
    double lambda_min_exact() const noexcept { return m_lo; }
    double lambda_max_exact() const noexcept { return m_hi; }
    float bin_width() const noexcept { return m_width; }
    std::size_t steps() const noexcept { return m_steps; }  ///< K

    /// \brief λ_b for jitter u ∈ [0, 1): `bias::bin_layout::lambda`, from the bin's float
    /// edges cached here (two loads and a multiply–add per bin, which vectorise; the
    /// layout's own call computes the edges in double each time).
    float lambda(std::size_t b, float u) const noexcept { return bias::bin_layout::jitter(m_edge_lo[b], m_edge_hi[b], u); }

    /// \brief The lattice position of jitter u ∈ [0, 1).
    bin_position position(float u) const noexcept {
        const float x = std::clamp(u, 0.0f, 1.0f) * static_cast<float>(m_steps);
        const auto q = std::min(static_cast<std::size_t>(x), m_steps - 1);
        return {q, x - static_cast<float>(q), u};
    }

    /// \brief The wavelength of node q (0 ≤ q ≤ K) of bin b, in double, never past λmax.
    double node(std::size_t b, std::size_t q) const noexcept {
        const double k = static_cast<double>(b * m_steps + q) / static_cast<double>(Bins * m_steps);
        return std::min(m_hi, m_lo + (m_hi - m_lo) * k);
    }

    /// \brief Is linear interpolation on this lattice exact for a piecewise-linear function
    /// with breakpoints at these wavelengths? (Every breakpoint inside the domain is a node.)
    bool reproduces(std::span<const double> knots) const noexcept {
        if (!m_whole_nm) return false;
        for (double k : knots)
            if (k > m_lo && k < m_hi) {
                const double x = (k - m_lo) * m_per_nm;
                if (std::fabs(x - std::round(x)) > 1e-6) return false;
            }
        return true;
    }

private:
    double m_lo, m_hi;
    float m_min, m_width;
    std::array<float, Bins> m_edge_lo, m_edge_hi;  ///< the layout's bin edges in float
    std::size_t m_steps = 1;
    int m_per_nm = 1;
    bool m_whole_nm = false;
};

/// \brief A function of wavelength at the bins of a sample: rows on a `bin_lattice`, or,
/// where the lattice would not reproduce it, the function itself at λ_b.
template <std::size_t Bins>
class binned_spectrum {
public:
    binned_spectrum() = default;

    /// \brief Tabulate a smooth `f(λ)` (λ in nm, double) at every node (the lattice's
    /// interpolation error is accepted: used for refractive indices).
    template <class F>
        requires(!std::is_same_v<std::remove_cvref_t<F>, tabulated_spectrum>)
    binned_spectrum(const bin_lattice<Bins>& lattice, F&& f) : m_steps(lattice.steps()) {
        m_rows.resize(m_steps + 1);
        for (std::size_t q = 0; q <= m_steps; ++q)
            for (std::size_t b = 0; b < Bins; ++b) m_rows[q][b] = static_cast<float>(f(lattice.node(b, q)));
    }

    /// \brief A table: on the lattice where that is exact, evaluated directly otherwise.
    binned_spectrum(const bin_lattice<Bins>& lattice, const tabulated_spectrum& s) : m_steps(lattice.steps()) {
        const auto knots = s.wavelengths();
        // a zero-mode table ending inside the domain on a non-zero value is a step there
        const bool steps_inside = s.mode() == outside::zero && !knots.empty() &&
                                  ((knots.front() > lattice.lambda_min_exact() && s.values().front() != 0.0) ||
                                   (knots.back() < lattice.lambda_max_exact() && s.values().back() != 0.0));
        if (knots.empty() || (lattice.reproduces(knots) && !steps_inside)) {
            *this = binned_spectrum(lattice, [&](double l) { return s(l); });
        } else {
            m_exact = [s](double l) { return s(l); };
            m_lattice = std::make_shared<const bin_lattice<Bins>>(lattice);
        }
    }

    /// \brief True if the value comes from the lattice rows (false: evaluated directly).
    bool on_lattice() const noexcept { return !m_exact; }

    /// \brief True if every bin reads the same value at every jitter: empty (zeros), or
    /// lattice rows holding one number. Each bin's view then blends the same two numbers
    /// with the same weights, so element 0 of a view stands bit for bit for every element.
    bool constant() const noexcept {
        if (m_exact) return false;
        for (const auto& row : m_rows)
            for (float v : row)
                if (!(v == m_rows.front()[0]) || std::signbit(v) != std::signbit(m_rows.front()[0])) return false;
        return true;
    }

    /// \brief The spectrum at the bins of one sample, read element by element (so that a
    /// loop over the bins can blend the rows as it goes, without a temporary spectrum).
    struct view {
        const float* lo;
        const float* hi;
        float s, t;
        float operator[](std::size_t b) const noexcept { return s * lo[b] + t * hi[b]; }
    };

    /// \brief The view at `p`. A directly evaluated spectrum is evaluated into `scratch`
    /// (which must outlive the view); an empty one reads zeros.
    view at(bin_position p, std::array<float, Bins>& scratch) const {
        if (m_exact) {
            for (std::size_t b = 0; b < Bins; ++b)
                scratch[b] = static_cast<float>(m_exact(m_lattice->lambda(b, p.u)));
            return {scratch.data(), zeros().data(), 1.0f, 0.0f};  // x·1 + 0·0 = x exactly
        }
        if (m_rows.empty()) return {zeros().data(), zeros().data(), 1.0f, 0.0f};
        return {m_rows[p.row].data(), m_rows[p.row + 1].data(), 1.0f - p.t, p.t};
    }

    /// \brief The spectrum at every bin of a sample whose jitter sits at `p`, into `out`.
    void evaluate(bin_position p, sampled_spectrum<Bins>& out) const {
        std::array<float, Bins> scratch;  // written only for a directly evaluated spectrum
        const view v = at(p, scratch);
        for (std::size_t b = 0; b < Bins; ++b) out[b] = v[b];
    }

    /// \brief The spectrum at every bin of a sample whose jitter sits at `p`.
    sampled_spectrum<Bins> operator()(bin_position p) const {
        sampled_spectrum<Bins> out;
        evaluate(p, out);
        return out;
    }

private:
    static const std::array<float, Bins>& zeros() noexcept {
        static constexpr std::array<float, Bins> z{};
        return z;
    }

    std::size_t m_steps = 0;
    std::vector<std::array<float, Bins>> m_rows;
    std::function<double(double)> m_exact;  ///< set when the lattice would not reproduce the table
    std::shared_ptr<const bin_lattice<Bins>> m_lattice;  ///< with m_exact: where the bins' λ_b are
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
            const float x = std::min(last, std::max(0.0f, wl[k] - m_min));  // minss/maxss; NaN → 0
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

/// \brief The emission tables of a scene, in the order `emission_ref` indexes them
/// (iris/render/lights/light.hpp): one per emitter, then the environment's — its radiance,
/// or the three basis spectra of an environment image.
inline std::vector<const tabulated_spectrum*> emission_spectra(const scene_desc& scene) {
    std::vector<const tabulated_spectrum*> out;
    for (const emitter_desc& e : scene.emitters) out.push_back(&e.radiance);
    if (scene.environment) {
        if (scene.environment->map)
            for (const auto& b : scene.environment->basis) out.push_back(&b);
        else
            out.push_back(&scene.environment->radiance);
    }
    return out;
}

/// \brief Whether any material of the scene reads a texture (its tables then carry the
/// three reflectance basis rows after the materials').
inline bool has_textures(const scene_desc& scene) noexcept {
    return std::any_of(scene.materials.begin(), scene.materials.end(), [](const material_desc& m) { return is_textured(m); });
}

/// \brief A material's reflectance at a hit, in `emission_ref`'s form over the albedo
/// tables: material m's own table times 1 (untextured), or the three basis rows (which
/// follow the materials' rows) mixed by the texture's weights there.
inline emission_ref albedo_ref(std::uint32_t m, std::uint32_t basis_first, const std::optional<glm::vec3>& texel) noexcept {
    if (!texel) return {m, 1, {1.0f, 0.0f, 0.0f}};
    return {basis_first, 3, *texel};
}

/// \brief The spectra the hero wavelengths read at every vertex, as `lattice_spectrum`s:
/// per material its reflectance (if its BxDF `reads_albedo`; none otherwise), then the
/// three reflectance basis spectra if a material is textured; and the emission tables
/// (`emission_spectra`).
struct hero_tables {
    std::vector<lattice_spectrum> albedo;
    std::vector<lattice_spectrum> emission;
    std::vector<lattice_spectrum> conductor_eta, conductor_k;  ///< per material; empty unless a conductor with an index
    /// Per medium id (iris/render/absorption.hpp: a material's solid, then the scene's own
    /// medium): σ_a, empty where it does not absorb; σ_s, empty where it does not scatter, and
    /// the phase function's g.
    std::vector<lattice_spectrum> absorption, scattering;
    std::vector<float> phase_g;
    std::vector<unsigned char> scatters_;  ///< per medium id: does it scatter?
    std::uint32_t albedo_basis = 0;  ///< the first basis row of `albedo` (= the material count)

    /// \brief exp(−σ_t(λ_k)·t), σ_t = σ_a + σ_s, of a length t (possibly ∞) through medium m
    /// (iris/render/absorption.hpp): what a shadow ray lets through.
    template <std::size_t N>
    sampled_spectrum<N> transmittance(std::uint32_t m, const sampled_wavelengths<N>& wl, float t) const noexcept {
        sampled_spectrum<N> v = absorption[m](wl);
        if (scatters_[m]) v += scattering[m](wl);
        for (std::size_t k = 0; k < N; ++k) v[k] = beer_lambert(v[k], t);
        return v;
    }
    /// \brief Does medium m scatter (iris/render/medium.hpp), or only absorb?
    bool scatters(std::uint32_t m) const noexcept { return scatters_[m] != 0; }
    /// \brief Medium m's coefficients at the wavelengths `wl`.
    template <std::size_t N>
    medium_coefficients<N> medium(std::uint32_t m, const sampled_wavelengths<N>& wl) const noexcept {
        return {absorption[m](wl), scattering[m](wl), phase_g[m], scatters_[m] != 0};
    }

    /// \brief Le(λ_k) = Σ_i weight_i · table_{first+i}(λ_k) (an emitter: its table times 1, exactly).
    template <std::size_t N>
    sampled_spectrum<N> emitted(const emission_ref& r, const sampled_wavelengths<N>& wl) const noexcept {
        return mix(emission, r, wl);
    }
    /// \brief The reflectance at the hero wavelengths (`albedo_ref`).
    template <std::size_t N>
    sampled_spectrum<N> reflectance(const emission_ref& r, const sampled_wavelengths<N>& wl) const noexcept {
        return mix(albedo, r, wl);
    }

    /// \brief The spectra BxDF `bxdf` of material `m` reads at the wavelengths `wl`, at a
    /// vertex with texture coordinates `uv`: its reflectance (an untextured material's own
    /// row, or a texel's basis mix — written to `albedo_at` for the B term), its index of
    /// refraction from the index model, a conductor's η and k from its tables. Each is read
    /// once per vertex, by whichever estimator made it.
    template <std::size_t N, class B>
    sampled_spectra<N> at_vertex(const B& bxdf, const scene_desc& scene, std::uint32_t m, glm::vec2 uv,
                                 const sampled_wavelengths<N>& wl, emission_ref& albedo_at) const noexcept {
        sampled_spectra<N> out;
        if constexpr (B::reads_albedo) {
            albedo_at = albedo_ref(m, albedo_basis, texture_weights(scene, scene.materials[m], uv));
            out.reflectance = reflectance(albedo_at, wl);
        }
        if constexpr (B::reads_eta) out.index = detail::etas(bxdf.ior(), wl);
        if constexpr (reads_conductor_v<B>)
            if (bxdf.has_ior()) {
                out.index = conductor_eta[m](wl);
                out.kappa = conductor_k[m](wl);
            }
        if constexpr (reads_film_v<B>)
            if (const material::thin_film* f = bxdf.film()) {
                for (std::size_t k = 0; k < N; ++k) out.lambda[k] = wl[k];
                out.film_index = detail::etas(f->ior, wl);
            }
        return out;
    }

    hero_tables() = default;
    explicit hero_tables(const scene_desc& scene) {
        const float lo = scene.lambda_min, hi = scene.lambda_max;
        for (const material_desc& m : scene.materials)
            visit_bxdf(m, [&](const auto& b) {
                using B = std::remove_cvref_t<decltype(b)>;
                if constexpr (B::reads_albedo) albedo.emplace_back(b.reflectance(), lo, hi);
                else albedo.emplace_back();
                if constexpr (reads_conductor_v<B>) {
                    if (b.has_ior()) {
                        conductor_eta.emplace_back(b.conductor_eta(), lo, hi);
                        conductor_k.emplace_back(b.conductor_k(), lo, hi);
                        return;
                    }
                }
                conductor_eta.emplace_back();
                conductor_k.emplace_back();
            });
        for (std::uint32_t id = 0; id < medium_count(scene); ++id) {
            const tabulated_spectrum* sa = medium_absorption(scene, id);
            const medium_scattering* ss = medium_scattering_of(scene, id);
            if (sa) absorption.emplace_back(*sa, lo, hi);
            else absorption.emplace_back();
            if (ss) scattering.emplace_back(ss->sigma_s, lo, hi);
            else scattering.emplace_back();
            phase_g.push_back(ss ? ss->g : 0.0f);
            scatters_.push_back(ss != nullptr);
        }
        albedo_basis = static_cast<std::uint32_t>(albedo.size());
        if (has_textures(scene))
            for (const tabulated_spectrum& b : reflectance_basis()) albedo.emplace_back(b, lo, hi);
        for (const tabulated_spectrum* e : emission_spectra(scene)) emission.emplace_back(*e, lo, hi);
    }

private:
    template <std::size_t N>
    static sampled_spectrum<N> mix(const std::vector<lattice_spectrum>& t, const emission_ref& r,
                                   const sampled_wavelengths<N>& wl) noexcept {
        sampled_spectrum<N> v = t[r.first](wl);
        if (r.count == 1) {
            if (r.weight[0] != 1.0f) v *= r.weight[0];
            return v;
        }
        v *= r.weight[0];
        for (std::uint32_t i = 1; i < r.count; ++i) v += t[r.first + i](wl) * r.weight[static_cast<int>(i)];
        return v;
    }
};

/// \brief Every spectrum the B term reads, made once per render: per material its
/// reflectance or its index of refraction (as its BxDF `reads_albedo` or `reads_eta`), a thin
/// film's index and the bins' λ (for the film's phase), per emitter its
/// emission tables (`emission_spectra`), and the CIE 1931 matching functions (their 1 nm tables).
template <std::size_t Bins>
struct bin_tables {
    using spectrum = binned_spectrum<Bins>;

    bin_lattice<Bins> lattice;
    std::vector<spectrum> albedo;  ///< per material (empty unless its BxDF reads_albedo), then the reflectance basis if textured
    std::vector<spectrum> eta;     ///< per material; empty unless its BxDF reads_eta
    std::vector<spectrum> eta2;     ///< η², likewise (Fresnel at the bins reads η² and 1/η², no squaring or division)
    std::vector<spectrum> inv_eta2; ///< 1/η², likewise
    std::vector<spectrum> k;        ///< per material: a conductor's k (its η is in `eta`); empty otherwise
    std::vector<spectrum> absorption;  ///< per medium id (iris/render/absorption.hpp): its σ_a; empty where it does not absorb
    /// Per medium id: its σ_a is the same at every bin (grey, or none): one e^{−σ_a d} serves
    /// all bins (propagation.hpp), the same numbers as one per bin.
    std::vector<std::uint8_t> grey_absorption;
    std::vector<spectrum> emission;  ///< indexed as `emission_ref` indexes them
    std::vector<spectrum> film_eta;  ///< per material: a thin film's index; empty otherwise
    spectrum lambda;                 ///< λ_b itself (a film's phase reads it)
    spectrum x_bar, y_bar, z_bar;

    bin_tables() = default;
    explicit bin_tables(const scene_desc& scene)
        : lattice(scene.lambda_min, scene.lambda_max),
          lambda(lattice, [](double l) { return l; }),
          x_bar(lattice, tabulated_spectrum::uniform(cie::cmf_lambda_min, 1.0, data::cie1931::x_bar)),
          y_bar(lattice, tabulated_spectrum::uniform(cie::cmf_lambda_min, 1.0, data::cie1931::y_bar)),
          z_bar(lattice, tabulated_spectrum::uniform(cie::cmf_lambda_min, 1.0, data::cie1931::z_bar)) {
        for (const material_desc& m : scene.materials)
            visit_bxdf(m, [&](const auto& b) {
                using B = std::remove_cvref_t<decltype(b)>;
                if constexpr (B::reads_albedo) albedo.emplace_back(lattice, b.reflectance());
                else albedo.emplace_back();
                if constexpr (B::reads_eta) {
                    const ior_model& ior = b.ior();
                    eta.emplace_back(lattice, [&](double l) { return refractive_index(ior, l); });
                    eta2.emplace_back(lattice, [&](double l) { return std::pow(refractive_index(ior, l), 2.0); });
                    inv_eta2.emplace_back(lattice, [&](double l) { return std::pow(refractive_index(ior, l), -2.0); });
                } else if constexpr (reads_conductor_v<B>) {
                    if (b.has_ior()) eta.emplace_back(lattice, b.conductor_eta());
                    else eta.emplace_back();
                    eta2.emplace_back();
                    inv_eta2.emplace_back();
                } else {
                    eta.emplace_back();
                    eta2.emplace_back();
                    inv_eta2.emplace_back();
                }
                if constexpr (reads_conductor_v<B>) {
                    if (b.has_ior()) {
                        k.emplace_back(lattice, b.conductor_k());
                        return;
                    }
                }
                k.emplace_back();
            });
        for (std::uint32_t id = 0; id < medium_count(scene); ++id) {
            if (const tabulated_spectrum* sa = medium_absorption(scene, id)) absorption.emplace_back(lattice, *sa);
            else absorption.emplace_back();
            grey_absorption.push_back(absorption.back().constant() ? 1 : 0);
        }
        for (const material_desc& m : scene.materials) {
            visit_bxdf(m, [&](const auto& b) {
                if constexpr (reads_film_v<std::remove_cvref_t<decltype(b)>>)
                    if (const material::thin_film* f = b.film()) {
                        film_eta.emplace_back(lattice, [f](double l) { return refractive_index(f->ior, l); });
                        return;
                    }
                film_eta.emplace_back();
            });
        }
        if (has_textures(scene))
            for (const tabulated_spectrum& b : reflectance_basis()) albedo.emplace_back(lattice, b);
        for (const tabulated_spectrum* e : emission_spectra(scene)) emission.emplace_back(lattice, *e);
    }
};

}  // namespace iris
