#pragma once
/// \file
/// \brief Spectral BSDFs of the scene's materials, evaluated at N wavelengths at once.
///
/// The same templates serve the C hero-rotated wavelengths (`N = C`) and the bins of the
/// bias-propagation term (`N = bins`), so the B term is one vectorised call per vertex,
/// not a loop of scalar material calls. Directions are world-space unit vectors pointing
/// away from the surface; `n` is the (outward) geometric normal.
///
/// Sampling is driven by the hero wavelength λ₀ alone. A sample reports, for every
/// wavelength λ_k, the BSDF value f(λ_k)·|cos θᵢ| along the hero's direction and the pdf
/// p(ωᵢ | λ_k) that λ_k would have had of producing that same direction — the inputs of
/// the HWSS MIS weight (SPEC §2). For delta lobes both are discrete weights; at a
/// refraction through a dispersive interface the direction depends on λ, so p(ωᵢ|λ_k) = 0
/// for k ≠ 0 (secondary wavelengths terminate, SPEC §2) and f(λ_k) = 0 with it.
/// Reflection off a dispersive interface keeps the secondaries: its direction does not
/// depend on λ.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <variant>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"
#include "iris/spectrum/spectrum.hpp"

namespace iris {

/// \brief Which lobe a sample took; the B term follows the hero's choice at delta events.
enum class lobe : unsigned char { diffuse, reflection, transmission };

template <std::size_t N>
struct bsdf_sample {
    glm::vec3 wi{0.0f};
    sampled_spectrum<N> f_cos;  ///< f(ωo, ωi, λ_k)·|cos θi|, or the discrete weight of a delta lobe
    sampled_spectrum<N> pdf;    ///< p(ωi | ωo, λ_k) (solid angle), or a discrete probability
    lobe kind = lobe::diffuse;
    bool delta = false;
    /// \brief η′ of a transmission: the hero's relative index from ωo's side to ωi's (1 for
    /// every other lobe). `f_cos` carries the radiance scaling 1/η′² across the interface;
    /// Russian roulette multiplies it back (`eta_scale` in the integrators), as pbrt-v4 does.
    float eta = 1.0f;
};

namespace detail {

inline constexpr float inv_pi = std::numbers::inv_pi_v<float>;

/// \brief Unpolarised Fresnel reflectance of a dielectric interface. `cos_i` is measured
/// on the side of the incident direction's normal; eta = n_inside / n_outside.
inline float fresnel_dielectric(float cos_i, float eta) noexcept {
    cos_i = std::clamp(cos_i, -1.0f, 1.0f);
    if (cos_i < 0.0f) {
        eta = 1.0f / eta;
        cos_i = -cos_i;
    }
    const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
    const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
    const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

/// \brief Refract `wi` (pointing away) through a surface with normal `n`; eta = n_inside /
/// n_outside with `n` pointing outside. Returns the transmitted direction and the relative
/// eta it saw (η_t/η_i), or nothing on total internal reflection.
struct refraction {
    glm::vec3 wt;
    float eta;
};
inline std::optional<refraction> refract(const glm::vec3& wi, glm::vec3 n, float eta) noexcept {
    float cos_i = glm::dot(n, wi);
    if (cos_i < 0.0f) {
        eta = 1.0f / eta;
        cos_i = -cos_i;
        n = -n;
    }
    const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
    const float sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1.0f) return std::nullopt;
    const float cos_t = std::sqrt(1.0f - sin2_t);
    return refraction{glm::normalize(-wi / eta + (cos_i / eta - cos_t) * n), eta};
}

/// \brief Isotropic GGX (Trowbridge–Reitz) in the local frame (n = +z).
struct ggx {
    float alpha;

    float d(const glm::vec3& wm) const noexcept {
        const float c2 = wm.z * wm.z;
        if (c2 <= 0.0f) return 0.0f;
        const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
        const float e = 1.0f + tan2 / (alpha * alpha);
        return 1.0f / (std::numbers::pi_v<float> * alpha * alpha * c2 * c2 * e * e);
    }
    float lambda(const glm::vec3& w) const noexcept {
        const float c2 = w.z * w.z;
        if (c2 <= 0.0f) return 0.0f;
        const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
        return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
    }
    float g1(const glm::vec3& w) const noexcept { return 1.0f / (1.0f + lambda(w)); }
    float g(const glm::vec3& wo, const glm::vec3& wi) const noexcept { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
    /// \brief Density of visible normals D_ωo(ωm) (Heitz 2018).
    float d_visible(const glm::vec3& wo, const glm::vec3& wm) const noexcept {
        return wo.z == 0.0f ? 0.0f : g1(wo) / std::fabs(wo.z) * d(wm) * std::fabs(glm::dot(wo, wm));
    }
    /// \brief Sample a visible normal (Heitz 2018, "Sampling the GGX distribution of visible normals").
    glm::vec3 sample_visible(glm::vec3 wo, glm::vec2 u) const noexcept {
        glm::vec3 wh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
        if (wh.z < 0.0f) wh = -wh;
        const glm::vec3 t1 = wh.z < 0.99999f ? glm::normalize(glm::cross(glm::vec3(0, 0, 1), wh)) : glm::vec3(1, 0, 0);
        const glm::vec3 t2 = glm::cross(wh, t1);
        const float r = std::sqrt(u.x);
        const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
        float px = r * std::cos(phi);
        float py = r * std::sin(phi);
        const float h = std::sqrt(std::max(0.0f, 1.0f - px * px));
        py = (1.0f - (1.0f + wh.z) / 2.0f) * h + (1.0f + wh.z) / 2.0f * py;
        const float pz = std::sqrt(std::max(0.0f, 1.0f - px * px - py * py));
        const glm::vec3 nh = px * t1 + py * t2 + pz * wh;
        return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
    }
};

/// \brief f·|cos θi| and pdf of the rough dielectric for one wavelength (local frame),
/// with the generalised half vector of Walter et al. 2007 (pbrt-v4's formulation).
struct rough_value {
    float f_cos = 0.0f;
    float pdf = 0.0f;
};
inline rough_value rough_dielectric(const ggx& m, const glm::vec3& wo, const glm::vec3& wi, float eta) noexcept {
    const float cos_o = wo.z, cos_i = wi.z;
    if (cos_o == 0.0f || cos_i == 0.0f) return {};
    const bool reflect = cos_i * cos_o > 0.0f;
    const float etap = reflect ? 1.0f : (cos_o > 0.0f ? eta : 1.0f / eta);
    glm::vec3 wm = wi * etap + wo;
    const float len2 = glm::dot(wm, wm);
    if (!(len2 > 0.0f)) return {};
    wm = wm / std::sqrt(len2);
    if (wm.z < 0.0f) wm = -wm;
    if (glm::dot(wm, wi) * cos_i < 0.0f || glm::dot(wm, wo) * cos_o < 0.0f) return {};  // back-facing microfacet
    const float fr = fresnel_dielectric(glm::dot(wo, wm), eta);
    if (reflect) {
        const float f = m.d(wm) * m.g(wo, wi) * fr / std::fabs(4.0f * cos_i * cos_o);
        const float pdf = m.d_visible(wo, wm) / (4.0f * std::fabs(glm::dot(wo, wm))) * fr;
        return {f * std::fabs(cos_i), pdf};
    }
    const float s = glm::dot(wi, wm) + glm::dot(wo, wm) / etap;
    const float denom = s * s * cos_i * cos_o;
    if (denom == 0.0f) return {};
    float ft = m.d(wm) * (1.0f - fr) * m.g(wo, wi) * std::fabs(glm::dot(wi, wm) * glm::dot(wo, wm) / denom);
    ft /= etap * etap;  // radiance is compressed/expanded across the interface
    const float dwm_dwi = std::fabs(glm::dot(wi, wm)) / (s * s);
    const float pdf = m.d_visible(wo, wm) * dwm_dwi * (1.0f - fr);
    return {ft * std::fabs(cos_i), pdf};
}

/// \brief Below this GGX α a rough dielectric is treated as smooth (numerically a delta).
inline constexpr float smooth_alpha = 1e-3f;

template <std::size_t N>
sampled_spectrum<N> etas(const ior_model& ior, const sampled_wavelengths<N>& wl) noexcept {
    sampled_spectrum<N> e;
    for (std::size_t k = 0; k < N; ++k) e[k] = static_cast<float>(refractive_index(ior, static_cast<double>(wl[k])));
    return e;
}

}  // namespace detail

namespace detail {
/// \brief A dielectric behaves as a delta BSDF when it is (numerically) smooth, or when
/// its index is exactly 1: an invisible interface, whose microfacet half vector is
/// undefined (ωi = −ωo), so it passes light straight through like smooth glass of η = 1.
inline bool effectively_smooth(const material::dielectric& d) noexcept {
    if (d.roughness < smooth_alpha) return true;
    const auto* c = std::get_if<constant_ior>(&d.ior);
    return c && c->value == 1.0;
}
}  // namespace detail

/// \brief Is this material a delta BSDF (mirror, smooth glass)?
inline bool is_delta(const material_desc& m) noexcept {
    if (std::holds_alternative<material::conductor>(m)) return true;
    if (const auto* d = std::get_if<material::dielectric>(&m)) return detail::effectively_smooth(*d);
    return false;
}

/// \brief A Lambertian surface is separable, f(λ)·|cos θi| = R(λ) · lambert_cos(n, ωo, ωi):
/// |cos θi|/π on ωo's side of the surface (two-sided), 0 across it.
inline float lambert_cos(const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi) noexcept {
    const float co = glm::dot(n, wo), ci = glm::dot(n, wi);
    return co * ci > 0.0f ? std::fabs(ci) * detail::inv_pi : 0.0f;
}

/// \brief f(ωo, ωi)·|cos θi| for non-delta materials (0 for delta ones) at N wavelengths,
/// given the material's spectra at those wavelengths on demand: `albedo()` the reflectance
/// (diffuse), `eta()` the index of refraction (dielectric). The integrator's B term passes
/// spectra read from its bin tables (iris/render/bins.hpp); `bsdf_eval` evaluates the scene's.
template <std::size_t N, class Albedo, class Eta>
sampled_spectrum<N> bsdf_eval_given(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo,
                                    const glm::vec3& wi, Albedo&& albedo, Eta&& eta) noexcept {
    if (std::holds_alternative<material::diffuse>(mat)) {
        const float c = lambert_cos(n, wo, wi);
        if (c == 0.0f) return {};
        return sampled_spectrum<N>(albedo()) * c;
    }
    if (const auto* g = std::get_if<material::dielectric>(&mat); g && !detail::effectively_smooth(*g)) {
        const frame fr = frame::from_normal(n);
        const glm::vec3 lo = fr.to_local(wo), li = fr.to_local(wi);
        const detail::ggx m{g->roughness};
        const auto e = eta();  // a spectrum, or anything indexable by k (the bins' lattice view)
        sampled_spectrum<N> out;
        for (std::size_t k = 0; k < N; ++k) out[k] = detail::rough_dielectric(m, lo, li, e[k]).f_cos;
        return out;
    }
    return {};
}

/// \brief f(ωo, ωi, λ_k)·|cos θi| for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_eval(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi,
                              const sampled_wavelengths<N>& wl) noexcept {
    return bsdf_eval_given<N>(
        mat, n, wo, wi, [&] { return sample(std::get<material::diffuse>(mat).reflectance, wl); },
        [&] { return detail::etas(std::get<material::dielectric>(mat).ior, wl); });
}

/// \brief p(ωi | ωo, λ_k) in solid angle for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_pdf(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi,
                             const sampled_wavelengths<N>& wl) noexcept {
    if (std::holds_alternative<material::diffuse>(mat)) return sampled_spectrum<N>(lambert_cos(n, wo, wi));
    if (const auto* g = std::get_if<material::dielectric>(&mat); g && !detail::effectively_smooth(*g)) {
        const frame fr = frame::from_normal(n);
        const glm::vec3 lo = fr.to_local(wo), li = fr.to_local(wi);
        const detail::ggx m{g->roughness};
        const auto eta = detail::etas(g->ior, wl);
        sampled_spectrum<N> out;
        for (std::size_t k = 0; k < N; ++k) out[k] = detail::rough_dielectric(m, lo, li, eta[k]).pdf;
        return out;
    }
    return {};
}

/// \brief Sample a direction with the hero wavelength wl[0]; report f·|cos| and pdf for
/// every wavelength along it. `u_lobe` picks reflection/transmission, `u` the direction.
/// `albedo()` gives the reflectance of a diffuse or conductor material at `wl` (the
/// integrator reads it from a lattice table; `bsdf_sample_hero` evaluates the scene's).
/// Returns nothing when the sample is absorbed or degenerate.
template <std::size_t N, class Albedo>
std::optional<bsdf_sample<N>> bsdf_sample_hero_given(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo,
                                                     const sampled_wavelengths<N>& wl, float u_lobe, glm::vec2 u,
                                                     Albedo&& albedo) noexcept {
    bsdf_sample<N> s;
    if (std::holds_alternative<material::diffuse>(mat)) {
        const float co = glm::dot(n, wo);
        if (co == 0.0f) return std::nullopt;
        // cosine-weighted hemisphere on wo's side (Malley: concentric disk → lift)
        const float r = std::sqrt(u.x), phi = 2.0f * std::numbers::pi_v<float> * u.y;
        const float x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0f, 1.0f - u.x));
        const frame fr = frame::from_normal(co > 0.0f ? n : -n);
        s.wi = glm::normalize(fr.to_world({x, y, z}));
        if (!(z > 0.0f)) return std::nullopt;
        s.f_cos = sampled_spectrum<N>(albedo()) * (z * detail::inv_pi);
        s.pdf = sampled_spectrum<N>(z * detail::inv_pi);
        s.kind = lobe::diffuse;
        return s;
    }
    if (std::holds_alternative<material::conductor>(mat)) {
        s.wi = reflect_about(wo, n);
        s.f_cos = sampled_spectrum<N>(albedo());
        s.pdf = sampled_spectrum<N>(1.0f);
        s.kind = lobe::reflection;
        s.delta = true;
        return s;
    }
    const auto& g = std::get<material::dielectric>(mat);
    const auto eta = detail::etas(g.ior, wl);
    const bool dispersive = is_dispersive(g.ior);
    if (detail::effectively_smooth(g)) {
        const float co = glm::dot(n, wo);
        sampled_spectrum<N> fr;
        for (std::size_t k = 0; k < N; ++k) fr[k] = detail::fresnel_dielectric(co, eta[k]);
        s.delta = true;
        if (u_lobe < fr[0]) {
            s.wi = reflect_about(wo, n);
            s.kind = lobe::reflection;
            s.f_cos = fr;
            s.pdf = fr;  // had λ_k been the hero, it would have reflected with probability F(λ_k)
            return s;
        }
        const auto t = detail::refract(wo, n, eta[0]);
        if (!t) return std::nullopt;  // unreachable: TIR means F = 1
        s.wi = t->wt;
        s.kind = lobe::transmission;
        s.eta = co > 0.0f ? eta[0] : 1.0f / eta[0];
        for (std::size_t k = 0; k < N; ++k) {
            if (dispersive && k > 0) continue;  // λ-dependent direction: secondaries terminate
            const float e = co > 0.0f ? eta[k] : 1.0f / eta[k];
            s.f_cos[k] = (1.0f - fr[k]) / (e * e);
            s.pdf[k] = 1.0f - fr[k];
        }
        return s;
    }
    // rough dielectric: sample a visible microfacet normal with the hero's eta
    const frame fr = frame::from_normal(n);
    const glm::vec3 lo = fr.to_local(wo);
    if (lo.z == 0.0f) return std::nullopt;
    const detail::ggx m{g.roughness};
    const glm::vec3 wm = m.sample_visible(lo, u);
    const float f0 = detail::fresnel_dielectric(glm::dot(lo, wm), eta[0]);
    glm::vec3 li;
    if (u_lobe < f0) {
        li = reflect_about(lo, wm);
        if (li.z * lo.z <= 0.0f) return std::nullopt;
        s.kind = lobe::reflection;
    } else {
        const auto t = detail::refract(lo, wm, eta[0]);
        if (!t || t->wt.z * lo.z >= 0.0f || t->wt.z == 0.0f) return std::nullopt;
        li = t->wt;
        s.kind = lobe::transmission;
        s.eta = lo.z > 0.0f ? eta[0] : 1.0f / eta[0];
    }
    s.wi = fr.to_world(li);
    for (std::size_t k = 0; k < N; ++k) {
        const auto v = detail::rough_dielectric(m, lo, li, eta[k]);
        s.f_cos[k] = v.f_cos;
        s.pdf[k] = v.pdf;
    }
    if (!(s.pdf[0] > 0.0f)) return std::nullopt;
    (void)dispersive;  // rough events keep every wavelength: all p(ωi|λ_k) are finite (SPEC §2)
    return s;
}

/// \brief `bsdf_sample_hero_given` with the material's reflectance evaluated at `wl`.
template <std::size_t N>
std::optional<bsdf_sample<N>> bsdf_sample_hero(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo,
                                               const sampled_wavelengths<N>& wl, float u_lobe, glm::vec2 u) noexcept {
    return bsdf_sample_hero_given(mat, n, wo, wl, u_lobe, u, [&] {
        if (const auto* d = std::get_if<material::diffuse>(&mat)) return sample(d->reflectance, wl);
        return sample(std::get<material::conductor>(mat).reflectance, wl);
    });
}

/// \brief The weight of a delta event at other wavelengths (the B-term bins) when they
/// follow the hero's lobe and direction: R(λ_b) off a conductor, F(λ_b) for reflection off
/// a dielectric, (1 − F(λ_b))/η_b² for transmission. Treating λ_b as if it took the hero's
/// refracted direction is the method's (only) bias (SPEC §3). The material's spectra come
/// on demand as in `bsdf_eval_given`: `albedo()` a conductor's reflectance, `eta2()` a
/// dielectric's η² and `inv_eta2()` its 1/η² (the integrator reads both from tables).
template <std::size_t M, class Albedo, class Eta2, class InvEta2>
sampled_spectrum<M> delta_weight_given(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, lobe kind,
                                       Albedo&& albedo, Eta2&& eta2, InvEta2&& inv_eta2) noexcept {
    if (std::holds_alternative<material::conductor>(mat)) return sampled_spectrum<M>(albedo());
    if (!std::holds_alternative<material::dielectric>(mat)) return {};
    // fresnel_dielectric(co, η_k) for every k at once, in the form of Walter et al. 2007
    // (eq. 22) with c = |cos θi| and g = √(η′² − 1 + c²) (= η′ cos θt):
    //   F = ½ (g−c)² [(c(g−c)+1)² + (c(g+c)−1)²] / [(g+c)² (c(g−c)+1)²],  F = 1 if g² ≤ 0,
    // one square root and one division per wavelength, and η′² read, not computed. The side
    // (co's sign) is the same for all wavelengths, so the loop is branch-free arithmetic and
    // selects, which the compiler vectorises (80 bins at every glass vertex: this is the B
    // term's hot loop; choosing the tables once, outside the loop, stops GCC vectorising it).
    const float co = std::clamp(glm::dot(n, wo), -1.0f, 1.0f);
    const bool flip = co < 0.0f, from_outside = co > 0.0f;  // as fresnel_dielectric and the hero's sample
    const bool reflection = kind == lobe::reflection;
    const float c = std::fabs(co), c2 = c * c;
    const auto sq = eta2();  // spectra, or anything indexable by k (the bins' lattice views)
    const auto isq = inv_eta2();
    sampled_spectrum<M> w;
    for (std::size_t k = 0; k < M; ++k) {
        const float e2 = sq[k], ie2 = isq[k];
        const float ef2 = flip ? ie2 : e2;              // η′²: the relative index seen from ωo's side
        const float inv_et2 = from_outside ? ie2 : e2;  // 1/η′² of the hero's transmission
        const float g2 = ef2 - 1.0f + c2;
        const float g = std::sqrt(std::max(0.0f, g2));
        const float gm = g - c, gp = g + c;
        const float u = c * gm + 1.0f, v = c * gp - 1.0f;
        const float ratio = 0.5f * (gm * gm * (u * u + v * v)) / (gp * gp * (u * u));  // everywhere: a select, not a branch
        const float f = g2 > 0.0f ? ratio : 1.0f;  // total internal reflection (also where g + c = 0)
        w[k] = reflection ? f : (1.0f - f) * inv_et2;
    }
    return w;
}

/// \brief `delta_weight_given` with η² and 1/η² computed from `eta()`, the index.
template <std::size_t M, class Albedo, class Eta>
sampled_spectrum<M> delta_weight_given(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, lobe kind,
                                       Albedo&& albedo, Eta&& eta) noexcept {
    const auto e = eta();
    sampled_spectrum<M> sq, inv;
    for (std::size_t k = 0; k < M; ++k) {
        sq[k] = e[k] * e[k];
        inv[k] = 1.0f / sq[k];
    }
    return delta_weight_given<M>(mat, n, wo, kind, albedo, [&] { return sq; }, [&] { return inv; });
}

/// \brief `delta_weight_given` with the scene's spectra evaluated at `wl`.
template <std::size_t M>
sampled_spectrum<M> delta_weight(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, lobe kind,
                                 const sampled_wavelengths<M>& wl) noexcept {
    return delta_weight_given<M>(
        mat, n, wo, kind, [&] { return sample(std::get<material::conductor>(mat).reflectance, wl); },
        [&] { return detail::etas(std::get<material::dielectric>(mat).ior, wl); });
}

}  // namespace iris
