#pragma once
/// \file
/// \brief `bdpt_integrator<Config, Bins>`: bidirectional path tracing with the C hero-rotated
/// wavelengths — a light subpath y₀ y₁ … and a camera subpath z₀ z₁ … per pixel sample,
/// every (s, t) strategy (s light vertices, t camera vertices) weighted by the balance
/// heuristic over strategies × wavelengths (docs/method.md §3, "Bidirectional path tracing").
///
/// | strategy | what | where it lands |
/// |---|---|---|
/// | s = 0, t ≥ 2 | the camera subpath hits an area light or escapes to the environment | the sample's pixel |
/// | s = 1, t ≥ 2 | next-event estimation from z_{t−1} (`light_sampler::sample_li`) | the sample's pixel |
/// | s ≥ 2, t ≥ 2 | y_{s−1} and z_{t−1} joined by a shadow ray | the sample's pixel |
/// | s ≥ 2, t = 1 | y_{s−1} joined to the pinhole (light tracing) | a splat on the pixel it projects to |
///
/// (s = 1, t = 1 is not used: a light seen directly is the s = 0 strategy's.)
///
/// **Weight.** A path x̄ = x₀ … x_{n−1} (x₀ on a light, x_{n−1} the camera) made by strategy s
/// with the hero λ₀ contributes, for each λ_j,
///   F_j = f(x̄, λ_j) / Σ_k Σ_{s′} n_{s′} p_{s′}(x̄ | λ_k),
/// the balance heuristic over every strategy s′ that can make x̄ and the C rotations of the
/// wavelengths (each λ_k the hero of one of them, as in the path tracer's corrected HWSS
/// weight). p_{s′}(x̄ | λ_k) = Π_{i<s′} p→_i(λ_k) Π_{i≥s′} p←_i(λ_k), p→_i the area density of
/// x_i sampled from the light's side, p←_i from the camera's; n_{s′} = 1 except for t′ = 1,
/// where one pass traces `paths` light subpaths for each pixel's one camera sample — folded
/// into the camera's density (its pixel pdf ÷ paths: pbrt-v4's whole-film pdf). In ratio form
/// (β = f/p_s(x̄|λ₀)), F_j = β_j / D with D = Σ_k Σ_{s′} p_{s′}(x̄|λ_k)/p_s(x̄|λ₀), computed from
/// prefix and suffix products of p/h (h_i the hero's own density of x_i), so a density that
/// is 0 at one wavelength (a dispersive refraction) never divides. A strategy s′ is counted
/// when its connection has no delta end (a delta BSDF; s′ = 0 needs a light a ray can hit —
/// not a point, spot or distant light; s′ ≥ 2 needs a light that starts light subpaths —
/// not a distant or environment light, whose paths are left to s = 0 and 1).
///
/// With `bdpt_settings::mis` false each strategy is weighted over the wavelengths alone
/// (D = Σ_k p_s(x̄|λ_k)/p_s(x̄|λ₀)): an unbiased estimator of the paths it can make, for tests.
///
/// **The B term** (PropagateUnused, α < 1) is carried along both subpaths — the camera
/// side's bins start at 1 − r_α(λ_b) as the path tracer's, the light side's at the emitted
/// spectrum (`bidirectional_propagation`) — and every strategy adds its bins' contribution
/// weighted by the balance heuristic over strategies with the hero alone, 1 / D_h,
/// D_h = Σ_{s′} p_{s′}(x̄|λ₀)/p_s(x̄|λ₀): those weights sum to one over the strategies that
/// can make x̄, so B's expectation is the path tracer's, and its laws hold (docs/method.md
/// §3, "The B term under bdpt").
///
/// **Random numbers.** The camera subpath reads the pixel's stream in the path tracer's layout
/// (iris/render/random.hpp: slot 0 the pixel jitter, 1 the hero's u, 2 the B term's jitter,
/// then per bounce light point, light choice, lobe, direction, roulette); the light subpath
/// reads a second stream of the same pixel and sample with its own seed, in the light
/// tracer's layout (iris/render/light_tracer.hpp).
///
/// **Russian roulette** on both subpaths divides the throughput by the survival probability;
/// the MIS weights leave it out (any weights that sum to one over the strategies keep the
/// estimator unbiased).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/bins.hpp"
#include "iris/render/camera.hpp"
#include "iris/render/film.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/interaction.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/light_tracer.hpp"
#include "iris/render/lights.hpp"
#include "iris/render/materials/materials.hpp"
#include "iris/render/propagation.hpp"
#include "iris/render/random.hpp"
#include "iris/render/scene.hpp"
#include "iris/sampling/hwss.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

template <class Config, std::size_t Bins = detail::bins_of<Config>()>
class bdpt_integrator {
public:
    static constexpr std::size_t C = Config::wavelength_count;
    static constexpr bool propagates = Config::bias_type::propagates;
    static constexpr bool scales_pdf = Config::bias_type::scales_pdf;
    static constexpr std::size_t bins = Bins;
    /// \brief The B term of one sample (iris/render/propagation.hpp), or nothing.
    using propagation_type = std::conditional_t<propagates, bidirectional_propagation<Bins>, no_propagation>;

    /// \brief A light subpath vertex (y₀ is the point on the light).
    struct light_vertex {
        surface_interaction si;      ///< wo toward y_{i−1}; y₀: the point and the light's normal (0: point, spot)
        sampled_spectrum<C> beta;    ///< the adjoint throughput arriving at y_i, ÷ the hero's density
        sampled_spectrum<C> pdf_fwd; ///< p→ (area; y₀: selection × position)
        sampled_spectrum<C> pdf_rev; ///< p← (area), set when y_{i+1} is sampled
        std::uint32_t material = 0;
        bool delta = false;        ///< y_{i+1} was sampled by a delta lobe
        bool connectible = true;  ///< its BSDF is not delta as a whole (a delta one joins with zero)
    };
    /// \brief A camera subpath vertex (z₀ is the pinhole).
    struct camera_vertex {
        glm::vec3 p{0.0f}, ng{0.0f};
        sampled_spectrum<C> pdf_fwd, pdf_rev;  ///< p← (area: its own direction) and p→, set when z_{i+1} is sampled
        bool delta = false;  ///< z_{i+1} was sampled by a delta lobe (before: whether its BSDF is delta)
    };
    /// \brief One vertex of a full path, for the weight: p→, p←, and whether it is delta — the
    /// lobe that continued the path there; the two vertices a strategy joins are not (a BSDF
    /// with delta and non-delta lobes, iris/render/materials/coated.hpp, is joined by its
    /// non-delta part whatever lobe continued its own subpath).
    struct mis_entry {
        sampled_spectrum<C> pl, pe;
        bool delta = false;
    };
    /// \brief Per-thread storage of one sample's subpaths (reused, never shrunk).
    struct workspace {
        std::vector<light_vertex> light;
        std::vector<camera_vertex> camera;
        std::vector<mis_entry> path;
        std::vector<float> suffix;
        std::vector<typename propagation_type::vertex_throughput> light_bins;  ///< the B term's t_b at each y_i
        bool light_on_surface = false;  ///< y₀ is on an area light (s′ = 0 can make its paths)
        std::optional<propagation_type> lterm;  ///< the light side's B term (copied only when on)
    };

    bdpt_integrator(const scene_desc& scene, const light_sampler& lights, const camera_rays& camera,
                    path_settings settings = {}, bdpt_settings strategies = {})
        : m_scene(scene), m_lights(lights), m_camera(camera), m_settings(settings), m_strategies(strategies),
          m_hero(scene),
          m_inv_paths(1.0f / (static_cast<float>(camera.width()) * static_cast<float>(camera.height()))) {
        if constexpr (propagates) m_bins = bin_tables<Bins>(scene);
    }

    /// \brief One sample of pixel `pixel`: the camera ray along unit `dir` (its jitter already
    /// drawn from `rng`'s slot 0), the light subpath from `lrng`. Appends one splat for the
    /// pixel (s ≥ 0, t ≥ 2, and the B term; none when it is 0) and one per t = 1 connection
    /// to `out` (anything with `push_back(splat)`). A pass is one sample of every pixel: the
    /// t = 1 splats are divided by the pixel count, the light subpaths of a pass. `dist` and
    /// `alpha` as for `path_integrator::trace`. Returns the rays traced.
    template <Intersector Tracer, class Distribution, class Out>
    std::uint32_t trace(const Tracer& tracer, std::uint32_t pixel, glm::vec3 dir, const Distribution& dist,
                        float alpha, sample_stream& rng, sample_stream& lrng, workspace& ws, Out& out) const {
        std::uint32_t rays = 0;
        const sampled_wavelengths<C> wl = dist.template sample_wavelengths<C>(rng.next());
        propagation_type bterm = make_propagation();
        if (propagates && alpha < 1.0f) bterm.start(dist, rng.next());
        const double inv_y = 1.0 / static_cast<double>(cie::y_integral);
        const splat_weights sc(dist, wl, inv_y);

        // the light side's bins: the same jitter and windows, copied only when the term is on
        if (!ws.lterm) ws.lterm.emplace(make_propagation());
        propagation_type& lterm = *ws.lterm;
        if (bterm.on()) lterm = bterm;
        else lterm.off();
        rays += light_subpath(tracer, wl, lrng, ws, lterm);
        rays += light_to_camera(tracer, wl, sc, ws, lterm, out);

        // the camera subpath, with every strategy ending at each of its vertices
        xyz own;
        ws.camera.clear();
        {
            camera_vertex z0;
            z0.p = m_camera.origin();
            z0.pdf_fwd = sampled_spectrum<C>(1.0f);  // the pinhole: delta in position, never hit
            ws.camera.push_back(z0);
        }
        sampled_spectrum<C> beta(1.0f);
        sampled_spectrum<C> pdf_dir(m_camera.pdf_direction(dir) * m_inv_paths);  // p(ω) of the last sampling, solid angle
        float eta_scale = 1.0f;
        bool prev_delta = true;
        glm::vec3 origin = m_camera.origin();
        for (int depth = 0;; ++depth) {
            rng.start_bounce(depth);
            const auto hit = tracer.intersect(origin, dir, std::numeric_limits<float>::infinity());
            ++rays;
            if (!hit) {
                if (m_lights.has_environment()) escaped(dir, wl, beta, pdf_dir, prev_delta, sc, ws, bterm, own);
                break;
            }
            const shape_desc& shape = m_scene.shapes[hit->shape];
            const auto si = make_interaction(m_scene, *hit, dir);
            if (!si) break;
            const surface_interaction& vx = *si;
            {
                // a hit at exactly grazing incidence (or at no distance) has no area density,
                // which every weight through it divides by: the path ends there, as a light
                // subpath's does (a set of measure zero)
                const glm::vec3 d = vx.sp.p - ws.camera.back().p;
                const float d2 = glm::dot(d, d), cos_in = std::fabs(glm::dot(vx.ng, vx.wo));
                if (!(d2 > 0.0f) || !(cos_in > 0.0f)) break;
                camera_vertex z;
                z.p = vx.sp.p;
                z.ng = vx.ng;
                z.pdf_fwd = pdf_dir * (cos_in / d2);
                ws.camera.push_back(z);
            }
            if (shape.emitter) hit_emitter(*shape.emitter, vx, wl, beta, sc, ws, bterm, own);
            if (depth >= m_settings.max_depth) break;
            const glm::vec3 lo = vx.to_local(vx.wo);
            glm::vec3 wi;
            const bool scattered = visit_bxdf(m_scene.materials[shape.material], [&](const auto& bxdf) {
                using B = std::remove_cvref_t<decltype(bxdf)>;
                emission_ref albedo;
                const sampled_spectra<C> hero = m_hero.at_vertex(bxdf, m_scene, shape.material, vx.uv, wl, albedo);
                bterm.enter(bxdf, shape.material, albedo);
                ws.camera.back().delta = B::delta;
                if constexpr (!B::delta) {
                    rays += next_event(tracer, bxdf, vx, lo, wl, hero, beta, sc, ws, bterm, rng, own);
                    rays += connect(tracer, bxdf, vx, lo, wl, hero, beta, sc, ws, bterm, lterm, own);
                }
                const float u_lobe = rng.next();
                const auto s = bxdf.template sample<C>(lo, wl, u_lobe, rng.next2(), hero);
                if (!s || !(s->pdf[0] > 0.0f)) return false;
                bterm.follow(bxdf, lo, *s);
                wi = glm::normalize(vx.to_world(s->wi));
                // p← of z_{i−1}: the density of sampling ωo from ωi here
                const std::size_t i = ws.camera.size() - 1;
                ws.camera[i].delta = s->delta;
                if (i >= 2) {
                    const sampled_spectrum<C> rev = s->delta ? s->pdf : bxdf.template pdf<C>(s->wi, lo, hero);
                    ws.camera[i - 1].pdf_rev = to_area(rev, ws.camera[i - 1].p, ws.camera[i - 1].ng, vx.sp.p);
                }
                beta *= s->f_cos / s->pdf[0];
                pdf_dir = s->pdf;
                prev_delta = s->delta;
                if (s->kind == lobe::transmission) eta_scale *= s->eta * s->eta;
                return true;
            });
            if (!scattered) break;
            if (depth + 1 >= m_settings.rr_start_depth) {
                const float m = bterm.roulette_max(beta.max_value()) * eta_scale;
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
        bterm.add_xyz(own);
        if (own.x != 0.0 || own.y != 0.0 || own.z != 0.0)  // (a NaN is kept: the film counts it)
            out.push_back(splat{pixel, xyz{own.x * inv_y, own.y * inv_y, own.z * inv_y}});
        return rays;
    }

private:
    using splat_weights = detail::splat_weights<Config, C>;
    propagation_type make_propagation() const noexcept {
        if constexpr (propagates) return propagation_type(m_bins);
        else return {};
    }

    /// \brief Is strategy (s, t) kept (`bdpt_settings::only_s`, `only_t`; `keep`: only the
    /// camera's s = 0 makes camera-only paths, so its other strategies are kept with `rest`)?
    bool kept(std::size_t s, std::size_t t) const noexcept {
        return (m_strategies.only_s < 0 || static_cast<std::size_t>(m_strategies.only_s) == s) &&
               (m_strategies.only_t < 0 || static_cast<std::size_t>(m_strategies.only_t) == t) &&
               (s == 0 || m_strategies.keep != bdpt_settings::paths::camera_only);
    }
    /// \brief Is an s = 0 path kept (`bdpt_settings::keep`)? It is camera-only if no other
    /// strategy can make it (`alone`) and a vertex between the camera and the light is not
    /// delta (`first` … `end` of ws.camera).
    bool kept_path(const workspace& ws, bool alone, std::size_t first, std::size_t end) const noexcept {
        if (m_strategies.keep == bdpt_settings::paths::all) return true;
        bool camera_only = false;
        if (alone)
            for (std::size_t i = first; i < end; ++i) camera_only |= !ws.camera[i].delta;
        return camera_only == (m_strategies.keep == bdpt_settings::paths::camera_only);
    }

    /// \brief A solid-angle density at `from` converted to area density at point p (unit
    /// geometric normal n; 0 for a point light, whose density is then 0 — nothing hits it).
    static sampled_spectrum<C> to_area(const sampled_spectrum<C>& pdf, const glm::vec3& p, const glm::vec3& n,
                                       const glm::vec3& from) noexcept {
        const glm::vec3 d = p - from;
        const float d2 = glm::dot(d, d);
        if (!(d2 > 0.0f)) return sampled_spectrum<C>(0.0f);
        return pdf * (std::fabs(glm::dot(n, d)) / (d2 * std::sqrt(d2)));
    }

    /// \brief The weights' denominators of a path of ws.path (x₀ on the light … x_{n−1} the
    /// camera) made by strategy s: F_R's D = Σ_k Σ_{s′} p_{s′}(x̄|λ_k)/p_s(x̄|λ₀), and the
    /// B term's, the hero's alone: D_h = Σ_{s′} p_{s′}(x̄|λ₀)/p_s(x̄|λ₀) (the k = 0 terms).
    /// `hit` says a ray can hit x₀ (s′ = 0), `finite` that light subpaths start at x₀'s light
    /// (s′ ≥ 2).
    struct denominators {
        float all = 0.0f, hero = 0.0f;
        bool alone = true;  ///< no other strategy can make x̄ (at any wavelength)
    };
    denominators denominator(workspace& ws, std::size_t s, bool hit, bool finite) const noexcept {
        const auto& e = ws.path;
        const std::size_t n = e.size();
        const auto valid = [&](std::size_t sp) {
            if (!m_strategies.mis) return sp == s;
            if (sp == 0) return hit;
            if (sp >= 2 && !finite) return false;
            if (sp == n - 1 && sp < 2) return false;  // (1, 1)
            return !e[sp - 1].delta && !e[sp].delta;
        };
        ws.suffix.resize(n + 1);
        denominators out;
        float d = 0.0f;
        for (std::size_t k = 0; k < C; ++k) {
            // suffix[sp] = Π_{i ≥ sp} p←_i(λ_k)/h_i, prefix = Π_{i < sp} p→_i(λ_k)/h_i
            // (a density that is exactly 0 makes its products exactly 0, even where the others
            // have overflowed: such a technique has no density, whatever else it has)
            ws.suffix[n] = 1.0f;
            for (std::size_t i = n; i-- > 0;) {
                const float h = i < s ? e[i].pl[0] : e[i].pe[0];
                const float r = e[i].pe[k] / h;
                ws.suffix[i] = r == 0.0f ? 0.0f : ws.suffix[i + 1] * r;
            }
            float prefix = 1.0f;
            for (std::size_t sp = 0; sp < n; ++sp) {
                if (valid(sp) && prefix > 0.0f && ws.suffix[sp] > 0.0f) {
                    d += prefix * ws.suffix[sp];
                    out.alone &= sp == s;
                }
                const float h = sp < s ? e[sp].pl[0] : e[sp].pe[0];
                const float r = e[sp].pl[k] / h;
                prefix = r == 0.0f ? 0.0f : prefix * r;
            }
            if (k == 0) out.hero = d;
        }
        out.all = d;
        return out;
    }

    /// \brief ws.path ← the light vertices y₀ … y_{s−1} (p→ their forward densities, p← their reverse).
    void push_light_vertices(workspace& ws, std::size_t s) const {
        ws.path.clear();
        for (std::size_t i = 0; i < s; ++i) ws.path.push_back({ws.light[i].pdf_fwd, ws.light[i].pdf_rev, ws.light[i].delta});
    }
    /// \brief Append the camera vertices z_{t−1} … z₀ (p→ their reverse densities, p← their forward).
    void push_camera_vertices(workspace& ws, std::size_t t) const {
        for (std::size_t i = t; i-- > 0;) ws.path.push_back({ws.camera[i].pdf_rev, ws.camera[i].pdf_fwd, ws.camera[i].delta});
    }

    /// \brief The light subpath: y₀ on a light chosen by power (none for a light at
    /// infinity: its paths are the camera's strategies'), then the hero's BSDF samples with
    /// the adjoint BSDF, as the light tracer's (iris/render/light_tracer.hpp); the B term's
    /// bins along it in `lterm`, their throughput at each vertex in ws.light_bins.
    template <Intersector Tracer>
    std::uint32_t light_subpath(const Tracer& tracer, const sampled_wavelengths<C>& wl, sample_stream& rng,
                                workspace& ws, propagation_type& lterm) const {
        std::uint32_t rays = 0;
        ws.light.clear();
        ws.light_bins.clear();
        const glm::vec2 u_pos = rng.next2();
        rng.start_bounce(0);
        const glm::vec2 u_dir = rng.next2();
        const float u_select = rng.next();
        const float u_side = rng.next();
        const auto ls = m_lights.sample_le(u_select, u_pos, u_dir, u_side);
        if (!ls || ls->infinite || !(ls->pdf_pos > 0.0f) || !(ls->pdf_dir > 0.0f)) return rays;
        ws.light_on_surface = ls->normal != glm::vec3(0.0f);
        {
            light_vertex y0;
            y0.si.sp = ls->origin;
            y0.si.ng = ls->normal;
            y0.pdf_fwd = sampled_spectrum<C>(ls->pdf_pos);
            y0.beta = m_hero.emitted(ls->le, wl) / ls->pdf_pos;
            ws.light.push_back(y0);
            lterm.start_light_subpath(ls->le, 1.0f / ls->pdf_pos);
            if constexpr (propagates)
                if (lterm.on()) ws.light_bins.push_back(lterm.throughput());
        }
        const float cos_l = ws.light_on_surface ? std::fabs(glm::dot(ls->normal, ls->dir)) : 1.0f;
        sampled_spectrum<C> beta = ws.light[0].beta * (cos_l / ls->pdf_dir);
        lterm.weigh(cos_l / ls->pdf_dir);
        // roulette looks at the throughput relative to the emitted one (β holds Φ/p_select,
        // not a number near 1 — on its own it would never end a light subpath), and at the
        // B term's bins relative to theirs (0 when it is off)
        const auto relative = [](float start) { return start > 0.0f && std::isfinite(start) ? 1.0f / start : 1.0f; };
        const float roulette_scale = relative(beta.max_value());
        const float bins_scale = relative(lterm.roulette_max(0.0f));
        sampled_spectrum<C> pdf_dir(ls->pdf_dir);
        glm::vec3 origin = offset_ray_origin(ls->origin, ls->normal, ls->dir);
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
            const glm::vec3 lo = vx.to_local(vx.wo);
            const float wo_ng = std::fabs(glm::dot(vx.wo, vx.ng));
            if (!(wo_ng > 0.0f) || lo.z == 0.0f) break;
            {
                light_vertex y;
                y.si = vx;
                y.beta = beta;
                y.pdf_fwd = to_area(pdf_dir, vx.sp.p, vx.ng, ws.light.back().si.sp.p);
                y.material = shape.material;
                ws.light.push_back(y);
                if constexpr (propagates)
                if (lterm.on()) ws.light_bins.push_back(lterm.throughput());
            }
            if (depth + 1 >= m_settings.max_depth) break;  // y_{max_depth} is the last a strategy uses
            const bool scattered = visit_bxdf(m_scene.materials[shape.material], [&](const auto& bxdf) {
                using B = std::remove_cvref_t<decltype(bxdf)>;
                emission_ref albedo;
                const sampled_spectra<C> hero = m_hero.at_vertex(bxdf, m_scene, shape.material, vx.uv, wl, albedo);
                ws.light.back().delta = B::delta;
                ws.light.back().connectible = !B::delta;
                lterm.enter(bxdf, shape.material, albedo);
                const glm::vec2 u = rng.next2();
                const float u_lobe = rng.next();
                const auto s = bxdf.template sample<C>(lo, wl, u_lobe, u, hero);
                if (!s || !(s->pdf[0] > 0.0f) || s->wi.z == 0.0f) return false;
                dir = glm::normalize(vx.to_world(s->wi));
                const float shading = std::fabs(lo.z) * std::fabs(glm::dot(dir, vx.ng)) / (wo_ng * std::fabs(s->wi.z));
                sampled_spectrum<C> f = s->f_cos;
                if constexpr (B::reads_eta)
                    if (s->kind == lobe::transmission)
                        for (std::size_t k = 0; k < C; ++k) {  // the adjoint: f* = f · η′² across the interface
                            const float e = lo.z > 0.0f ? hero.index[k] : 1.0f / hero.index[k];
                            f[k] *= e * e;
                        }
                beta *= f * (shading / s->pdf[0]);
                lterm.follow_adjoint(bxdf, lo, *s, shading);
                const std::size_t i = ws.light.size() - 1;
                ws.light[i].delta = s->delta;
                const sampled_spectrum<C> rev = s->delta ? s->pdf : bxdf.template pdf<C>(s->wi, lo, hero);
                ws.light[i - 1].pdf_rev = to_area(rev, ws.light[i - 1].si.sp.p, ws.light[i - 1].si.ng, vx.sp.p);
                pdf_dir = s->pdf;
                return true;
            });
            if (!scattered) break;
            if (depth + 1 >= m_settings.rr_start_depth) {
                const float mb = lterm.roulette_max(0.0f) * bins_scale, mf = beta.max_value() * roulette_scale;
                const float m = mb > mf ? mb : mf;  // (a NaN in the bins is ignored)
                const float survive = m < 1.0f ? m : 1.0f;
                if (!(survive > 0.0f) || rng.next() >= survive) break;
                if (survive < 1.0f) {
                    beta /= survive;
                    lterm.survive(survive);
                }
            }
            origin = offset_ray_origin(vx.sp, vx.ng, dir);
        }
        return rays;
    }

    /// \brief What a non-delta light vertex y (index i) sends toward unit w (world): the
    /// adjoint f*(ωo → w)·|w·n_g| with the shading correction (as the light tracer's), p→ of w
    /// and p← of ωo given w (solid angle at y), and the B term's bins in `yterm` (`bins`:
    /// they carry something). Zero for a delta material.
    struct light_eval {
        sampled_spectrum<C> f, pdf_fwd, pdf_rev;
        bool bins = false;
    };
    light_eval eval_light_vertex(const workspace& ws, std::size_t i, const glm::vec3& w, const sampled_wavelengths<C>& wl,
                                 propagation_type& yterm) const noexcept {
        const light_vertex& y = ws.light[i];
        return visit_bxdf(m_scene.materials[y.material], [&](const auto& bxdf) -> light_eval {
            using B = std::remove_cvref_t<decltype(bxdf)>;
            if constexpr (B::delta) {
                return {};
            } else {
                emission_ref albedo;
                const sampled_spectra<C> hero = m_hero.at_vertex(bxdf, m_scene, y.material, y.si.uv, wl, albedo);
                const glm::vec3 lo = y.si.to_local(y.si.wo), lw = y.si.to_local(w);
                const float wo_ng = std::fabs(glm::dot(y.si.wo, y.si.ng));
                const bsdf_value<C> v = bxdf.template eval<C>(lw, lo, hero);  // f(w, ωo)·|ωo·n_s| and p(ωo | w)
                light_eval out;
                out.f = v.f_cos * (std::fabs(glm::dot(w, y.si.ng)) / wo_ng);
                out.pdf_fwd = bxdf.template pdf<C>(lo, lw, hero);
                out.pdf_rev = v.pdf;
                if constexpr (propagates) {
                    yterm.enter(bxdf, y.material, albedo);
                    yterm.prepare_light(bxdf, lw, lo);  // the bins' f(w, ωo)·|ωo·n_s|
                    out.bins = yterm.template receives_light<B>();
                    if (out.bins) yterm.template light_vertex<B>(ws.light_bins[i], std::fabs(glm::dot(w, y.si.ng)) / wo_ng);
                }
                return out;
            }
        });
    }

    /// \brief t = 1: each non-delta light vertex y_{s−1} (s ≥ 2) joined to the pinhole and splatted.
    template <Intersector Tracer, class Out>
    std::uint32_t light_to_camera(const Tracer& tracer, const sampled_wavelengths<C>& wl, const splat_weights& sc,
                                  workspace& ws, propagation_type& yterm, Out& out) const {
        const double k = sc.k * static_cast<double>(m_inv_paths);
        std::uint32_t rays = 0;
        for (std::size_t s = 2; s <= ws.light.size(); ++s) {
            if (!kept(s, 1)) continue;
            const light_vertex& y = ws.light[s - 1];
            if (!y.connectible) continue;
            const auto link = detail::to_camera(m_camera, y.si.sp, y.si.ng);
            if (!link) continue;
            const light_eval ye = eval_light_vertex(ws, s - 1, link->w, wl, yterm);
            if (ye.f.is_zero() && !ye.bins) continue;
            ++rays;
            if (tracer.occluded(link->shadow.origin, link->shadow.direction, link->shadow.t_max)) continue;
            push_light_vertices(ws, s);
            ws.path[s - 1].delta = false;  // joined, whatever lobe continued its subpath
            // the camera's side: y_{s−1} from the pinhole (pixel pdf ÷ paths), y_{s−2} from y_{s−1}
            ws.path[s - 1].pe = sampled_spectrum<C>(link->g * m_inv_paths * std::fabs(glm::dot(link->w, y.si.ng)));
            ws.path[s - 2].pe = to_area(ye.pdf_rev, ws.light[s - 2].si.sp.p, ws.light[s - 2].si.ng, y.si.sp.p);
            ws.path.push_back({sampled_spectrum<C>(0.0f), sampled_spectrum<C>(1.0f), false});  // z₀
            const denominators d = denominator(ws, s, ws.light_on_surface, true);
            xyz x = sc.hero(y.beta * ye.f * (link->g / d.all));
            if (ye.bins) yterm.connect_camera(link->g / d.hero, x);
            out.push_back(splat{link->pixel, {x.x * k, x.y * k, x.z * k}});
        }
        return rays;
    }

    /// \brief s = 0 at an area light: the camera subpath's last vertex z_{t−1} (= vx) is on emitter e.
    void hit_emitter(std::uint32_t e, const surface_interaction& vx, const sampled_wavelengths<C>& wl,
                     const sampled_spectrum<C>& beta, const splat_weights& sc, workspace& ws, propagation_type& bterm,
                     xyz& own) const {
        const emitter_desc& em = m_scene.emitters[e];
        const float cos_l = glm::dot(vx.ng, vx.wo);
        if (!(em.two_sided ? cos_l != 0.0f : cos_l > 0.0f)) return;
        const emission_ref le{e, 1, {1.0f, 0.0f, 0.0f}};
        const float pa = m_lights.pdf_area(vx.shape, vx.prim);
        const std::size_t t = ws.camera.size();
        if (!kept(0, t)) return;
        ws.path.clear();
        push_camera_vertices(ws, t);
        ws.path[0].pl = sampled_spectrum<C>(pa);
        ws.path[0].delta = false;
        if (t >= 3) {  // z_{t−2} as the light would emit toward it
            const camera_vertex& z = ws.camera[t - 2];
            const float pe = (em.two_sided ? 0.5f : 1.0f) * std::fabs(cos_l) / pi;
            ws.path[1].pl = to_area(sampled_spectrum<C>(pe), z.p, z.ng, vx.sp.p);
        }
        const denominators d = denominator(ws, 0, true, true);
        if (!kept_path(ws, d.alone, 1, t - 1)) return;
        add(own, sc, beta * m_hero.emitted(le, wl) / d.all);
        bterm.emission(le, 1.0f / d.hero);
    }

    /// \brief s = 0 at the environment: the camera ray escaped along `dir`.
    void escaped(const glm::vec3& dir, const sampled_wavelengths<C>& wl, const sampled_spectrum<C>& beta,
                 const sampled_spectrum<C>& pdf_dir, bool prev_delta, const splat_weights& sc, workspace& ws,
                 propagation_type& bterm, xyz& own) const {
        const emission_ref le = m_lights.environment_emission(dir);
        const float pl = prev_delta ? 0.0f : m_lights.pdf_environment(dir);
        const std::size_t t = ws.camera.size();
        if (!kept(0, t + 1)) return;
        ws.path.clear();
        ws.path.push_back({sampled_spectrum<C>(pl), pdf_dir, false});  // the environment, in solid angle
        push_camera_vertices(ws, t);
        const denominators d = denominator(ws, 0, true, false);
        if (!kept_path(ws, d.alone, 1, t)) return;
        add(own, sc, beta * m_hero.emitted(le, wl) / d.all);
        bterm.emission(le, 1.0f / d.hero);
    }

    /// \brief s = 1: next-event estimation from the camera subpath's last vertex vx.
    template <Intersector Tracer, class B>
    std::uint32_t next_event(const Tracer& tracer, const B& bxdf, const surface_interaction& vx, const glm::vec3& lo,
                             const sampled_wavelengths<C>& wl, const sampled_spectra<C>& hero,
                             const sampled_spectrum<C>& beta, const splat_weights& sc, workspace& ws,
                             propagation_type& bterm, sample_stream& rng, xyz& own) const {
        if (m_lights.empty()) return 0;
        const glm::vec2 u_point = rng.next2();
        const float u_choice = rng.next();
        const auto ls = m_lights.sample_li(vx.sp, vx.ng, u_choice, u_point);
        if (!ls || !(ls->pdf > 0.0f)) return 0;
        const glm::vec3 li = vx.to_local(ls->wi);
        bsdf_value<C> fb;
        if (ls->delta) fb.f_cos = bxdf.template f_cos<C>(lo, li, hero);
        else fb = bxdf.template eval<C>(lo, li, hero);
        bterm.prepare_light(bxdf, lo, li);
        if (fb.f_cos.is_zero() && !bterm.template receives_light<B>()) return 0;
        if (tracer.occluded(ls->shadow.origin, ls->shadow.direction, ls->shadow.t_max)) return 1;
        const std::size_t t = ws.camera.size();
        if (!kept(1, t)) return 1;
        ws.path.clear();
        // x₀ on the light: p→ its light-sampling density, p← the BSDF's (area for a finite light)
        if (ls->infinite) {
            ws.path.push_back({sampled_spectrum<C>(ls->pdf), fb.pdf, false});
        } else {
            const glm::vec3 d = ls->point - vx.sp.p;
            const float d2 = glm::dot(d, d);
            const float g = ls->delta ? 1.0f : std::fabs(glm::dot(ls->normal, ls->wi)) / d2;  // solid angle → area
            ws.path.push_back({sampled_spectrum<C>(ls->pdf * g), fb.pdf * g, false});
        }
        push_camera_vertices(ws, t);
        if (!ls->infinite) {
            ws.path[1].pl = to_area(sampled_spectrum<C>(ls->pdf_emit), vx.sp.p, vx.ng, ls->point);
            if (t >= 3) {
                const camera_vertex& z = ws.camera[t - 2];
                ws.path[2].pl = to_area(bxdf.template pdf<C>(li, lo, hero), z.p, z.ng, vx.sp.p);
            }
        }
        const denominators d = denominator(ws, 1, !ls->delta, !ls->infinite);
        if (!fb.f_cos.is_zero()) add(own, sc, beta * fb.f_cos * m_hero.emitted(ls->le, wl) / (ls->pdf * d.all));
        bterm.template light<B>(ls->le, 1.0f / d.hero, ls->pdf);
        return 1;
    }

    /// \brief s ≥ 2, t ≥ 2: the camera subpath's last vertex vx joined to each non-delta light
    /// vertex y_{s−1} (s ≥ 2) within the path length.
    template <Intersector Tracer, class B>
    std::uint32_t connect(const Tracer& tracer, const B& bxdf, const surface_interaction& vx, const glm::vec3& lo,
                          const sampled_wavelengths<C>& wl, const sampled_spectra<C>& hero,
                          const sampled_spectrum<C>& beta, const splat_weights& sc, workspace& ws,
                          propagation_type& bterm, propagation_type& yterm, xyz& own) const {
        std::uint32_t rays = 0;
        const std::size_t t = ws.camera.size();
        // path depth s + t − 2 ≤ max_depth
        const auto max_s = static_cast<std::size_t>(m_settings.max_depth) + 2 - t;
        for (std::size_t s = 2; s <= ws.light.size() && s <= max_s; ++s) {
            if (!kept(s, t)) continue;
            const light_vertex& y = ws.light[s - 1];
            if (!y.connectible) continue;
            glm::vec3 w = y.si.sp.p - vx.sp.p;
            const float d2 = glm::dot(w, w);
            if (!(d2 > 0.0f)) continue;
            w /= std::sqrt(d2);
            const glm::vec3 lw = vx.to_local(w);
            const bsdf_value<C> fz = bxdf.template eval<C>(lo, lw, hero);
            bterm.prepare_light(bxdf, lo, lw);  // the bins' f(ωo, w)·|w·n_s|
            const bool bins_z = bterm.template receives_light<B>();
            if (fz.f_cos.is_zero() && !bins_z) continue;
            const light_eval ye = eval_light_vertex(ws, s - 1, -w, wl, yterm);
            const bool hero_on = !fz.f_cos.is_zero() && !ye.f.is_zero(), bins_on = bins_z && ye.bins;
            if (!hero_on && !bins_on) continue;
            ++rays;
            const shadow_segment sh = shadow_ray_between(vx.sp, vx.ng, y.si.sp, y.si.ng);
            if (tracer.occluded(sh.origin, sh.direction, sh.t_max)) continue;
            push_light_vertices(ws, s);
            ws.path[s - 1].delta = false;  // joined, whatever lobe continued its subpath
            ws.path[s - 1].pe = to_area(fz.pdf, y.si.sp.p, y.si.ng, vx.sp.p);
            ws.path[s - 2].pe = to_area(ye.pdf_rev, ws.light[s - 2].si.sp.p, ws.light[s - 2].si.ng, y.si.sp.p);
            push_camera_vertices(ws, t);
            ws.path[s].pl = to_area(ye.pdf_fwd, vx.sp.p, vx.ng, y.si.sp.p);
            if (t >= 3) {
                const camera_vertex& z = ws.camera[t - 2];
                ws.path[s + 1].pl = to_area(bxdf.template pdf<C>(lw, lo, hero), z.p, z.ng, vx.sp.p);
            }
            const denominators d = denominator(ws, s, ws.light_on_surface, true);
            if (hero_on) add(own, sc, beta * fz.f_cos * ye.f * y.beta / (d2 * d.all));
            if (bins_on) bterm.template connect_vertex<B>(yterm, 1.0f / (d2 * d.hero), own);
        }
        return rays;
    }

    static void add(xyz& own, const splat_weights& sc, const sampled_spectrum<C>& v) noexcept {
        const xyz x = sc.hero(v);
        own.x += x.x;
        own.y += x.y;
        own.z += x.z;
    }

    static constexpr float pi = 3.14159265358979323846f;

    const scene_desc& m_scene;
    const light_sampler& m_lights;
    const camera_rays& m_camera;
    path_settings m_settings;
    bdpt_settings m_strategies;
    hero_tables m_hero;
    bin_tables<Bins> m_bins;
    float m_inv_paths;  ///< 1 / the light subpaths of a pass (one per pixel)
};

}  // namespace iris
