#pragma once
/// \file
/// \brief `light_integrator<Config, Bins>`: light tracing — paths started at the emitters,
/// each vertex connected to the pinhole camera and *splatted* onto the pixel it projects to
/// (the t = 1 strategies of bidirectional path tracing) — with the C hero-rotated
/// wavelengths and the config's bias policy, as the path tracer has them
/// (docs/method.md §3, "Light tracing").
///
/// Per light subpath x̄ = (x₀ on a light, x₁, …), the splat of vertex x_i onto pixel j is
///   F_R = Σ_c r_α(λ_c) f_j(x̄_i, λ_c) / (p_α(λ_c) Σ_k p(x̄_i | λ_k))   (÷ Z_α for ScaledPdf),
/// f_j the measurement contribution of the path x₀ … x_i → camera (its last factor the
/// camera's importance W_e(x_i → camera) cos θ_c / d² and the adjoint BSDF at x_i), and
/// p(x̄_i | λ_k) the density of sampling x₀ … x_i with λ_k as the hero (a light, a point and
/// a direction on it, then the BSDF's directions; the connection is deterministic). In ratio
/// form, β_c = f(λ_c)/p(x̄ | λ₀) and ρ_k = p(x̄ | λ_k)/p(x̄ | λ₀), as `path_integrator`.
/// There is one strategy per pixel path, so no weight over strategies: light tracing is an
/// estimator of the whole image on its own, except for what no light subpath reaches the
/// camera from — the environment and specular chains ending at the camera (seen only
/// through a delta BSDF: a pinhole cannot be hit). The B term is carried from the light:
///   B = Σ_b (1 − r_α(λ_b)) f_j(x̄_i, λ_b) Δλ / p(x̄_i | λ₀),
/// its bins started with the emitter's Le(λ_b) and following the hero's scattering with
/// the adjoint BSDF (`propagation::start_emitted`, `follow_adjoint`, `connect`).
///
/// **Adjoint BSDF.** A light subpath carries importance's adjoint, so at each vertex the BSDF
/// is f*(ωo, ωi) = f(ωi, ωo), ωo toward the light: a transmission is not compressed by
/// 1/η′² (the radiance BxDFs' factor is multiplied back, per wavelength), and a shading
/// normal n_s ≠ n_g multiplies the weight by |ωo·n_s| |ωi·n_g| / (|ωo·n_g| |ωi·n_s|)
/// (Veach 1997, §5.3), which keeps light tracing and path tracing in agreement on meshes
/// with vertex normals.
///
/// **Splats.** `trace` appends (pixel, XYZ / paths) to a list; one pass of light subpaths,
/// one per pixel, is added with `film::add_pass`, so each pixel's sample of a pass is the sum
/// of what landed on it (iris/render/film.hpp).
///
/// **Random numbers** (iris/render/random.hpp's slots): slot 0 the point on the light, 1 the
/// hero's u, 2 the B term's jitter; bounce 0 the emitted direction (2-D), the light choice
/// and the side of a two-sided emitter; bounce k ≥ 1 (the (k−1)-th scattering) the BSDF
/// direction (2-D), the lobe, roulette.

#include <cmath>
#include <cstddef>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/bins.hpp"
#include "iris/render/camera.hpp"
#include "iris/render/film.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/interaction.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/lights.hpp"
#include "iris/render/materials/materials.hpp"
#include "iris/render/propagation.hpp"
#include "iris/render/random.hpp"
#include "iris/render/scene.hpp"
#include "iris/sampling/hwss.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

namespace detail {
/// \brief XYZ of a subpath's contributions (light tracing, bidirectional): the C
/// wavelengths' values through the restriction's weights r_α(λ_j)/p_α(λ_j) (÷ Z_α for
/// ScaledPdf; computed once per sample), the B term's added by the caller, then × k
/// (1/(paths · ∫ȳ) for splats).
template <class Config, std::size_t C>
struct splat_weights {
    std::array<double, C> w{};
    const sampled_wavelengths<C>& wl;
    double k;
    template <class Distribution>
    splat_weights(const Distribution& dist, const sampled_wavelengths<C>& wavelengths, double scale) noexcept
        : w(restricted_weights<Config>(dist, wavelengths)), wl(wavelengths), k(scale) {}
    xyz hero(const sampled_spectrum<C>& value) const noexcept {
        xyz v;
        for (std::size_t j = 0; j < C; ++j)
            if (w[j] != 0.0 && value[j] != 0.0f) add_cmf(v, w[j] * static_cast<double>(value[j]), wl[j]);
        return v;
    }
    xyz finish(const xyz& v) const noexcept { return {v.x * k, v.y * k, v.z * k}; }
};
/// \brief A vertex's connection to the camera: the pixel it projects to, the unit
/// direction from it toward the camera, W_e cos θ_c / d² (the camera's importance and
/// its cosine, per unit area at the vertex: 1/(A_p cos³θ_c d²), camera.hpp) and the shadow
/// segment to test.
struct camera_link {
    std::uint32_t pixel = 0;
    glm::vec3 w{0.0f};
    float g = 0.0f;
    shadow_segment shadow;
};
inline std::optional<camera_link> to_camera(const camera_rays& camera, const surface_point& sp, const glm::vec3& ng) noexcept {
    const glm::vec3 d = sp.p - camera.origin();
    const float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f) || !std::isfinite(d2)) return std::nullopt;
    const glm::vec3 from_camera = d / std::sqrt(d2);
    const auto r = camera.raster(from_camera);
    if (!r) return std::nullopt;
    camera_link l;
    l.pixel = static_cast<std::uint32_t>(static_cast<int>(r->y) * camera.width() + static_cast<int>(r->x));
    l.w = -from_camera;
    l.g = camera.pdf_direction(from_camera) / d2;  // W_e cos θ_c = 1/(A_p cos³θ_c)
    const glm::vec3 o = offset_ray_origin(sp, ng, l.w);
    l.shadow = {o, camera.origin() - o, 1.0f - 1e-4f};
    return l;
}
}  // namespace detail

template <class Config, std::size_t Bins = detail::bins_of<Config>()>
class light_integrator {
public:
    static constexpr std::size_t C = Config::wavelength_count;
    static constexpr bool propagates = Config::bias_type::propagates;
    static constexpr bool scales_pdf = Config::bias_type::scales_pdf;
    static constexpr std::size_t bins = Bins;

    light_integrator(const scene_desc& scene, const light_sampler& lights, const camera_rays& camera,
                     path_settings settings = {})
        : m_scene(scene), m_lights(lights), m_camera(camera), m_settings(settings), m_hero(scene) {
        if constexpr (propagates) m_bins = bin_tables<Bins>(scene);
    }

    /// \brief Trace one light subpath with the numbers of `rng` and append its splats to
    /// `out` (anything with `push_back(splat)`), each divided by `paths`, the number of
    /// light subpaths of the pass (a pixel's pass sample is then an estimate of its value).
    /// `dist` and `alpha` as for `path_integrator::trace`. Returns the rays traced.
    template <Intersector Tracer, class Distribution, class Out>
    std::uint32_t trace(const Tracer& tracer, const Distribution& dist, float alpha, sample_stream& rng, double paths,
                        Out& out) const {
        std::uint32_t rays = 0;
        const glm::vec2 u_pos = rng.next2();
        const sampled_wavelengths<C> wl = dist.template sample_wavelengths<C>(rng.next());
        propagation_type bterm = make_propagation();
        if (propagates && alpha < 1.0f) bterm.start(dist, rng.next());
        rng.start_bounce(0);
        const glm::vec2 u_dir = rng.next2();
        const float u_select = rng.next();
        const float u_side = rng.next();
        const auto ls = m_lights.sample_le(u_select, u_pos, u_dir, u_side);
        if (!ls || !(ls->pdf_pos > 0.0f) || !(ls->pdf_dir > 0.0f)) return rays;

        const splat_weights sc(dist, wl, 1.0 / (paths * static_cast<double>(cie::y_integral)));
        const bool on_surface = ls->normal != glm::vec3(0.0f);  // an area light (the others are in free space)
        const sampled_spectrum<C> le = m_hero.emitted(ls->le, wl);
        bterm.start_emitted(ls->le, 1.0f);
        sampled_spectrum<C> rho(1.0f);

        if (on_surface) {  // the emitter's own point, seen by the camera
            const auto link = detail::to_camera(m_camera, ls->origin, ls->normal);
            const std::uint32_t e = ls->le.first;
            const float c = link ? glm::dot(ls->normal, link->w) : 0.0f;
            if (link && (m_scene.emitters[e].two_sided ? c != 0.0f : c > 0.0f)) {
                ++rays;
                if (!tracer.occluded(link->shadow.origin, link->shadow.direction, link->shadow.t_max)) {
                    const float k = std::fabs(c) * link->g / ls->pdf_pos;
                    xyz v = sc.hero(le * (k / hwss_ratio_sum(rho)));
                    bterm.connect_emitter(k, v);
                    out.push_back(splat{link->pixel, sc.finish(v)});
                }
            }
        }

        const float cos_l = on_surface ? std::fabs(glm::dot(ls->normal, ls->dir)) : 1.0f;
        sampled_spectrum<C> beta = le * (cos_l / (ls->pdf_pos * ls->pdf_dir));
        bterm.weigh(cos_l / (ls->pdf_pos * ls->pdf_dir));
        glm::vec3 origin = offset_ray_origin(ls->origin, on_surface ? ls->normal : glm::vec3(0.0f), ls->dir);
        glm::vec3 dir = ls->dir;

        for (int depth = 0; depth < m_settings.max_depth; ++depth) {
            rng.start_bounce(depth + 1);
            const auto hit = tracer.intersect(origin, dir, std::numeric_limits<float>::infinity());
            ++rays;
            if (!hit) break;
            const shape_desc& shape = m_scene.shapes[hit->shape];
            const auto si = make_interaction(m_scene, *hit, dir);
            if (!si) break;
            const surface_interaction& vx = *si;
            const glm::vec3 lo = vx.to_local(vx.wo);  // toward the light, in the shading frame
            const float wo_ng = std::fabs(glm::dot(vx.wo, vx.ng));
            if (!(wo_ng > 0.0f) || lo.z == 0.0f) break;
            glm::vec3 wi;
            const bool scattered = visit_bxdf(m_scene.materials[shape.material], [&](const auto& bxdf) {
                using B = std::remove_cvref_t<decltype(bxdf)>;
                emission_ref albedo;
                const sampled_spectra<C> hero = m_hero.at_vertex(bxdf, m_scene, shape.material, vx.uv, wl, albedo);
                bterm.enter(bxdf, shape.material, albedo);
                if constexpr (!B::delta) {
                    if (const auto link = detail::to_camera(m_camera, vx.sp, vx.ng)) {
                        // f*(ωo, ωc)·|ωc·n_s| with the shading correction: f(ωc, ωo)·|ωo·n_s| · |ωc·n_g| / |ωo·n_g|
                        const glm::vec3 lc = vx.to_local(link->w);
                        const float k = std::fabs(glm::dot(link->w, vx.ng)) / wo_ng * link->g;
                        const sampled_spectrum<C> f = bxdf.template f_cos<C>(lc, lo, hero);
                        bterm.prepare_light(bxdf, lc, lo);  // the bins' f(ωc, ωo)·|ωo·n_s|
                        if (!f.is_zero() || bterm.template receives_light<B>()) {
                            ++rays;
                            if (!tracer.occluded(link->shadow.origin, link->shadow.direction, link->shadow.t_max)) {
                                xyz v = sc.hero(beta * f * (k / hwss_ratio_sum(rho)));
                                bterm.template connect<B>(k, v);
                                out.push_back(splat{link->pixel, sc.finish(v)});
                            }
                        }
                    }
                }
                const glm::vec2 u = rng.next2();
                const float u_lobe = rng.next();
                const auto s = bxdf.template sample<C>(lo, wl, u_lobe, u, hero);
                if (!s || !(s->pdf[0] > 0.0f) || s->wi.z == 0.0f) return false;
                wi = glm::normalize(vx.to_world(s->wi));
                // the shading correction |ωo·n_s| |ωi·n_g| / (|ωo·n_g| |ωi·n_s|)
                const float shading = std::fabs(lo.z) * std::fabs(glm::dot(wi, vx.ng)) / (wo_ng * std::fabs(s->wi.z));
                sampled_spectrum<C> f = s->f_cos;
                if constexpr (B::reads_eta)
                    if (s->kind == lobe::transmission)
                        for (std::size_t k = 0; k < C; ++k) {  // f* = f · η′² across the interface, λ_k's own η′
                            const float e = lo.z > 0.0f ? hero.index[k] : 1.0f / hero.index[k];
                            f[k] *= e * e;
                        }
                beta *= f * (shading / s->pdf[0]);
                rho *= s->pdf / s->pdf[0];
                bterm.follow_adjoint(bxdf, lo, *s, shading);
                return true;
            });
            if (!scattered) break;
            if (depth + 1 >= m_settings.rr_start_depth) {
                const float m = bterm.roulette_max(beta.max_value());
                const float survive = m < 1.0f ? m : 1.0f;
                if (!(survive > 0.0f) || rng.next() >= survive) break;
                if (survive < 1.0f) {
                    beta /= survive;
                    bterm.survive(survive);
                }
            }
            origin = offset_ray_origin(vx.sp, vx.ng, wi);
            dir = wi;
        }
        return rays;
    }

private:
    using propagation_type = std::conditional_t<propagates, propagation<Bins>, no_propagation>;
    using splat_weights = detail::splat_weights<Config, C>;
    propagation_type make_propagation() const noexcept {
        if constexpr (propagates) return propagation_type(m_bins);
        else return {};
    }

    const scene_desc& m_scene;
    const light_sampler& m_lights;
    const camera_rays& m_camera;
    path_settings m_settings;
    hero_tables m_hero;
    bin_tables<Bins> m_bins;
};

}  // namespace iris
