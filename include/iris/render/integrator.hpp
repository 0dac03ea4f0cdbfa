#pragma once
/// \file
/// \brief `path_integrator<Config, Bins>`: unidirectional spectral path tracing with
/// next-event estimation, MIS between BSDF and light sampling, Russian roulette, C
/// hero-rotated wavelengths with the corrected HWSS MIS weight (docs/method.md §3, fix 1 in §4), and the
/// config's bias policy (docs/method.md §2, Bias policies).
///
/// Estimator per sample (docs/method.md §3): F = F_R (÷ Z_α for ScaledPdf) + B (PropagateUnused).
///   F_R = Σ_j r_α(λ_j) f(x̄, λ_j) / (p_α(λ_j) Σ_k p(x̄ | λ_k)),
/// where p(x̄ | λ_k) sums over the two strategies that can make the last vertex (BSDF
/// sampling and light sampling): the balance heuristic over C wavelengths × 2 strategies.
/// It is tracked in ratio form, as pbrt-v4 does: β_k = f(λ_k)/p(x̄|λ₀) and
/// ρ_k = p(x̄|λ_k)/p(x̄|λ₀), so f_j / Σ_k p_k = β_j / Σ_k ρ_k.
///   B = Σ_b (1 − r_α(λ_b)) f_h(x̄, λ_b) Δλ / p(x̄ | λ₀)
/// with the hero's own BSDF/light balance weights, carried by its own component
/// (`propagation<Bins>`, iris/render/propagation.hpp; `no_propagation` for policies without
/// B), whose steps `trace` calls where the hero path makes them.
/// The C wavelengths read reflectances and emitters from float tables on an exact 1 nm
/// lattice (`hero_tables`, same header), falling back to the scene's tables where the
/// lattice would not reproduce them exactly.
///
/// Materials are reached through one `visit_bxdf` per vertex
/// (iris/render/materials/materials.hpp): the rest of the vertex — next-event estimation,
/// BSDF sampling, the bins following the hero — is compiled for that material's BxDF, and
/// reads its spectra once (the hero's from `hero_tables` and the index model, the bins' from
/// `bin_tables` through the B term's `enter`). A vertex is: emission found by BSDF sampling
/// (`collect_emission`), next-event estimation (`next_event`), BSDF sampling, Russian
/// roulette (`survives_roulette`).
///
/// One instantiation serves every scene: without λ-dependent directions every p(x̄|λ_k)
/// equals the hero's, each ratio is exactly 1 and the MIS weight reduces to 1/C; a
/// separate instantiation that skipped the ratios saved nothing measurable and was
/// removed (docs/performance.md).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/absorption.hpp"
#include "iris/render/bins.hpp"
#include "iris/render/materials/materials.hpp"
#include "iris/render/medium.hpp"
#include "iris/render/propagation.hpp"
#include "iris/render/frame.hpp"
#include "iris/render/interaction.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/lights.hpp"
#include "iris/render/random.hpp"
#include "iris/render/sample_policy.hpp"
#include "iris/render/scene.hpp"
#include "iris/render/spectral_bands.hpp"
#include "iris/render/texture.hpp"
#include "iris/sampling/hwss.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief One sample's pixel estimate and the number of rays it traced.
struct path_sample {
    xyz value;
    std::uint32_t rays = 0;
};

/// \brief Settings of the path tracer that are not part of the sampling policy.
struct path_settings {
    int max_depth = 32;      ///< scattering events; emission is still collected at the last vertex
    int rr_start_depth = 3;  ///< Russian roulette from this depth on
};

/// \brief Which strategies a bidirectional render keeps, and how it weights them
/// (`bdpt_integrator`, iris/render/bdpt.hpp).
struct bdpt_settings {
    /// \brief Which paths a render keeps: all, or (for measurements) the paths no strategy
    /// but the camera's unidirectional s = 0 can make through a non-delta vertex — a light
    /// found by BSDF sampling after a specular–non-delta–specular chain (a caustic seen
    /// through glass) — or all the others. The two images sum to the whole.
    enum class paths { all, camera_only, rest };
    bool mis = true;  ///< false: each strategy weighted over the wavelengths alone (docs/method.md §3)
    int only_s = -1;  ///< ≥ 0: only strategies with this many light vertices
    int only_t = -1;  ///< ≥ 0: only strategies with this many camera vertices
    paths keep = paths::all;
};


template <class Config, std::size_t Bins = detail::bins_of<Config>()>
class path_integrator {
public:
    static constexpr std::size_t C = Config::wavelength_count;
    static constexpr bool propagates = Config::bias_type::propagates;
    static constexpr bool scales_pdf = Config::bias_type::scales_pdf;
    static constexpr std::size_t bins = Bins;

    path_integrator(const scene_desc& scene, const light_sampler& lights, path_settings settings = {})
        : m_scene(scene), m_lights(lights), m_settings(settings), m_hero(scene) {
        if constexpr (propagates) m_bins = bin_tables<Bins>(scene);
    }

    /// \brief Trace one path from `origin` along unit `dir`. `dist` is the restricted
    /// distribution at this sample's α (its `restriction`, `normalisation` and
    /// `sample_wavelengths<C>`); `alpha < 1` switches the B term on for PropagateUnused.
    /// With `spectral`, the sample's point contributions are also added to it (the spectral
    /// film's row, iris/render/spectral_bands.hpp).
    template <Intersector Tracer, class Distribution>
    path_sample trace(const Tracer& tracer, glm::vec3 origin, glm::vec3 dir, const Distribution& dist, float alpha,
                      sample_stream& rng, spectral_row* spectral = nullptr) const noexcept {
        path_sample out;
        const sampled_wavelengths<C> wl = dist.template sample_wavelengths<C>(rng.next());
        propagation_type bterm = make_propagation();
        if (propagates && alpha < 1.0f) bterm.start(dist, rng.next());  // only while the restriction is not yet relaxed
        hero_path hp;

        hp.medium = outside_medium(m_scene);  // the camera is in the scene's medium, if any
        for (int depth = 0;; ++depth) {
            rng.start_bounce(depth);  // the bounce's slots (random.hpp), whatever was skipped before
            const auto hit = tracer.intersect(origin, dir, std::numeric_limits<float>::infinity());
            ++out.rays;
            if (hp.medium != no_medium) {  // inside a medium (iris/render/absorption.hpp)
                const float t = hit ? hit->t : std::numeric_limits<float>::infinity();
                if (!m_hero.scatters(hp.medium)) {  // absorbing only: Beer–Lambert (docs/method.md §8)
                    hp.beta *= m_hero.transmittance(hp.medium, wl, t);
                    bterm.attenuate(hp.medium, t);
                } else {  // a free flight with the spectral MIS (iris/render/medium.hpp, docs/method.md §10)
                    const medium_coefficients<C> mc = m_hero.medium(hp.medium, wl);
                    const flight<C> fl = medium_flight(mc, t, rng.next_medium());
                    hp.beta *= fl.beta;
                    hp.rho *= fl.ratio;
                    bterm.attenuate(hp.medium, fl.t);
                    if (fl.scattered) {
                        if (depth >= m_settings.max_depth) break;
                        const surface_interaction vx = medium_interaction(origin + fl.t * dir, dir);
                        const hg_phase phase{mc.g};
                        bterm.enter(phase, hp.medium, emission_ref{});
                        glm::vec3 wi;
                        if (!scatter(tracer, phase, vx, no_medium, vx.wo, wl, sampled_spectra<C>{}, hp, bterm, rng, out, wi))
                            break;
                        if (depth + 1 >= m_settings.rr_start_depth && !survives_roulette(hp, bterm, rng)) break;
                        origin = vx.sp.p;
                        dir = wi;
                        continue;
                    }
                    hp.pass *= fl.hero_pass;
                }
            }
            if (!hit) {
                if (m_lights.has_environment()) collect_environment(dir, wl, hp, bterm);
                break;
            }
            const shape_desc& shape = m_scene.shapes[hit->shape];
            const auto si = make_interaction(m_scene, *hit, dir);
            if (!si) break;  // degenerate triangle
            const surface_interaction& vx = *si;

            if (shape.emitter) collect_emission(*shape.emitter, vx, wl, hp, bterm);  // found by BSDF sampling
            if (depth >= m_settings.max_depth) break;
            const glm::vec3 lo = vx.to_local(vx.wo);  // the BxDF's ωo, in the shading frame
            // one visit: the rest of the vertex is compiled for its material's BxDF
            glm::vec3 wi;
            const bool scattered = visit_bxdf(m_scene.materials[shape.material], [&](const auto& bxdf) {
                // the material's spectra, each read once per vertex (a diffuse vertex reads its
                // reflectance for NEE and for BSDF sampling): the hero's from its lattice tables
                // and the index model, the bins' from theirs
                emission_ref albedo;  // the reflectance at the hit: the material's table, or a texel's basis mix
                const sampled_spectra<C> hero = m_hero.at_vertex(bxdf, m_scene, shape.material, vx.uv, wl, albedo);
                bterm.enter(bxdf, shape.material, albedo);
                return scatter(tracer, bxdf, vx, shape.material, lo, wl, hero, hp, bterm, rng, out, wi);
            });
            if (!scattered) break;
            hp.medium = medium_after(m_scene, shape.material, vx.ng, wi, hp.medium);
            if (depth + 1 >= m_settings.rr_start_depth && !survives_roulette(hp, bterm, rng)) break;
            origin = offset_ray_origin(vx.sp, vx.ng, wi);
            dir = wi;
        }

        // F_R: Σ_j r_α(λ_j)/p_α(λ_j) (÷ Z_α) · L_j · cmf(λ_j), then B's Σ_b
        xyz v;
        if (!hp.lc.is_zero()) {  // (many paths carry nothing: no weights to compute)
            const std::array<double, C> w = detail::restricted_weights<Config>(dist, wl);
            for (std::size_t j = 0; j < C; ++j) {
                if (!(wl.pdf(j) > 0.0f) || hp.lc[j] == 0.0f) continue;
                add_cmf(v, w[j] * static_cast<double>(hp.lc[j]), wl[j]);
                if (spectral) spectral->add(wl[j], w[j] * static_cast<double>(hp.lc[j]));
            }
        }
        bterm.add_xyz(v);
        if (spectral) bterm.add_spectral(*spectral);
        constexpr double k = 1.0 / cie::y_integral;
        out.value = {v.x * k, v.y * k, v.z * k};
        return out;
    }

private:
    using propagation_type = std::conditional_t<propagates, propagation<Bins>, no_propagation>;
    propagation_type make_propagation() const noexcept {
        if constexpr (propagates) return propagation_type(m_bins);
        else return {};
    }

    /// \brief The hero path's state in ratio form (pbrt-v4's): β_k = f(λ_k)/p(x̄|λ₀),
    /// ρ_k = p(x̄|λ_k)/p(x̄|λ₀) (and before the last vertex, for the light-sampling MIS
    /// weight of emission found by BSDF sampling), the C wavelengths' radiance so far, and
    /// what the last scattering was.
    struct hero_path {
        sampled_spectrum<C> beta{1.0f}, rho{1.0f}, rho_before{1.0f}, lc;
        /// Π η′² over the hero's transmissions: β carries 1/η′² per crossing (radiance is
        /// compressed entering glass), which says nothing about what the path will still
        /// carry out of it; roulette looks at β·eta_scale (pbrt-v4's etaScale)
        float eta_scale = 1.0f;
        bool prev_delta = true;  ///< the camera ray: no light-sampling strategy competes
        float prev_pdf = 0.0f;
        std::uint32_t medium = no_medium;  ///< the medium the ray is in (iris/render/absorption.hpp)
        /// the hero's probability of flying through the scattering media since the last
        /// vertex without scattering: part of its BSDF-sampling strategy's density for light
        /// found at the end of the flight (iris/render/medium.hpp)
        float pass = 1.0f;

        void scatter(const bsdf_sample<C>& s) noexcept {
            const float p0 = s.pdf[0];
            pass = 1.0f;
            beta *= s.f_cos / p0;
            rho_before = rho;
            rho *= s.pdf / p0;
            prev_delta = s.delta;
            prev_pdf = p0;
            if (s.kind == lobe::transmission) eta_scale *= s.eta * s.eta;
        }
    };

    /// \brief The rest of a vertex once its BxDF's spectra are read (`hero`, and the B term's
    /// `enter`): next-event estimation unless the BxDF is delta, then BSDF sampling with the
    /// hero wavelength, which the bins follow. False: the path ends. `wi` (world): the
    /// direction sampled. A surface of material `material`, or a point in a medium (`hg_phase`,
    /// material `no_medium`). The sample stays in here: returning it through the material's
    /// visit cost a copy with store-forwarding stalls.
    template <Intersector Tracer, class B, class Prop>
    bool scatter(const Tracer& tracer, const B& bxdf, const surface_interaction& vx, std::uint32_t material,
                 const glm::vec3& lo, const sampled_wavelengths<C>& wl, const sampled_spectra<C>& hero, hero_path& hp,
                 Prop& bterm, sample_stream& rng, path_sample& out, glm::vec3& wi) const noexcept {
        if constexpr (!B::delta) next_event(tracer, bxdf, vx, material, lo, wl, hero, hp, bterm, rng, out);
        const float u_lobe = rng.next();
        const auto s = bxdf.template sample<C>(lo, wl, u_lobe, rng.next2(), hero);
        if (!s || !(s->pdf[0] > 0.0f)) return false;
        bterm.follow(bxdf, lo, *s);
        hp.scatter(*s);
        wi = glm::normalize(vx.to_world(s->wi));
        return true;
    }

    /// \brief A scattering point p in a medium, reached along unit `dir`, as an interaction:
    /// no surface (a zero normal and error, so rays leave from p itself), the identity frame
    /// (the phase function takes world directions).
    static surface_interaction medium_interaction(const glm::vec3& p, const glm::vec3& dir) noexcept {
        surface_interaction vx;
        vx.sp = {p, glm::vec3(0.0f)};
        vx.shading = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
        vx.wo = -dir;
        return vx;
    }

    /// \brief The environment found by a ray escaping along unit `dir` (BSDF sampling, or
    /// seen directly), MIS-weighted against light sampling unless the last scattering was delta.
    template <class Prop>
    void collect_environment(const glm::vec3& dir, const sampled_wavelengths<C>& wl, hero_path& hp,
                             Prop& bterm) const noexcept {
        const float pl = hp.prev_delta ? 0.0f : m_lights.pdf_environment(dir);
        collect(m_lights.environment_emission(dir), pl > 0.0f, pl, wl, hp, bterm);
    }

    /// \brief Emission found by BSDF sampling (or seen directly), MIS-weighted against light
    /// sampling unless the last scattering was delta.
    template <class Prop>
    void collect_emission(std::uint32_t e, const surface_interaction& vx, const sampled_wavelengths<C>& wl,
                          hero_path& hp, Prop& bterm) const noexcept {
        const emitter_desc& em = m_scene.emitters[e];
        const float cos_l = glm::dot(vx.ng, vx.wo);
        if (!(em.two_sided ? cos_l != 0.0f : cos_l > 0.0f)) return;
        const float pl = hp.prev_delta ? 0.0f : m_lights.pdf_area(vx.shape, vx.prim) * vx.t * vx.t / std::fabs(cos_l);
        collect(emission_ref{e, 1, {1.0f, 0.0f, 0.0f}}, !hp.prev_delta, pl, wl, hp, bterm);
    }

    /// \brief Emission `le` reached by BSDF sampling, whose light-sampling pdf (solid angle)
    /// is `pl`: with `mis`, the balance heuristic over C wavelengths × {BSDF, light}
    /// (docs/method.md), otherwise over the wavelengths alone.
    template <class Prop>
    void collect(const emission_ref& le, bool mis, float pl, const sampled_wavelengths<C>& wl, hero_path& hp,
                 Prop& bterm) const noexcept {
        float denom, w_hero = 1.0f;
        if (mis) {
            const float pb = hp.prev_pdf * hp.pass;  // the hero's BSDF strategy, through the media flown
            denom = hwss_emission_ratio_sum(hp.rho, hp.rho_before, pl, pb);
            w_hero = balance_heuristic(pb, pl);
        } else {
            denom = hwss_ratio_sum(hp.rho);
        }
        hp.lc += hp.beta * m_hero.emitted(le, wl) / denom;
        bterm.emission(le, w_hero);
    }

    /// \brief Next-event estimation at a non-delta vertex: one light (chosen by power), one
    /// direction toward it in solid angle, one shadow ray; the balance heuristic over C
    /// wavelengths × {BSDF, light} sampling for the hero path and the hero's two-strategy
    /// weight for the B term. A delta light (point, spot, distant) has no BSDF strategy:
    /// its weight is over the wavelengths alone (p_b = 0 in the same formula), and the BxDF's
    /// pdf is not evaluated. `lo` is ωo in the shading frame.
    template <Intersector Tracer, class B, class Prop>
    void next_event(const Tracer& tracer, const B& bxdf, const surface_interaction& vx, std::uint32_t material,
                    const glm::vec3& lo, const sampled_wavelengths<C>& wl, const sampled_spectra<C>& hero, hero_path& hp,
                    Prop& bterm, sample_stream& rng, path_sample& out) const noexcept {
        if (m_lights.empty()) return;
        const glm::vec2 u_point = rng.next2();  // slots in the order of random.hpp's layout
        const float u_choice = rng.next();
        const auto ls = m_lights.sample_li(vx.sp, vx.ng, u_choice, u_point);
        if (!ls || !(ls->pdf > 0.0f)) return;
        const glm::vec3 li = vx.to_local(ls->wi);
        // f·|cos| and, for a light a BSDF sample could hit, the BSDF's pdf: one evaluation
        bsdf_value<C> fb;
        if (ls->delta) fb.f_cos = bxdf.template f_cos<C>(lo, li, hero);
        else fb = bxdf.template eval<C>(lo, li, hero);
        const sampled_spectrum<C>& f = fb.f_cos;
        bterm.prepare_light(bxdf, lo, li);
        if (f.is_zero() && !bterm.template receives_light<B>()) return;
        ++out.rays;
        if (tracer.occluded(ls->shadow.origin, ls->shadow.direction, ls->shadow.t_max)) return;
        const float pl = ls->pdf;
        const sampled_spectrum<C>& pb = fb.pdf;
        // the medium toward the light: the vertex's own in a medium, else the one the surface leads to
        std::uint32_t medium;
        if constexpr (is_phase_v<B>) medium = hp.medium;
        else medium = medium_after(m_scene, material, vx.ng, ls->wi, hp.medium);
        if (medium == no_medium) {
            const float w_light = balance_heuristic(pl, pb[0]);
            hp.lc += hp.beta * f * m_hero.emitted(ls->le, wl) / (pl * hwss_light_ratio_sum(hp.rho, pb, pl));
            bterm.template light<B>(ls->le, w_light, pl);
        } else {  // the shadow ray crosses a medium (a lamp inside coloured glass, fog)
            const float d = std::isfinite(ls->shadow.t_max) ? glm::length(ls->shadow.direction)
                                                            : std::numeric_limits<float>::infinity();
            // BSDF sampling reaches the light only by flying through: its density has the
            // flight's probability, per wavelength (iris/render/medium.hpp)
            sampled_spectrum<C> pbt = pb;
            float pass0 = 1.0f;
            if (m_hero.scatters(medium)) {
                const sampled_spectrum<C> ss = m_hero.scattering[medium](wl);
                for (std::size_t k = 0; k < C; ++k) pbt[k] = pb[k] * exp_neg(ss[k], d);
                pass0 = exp_neg(ss[0], d);
            }
            const float w_light = balance_heuristic(pl, pbt[0]);
            hp.lc += hp.beta * f * m_hero.transmittance(medium, wl, d) * m_hero.emitted(ls->le, wl) /
                     (pl * hwss_light_ratio_sum(hp.rho, pbt, pl));
            bterm.template light_absorbed<B>(ls->le, w_light, pl, medium, d, pass0);
        }
    }

    /// \brief Russian roulette on the largest remaining weight (same for every λ: MIS ratios
    /// unchanged), the B term's counted as it is carried (bins in the windows are 0), with
    /// the radiance scaling of the transmissions so far undone (η′², hero's). False: the
    /// path ends; otherwise the weights are divided by the survival probability.
    template <class Prop>
    static bool survives_roulette(hero_path& hp, Prop& bterm, sample_stream& rng) noexcept {
        const float m = bterm.roulette_max(hp.beta.max_value()) * hp.eta_scale;
        const float survive = m < 1.0f ? m : 1.0f;  // (NaN → 1, as fmin)
        if (!(survive > 0.0f) || rng.next() >= survive) return false;
        if (survive < 1.0f) {  // x / 1 = x: skip the pass
            hp.beta /= survive;
            bterm.survive(survive);
        }
        return true;
    }

    const scene_desc& m_scene;
    const light_sampler& m_lights;
    path_settings m_settings;
    hero_tables m_hero;       ///< the spectra the C wavelengths read, on an exact 1 nm lattice
    bin_tables<Bins> m_bins;  ///< empty unless the bias policy propagates
};

}  // namespace iris
