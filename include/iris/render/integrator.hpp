#pragma once
/// \file
/// \brief `path_integrator<Config, Features>`: unidirectional spectral path tracing with
/// next-event estimation, MIS between BSDF and light sampling, Russian roulette, C
/// hero-rotated wavelengths with the corrected HWSS MIS weight (SPEC §2), and the
/// config's bias policy (SPEC §3).
///
/// Estimator per sample (SPEC): F = F_R (÷ Z_α for ScaledPdf) + B (PropagateUnused).
///   F_R = Σ_j r_α(λ_j) f(x̄, λ_j) / (p_α(λ_j) Σ_k p(x̄ | λ_k)),
/// where p(x̄ | λ_k) sums over the two strategies that can make the last vertex (BSDF
/// sampling and light sampling): the balance heuristic over C wavelengths × 2 strategies.
/// It is tracked in ratio form, as pbrt-v4 does: β_k = f(λ_k)/p(x̄|λ₀) and
/// ρ_k = p(x̄|λ_k)/p(x̄|λ₀), so f_j / Σ_k p_k = β_j / Σ_k ρ_k.
///   B = Σ_b (1 − r_α(λ_b)) f_h(x̄, λ_b) Δλ / p(x̄ | λ₀)
/// with the hero's own BSDF/light balance weights; λ_b = λmin + (b + u)Δλ (one jitter u
/// per sample shared by all bins, so each λ_b is uniform in its bin). The spectra of the
/// B term are read from tables on the bins' lattice built once per integrator
/// (iris/render/bins.hpp): each is one blend of two rows, not a per-bin table lookup. The
/// bins' throughput starts at 1 − r_α(λ_b), so the sum over bins needs no weight at the end
/// and Russian roulette sees only what B carries.
/// The C wavelengths read reflectances and emitters from float tables on an exact 1 nm
/// lattice (`hero_tables`, same header), falling back to the scene's tables where the
/// lattice would not reproduce them exactly.
///
/// `Dispersive = false` is the instantiation for scenes without λ-dependent directions:
/// there every p(x̄|λ_k) equals the hero's, ρ ≡ 1, so no per-wavelength pdf is evaluated
/// or tracked (the feature summary picks it; docs/performance.md measures what it saves).

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/bins.hpp"
#include "iris/render/bsdf.hpp"
#include "iris/render/frame.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/lights.hpp"
#include "iris/render/random.hpp"
#include "iris/render/scene.hpp"
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

namespace detail {
/// \brief The B term's bin count of a config: its bias policy's `bins` (80 — 5 nm on
/// 380–780 nm — for PropagateUnused; fewer for `propagate_coarse<B>`); 1 (unused) for
/// policies without a B term, so that they carry no 80-wide spectra.
template <class Config>
constexpr std::size_t bins_of() noexcept {
    if constexpr (requires { Config::bias_type::bins; }) return Config::bias_type::bins;
    else return 1;
}
}  // namespace detail

template <class Config, bool Dispersive, std::size_t Bins = detail::bins_of<Config>()>
class path_integrator {
public:
    static constexpr std::size_t C = Config::wavelength_count;
    static constexpr bool propagates = Config::bias_type::propagates;
    static constexpr bool scales_pdf = Config::bias_type::scales_pdf;
    static constexpr bool dispersive = Dispersive;
    static constexpr std::size_t bins = Bins;

    path_integrator(const scene_desc& scene, const light_sampler& lights, path_settings settings = {})
        : m_scene(scene), m_lights(lights), m_settings(settings), m_hero(scene) {
        if constexpr (propagates) m_bins = bin_tables<Bins>(scene);
    }

    /// \brief Trace one path from `origin` along unit `dir`. `dist` is the restricted
    /// distribution at this sample's α (its `restriction`, `normalisation` and
    /// `sample_wavelengths<C>`); `alpha < 1` switches the B term on for PropagateUnused.
    template <Intersector Tracer, class Distribution>
    path_sample trace(const Tracer& tracer, glm::vec3 origin, glm::vec3 dir, const Distribution& dist, float alpha,
                      sample_stream& rng) const noexcept {
        path_sample out;
        const sampled_wavelengths<C> wl = dist.template sample_wavelengths<C>(rng.next());

        // B-term bins (only while the restriction is not yet relaxed)
        bool use_bins = propagates && alpha < 1.0f;
        bin_position bp;
        // the B term's path throughput, which starts at 1 − r_α(λ_b) (the share of each bin
        // that B carries: bins inside the windows start and stay 0), its radiance, and a
        // vertex's reflectance and BSDF value at the bins
        sampled_spectrum<Bins> tb, lb, bin_refl, fb;
        float tb_max = 0.0f;  // max of tb, kept by every update of tb (for Russian roulette)
        if (use_bins) {
            const float jitter = rng.next();
            bp = m_bins.lattice.position(jitter);
            use_bins = complement(dist, jitter, tb);  // false: every bin inside the windows, B = 0
            tb_max = 1.0f;
        }

        sampled_spectrum<C> beta(1.0f), rho(1.0f), rho_before(1.0f), lc;
        std::array<float, Bins> scratch, eta_scratch, eta2_scratch, inv_eta2_scratch;  // for spectra off the bins' lattice (binned_spectrum::at)
        // Π η′² over the hero's transmissions: β carries 1/η′² per crossing (radiance is
        // compressed entering glass), which says nothing about what the path will still
        // carry out of it; roulette looks at β·eta_scale (pbrt-v4's etaScale)
        float eta_scale = 1.0f;
        bool prev_delta = true;  // the camera ray: no light-sampling strategy competes
        float prev_pdf = 0.0f;

        for (int depth = 0;; ++depth) {
            const auto hit = tracer.intersect(origin, dir, std::numeric_limits<float>::infinity());
            ++out.rays;
            if (!hit) {
                if (m_scene.environment) {  // not light-sampled: BSDF sampling is its only strategy
                    const float denom = sum_rho(rho);
                    lc += beta * m_hero.environment(wl) / denom;
                    if (use_bins) add_light(lb, tb, m_bins.environment.at(bp, scratch), 1.0f);
                }
                break;
            }
            const shape_desc& shape = m_scene.shapes[hit->shape];
            const auto& tri = shape.mesh.triangles[hit->prim];
            const glm::vec3 &v0 = shape.mesh.positions[tri[0]], &v1 = shape.mesh.positions[tri[1]],
                            &v2 = shape.mesh.positions[tri[2]];
            const surface_point sp = point_on_triangle(v0, v1, v2, hit->u, hit->v);  // with its error bound
            const glm::vec3 p = sp.p;
            const glm::vec3 wo = -dir;
            glm::vec3 ng = glm::cross(v1 - v0, v2 - v0);
            const float ng_len = glm::length(ng);
            if (!(ng_len > 0.0f)) break;  // degenerate triangle
            ng /= ng_len;

            // emission found by BSDF sampling (or seen directly)
            if (shape.emitter) {
                const emitter_desc& em = m_scene.emitters[*shape.emitter];
                const float cos_l = glm::dot(ng, wo);
                if (em.two_sided ? cos_l != 0.0f : cos_l > 0.0f) {
                    float denom, w_hero = 1.0f;
                    if (prev_delta) {
                        denom = sum_rho(rho);
                    } else {
                        const float pl = m_lights.pdf_area(hit->shape, hit->prim) * hit->t * hit->t / std::fabs(cos_l);
                        denom = sum_rho(rho) + (pl / prev_pdf) * sum_rho(rho_before);
                        w_hero = prev_pdf / (prev_pdf + pl);
                    }
                    lc += beta * m_hero.emission[*shape.emitter](wl) / denom;
                    if (use_bins) add_light(lb, tb, m_bins.emission[*shape.emitter].at(bp, scratch), w_hero);
                }
            }
            if (depth >= m_settings.max_depth) break;
            const material_desc& mat = m_scene.materials[shape.material];
            const bool delta = is_delta(mat);
            // a diffuse vertex reads its reflectance twice (NEE and BSDF sampling): look it up
            // once, for the hero wavelengths and for the bins
            const bool has_albedo = !std::holds_alternative<material::dielectric>(mat);
            // Lambertian: the bins' BSDF is bin_refl times one number (lambert_cos), no 80-wide product
            const bool lambertian = std::holds_alternative<material::diffuse>(mat);
            sampled_spectrum<C> hero_refl;
            if (has_albedo) {
                hero_refl = m_hero.albedo[shape.material](wl);
                if (use_bins) m_bins.albedo[shape.material].evaluate(bp, bin_refl);
            }
            const auto hero_albedo = [&] { return hero_refl; };
            const auto hero_eta = [&] { return detail::etas(std::get<material::dielectric>(mat).ior, wl); };
            const auto bin_albedo = [&]() -> const sampled_spectrum<Bins>& { return bin_refl; };
            const auto bin_eta = [&] { return m_bins.eta[shape.material].at(bp, eta_scratch); };
            const auto bin_eta2 = [&] { return m_bins.eta2[shape.material].at(bp, eta2_scratch); };
            const auto bin_inv_eta2 = [&] { return m_bins.inv_eta2[shape.material].at(bp, inv_eta2_scratch); };

            // next-event estimation
            if (!delta && !m_lights.empty()) {
                const auto ls = m_lights.sample(rng.next(), rng.next2());
                if (ls) {
                    const glm::vec3 to_light = ls->point.p - p;
                    const float d2 = glm::dot(to_light, to_light);
                    const float d = std::sqrt(d2);
                    const glm::vec3 wi = to_light / d;
                    const float cos_l = -glm::dot(ls->normal, wi);
                    const emitter_desc& em = m_scene.emitters[ls->emitter];
                    const bool emits = em.two_sided ? cos_l != 0.0f : cos_l > 0.0f;
                    if (emits && d > 0.0f) {
                        const sampled_spectrum<C> f = bsdf_eval_given<C>(mat, ng, wo, wi, hero_albedo, hero_eta);
                        // the bins' BSDF too: a surface black at every hero wavelength (say,
                        // inside the restriction's windows) may still reflect at the bins,
                        // and B must keep its light-sampling share there (SPEC U1)
                        float cb = 0.0f;  // Lambertian: the bins' value is bin_refl · cb
                        if (use_bins) {
                            if (lambertian) cb = lambert_cos(ng, wo, wi);
                            else fb = bsdf_eval_given<Bins>(mat, ng, wo, wi, bin_albedo, bin_eta);
                        }
                        const auto bins_reflect = [&] {
                            return use_bins && (lambertian ? cb != 0.0f && !bin_refl.is_zero() : !fb.is_zero());
                        };
                        if (!f.is_zero() || bins_reflect()) {
                            ++out.rays;
                            const shadow_segment sh = shadow_ray_between(sp, ng, ls->point, ls->normal);
                            if (!tracer.occluded(sh.origin, sh.direction, sh.t_max)) {
                                const float pl = ls->pdf_area * d2 / std::fabs(cos_l);
                                const sampled_spectrum<C> pb = bsdf_pdfs(mat, ng, wo, wi, wl);
                                float denom = 0.0f;
                                for (std::size_t k = 0; k < C; ++k) denom += rho_k(rho, k) * (1.0f + pb[k] / pl);
                                lc += beta * f * m_hero.emission[ls->emitter](wl) / (pl * denom);
                                if (use_bins) {
                                    const float w_hero = pl / (pl + pb[0]);
                                    const auto e = m_bins.emission[ls->emitter].at(bp, scratch);
                                    if (lambertian) add_light(lb, tb, bin_refl, e, cb * (w_hero / pl));
                                    else add_light(lb, tb, fb, e, w_hero / pl);
                                }
                            }
                        }
                    }
                }
            }

            // BSDF sampling with the hero wavelength
            const float u_lobe = rng.next();
            const auto bs = bsdf_sample_hero_given(mat, ng, wo, wl, u_lobe, rng.next2(), hero_albedo);
            if (!bs) break;
            const float p0 = bs->pdf[0];
            if (!(p0 > 0.0f)) break;
            if (use_bins) {
                const float inv_p0 = 1.0f / p0;
                if (bs->delta)
                    tb_max = scale(tb, delta_weight_given<Bins>(mat, ng, wo, bs->kind, bin_albedo, bin_eta2, bin_inv_eta2), inv_p0);
                else if (lambertian)
                    tb_max = scale(tb, bin_refl, lambert_cos(ng, wo, bs->wi) * inv_p0);
                else
                    tb_max = scale(tb, bsdf_eval_given<Bins>(mat, ng, wo, bs->wi, bin_albedo, bin_eta), inv_p0);
            }
            beta *= bs->f_cos / p0;
            if constexpr (Dispersive) {
                rho_before = rho;
                rho *= bs->pdf / p0;
            }
            prev_delta = bs->delta;
            prev_pdf = p0;
            if (bs->kind == lobe::transmission) eta_scale *= bs->eta * bs->eta;

            // Russian roulette on the largest remaining weight (same for every λ: MIS ratios
            // unchanged), the B term's counted as it is carried (bins in the windows are 0),
            // without the radiance scaling of the transmissions so far (η′², hero's)
            if (depth + 1 >= m_settings.rr_start_depth) {
                float m = beta.max_value();
                if (use_bins && tb_max > m) m = tb_max;
                m *= eta_scale;
                const float survive = m < 1.0f ? m : 1.0f;  // (NaN → 1, as fmin)
                if (!(survive > 0.0f) || rng.next() >= survive) break;
                if (survive < 1.0f) {  // x / 1 = x: skip the pass
                    beta /= survive;
                    if (use_bins) tb /= survive;
                }
            }
            origin = offset_ray_origin(sp, ng, bs->wi);
            dir = bs->wi;
        }

        // F_R: Σ_j r_α(λ_j)/p_α(λ_j) · L_j · cmf(λ_j)
        xyz v;
        const float z = scales_pdf ? dist.normalisation() : 1.0f;
        for (std::size_t j = 0; j < C; ++j) {
            if (!(wl.pdf(j) > 0.0f) || lc[j] == 0.0f) continue;
            const double w = static_cast<double>(dist.restriction(wl[j])) / (static_cast<double>(wl.pdf(j)) * z);
            add_cmf(v, w * static_cast<double>(lc[j]), wl[j]);
        }
        if (use_bins) {
            // Σ_b (1 − r_α(λ_b)) Δλ L_b · cmf(λ_b): one pass, three sums in 8 interleaved
            // partial sums each, in an order fixed here (so the same on every instruction
            // set) that vectorises (one chain of 80 dependent adds would be latency-bound)
            std::array<float, Bins> sy_, sz_;  // more scratch, used only off the lattice
            const auto xb = m_bins.x_bar.at(bp, scratch), yb = m_bins.y_bar.at(bp, sy_), zb = m_bins.z_bar.at(bp, sz_);
            constexpr std::size_t lanes = 8;
            std::array<float, lanes> sx{}, sy{}, sz{};
            const auto add = [&](std::size_t b, std::size_t l) {
                const float w = lb[b];  // 1 − r_α(λ_b) is in the throughput already
                sx[l] += w * xb[b];
                sy[l] += w * yb[b];
                sz[l] += w * zb[b];
            };
            std::size_t b0 = 0;
            for (; b0 + lanes <= Bins; b0 += lanes)
                for (std::size_t l = 0; l < lanes; ++l) add(b0 + l, l);
            for (std::size_t l = 0; b0 + l < Bins; ++l) add(b0 + l, l);
            float x = 0.0f, y = 0.0f, zz = 0.0f;
            for (std::size_t l = 0; l < lanes; ++l) {
                x += sx[l];
                y += sy[l];
                zz += sz[l];
            }
            const double dl = static_cast<double>(m_bins.lattice.bin_width());
            v.x += dl * static_cast<double>(x);
            v.y += dl * static_cast<double>(y);
            v.z += dl * static_cast<double>(zz);
        }
        constexpr double k = 1.0 / cie::y_integral;
        out.value = {v.x * k, v.y * k, v.z * k};
        return out;
    }

private:
    using bin_view = typename binned_spectrum<Bins>::view;
    // The B term's updates, each one pass over the bins (no temporary spectra)
    /// \brief lb += tb · e · s (emission e reached with weight s).
    static void add_light(sampled_spectrum<Bins>& lb, const sampled_spectrum<Bins>& tb, const bin_view& e,
                          float s) noexcept {
        for (std::size_t b = 0; b < Bins; ++b) lb[b] += tb[b] * e[b] * s;
    }
    /// \brief lb += tb · f · e · s (emission e through the BSDF value f, weight s).
    static void add_light(sampled_spectrum<Bins>& lb, const sampled_spectrum<Bins>& tb,
                          const sampled_spectrum<Bins>& f, const bin_view& e, float s) noexcept {
        for (std::size_t b = 0; b < Bins; ++b) lb[b] += tb[b] * f[b] * e[b] * s;
    }
    /// \brief tb ← tb · f · s; returns the largest new tb. The throughput is ≥ 0, and for
    /// floats ≥ +0 the order of their bit patterns as int32 is their numeric order (negative
    /// values, −0 and negative NaNs count as 0; a positive NaN wins and the caller's
    /// `tb_max > m` then ignores it): an integer maximum vectorises, a float one that
    /// honours NaN does not. In 16 interleaved lanes (the order cannot change a maximum).
    static float scale(sampled_spectrum<Bins>& tb, const sampled_spectrum<Bins>& f, float s) noexcept {
        for (std::size_t b = 0; b < Bins; ++b) tb[b] *= f[b] * s;
        constexpr std::size_t lanes = 16;
        std::array<std::int32_t, lanes> m{};
        const auto step = [&](std::size_t b, std::size_t l) {
            const auto v = std::bit_cast<std::int32_t>(tb[b]);
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
    template <class Distribution>
    bool complement(const Distribution& dist, float u, sampled_spectrum<Bins>& out) const noexcept {
        const auto& lat = m_bins.lattice;
        if constexpr (requires { dist.bound_kernel().support(); } &&
                      requires { requires std::remove_cvref_t<decltype(dist.bound_kernel())>::indicator; }) {
            out = sampled_spectrum<Bins>(1.0f);
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
    static float rho_k(const sampled_spectrum<C>& rho, std::size_t k) noexcept {
        if constexpr (Dispersive) return rho[k];
        else {
            (void)rho;
            (void)k;
            return 1.0f;
        }
    }
    static float sum_rho(const sampled_spectrum<C>& rho) noexcept {
        if constexpr (Dispersive) return rho.sum();
        else {
            (void)rho;
            return static_cast<float>(C);
        }
    }
    /// \brief Per-wavelength BSDF pdfs; without dispersion all equal the hero's.
    static sampled_spectrum<C> bsdf_pdfs(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo,
                                         const glm::vec3& wi, const sampled_wavelengths<C>& wl) noexcept {
        if constexpr (Dispersive) return bsdf_pdf(mat, n, wo, wi, wl);
        else return sampled_spectrum<C>(bsdf_pdf(mat, n, wo, wi, sampled_wavelengths<1>({wl[0]}, {1.0f}))[0]);
    }
    static void add_cmf(xyz& v, double w, float lambda) noexcept {
        const double l = static_cast<double>(lambda);
        v.x += w * cie::x_bar(l);
        v.y += w * cie::y_bar(l);
        v.z += w * cie::z_bar(l);
    }

    const scene_desc& m_scene;
    const light_sampler& m_lights;
    path_settings m_settings;
    hero_tables m_hero;       ///< the spectra the C wavelengths read, on an exact 1 nm lattice
    bin_tables<Bins> m_bins;  ///< empty unless the bias policy propagates
};

}  // namespace iris
