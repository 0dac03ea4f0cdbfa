#pragma once
/// \file
/// \brief `bsdf_only_integrator`: the second, independent estimator of a pixel's XYZ, used
/// to check `path_integrator` (tests/renderer/estimators_test.cpp) and available to users
/// as `iris-render --estimator bsdf-only`.
///
/// Pure BSDF sampling at one wavelength: λ uniform on the scene's domain (pdf 1/Δ), a path
/// that follows BSDF samples alone and adds the emission of every emitter it hits, front
/// side (or either side if two-sided), with weight 1. No light sampling, no MIS, no hero
/// rotation, no restriction or B term, no lattice tables: spectra are read from the scene's
/// own tables. Surface geometry comes from the same `surface_interaction` (its point,
/// normals and shading frame). Per sample,
///   XYZ = L(λ) · (x̄, ȳ, z̄)(λ) · Δ / ∫ȳ,   L(λ) = Σ_vertices β(λ) · Le(λ).
/// It shares with `path_integrator` only what both must trust: the scene, the ray tracer
/// and the BSDFs' sampling routine (guarded by the BSDF tests). Not even the ray offsets:
/// its rays start on the surface and skip the triangle they leave (`intersect_leaving`). Everything next-event estimation adds —
/// light choice, area pdfs, shadow rays, the two-strategy and C-wavelength MIS weights —
/// is absent, so an error in any of it shows as a disagreement between the two estimators.
/// In a scattering medium it flies by analog collisions on σ_t at its one wavelength,
/// scattering with weight σ_s/σ_t and sampling the phase function (docs/method.md §10): a
/// technique the path tracer does not use. It is unbiased for every scene without delta lights, dispersive ones included (one
/// wavelength, so a λ-dependent refraction needs no termination), but small lamps make it
/// noisy. Point, spot and distant lights cannot be hit by a ray: it does not see them
/// (`scene_features::has_delta_lights`; their checks are closed forms,
/// tests/renderer/light_render_test.cpp). An environment image is looked up where a path
/// escapes, with the same bilinear lookup as the lights' (`lights::environment_light::emission`,
/// which is the image's definition, not a sampling routine).

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/absorption.hpp"
#include "iris/render/medium.hpp"
#include "iris/render/bsdf.hpp"
#include "iris/render/frame.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/interaction.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/lights/environment.hpp"
#include "iris/render/random.hpp"
#include "iris/render/scene.hpp"
#include "iris/render/texture.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

class bsdf_only_integrator {
public:
    static constexpr std::size_t C = 1;

    explicit bsdf_only_integrator(const scene_desc& scene, path_settings settings = {})
        : m_scene(scene), m_settings(settings) {
        if (scene.environment) m_environment = lights::environment_light(*scene.environment, 0);
    }

    /// \brief One path from `origin` along unit `dir`. The distribution and α of the
    /// renderer's loop are ignored (this estimator has no wavelength policy). With
    /// `spectral`, the sample's one point contribution, (λ, (λmax − λmin) · L(λ)), is added
    /// to it (iris/render/spectral_bands.hpp).
    template <Intersector Tracer, class Distribution>
    path_sample trace(const Tracer& tracer, glm::vec3 origin, glm::vec3 dir, const Distribution& /*unused*/,
                      float /*alpha*/, sample_stream& rng, spectral_row* spectral = nullptr) const noexcept {
        path_sample out;
        const float width = m_scene.lambda_max - m_scene.lambda_min;
        float lambda = m_scene.lambda_min + rng.next() * width;
        if (!(lambda < m_scene.lambda_max)) lambda = m_scene.lambda_min;  // rounding up to λmax
        const sampled_wavelengths<1> wl({lambda}, {1.0f / width});
        float beta = 1.0f;
        double radiance = 0.0;

        std::uint32_t from_shape = no_triangle, from_prim = no_triangle;  // the triangle the ray leaves
        // the medium the ray is in (iris/render/absorption.hpp): the camera's is the scene's own
        std::uint32_t medium = m_scene.medium ? static_cast<std::uint32_t>(m_scene.materials.size()) : no_medium;
        for (int depth = 0;; ++depth) {
            const auto hit = intersect_leaving(tracer, origin, dir, from_shape, from_prim, out.rays);
            std::optional<surface_interaction> si;
            if (hit) {
                si = make_interaction(m_scene, *hit, dir);
                if (!si) break;  // degenerate triangle
            }
            if (medium != no_medium) {
                // σ_a(λ), σ_s(λ) from the scene's own tables
                const tabulated_spectrum* sa = medium_absorption(m_scene, medium);
                const medium_scattering* ms = medium_scattering_of(m_scene, medium);
                const double sigma_a = sa ? (*sa)(static_cast<double>(lambda)) : 0.0;
                const double sigma_s = ms ? ms->sigma_s(static_cast<double>(lambda)) : 0.0;
                const double t_hit = si ? static_cast<double>(glm::distance(origin, si->sp.p))
                                        : std::numeric_limits<double>::infinity();
                if (sigma_s > 0.0) {
                    // analog free flight on σ_t: collide at t with density σ_t e^{−σ_t t}, scatter
                    // with weight σ_s/σ_t; flying through has the probability of the transmittance
                    const double sigma_t = sigma_a + sigma_s;
                    const double t = -std::log1p(-static_cast<double>(rng.next_medium())) / sigma_t;
                    if (t < t_hit) {
                        if (depth >= m_settings.max_depth) break;
                        rng.start_bounce(depth);
                        beta *= static_cast<float>(sigma_s / sigma_t);
                        const hg_phase phase{ms->g};
                        const auto ps = phase.sample<1>(-dir, wl, 0.0f, rng.next2(), sampled_spectra<1>{});
                        if (!ps || !(beta > 0.0f)) break;
                        if (depth + 1 >= m_settings.rr_start_depth) {
                            const float survive = beta < 1.0f ? beta : 1.0f;
                            if (rng.next() >= survive) break;
                            beta /= survive;
                        }
                        origin += static_cast<float>(t) * dir;
                        dir = ps->wi;
                        from_shape = from_prim = no_triangle;
                        continue;
                    }
                } else if (sigma_a > 0.0) {
                    if (!hit) break;  // an infinite length of absorbing material
                    beta *= static_cast<float>(std::exp(-sigma_a * t_hit));
                }
            }
            if (!hit) {
                if (m_scene.environment) radiance += static_cast<double>(beta) * environment(dir, lambda);
                break;
            }
            const shape_desc& shape = m_scene.shapes[hit->shape];
            const glm::vec3& wo = si->wo;
            if (shape.emitter) {
                const emitter_desc& em = m_scene.emitters[*shape.emitter];
                const float c = glm::dot(si->ng, wo);
                if (c > 0.0f || (em.two_sided && c < 0.0f))
                    radiance += static_cast<double>(beta) * em.radiance(lambda);
            }
            if (depth >= m_settings.max_depth) break;
            const material_desc& mat = m_scene.materials[shape.material];
            rng.start_bounce(depth);              // the bounce's slots (render/random.hpp; a no-op for `independent`)
            const glm::vec2 u_dir = rng.next2();  // drawn in this order since the first release
            const float u_lobe = rng.next();
            const auto bs = bsdf_sample_hero(mat, si->shading, wo, wl, u_lobe, u_dir, texture_weights(m_scene, mat, si->uv));
            if (!bs || !(bs->pdf[0] > 0.0f)) break;
            beta *= bs->f_cos[0] / bs->pdf[0];
            if (!(beta > 0.0f)) break;
            if (depth + 1 >= m_settings.rr_start_depth) {  // Russian roulette on β itself
                const float survive = beta < 1.0f ? beta : 1.0f;
                if (rng.next() >= survive) break;
                beta /= survive;
            }
            // the medium after a dielectric boundary: its inside (the back of n_g) if it holds one,
            // clear if not; the scene's own going out; other surfaces keep it (written here, not
            // shared with the path tracer's `medium_after`)
            if (const auto* d = std::get_if<material::dielectric>(&mat)) {
                if (glm::dot(bs->wi, si->ng) < 0.0f) medium = d->absorption || d->scattering ? shape.material : no_medium;
                else medium = m_scene.medium ? static_cast<std::uint32_t>(m_scene.materials.size()) : no_medium;
            }
            origin = si->sp.p;  // not offset: see intersect_leaving
            dir = bs->wi;
            from_shape = hit->shape;
            from_prim = hit->prim;
        }
        const double w = radiance * static_cast<double>(width) / cie::y_integral;
        const double l = static_cast<double>(lambda);
        out.value = {w * cie::x_bar(l), w * cie::y_bar(l), w * cie::z_bar(l)};
        if (spectral) spectral->add(l, radiance * static_cast<double>(width));
        return out;
    }

private:
    static constexpr std::uint32_t no_triangle = 0xffffffffu;

    /// \brief L(λ) arriving along unit `dir` from the environment.
    double environment(const glm::vec3& dir, float lambda) const noexcept {
        const environment_desc& env = *m_scene.environment;
        if (!env.map) return env.radiance(lambda);
        const emission_ref le = m_environment.emission(dir);
        double v = 0.0;
        for (std::size_t i = 0; i < 3; ++i) v += static_cast<double>(le.weight[static_cast<int>(i)]) * env.basis[i](lambda);
        return v;
    }

    /// \brief The first hit along the ray other than the (flat) triangle it leaves. Rays
    /// start on the surface itself, not offset from it: a ray leaving a plane cannot meet it
    /// again, so any hit on that triangle is the start point re-found (at t ≈ 0, on either
    /// side of the plane by rounding) and is stepped past. This shares nothing with the
    /// offsets of `path_integrator` (iris/render/frame.hpp), and no surface is too close to
    /// be seen: a cube 0.1 mm above a floor is hit from the floor.
    template <Intersector Tracer>
    static std::optional<ray_hit> intersect_leaving(const Tracer& tracer, glm::vec3 o, const glm::vec3& d,
                                                    std::uint32_t shape, std::uint32_t prim, std::uint32_t& rays) noexcept {
        const float scale = 1.0f + std::fmax(std::fabs(o.x), std::fmax(std::fabs(o.y), std::fabs(o.z)));
        float step = 0x1.0p-23f * scale;  // one float spacing at |o|, doubled on every re-hit
        for (int k = 0; k < 12; ++k) {
            const auto h = tracer.intersect(o, d, std::numeric_limits<float>::infinity());
            ++rays;
            if (!h || h->shape != shape || h->prim != prim) return h;
            // Embree's t of the start point is rounding noise (it can stay ~5e-8 while the
            // origin creeps on by single float steps, so stepping to it is not enough):
            // move on along d past it by a step that doubles on every re-hit, at most
            // 2^-12·(1 + |o|) — a few µm in scenes of metres, less than any gap iris
            // renders — before giving up on the ray
            o += std::fmax(h->t, 0.0f) * d + step * d;
            step *= 2.0f;
        }
        return std::nullopt;
    }

    const scene_desc& m_scene;
    path_settings m_settings;
    lights::environment_light m_environment;  ///< the image's lookup (no sampling is used)
};

}  // namespace iris
