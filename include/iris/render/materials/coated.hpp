#pragma once
/// \file
/// \brief `coated_bxdf`: the BxDF of `material::coated`, a diffuse or conductor base under a
/// clear dielectric coat of constant index η (pbrt-v4's `coateddiffuse`/`coatedconductor`;
/// docs/method.md §7 derives what follows).
///
/// The BSDF is the coat's own reflection plus the light that crosses the coat, bounces
/// between the base and the coat's underside and leaves again, at most `max_depth` layer
/// crossings (pbrt-v4's `maxdepth`; ⌈max_depth/2⌉ visits of the base). Three of its four
/// cases have closed forms and are evaluated exactly, deterministically:
///
/// | coat | base | BSDF |
/// |---|---|---|
/// | smooth | diffuse | a mirror lobe F(θo) + a diffuse lobe in closed form (geometric series in ρ·r_i) |
/// | smooth | smooth conductor | one mirror lobe of weight R(λ) (geometric series in F·F_c·T²) |
/// | smooth | rough conductor | a mirror lobe F(θo) + the transmitted part by a random walk |
/// | rough | any | the coat's GGX reflection + the transmitted part by a random walk |
///
/// The random walk is pbrt-v4's layered estimator without a scattering medium (light
/// entering and leaving through the coat, connected at each base visit with MIS), with one
/// change: the MIS weights of its two connections use the densities of the same variable
/// (pbrt-v4 weighs the exit's density of ωi against the base's of the inner direction), so
/// they sum to one exactly. It is seeded by the bits of (ωo, ωi): f is a deterministic
/// function of the directions, the same for the hero's wavelengths and the B term's bins,
/// and unbiased over directions (as pbrt-v4's). Every choice in it is wavelength-independent
/// (the coat's index is constant), so one walk serves all N wavelengths.
///
/// Sampling does not follow the walk: a direction is drawn from a mixture with a density
/// known exactly (the coat's reflection with probability F(θo), else a lobe for the base:
/// cosine for diffuse, GGX around the mirror direction mixed with cosine for conductors), and
/// reports the BSDF value `eval` gives for it — so the MIS weights of light and BSDF sampling
/// use one density, and the bins follow with f·|cos| like any non-delta BxDF. A smooth coat's
/// mirror lobe is a delta sample of a BxDF that is not delta as a whole (`bsdf_sample::delta`).
/// Two-sided, as pbrt-v4's: seen from below, the coat is on the lower side.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <variant>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/render/materials/conductor.hpp"
#include "iris/render/materials/fresnel.hpp"
#include "iris/render/materials/lambertian.hpp"
#include "iris/render/materials/microfacet.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief r_i of `material::coated`: 2∫₀¹ c·F_int(c)·exp(−2τ/c) dc, the cosine-weighted mean
/// over the directions leaving the base of the coat's internal reflectance (total beyond the
/// critical angle) times the round trip's transmittance. Simpson's rule on each side of the
/// critical angle, the upper side in c = c_crit + (1 − c_crit)t² (the reflectance has a
/// square-root kink there); 2·`n` points, relative error below 10⁻⁶ at the default.
inline float coated_internal_reflectance(float eta, float thickness, int n = 1024) noexcept {
    if (!(eta > 1.0f)) return 0.0f;  // index 1: no interface
    if (n % 2) ++n;
    const double inv_e2 = 1.0 / (static_cast<double>(eta) * eta);
    const double c_crit = std::sqrt(1.0 - inv_e2);
    const auto tr2 = [&](double c) { return thickness > 0.0f && c > 0.0 ? std::exp(-2.0 * thickness / c) : (thickness > 0.0f ? 0.0 : 1.0); };
    const auto simpson = [&](auto&& g) {
        double sum = g(0.0) + g(1.0);
        for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * g(static_cast<double>(i) / n);
        return sum / (3.0 * n);
    };
    // [0, c_crit]: total internal reflection, in c = c_crit·t
    const double below = simpson([&](double t) {
        const double c = c_crit * t;
        return 2.0 * c * tr2(c) * c_crit;
    });
    const double above = simpson([&](double t) {
        const double c = c_crit + (1.0 - c_crit) * t * t;
        const double f = detail::fresnel_walter(static_cast<float>(c), static_cast<float>(inv_e2));
        return 2.0 * c * f * tr2(c) * 2.0 * (1.0 - c_crit) * t;
    });
    return static_cast<float>(below + above);
}

namespace detail {

/// \brief The random numbers of one layered walk: SplitMix64 from the bits of (ωo, ωi).
struct walk_random {
    std::uint64_t state;

    walk_random(const glm::vec3& a, const glm::vec3& b) noexcept : state(0x6a09e667f3bcc909ull) {
        for (float x : {a.x, a.y, a.z, b.x, b.y, b.z}) state = mix(state ^ std::bit_cast<std::uint32_t>(x));
    }
    static std::uint64_t mix(std::uint64_t z) noexcept {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    std::uint64_t next_bits() noexcept { return mix(state += 0x9e3779b97f4a7c15ull); }
    float next() noexcept { return static_cast<float>(next_bits() >> 40) * 0x1p-24f; }
    glm::vec2 next2() noexcept {
        const float a = next();
        return {a, next()};
    }
};

/// \brief exp(−τ/|cos θ|): what crossing the coat at direction w keeps (1 without a thickness).
inline float coat_transmittance(float thickness, const glm::vec3& w) noexcept {
    if (!(thickness > 0.0f)) return 1.0f;
    const float c = std::fabs(w.z);
    return c > 0.0f ? std::exp(-thickness / c) : 0.0f;
}

/// \brief The coat as an interface (+z outside, index η inside), scalar: its index is the
/// same at every wavelength. Samples restricted to one lobe report their weight f·|cos|/p
/// (radiance: a transmission carries 1/η′²) and the lobe's own density (0 when smooth).
struct coat_interface {
    float eta;
    ggx m;
    bool smooth;

    struct scatter {
        glm::vec3 wi{0.0f};
        float weight = 0.0f;  ///< f·|cos θi| / p
        float pdf = 0.0f;     ///< the lobe's density of wi (0: a delta lobe)
        float etap = 1.0f;    ///< η′ of a transmission from w's side to wi's
    };

    float fresnel(float cos_o) const noexcept { return fresnel_dielectric(cos_o, eta); }

    /// \brief Through the coat from w (either side).
    std::optional<scatter> transmit(const glm::vec3& w, glm::vec2 u) const noexcept {
        if (smooth) {
            const auto t = refract(w, {0.0f, 0.0f, 1.0f}, eta);
            if (!t || t->wt.z == 0.0f) return std::nullopt;
            return scatter{t->wt, (1.0f - fresnel(w.z)) / (t->eta * t->eta), 0.0f, t->eta};
        }
        const bool below = w.z < 0.0f;
        const glm::vec3 wl = below ? -w : w;
        const float el = below ? 1.0f / eta : eta;
        const auto t = refract(wl, m.sample_visible(wl, u), el);
        if (!t || !(t->wt.z < 0.0f)) return std::nullopt;
        const auto v = rough_dielectric_value(m, wl, t->wt, el);
        if (!(v.pdf > 0.0f) || !(v.selection > 0.0f)) return std::nullopt;
        const float p = v.pdf / v.selection;
        return scatter{below ? -t->wt : t->wt, v.f_cos / p, p, t->eta};
    }

    /// \brief Reflection off the coat from w (either side; from below, total beyond the
    /// critical angle).
    std::optional<scatter> reflect(const glm::vec3& w, glm::vec2 u) const noexcept {
        if (smooth) return scatter{{-w.x, -w.y, w.z}, fresnel(w.z), 0.0f, 1.0f};
        const bool below = w.z < 0.0f;
        const glm::vec3 wl = below ? -w : w;
        const float el = below ? 1.0f / eta : eta;
        const glm::vec3 wr = reflect_about(wl, m.sample_visible(wl, u));
        if (!(wr.z > 0.0f)) return std::nullopt;
        const auto v = rough_dielectric_value(m, wl, wr, el);
        if (!(v.pdf > 0.0f) || !(v.selection > 0.0f)) return std::nullopt;
        const float p = v.pdf / v.selection;
        return scatter{below ? -wr : wr, v.f_cos / p, p, 1.0f};
    }

    /// \brief A rough coat's transmission from wo to wi (opposite sides): f·|cos θi|
    /// (radiance) and the transmission lobe's density of wi.
    rough_value transmission(const glm::vec3& wo, const glm::vec3& wi) const noexcept {
        auto v = rough_dielectric_value(m, wo, wi, eta);
        if (!(v.selection > 0.0f)) return {};
        v.pdf /= v.selection;
        return v;
    }
};

/// \brief The base's spectra seen from inside the coat: a conductor's η and k relative to
/// the coat (divided by its index, as pbrt-v4's coatedconductor), the reflectance as given.
template <std::size_t N, class S>
struct under_coat {
    const S& outer;
    sampled_spectrum<N> index, kappa;

    decltype(auto) albedo() const noexcept { return outer.albedo(); }
    const sampled_spectrum<N>& eta() const noexcept { return index; }
    const sampled_spectrum<N>& k() const noexcept { return kappa; }
};

inline float power_weight(float a, float b) noexcept {
    const float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/// \brief The most base visits a walk makes (`material::coated::max_depth` ≤ 100).
inline constexpr int max_coat_visits = 50;

/// \brief A walk's contributions at one visit of the base, as scalars and the cosines at
/// which the base's spectral factor (ρ, or the conductor's Fresnel) multiplies them: the
/// walk runs once, wavelength-free, and `coated_bxdf` applies the spectra at N wavelengths.
struct coat_visit {
    float light = 0.0f;      ///< the connection through the virtual light: × the base's factor at `light_cos`
    float light_cos = 0.0f;
    float bounce_cos = 0.0f; ///< the base's sampled bounce: its factor joins every later contribution
    float exit = 0.0f;       ///< the connection through that bounce (after its factor)
    bool bounced = false;
};
struct coat_walk {
    std::array<coat_visit, max_coat_visits> visits;
    int count = 0;
};

}  // namespace detail

struct coated_bxdf {
    const material::coated& data;

    explicit coated_bxdf(const material::coated& d) noexcept
        : data(d), m_top{d.eta, detail::ggx{d.roughness}, d.roughness < smooth_alpha || d.eta == 1.0f} {}

    static constexpr bool delta = false;
    static constexpr bool reads_albedo = true;
    static constexpr bool reads_eta = false;
    static constexpr bool reads_conductor = true;

    const material::conductor* conductor_base() const noexcept { return std::get_if<material::conductor>(&data.base); }
    const tabulated_spectrum& reflectance() const noexcept {
        if (const auto* c = conductor_base()) return c->reflectance;
        return std::get<material::diffuse>(data.base).reflectance;
    }
    bool has_ior() const noexcept {
        const auto* c = conductor_base();
        return c && c->ior.has_value();
    }
    const tabulated_spectrum& conductor_eta() const noexcept { return conductor_base()->ior->eta; }
    const tabulated_spectrum& conductor_k() const noexcept { return conductor_base()->ior->k; }

    bool smooth_coat() const noexcept { return m_top.smooth; }
    /// \brief A smooth conductor base: a delta base (with a smooth coat, a delta BSDF).
    bool delta_base() const noexcept {
        const auto* c = conductor_base();
        return c && c->roughness < smooth_alpha;
    }
    /// \brief Visits of the base a walk may make: ⌈max_depth/2⌉.
    int base_visits() const noexcept { return (data.max_depth + 1) / 2; }

    template <std::size_t N, class S>
    bsdf_value<N> eval(glm::vec3 wo, glm::vec3 wi, const S& s) const noexcept {
        if (wo.z < 0.0f) {
            wo.z = -wo.z;
            wi.z = -wi.z;
        }
        return eval_above<N>(wo, wi, s);
    }
    template <std::size_t N, class S>
    sampled_spectrum<N> f_cos(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        return eval<N>(wo, wi, s).f_cos;
    }
    template <std::size_t N, class S>
    sampled_spectrum<N> pdf(glm::vec3 wo, glm::vec3 wi, const S& /*s*/) const noexcept {
        if (wo.z < 0.0f) {
            wo.z = -wo.z;
            wi.z = -wi.z;
        }
        return sampled_spectrum<N>(density(wo, wi));
    }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(glm::vec3 wo, const sampled_wavelengths<N>& /*wl*/, float u_lobe, glm::vec2 u,
                                         const S& s) const noexcept {
        if (wo.z == 0.0f) return std::nullopt;
        const bool below = wo.z < 0.0f;
        if (below) wo.z = -wo.z;
        auto out = sample_above<N>(wo, u_lobe, u, s);
        if (out && below) out->wi.z = -out->wi.z;
        return out;
    }

    /// \brief The bins after the hero's sample: the mirror lobe's weight after a delta
    /// sample (kind `reflection`), f·|cos| after any other.
    template <std::size_t M, class S>
    sampled_spectrum<M> follow(glm::vec3 wo, glm::vec3 wi, lobe kind, const S& s) const noexcept {
        if (wo.z < 0.0f) {
            wo.z = -wo.z;
            wi.z = -wi.z;
        }
        if (smooth_coat() && kind == lobe::reflection) return mirror_weight<M>(wo.z, s);
        return eval_above<M>(wo, wi, s).f_cos;
    }

    /// \brief The smooth coat's diffuse lobe over a diffuse base, in closed form (ωo, ωi above):
    /// (1 − F(θo))(1 − F(θi)) T(θo′) T(θi′) ρ/(πη²) · Σ_{n<K} (ρ r_i)ⁿ · cos θi, θ′ the refracted
    /// angles, T the transmittance of one crossing, K = ⌈max_depth/2⌉ (docs/method.md §7).
    template <std::size_t N, class S>
    sampled_spectrum<N> diffuse_closed_form(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        const float eta = data.eta, inv_e2 = 1.0f / (eta * eta);
        const auto inner_cos = [&](float c) { return std::sqrt(std::max(0.0f, 1.0f - (1.0f - c * c) * inv_e2)); };
        const float t = detail::coat_transmittance(data.thickness, {0.0f, 0.0f, inner_cos(wo.z)}) *
                        detail::coat_transmittance(data.thickness, {0.0f, 0.0f, inner_cos(wi.z)});
        const float g = (1.0f - m_top.fresnel(wo.z)) * (1.0f - m_top.fresnel(wi.z)) * t * inv_e2 * detail::inv_pi * wi.z;
        const float ri = data.internal_reflectance >= 0.0f ? data.internal_reflectance
                                                           : coated_internal_reflectance(data.eta, data.thickness);
        const int visits = base_visits();
        const auto& rho = s.albedo();
        sampled_spectrum<N> f;
        for (std::size_t k = 0; k < N; ++k) {
            const float x = rho[k] * ri;
            float sum = 0.0f, term = 1.0f;
            for (int n = 0; n < visits; ++n) {
                sum += term;
                term *= x;
            }
            f[k] = g * rho[k] * sum;
        }
        return f;
    }

    /// \brief The transmitted part by the layered random walk (ωo, ωi above), `samples` walks.
    template <std::size_t N, class S>
    sampled_spectrum<N> walk(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        detail::walk_random r(wo, wi);
        const auto base_s = inner<N>(s);
        sampled_spectrum<N> sum;
        detail::coat_walk w;
        for (int n = 0; n < data.samples; ++n) {
            walk_once(wo, wi, r, w);
            sum += spectra_of<N>(w, base_s);
        }
        return data.samples > 1 ? sum * (1.0f / static_cast<float>(data.samples)) : sum;
    }

private:
    detail::coat_interface m_top;

    /// The probability of sampling the coat's own reflection: F(θo), as the hero's smooth
    /// dielectric (wavelength-independent: the coat's index is constant).
    float coat_probability(float cos_o) const noexcept { return m_top.fresnel(cos_o); }
    /// GGX α of the conductor base's sampling lobe seen through the coat.
    float base_alpha(const material::conductor& c) const noexcept {
        const float ab = c.roughness * data.eta, at = smooth_coat() ? 0.0f : data.roughness;
        return std::clamp(std::sqrt(ab * ab + at * at), smooth_alpha, 1.0f);
    }
    static constexpr float base_ggx_share = 0.75f;  // of a conductor base's lobe; the rest cosine

    static float reflection_density(const detail::ggx& m, const glm::vec3& wo, const glm::vec3& wi) noexcept {
        glm::vec3 wm = wo + wi;
        const float len2 = glm::dot(wm, wm);
        if (!(len2 > 0.0f)) return 0.0f;
        wm /= std::sqrt(len2);
        const float c = glm::dot(wo, wm);
        return c > 0.0f ? m.d_visible(wo, wm) / (4.0f * c) : 0.0f;
    }
    /// The density of the non-delta directions `sample_above` draws (ωo above).
    float density(const glm::vec3& wo, const glm::vec3& wi) const noexcept {
        if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
        if (smooth_coat() && delta_base()) return 0.0f;
        const float pr = coat_probability(wo.z);
        float base = wi.z * detail::inv_pi;
        if (const auto* c = conductor_base())
            base = base_ggx_share * reflection_density(detail::ggx{base_alpha(*c)}, wo, wi) + (1.0f - base_ggx_share) * base;
        const float top = smooth_coat() ? 0.0f : pr * reflection_density(m_top.m, wo, wi);
        return top + (1.0f - pr) * base;
    }

    /// R(λ) of a smooth coat: F(θo), and with a smooth conductor base the light that
    /// leaves along the same mirror direction: F + (1−F)² Σ_{n<K} (T² F_c)ⁿ⁺¹ Fⁿ.
    template <std::size_t N, class S>
    sampled_spectrum<N> mirror_weight(float cos_o, const S& s) const noexcept {
        const float f = m_top.fresnel(cos_o);
        if (!delta_base()) return sampled_spectrum<N>(f);
        const float ci = std::sqrt(std::max(0.0f, 1.0f - (1.0f - cos_o * cos_o) / (data.eta * data.eta)));
        const float t = detail::coat_transmittance(data.thickness, {0.0f, 0.0f, ci});
        const sampled_spectrum<N> fc = base_factor<N>(ci, inner<N>(s));
        const int visits = base_visits();
        sampled_spectrum<N> r;
        for (std::size_t k = 0; k < N; ++k) {
            const float x = t * t * fc[k];
            float sum = 0.0f, term = x;
            for (int n = 0; n < visits; ++n) {
                sum += term;
                term *= x * f;
            }
            r[k] = f + (1.0f - f) * (1.0f - f) * sum;
        }
        return r;
    }

    template <std::size_t N, class S>
    detail::under_coat<N, S> inner(const S& s) const noexcept {
        detail::under_coat<N, S> u{s, {}, {}};
        if (has_ior()) {
            const float inv = 1.0f / data.eta;
            const auto& e = s.eta();
            const auto& k = s.k();
            for (std::size_t i = 0; i < N; ++i) {
                u.index[i] = e[i] * inv;
                u.kappa[i] = k[i] * inv;
            }
        }
        return u;
    }

    template <std::size_t N, class S>
    bsdf_value<N> eval_above(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        bsdf_value<N> out;
        if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return out;
        if (smooth_coat() && delta_base()) return out;
        if (!smooth_coat()) {
            const auto v = detail::rough_dielectric_value(m_top.m, wo, wi, data.eta);
            out.f_cos = sampled_spectrum<N>(v.f_cos);
        }
        if (smooth_coat() && !conductor_base()) out.f_cos += diffuse_closed_form<N>(wo, wi, s);
        else out.f_cos += walk<N>(wo, wi, s);
        out.pdf = sampled_spectrum<N>(density(wo, wi));
        return out;
    }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample_above(const glm::vec3& wo, float u_lobe, glm::vec2 u, const S& s) const noexcept {
        bsdf_sample<N> out;
        if (smooth_coat() && delta_base()) {
            out.wi = {-wo.x, -wo.y, wo.z};
            out.f_cos = mirror_weight<N>(wo.z, s);
            out.pdf = sampled_spectrum<N>(1.0f);
            out.kind = lobe::reflection;
            out.delta = true;
            return out;
        }
        const float pr = coat_probability(wo.z);
        glm::vec3 wi;
        if (u_lobe < pr) {
            if (smooth_coat()) {
                out.wi = {-wo.x, -wo.y, wo.z};
                out.f_cos = sampled_spectrum<N>(pr);
                out.pdf = sampled_spectrum<N>(pr);
                out.kind = lobe::reflection;
                out.delta = true;
                return out;
            }
            wi = reflect_about(wo, m_top.m.sample_visible(wo, u));
        } else {
            const float ub = (u_lobe - pr) / (1.0f - pr);
            const auto* c = conductor_base();
            if (c && ub < base_ggx_share) wi = reflect_about(wo, detail::ggx{base_alpha(*c)}.sample_visible(wo, u));
            else {
                const float rr = std::sqrt(u.x), phi = 2.0f * std::numbers::pi_v<float> * u.y;
                wi = {rr * std::cos(phi), rr * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
            }
        }
        if (!(wi.z > 0.0f)) return std::nullopt;
        const auto v = eval_above<N>(wo, wi, s);
        if (!(v.pdf[0] > 0.0f)) return std::nullopt;
        out.wi = wi;
        out.f_cos = v.f_cos;
        out.pdf = v.pdf;
        out.kind = lobe::diffuse;
        return out;
    }

    /// The base as the walk sees it (from inside the layer, ωo above it), without its spectral
    /// factor: ρ for a diffuse base, the conductor's Fresnel at `cos` for a metal.
    struct base_value {
        float f_cos = 0.0f, pdf = 0.0f, cos = 0.0f;
    };
    struct base_scatter {
        glm::vec3 wi{0.0f};
        float weight = 0.0f;  ///< f·|cos θi|/p without the spectral factor
        float pdf = 0.0f;     ///< 0 for the smooth metal's mirror
        float cos = 0.0f;
    };
    base_value base_eval(const glm::vec3& wo, const glm::vec3& wi) const noexcept {
        if (!(wo.z * wi.z > 0.0f)) return {};
        const auto* c = conductor_base();
        if (!c) {
            const float p = std::fabs(wi.z) * detail::inv_pi;
            return {p, p, 0.0f};
        }
        glm::vec3 wm = wo + wi;
        const float len2 = glm::dot(wm, wm);
        if (!(len2 > 0.0f)) return {};
        wm /= std::sqrt(len2);
        if (wm.z < 0.0f) wm = -wm;
        const detail::ggx m{c->roughness};
        const float cm = std::fabs(glm::dot(wo, wm));
        if (!(cm > 0.0f)) return {};
        return {m.d(wm) * m.g(wo, wi) / (4.0f * std::fabs(wo.z)), m.d_visible(wo, wm) / (4.0f * cm), cm};
    }
    std::optional<base_scatter> base_sample(const glm::vec3& wo, glm::vec2 u) const noexcept {
        const auto* c = conductor_base();
        if (!c) {
            const float rr = std::sqrt(u.x), phi = 2.0f * std::numbers::pi_v<float> * u.y;
            const float z = std::sqrt(std::max(0.0f, 1.0f - u.x));
            if (!(z > 0.0f)) return std::nullopt;
            return base_scatter{{rr * std::cos(phi), rr * std::sin(phi), z}, 1.0f, z * detail::inv_pi, 0.0f};
        }
        if (c->roughness < smooth_alpha) return base_scatter{{-wo.x, -wo.y, wo.z}, 1.0f, 0.0f, std::fabs(wo.z)};
        const glm::vec3 wi = reflect_about(wo, detail::ggx{c->roughness}.sample_visible(wo, u));
        const base_value v = base_eval(wo, wi);
        if (!(v.pdf > 0.0f)) return std::nullopt;
        return base_scatter{wi, v.f_cos / v.pdf, v.pdf, v.cos};
    }
    /// The base's spectral factor at N wavelengths: ρ, or F_c(cos, λ) relative to the coat.
    template <std::size_t N, class U>
    sampled_spectrum<N> base_factor(float cos, const U& s) const noexcept {
        if (const auto* c = conductor_base()) return conductor_spectra{*c}.template fresnel<N>(cos, s);
        return sampled_spectrum<N>(s.albedo());
    }

    /// One walk, wavelength-free (docs/method.md §7): enter through the coat from ωo, visit
    /// the base, and at each visit connect to ωi two ways — through a direction sampled
    /// from ωi into the coat (the "virtual light"), and through the direction the base
    /// samples, leaving through a rough coat — with MIS between them; record each visit's
    /// scalar contributions (f·|cos θi| without the base's spectral factors).
    void walk_once(const glm::vec3& wo, const glm::vec3& wi, detail::walk_random& r, detail::coat_walk& out) const noexcept {
        out.count = 0;
        const auto enter = m_top.transmit(wo, r.next2());
        const auto light = m_top.transmit(wi, r.next2());
        if (!enter || !light) return;
        // the virtual light's weight: importance transport (the 1/η′² undone), without its cosine
        const float light_cos = std::fabs(light->wi.z);
        if (!(light_cos > 0.0f)) return;
        const float light_weight = light->weight * light->etap * light->etap / light_cos;
        float beta = enter->weight;
        glm::vec3 w = enter->wi;  // travelling down
        const int depth_max = std::min(data.max_depth, 2 * detail::max_coat_visits);
        for (int depth = 0; depth < depth_max && beta > 0.0f; ++depth) {
            beta *= detail::coat_transmittance(data.thickness, w);
            if (depth % 2 == 0) {
                // at the base, seen from ωb = −w
                detail::coat_visit& v = out.visits[static_cast<std::size_t>(out.count++)];
                v = {};
                const glm::vec3 wb = -w;
                if (!delta_base()) {
                    const glm::vec3 wl = -light->wi;
                    const base_value bv = base_eval(wb, wl);
                    const float mis = smooth_coat() ? 1.0f : detail::power_weight(light->pdf, bv.pdf);
                    v.light = beta * bv.f_cos * mis * detail::coat_transmittance(data.thickness, wl) * light_weight * wi.z;
                    v.light_cos = bv.cos;
                }
                const auto bs = base_sample(wb, r.next2());
                if (!bs) break;
                beta *= bs->weight;
                v.bounce_cos = bs->cos;
                v.bounced = true;
                w = bs->wi;  // travelling up
                if (!smooth_coat()) {
                    const auto tv = m_top.transmission(-w, wi);
                    if (tv.f_cos > 0.0f) {
                        const float mis = bs->pdf == 0.0f ? 1.0f : detail::power_weight(bs->pdf, m_top.transmission(wi, -w).pdf);
                        v.exit = beta * detail::coat_transmittance(data.thickness, w) * tv.f_cos * mis;
                    }
                }
            } else {
                // at the coat's underside: back down
                const auto rs = m_top.reflect(-w, r.next2());
                if (!rs || !(rs->wi.z < 0.0f)) break;
                beta *= rs->weight;
                w = rs->wi;
            }
        }
    }

    /// A walk's f·|cos θi| at N wavelengths: each contribution times the base's spectral
    /// factors of the bounces before it.
    template <std::size_t N, class U>
    sampled_spectrum<N> spectra_of(const detail::coat_walk& w, const U& s) const noexcept {
        sampled_spectrum<N> f, prefix(1.0f);
        for (int k = 0; k < w.count; ++k) {
            const detail::coat_visit& v = w.visits[static_cast<std::size_t>(k)];
            if (v.light != 0.0f) f += prefix * base_factor<N>(v.light_cos, s) * v.light;
            if (!v.bounced) break;
            prefix *= base_factor<N>(v.bounce_cos, s);
            if (v.exit != 0.0f) f += prefix * v.exit;
        }
        return f;
    }
};

}  // namespace iris
