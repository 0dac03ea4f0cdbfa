#pragma once
/// \file
/// \brief The B term of one path (docs/method.md §3), as one component: `propagation<Bins>` for the
/// bias policies that propagate, `no_propagation` (every step a no-op the compiler drops)
/// for the others. The path integrator calls its steps where the hero path makes them:
///
/// | step | when | what B does |
/// |---|---|---|
/// | `start(dist, u)` | first, while α < 1 | jitter the bins, throughput t_b = 1 − r_α(λ_b) |
/// | `emission(le, w)` | the hero's ray finds light (an emitter or the environment) | L_b += t_b · Le(λ_b) · w |
/// | `enter(bxdf, m, albedo)` | each vertex | read material m's spectra at the bins (its reflectance there: `albedo`) |
/// | `prepare_light`, `receives_light`, `light(le, w, p_l)` | next-event estimation | the bins' f·\|cos\| toward the light; L_b += t_b f_b Le_b · w/p_l |
/// | `follow(bxdf, s)` | the hero samples the BSDF | t_b ← t_b · follow_b / p(ωi \| λ₀) |
/// | `roulette_max`, `survive(q)` | Russian roulette | B's largest weight counts; t_b ← t_b / q |
/// | `add_xyz(v)` | the path ends | v += Δλ Σ_b L_b cmf(λ_b) |
///
/// Light tracing adds `start_emitted`, `follow_adjoint`, `weigh`, `connect`; bidirectional
/// path tracing uses `bidirectional_propagation` (below), which joins two subpaths' bins.
///
/// B = Σ_b (1 − r_α(λ_b)) f_h(x̄, λ_b) Δλ / p(x̄ | λ₀), λ_b = λmin + (b + u)Δλ with one
/// jitter u per sample shared by all bins (each λ_b is uniform in its bin). Its spectra come
/// from the lattice tables of iris/render/bins.hpp; every step is one pass over the bins
/// with no temporary spectrum. Bins inside the windows start at 0 and stay 0, so the sum
/// needs no weight at the end and roulette sees only what B carries (except on a
/// bidirectional light subpath, whose bins start at Le and take the complement at the end:
/// `bidirectional_propagation`).

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <glm/vec3.hpp>

#include "iris/render/absorption.hpp"
#include "iris/render/bins.hpp"
#include "iris/render/lights/light.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/render/medium.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/render/spectral_bands.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief The B term of a policy without one: it is never on, and every step is empty.
struct no_propagation {
    static constexpr bool on() noexcept { return false; }
    void off() noexcept {}
    template <class Distribution>
    void start(const Distribution&, float) noexcept {}
    void emission(const emission_ref&, float) noexcept {}
    template <class B>
    void enter(const B&, std::uint32_t, const emission_ref&) noexcept {}
    template <class B>
    void prepare_light(const B&, const glm::vec3&, const glm::vec3&) noexcept {}
    template <class B>
    static constexpr bool receives_light() noexcept {
        return false;
    }
    template <class B>
    void light(const emission_ref&, float, float) noexcept {}
    template <class B, std::size_t C>
    void follow(const B&, const glm::vec3&, const bsdf_sample<C>&) noexcept {}
    void attenuate(std::uint32_t, float) noexcept {}
    template <class B>
    void light_absorbed(const emission_ref&, float, float, std::uint32_t, float, float) noexcept {}
    static constexpr float roulette_max(float m) noexcept { return m; }
    void survive(float) noexcept {}
    void add_xyz(xyz&) const noexcept {}
    void add_spectral(spectral_row&) const noexcept {}
    void start_emitted(const emission_ref&, float) noexcept {}
    template <class B, std::size_t C>
    void follow_adjoint(const B&, const glm::vec3&, const bsdf_sample<C>&, float) noexcept {}
    void weigh(float) noexcept {}
    template <class B>
    void connect(float, xyz&) noexcept {}
    void connect_emitter(float, xyz&) noexcept {}
    struct vertex_throughput {};
    void start_light_subpath(const emission_ref&, float) noexcept {}
    vertex_throughput throughput() const noexcept { return {}; }
    template <class B>
    void light_vertex(const vertex_throughput&, float) noexcept {}
    template <class B>
    void connect_vertex(const no_propagation&, float, xyz&) noexcept {}
    void connect_camera(float, xyz&) noexcept {}
};

/// \brief The B term of one path over `Bins` bins, reading the tables of one render.
template <std::size_t Bins>
class propagation {
public:
    explicit propagation(const bin_tables<Bins>& tables) noexcept : m_t(&tables) {}

    /// \brief Is the term on (started with some bin outside the windows)? Off, every step
    /// is a no-op (bdpt skips copying and keeping an unused light side's bins).
    bool on() const noexcept { return m_on; }
    /// \brief Turn the term off (as `start` does when every bin is inside the windows).
    void off() noexcept { m_on = false; }

    /// \brief Start with jitter u: t_b = 1 − r_α(λ_b). Off if every bin is inside the windows.
    template <class Distribution>
    void start(const Distribution& dist, float u) noexcept {
        m_bp = m_t->lattice.position(u);
        if constexpr (requires { dist.complement(m_t->lattice, u, m_tb); })
            m_on = dist.complement(m_t->lattice, u, m_tb);  // a policy behind a virtual call (render/sample_policy.hpp)
        else
            m_on = complement(dist, m_t->lattice, u, m_tb);
        m_tb_max = 1.0f;
    }

    /// \brief The hero's BSDF-sampled ray found light `le` (an emitter, or the environment
    /// it escaped to) with its BSDF-sampling weight w.
    void emission(const emission_ref& le, float w) noexcept {
        if (!m_on) return;
        float k = w;
        const view v = emitted(le, k);
        add_light(v, k);
    }

    /// \brief A vertex of material m: its reflectance at the bins is read once, here, from
    /// `albedo` (iris/render/bins.hpp's `albedo_ref`: m's own row, or a texel's three basis
    /// rows mixed); its indices are read as the BxDF asks for them.
    template <class B>
    void enter(const B& /*bxdf*/, std::uint32_t m, const emission_ref& albedo) noexcept {
        m_material = m;
        if constexpr (B::reads_albedo) {
            if (!m_on) return;
            if (albedo.count == 1) {
                m_t->albedo[albedo.first].evaluate(m_bp, m_refl);
                return;
            }
            for (std::size_t b = 0; b < Bins; ++b) m_refl[b] = 0.0f;
            for (std::uint32_t i = 0; i < albedo.count; ++i) {
                const view v = m_t->albedo[albedo.first + i].at(m_bp, m_scratch);
                const float w = albedo.weight[static_cast<int>(i)];
                for (std::size_t b = 0; b < Bins; ++b) m_refl[b] += w * v[b];
            }
        }
    }

    /// \brief Next-event estimation toward unit wi, before the shadow ray: the bins' value
    /// f·|cos θi| (a separable BxDF: its reflectance times one number). Directions in the
    /// vertex's shading frame, as the BxDF takes them.
    template <class B>
    void prepare_light(const B& bxdf, const glm::vec3& wo, const glm::vec3& wi) noexcept {
        if (!m_on) return;
        if constexpr (separable_bxdf<B>) m_cos = B::cos_factor(wo, wi);
        else m_f = bxdf.template f_cos<Bins>(wo, wi, spectra());
    }
    /// \brief Would light from there reach B? A surface black at every hero wavelength
    /// (say, inside the windows) may still reflect at the bins, and B must keep its
    /// light-sampling share there (docs/method.md §4, U1).
    template <class B>
    bool receives_light() const noexcept {
        if constexpr (separable_bxdf<B>) return m_on && m_cos != 0.0f && !m_refl.is_zero();
        else return m_on && !m_f.is_zero();
    }
    /// \brief The shadow ray is clear: L_b += t_b f_b Le_b · w/p_l (w the hero's light-sampling
    /// weight, p_l the light's solid-angle pdf).
    template <class B>
    void light(const emission_ref& r, float w, float pl) noexcept {
        if (!m_on) return;
        float k = w / pl;
        const view le = emitted(r, k);
        if constexpr (separable_bxdf<B>) add_light(m_refl, le, m_cos * k);
        else add_light(m_f, le, k);
    }

    /// \brief `light`, for a shadow ray that crosses a length d of medium m: the bins' value
    /// toward the light times exp(−σ_a(λ_b)·d) (iris/render/absorption.hpp) and, in a medium
    /// that scatters, the hero's e^{−σ_s(λ₀)·d} = `pass0`: the bins see the hero's scattering
    /// and their own absorption (docs/method.md §10).
    template <class B>
    void light_absorbed(const emission_ref& r, float w, float pl, std::uint32_t m, float d, float pass0) noexcept {
        if (!m_on) return;
        float k = w / pl * pass0;
        const view le = emitted(r, k);
        const view sigma = m_t->absorption[m].at(m_bp, m_att_scratch);
        sampled_spectrum<Bins> f;
        if (m_t->grey_absorption[m]) {  // one exponential for every bin: the same numbers
            const float e = beer_lambert(sigma[0], d);
            for (std::size_t b = 0; b < Bins; ++b) f[b] = (separable_bxdf<B> ? m_refl[b] * m_cos : m_f[b]) * e;
        } else {
            for (std::size_t b = 0; b < Bins; ++b) {
                const float fb = separable_bxdf<B> ? m_refl[b] * m_cos : m_f[b];
                f[b] = fb * beer_lambert(sigma[b], d);
            }
        }
        add_light(f, le, k);
    }
    /// \brief The hero's ray crossed a length t of medium m (to a surface, or to a scattering
    /// in it): t_b ← t_b · exp(−σ_a(λ_b)·t). In a medium that scatters this is the whole of
    /// the bins' weight: the hero's flight, sampled on its own σ_s, is taken as theirs
    /// (docs/method.md §10).
    void attenuate(std::uint32_t m, float t) noexcept {
        if (!m_on) return;
        const view sigma = m_t->absorption[m].at(m_bp, m_att_scratch);
        float mx = 0.0f;
        if (m_t->grey_absorption[m]) {  // one exponential for every bin: the same numbers
            const float e = beer_lambert(sigma[0], t);
            for (std::size_t b = 0; b < Bins; ++b) {
                m_tb[b] *= e;
                mx = m_tb[b] > mx ? m_tb[b] : mx;
            }
        } else {
            for (std::size_t b = 0; b < Bins; ++b) {
                m_tb[b] *= beer_lambert(sigma[b], t);
                mx = m_tb[b] > mx ? m_tb[b] : mx;
            }
        }
        m_tb_max = mx;
    }

    /// \brief The bins follow the hero's sampled direction and lobe (`wo` and the sample's
    /// direction in the shading frame).
    template <class B, std::size_t C>
    void follow(const B& bxdf, const glm::vec3& wo, const bsdf_sample<C>& s) noexcept {
        if (!m_on) return;
        if constexpr (is_phase_v<B>) return;  // sampled exactly: f/p = 1 at every bin (iris/render/medium.hpp)
        const float inv_p0 = 1.0f / s.pdf[0];
        if constexpr (separable_bxdf<B>) m_tb_max = scale(m_refl, B::cos_factor(wo, s.wi) * inv_p0);
        else m_tb_max = scale(bxdf.template follow<Bins>(wo, s.wi, s.kind, spectra()), inv_p0);
    }

    /// \name Light subpaths (iris/render/light_tracer.hpp; docs/method.md §3, "Light tracing")
    /// The same throughput t_b, built from the light's side: it starts at the emitter,
    /// follows the hero's scattering with the adjoint BSDF, and each connection to the camera
    /// is one contribution of its own.
    /// @{
    /// \brief The light subpath leaves an emitter: t_b ← t_b · Le(λ_b) · k.
    void start_emitted(const emission_ref& le, float k) noexcept {
        if (!m_on) return;
        const view v = emitted(le, k);
        for (std::size_t b = 0; b < Bins; ++b) m_tb[b] *= v[b] * k;
        m_tb_max = 0.0f;
        for (std::size_t b = 0; b < Bins; ++b) m_tb_max = m_tb[b] > m_tb_max ? m_tb[b] : m_tb_max;
    }
    /// \brief The bins follow the hero's sampled direction with the adjoint BSDF: `follow`'s
    /// weight times (η′_b)² across a transmission (importance is not compressed by the
    /// interface, radiance is: f* = f · η′² there, η′ the relative index from ωo's side to
    /// ωi's, here each bin's own) and times `shading`, the shading-normal correction.
    template <class B, std::size_t C>
    void follow_adjoint(const B& bxdf, const glm::vec3& wo, const bsdf_sample<C>& s, float shading) noexcept {
        if (!m_on) return;
        const float k = shading / s.pdf[0];
        if constexpr (separable_bxdf<B>) {
            m_tb_max = scale(m_refl, B::cos_factor(wo, s.wi) * k);
        } else {
            sampled_spectrum<Bins> f = bxdf.template follow<Bins>(wo, s.wi, s.kind, spectra());
            if constexpr (B::reads_eta)
                if (s.kind == lobe::transmission) {
                    const view e2 = wo.z > 0.0f ? spectra().eta2() : spectra().inv_eta2();
                    for (std::size_t b = 0; b < Bins; ++b) f[b] *= e2[b];
                }
            m_tb_max = scale(f, k);
        }
    }
    /// \brief Multiply the throughput by k (the light subpath's cos θ / (p_pos p_dir)).
    void weigh(float k) noexcept {
        if (!m_on) return;
        for (std::size_t b = 0; b < Bins; ++b) m_tb[b] *= k;
        m_tb_max *= k;
    }
    /// \brief A connection of the light subpath's vertex to the camera, after
    /// `prepare_light(bxdf, ωc, ωo)` made the bins' f(ωc, ωo)·|cos θo| — the adjoint BSDF's
    /// value toward the camera up to the factor in k: v += Δλ Σ_b t_b f_b k cmf(λ_b). Not yet
    /// divided by ∫ȳ.
    template <class B>
    void connect(float k, xyz& v) noexcept {
        if (!m_on) return;
        if constexpr (separable_bxdf<B>) {
            const float g = m_cos * k;
            for (std::size_t b = 0; b < Bins; ++b) m_mix[b] = m_tb[b] * m_refl[b] * g;
        } else {
            for (std::size_t b = 0; b < Bins; ++b) m_mix[b] = m_tb[b] * m_f[b] * k;
        }
        sum_xyz(m_mix.data(), v);
    }
    /// \brief The emitter's own point seen by the camera (the light subpath's first vertex):
    /// v += Δλ Σ_b t_b k cmf(λ_b), t_b holding Le(λ_b) since `start_emitted`.
    void connect_emitter(float k, xyz& v) noexcept {
        if (!m_on) return;
        for (std::size_t b = 0; b < Bins; ++b) m_mix[b] = m_tb[b] * k;
        sum_xyz(m_mix.data(), v);
    }
    /// @}

    /// \brief The larger of m and B's largest throughput (a NaN in B is ignored).
    float roulette_max(float m) const noexcept { return m_on && m_tb_max > m ? m_tb_max : m; }
    /// \brief The path survived roulette with probability q < 1.
    void survive(float q) noexcept {
        if (m_on) m_tb /= q;
    }

    /// \brief v += Δλ Σ_b L_b cmf(λ_b): one pass, three sums in 8 interleaved partial sums
    /// each, in an order fixed here (so the same on every instruction set) that vectorises
    /// (one chain of 80 dependent adds would be latency-bound). Not yet divided by ∫ȳ.
    void add_xyz(xyz& v) const noexcept {
        if (!m_on) return;
        sum_xyz(m_lb.values().data(), v);
    }

    /// \brief The bins' point contributions (λ_b, Δλ · L_b) to a spectral row: what
    /// `add_xyz` weights by cmf(λ_b) (iris/render/spectral_bands.hpp).
    void add_spectral(spectral_row& row) const noexcept {
        if (!m_on) return;
        const double dl = static_cast<double>(m_t->lattice.bin_width());
        for (std::size_t b = 0; b < Bins; ++b)
            if (m_lb[b] != 0.0f) row.add(m_t->lattice.lambda(b, m_bp.u), dl * static_cast<double>(m_lb[b]));
    }

protected:
    /// \brief v += Δλ Σ_b w_b cmf(λ_b), in the fixed order `add_xyz` describes.
    void sum_xyz(const float* w_b, xyz& v) const noexcept {
        std::array<float, Bins> sx_, sy_, sz_;  // scratch, used only off the lattice
        const auto xb = m_t->x_bar.at(m_bp, sx_), yb = m_t->y_bar.at(m_bp, sy_), zb = m_t->z_bar.at(m_bp, sz_);
        constexpr std::size_t lanes = 8;
        std::array<float, lanes> sx{}, sy{}, sz{};
        const auto add = [&](std::size_t b, std::size_t l) {
            const float w = w_b[b];  // 1 − r_α(λ_b) is in the throughput already
            sx[l] += w * xb[b];
            sy[l] += w * yb[b];
            sz[l] += w * zb[b];
        };
        std::size_t b0 = 0;
        for (; b0 + lanes <= Bins; b0 += lanes)
            for (std::size_t l = 0; l < lanes; ++l) add(b0 + l, l);
        for (std::size_t l = 0; b0 + l < Bins; ++l) add(b0 + l, l);
        float x = 0.0f, y = 0.0f, z = 0.0f;
        for (std::size_t l = 0; l < lanes; ++l) {
            x += sx[l];
            y += sy[l];
            z += sz[l];
        }
        const double dl = static_cast<double>(m_t->lattice.bin_width());
        v.x += dl * static_cast<double>(x);
        v.y += dl * static_cast<double>(y);
        v.z += dl * static_cast<double>(z);
    }

    using view = typename binned_spectrum<Bins>::view;

    /// \brief The current material's spectra at the bins, as a BxDF reads them (bxdf.hpp):
    /// the reflectance read by `enter`, views of η, η², 1/η² on the lattice, and for a thin
    /// film λ_b itself and the film's index.
    struct bin_spectra {
        const propagation& p;
        const sampled_spectrum<Bins>& albedo() const noexcept { return p.m_refl; }
        view eta() const { return p.m_t->eta[p.m_material].at(p.m_bp, p.m_eta_scratch); }
        view eta2() const { return p.m_t->eta2[p.m_material].at(p.m_bp, p.m_eta2_scratch); }
        view inv_eta2() const { return p.m_t->inv_eta2[p.m_material].at(p.m_bp, p.m_inv_eta2_scratch); }
        view k() const { return p.m_t->k[p.m_material].at(p.m_bp, p.m_k_scratch); }
        view wavelength() const { return p.m_t->lambda.at(p.m_bp, p.m_film_scratch); }
        view film_eta() const { return p.m_t->film_eta[p.m_material].at(p.m_bp, p.m_film_scratch); }
    };
    bin_spectra spectra() const noexcept { return {*this}; }
    static_assert(film_source<bin_spectra>, "the bins must give a film's λ_b and index (materials/bxdf.hpp)");

    /// \brief Le at the bins as a view, and the scale `k` multiplied by what the view does
    /// not hold: an emitter's table and its weight (× 1 is exact, so an area light costs what
    /// it did), or the three basis tables of an environment texel mixed into `m_mix`.
    view emitted(const emission_ref& r, float& k) noexcept {
        if (r.count == 1) {
            if (r.weight[0] != 1.0f) k *= r.weight[0];
            return m_t->emission[r.first].at(m_bp, m_scratch);
        }
        for (std::size_t b = 0; b < Bins; ++b) m_mix[b] = 0.0f;
        for (std::uint32_t i = 0; i < r.count; ++i) {
            const view v = m_t->emission[r.first + i].at(m_bp, m_scratch);
            const float wi = r.weight[static_cast<int>(i)];
            for (std::size_t b = 0; b < Bins; ++b) m_mix[b] += wi * v[b];
        }
        return {m_mix.data(), m_mix.data(), 1.0f, 0.0f};  // x·1 + x·0 = x
    }

    /// \brief L_b += t_b · e_b · s. (The loops take their arrays as restrict pointers: `e` may
    /// view `m_scratch`, a member like L_b, and without them GCC versions the loop for
    /// aliasing — measured 3 % of `paper`'s time.)
    void add_light(const view& e, float s) noexcept { add_light(&m_lb[0], m_tb.values().data(), nullptr, e.lo, e.hi, e.s, e.t, s); }
    /// \brief L_b += t_b · f_b · e_b · s.
    void add_light(const sampled_spectrum<Bins>& f, const view& e, float s) noexcept {
        add_light(&m_lb[0], m_tb.values().data(), f.values().data(), e.lo, e.hi, e.s, e.t, s);
    }
    /// \brief lb_b += tb_b (· f_b) · (es·lo_b + et·hi_b) · s, the blend of `view::operator[]`.
    static void add_light(float* __restrict lb, const float* __restrict tb, const float* __restrict f,
                          const float* __restrict lo, const float* __restrict hi, float es, float et, float s) noexcept {
        if (f)
            for (std::size_t b = 0; b < Bins; ++b) lb[b] += tb[b] * f[b] * (es * lo[b] + et * hi[b]) * s;
        else
            for (std::size_t b = 0; b < Bins; ++b) lb[b] += tb[b] * (es * lo[b] + et * hi[b]) * s;
    }
    /// \brief t_b ← t_b · f_b · s; returns the largest new t_b. The throughput is ≥ 0, and
    /// for floats ≥ +0 the order of their bit patterns as int32 is their numeric order
    /// (negative values, −0 and negative NaNs count as 0; a positive NaN wins and
    /// `roulette_max` then ignores it): an integer maximum vectorises, a float one that
    /// honours NaN does not. In 16 interleaved lanes (the order cannot change a maximum).
    float scale(const sampled_spectrum<Bins>& f, float s) noexcept {
        for (std::size_t b = 0; b < Bins; ++b) m_tb[b] *= f[b] * s;
        constexpr std::size_t lanes = 16;
        std::array<std::int32_t, lanes> m{};
        const auto step = [&](std::size_t b, std::size_t l) {
            const auto v = std::bit_cast<std::int32_t>(m_tb[b]);
            m[l] = v > m[l] ? v : m[l];
        };
        std::size_t b0 = 0;
        for (; b0 + lanes <= Bins; b0 += lanes)
            for (std::size_t l = 0; l < lanes; ++l) step(b0 + l, l);
        for (std::size_t l = 0; b0 + l < Bins; ++l) step(b0 + l, l);
        std::int32_t out = 0;
        for (auto v : m) out = v > out ? v : out;
        return std::bit_cast<float>(out);
    }

    /// \brief out ← 1 − r_α(λ_b) at every bin of a sample with jitter u; false if that is 0
    /// everywhere. For a 0/1 kernel (boxes) r_α is 1 exactly on its support, a few disjoint
    /// intervals: each covers a run of bins [first, end), found by a division and moved onto
    /// the exact test lo ≤ λ_b ≤ hi (the one a kernel call would make), then zeroed in one
    /// branch-free pass. Other kernels are evaluated bin by bin.
public:
    template <class Distribution>
    static bool complement(const Distribution& dist, const bin_lattice<Bins>& lat, float u,
                           sampled_spectrum<Bins>& out) noexcept {
        if constexpr (requires { dist.bound_kernel().support(); } &&
                      requires { requires std::remove_cvref_t<decltype(dist.bound_kernel())>::indicator; }) {
            for (std::size_t b = 0; b < Bins; ++b) out[b] = 1.0f;  // in place: assigning a temporary costs a 320-byte rep movsq per sample
            const auto lambda = [&](int b) { return lat.lambda(static_cast<std::size_t>(b), u); };  // non-decreasing
            constexpr int n = static_cast<int>(Bins);
            int covered = 0;
            for (const auto& s : dist.bound_kernel().support()) {
                const auto estimate = [&](float edge) {
                    const float x = (edge - lat.lambda_min()) / lat.bin_width() - u;
                    return x <= 0.0f ? 0 : (x >= static_cast<float>(n) ? n : static_cast<int>(x));
                };
                int first = estimate(s.lo), end = estimate(s.hi);
                while (first > 0 && lambda(first - 1) >= s.lo) --first;
                while (first < n && lambda(first) < s.lo) ++first;
                while (end > 0 && lambda(end - 1) > s.hi) --end;
                while (end < n && lambda(end) <= s.hi) ++end;
                if (end <= first) continue;
                covered += end - first;
                const auto width = static_cast<unsigned>(end - first);
                for (int b = 0; b < n; ++b)  // b ∈ [first, end) as one unsigned comparison
                    out[static_cast<std::size_t>(b)] =
                        static_cast<unsigned>(b - first) < width ? 0.0f : out[static_cast<std::size_t>(b)];
            }
            return covered < n;  // the intervals are disjoint: their runs are too
        } else {
            bool any = false;
            for (std::size_t b = 0; b < Bins; ++b) {
                out[b] = 1.0f - dist.restriction(lat.lambda(b, u));
                any |= out[b] != 0.0f;
            }
            return any;
        }
    }

protected:
    const bin_tables<Bins>* m_t;  ///< a pointer, so that a workspace's instance can be reassigned
    bool m_on = false;
    bin_position m_bp;
    std::uint32_t m_material = 0;
    float m_tb_max = 0.0f;  ///< max of t_b, kept by every update of t_b (for Russian roulette)
    float m_cos = 0.0f;     ///< a separable BxDF's factor toward the light being sampled
    /// t_b (starts at 1 − r_α(λ_b)), L_b, the vertex's reflectance and its f·|cos| toward the light
    sampled_spectrum<Bins> m_tb, m_lb, m_refl, m_f;
    std::array<float, Bins> m_scratch;  ///< for emitters off the lattice (binned_spectrum::at)
    std::array<float, Bins> m_mix;      ///< an environment texel's spectrum at the bins
    mutable std::array<float, Bins> m_eta_scratch, m_eta2_scratch, m_inv_eta2_scratch, m_k_scratch;
    mutable std::array<float, Bins> m_film_scratch;  ///< never written: λ and a film's index are on the lattice
    std::array<float, Bins> m_att_scratch;  ///< σ_a at the bins, off the lattice
};

/// \brief The B term of one bidirectional sample (iris/render/bdpt.hpp; docs/method.md §3,
/// "The B term under bdpt"): `propagation`'s steps, and those that join a light subpath's
/// vertex to a camera subpath's or to the camera.
template <std::size_t Bins>
class bidirectional_propagation : public propagation<Bins> {
public:
    using propagation<Bins>::propagation;

    /// \name Bidirectional paths
    /// Two instances per sample: the camera subpath's (started by `start`, as the path
    /// tracer's: its t_b carries 1 − r_α(λ_b)), and a copy of it for the light subpath, whose
    /// t_b starts at the emitted spectrum alone — the complement is applied once per path:
    /// by the camera side's throughput, or at a connection to the camera. The light side's
    /// t_b at each vertex is kept (`throughput`); a connection of light vertex y to camera
    /// vertex z puts the light instance at y (`enter`, `prepare_light` toward z, then
    /// `light_vertex`) and the camera instance at z (`prepare_light` toward y, then
    /// `connect_vertex`).
    /// @{
    using vertex_throughput = sampled_spectrum<Bins>;
    /// \brief The light side leaves an emitter: the complement 1 − r_α is set aside,
    /// t_b ← Le(λ_b) · k.
    void start_light_subpath(const emission_ref& le, float k) noexcept {
        if (!this->m_on) return;
        this->m_c = this->m_tb;
        const typename propagation<Bins>::view v = this->emitted(le, k);
        for (std::size_t b = 0; b < Bins; ++b) this->m_tb[b] = v[b] * k;
        this->m_tb_max = 0.0f;
        for (std::size_t b = 0; b < Bins; ++b) this->m_tb_max = this->m_tb[b] > this->m_tb_max ? this->m_tb[b] : this->m_tb_max;
    }
    /// \brief The throughput arriving at the current vertex (kept per light vertex).
    const vertex_throughput& throughput() const noexcept { return this->m_tb; }
    /// \brief At light vertex y (after `enter` and `prepare_light(bxdf, ω toward z, ωo)`):
    /// g_b ← t_b(y) · f_b · k — the adjoint BSDF toward z with k its shading correction.
    template <class B>
    void light_vertex(const vertex_throughput& t, float k) noexcept {
        if (!this->m_on) return;
        if constexpr (separable_bxdf<B>) {
            const float g = this->m_cos * k;
            for (std::size_t b = 0; b < Bins; ++b) this->m_g[b] = t[b] * this->m_refl[b] * g;
        } else {
            for (std::size_t b = 0; b < Bins; ++b) this->m_g[b] = t[b] * this->m_f[b] * k;
        }
    }
    /// \brief At camera vertex z (after `prepare_light(bxdf, ωo, ω toward y)`), joined to the
    /// light instance `y` at its vertex: v += Δλ Σ_b t_b f_b g_b k cmf(λ_b), k the geometry
    /// term and the weight. Not yet divided by ∫ȳ.
    template <class B>
    void connect_vertex(const bidirectional_propagation& y, float k, xyz& v) noexcept {
        if (!this->m_on) return;
        if constexpr (separable_bxdf<B>) {
            const float g = this->m_cos * k;
            for (std::size_t b = 0; b < Bins; ++b) this->m_mix[b] = this->m_tb[b] * this->m_refl[b] * y.m_g[b] * g;
        } else {
            for (std::size_t b = 0; b < Bins; ++b) this->m_mix[b] = this->m_tb[b] * this->m_f[b] * y.m_g[b] * k;
        }
        this->sum_xyz(this->m_mix.data(), v);
    }
    /// \brief The light instance's vertex (after `light_vertex`) joined to the camera:
    /// v += Δλ Σ_b (1 − r_α(λ_b)) g_b k cmf(λ_b), k the camera's factor and the weight.
    void connect_camera(float k, xyz& v) noexcept {
        if (!this->m_on) return;
        for (std::size_t b = 0; b < Bins; ++b) this->m_mix[b] = this->m_c[b] * this->m_g[b] * k;
        this->sum_xyz(this->m_mix.data(), v);
    }
    /// @}

private:
    /// the light side's complement 1 − r_α(λ_b), set aside, and a light vertex's t_b f_b
    /// (with its shading correction) toward the vertex it is joined to
    sampled_spectrum<Bins> m_c, m_g;
};

}  // namespace iris
