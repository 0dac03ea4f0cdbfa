#pragma once
/// \file
/// \brief What every material of iris is: a BxDF type evaluated at N wavelengths at once,
/// and the spectra it reads. One header per material in this directory; `materials.hpp`
/// lists them and maps a scene's `material_desc` to one (`visit_bxdf`).
///
/// A BxDF is a small value type made at a vertex from its material's data. Directions are
/// unit vectors pointing away from the surface, in the vertex's shading frame, whose normal
/// is +z (`surface_interaction::shading`, iris/render/interaction.hpp: the frame is built
/// once per vertex, not per call), and every call takes the material's spectra at the wavelengths being evaluated
/// from a *spectra source* `S` (below). The same templates serve the C hero-rotated
/// wavelengths (N = C) and the B term's bins (N = bins), so the B term is one vectorised
/// call per vertex, not a loop of scalar material calls. The members (`bxdf` checks them):
///
/// | member | what it is |
/// |---|---|
/// | `delta` | a delta BSDF (mirror, smooth glass): no `f_cos`/`pdf` for a given ωi, no light sampling |
/// | `reads_albedo`, `reads_eta` | which spectra it reads: `reflectance()` or `ior()` then exist |
/// | `film()` (optional) | the material's thin film or null; then `wavelength()` and `film_eta()` are read where it is set |
/// | `reads_conductor` (optional) | a conductor's η and k (`conductor_eta()`, `conductor_k()` tables, read as `eta()`, `k()`) where `has_ior()` |
/// | `f_cos<N>(wo, wi, s)` | f(ωo, ωi, λ_k)·\|cos θi\| (0 for delta BxDFs) |
/// | `pdf<N>(wo, wi, s)` | p(ωi \| ωo, λ_k), solid angle (0 for delta BxDFs) |
/// | `eval<N>(wo, wi, s)` | both at once (`bsdf_value`), sharing what they have in common |
/// | `sample<N>(wo, wl, u_lobe, u, s)` | a direction for the hero λ₀ = wl[0], with f·\|cos\| and pdf of every λ_k along it |
/// | `follow<M>(wo, wi, kind, s)` | the weight of M other wavelengths (the bins) that follow the hero's direction and lobe |
///
/// Sampling is driven by the hero alone. A sample reports, for every λ_k, f(λ_k)·|cos θi|
/// along the hero's direction and the pdf p(ωi | λ_k) that λ_k would have had of producing
/// that same direction — the inputs of the HWSS MIS weight (docs/method.md §3). For delta lobes both
/// are discrete weights; at a refraction through a dispersive interface the direction
/// depends on λ, so p(ωi|λ_k) = 0 for k ≠ 0 (secondary wavelengths terminate, docs/method.md §3) and
/// f(λ_k) = 0 with it. `follow` is what the B term multiplies its bins by when they take
/// the hero's direction: f·|cos| for non-delta BxDFs, the lobe's discrete weight for delta
/// ones — treating λ_b as if it took the hero's refracted direction is the method's (only)
/// bias (docs/method.md §3).
///
/// A BxDF whose value factors as f(λ)·|cos θi| = R(λ)·g(ωo, ωi) also has `cos_factor(wo,
/// wi)` = g (`separable_bxdf`): the B term then multiplies its 80 bins by R once and by
/// one number per direction, not by an 80-wide product.
///
/// A spectra source gives the material's spectra at the N wavelengths being evaluated,
/// each as anything indexable by k < N (a `sampled_spectrum<N>`, or a view of the bins'
/// lattice tables, iris/render/bins.hpp): `albedo()` the reflectance, `eta()` the index of
/// refraction, `eta2()` and `inv_eta2()` its square and inverse square (the bins' Fresnel
/// reads them from tables, not computing them). A BxDF calls only those of its own
/// material; `sampled_spectra` holds them as values, the integrator reads its own tables.

#include <concepts>
#include <cstddef>
#include <numbers>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief Which lobe a sample took; the B term follows the hero's choice at delta events.
enum class lobe : unsigned char { diffuse, reflection, transmission };

/// \brief f(ωo, ωi, λ_k)·|cos θi| and p(ωi | ωo, λ_k) of one pair of directions.
template <std::size_t N>
struct bsdf_value {
    sampled_spectrum<N> f_cos, pdf;
};

template <std::size_t N>
struct bsdf_sample {
    glm::vec3 wi{0.0f};         ///< in the shading frame, as the BxDF's arguments
    sampled_spectrum<N> f_cos;  ///< f(ωo, ωi, λ_k)·|cos θi|, or the discrete weight of a delta lobe
    sampled_spectrum<N> pdf;    ///< p(ωi | ωo, λ_k) (solid angle), or a discrete probability
    lobe kind = lobe::diffuse;
    bool delta = false;
    /// \brief η′ of a transmission: the hero's relative index from ωo's side to ωi's (1 for
    /// every other lobe). `f_cos` carries the radiance scaling 1/η′² across the interface;
    /// Russian roulette multiplies it back (`eta_scale` in the integrators), as pbrt-v4 does.
    float eta = 1.0f;
};

/// \brief A material's spectra held as values at N wavelengths (what a BxDF reads through
/// `albedo()`, `eta()`, `eta2()`, `inv_eta2()`, and a conductor's `k()`); only those of
/// its material are set.
template <std::size_t N>
struct sampled_spectra {
    sampled_spectrum<N> reflectance, index, index2, inv_index2, kappa;
    sampled_spectrum<N> lambda, film_index;  ///< set for a material with a thin film

    const sampled_spectrum<N>& albedo() const noexcept { return reflectance; }
    const sampled_spectrum<N>& wavelength() const noexcept { return lambda; }
    const sampled_spectrum<N>& film_eta() const noexcept { return film_index; }
    const sampled_spectrum<N>& eta() const noexcept { return index; }
    const sampled_spectrum<N>& eta2() const noexcept { return index2; }
    const sampled_spectrum<N>& inv_eta2() const noexcept { return inv_index2; }
    const sampled_spectrum<N>& k() const noexcept { return kappa; }

    static sampled_spectra with_albedo(const sampled_spectrum<N>& r) noexcept {
        sampled_spectra s;
        s.reflectance = r;
        return s;
    }
    /// \brief η, with η² and 1/η² computed from it.
    static sampled_spectra with_eta(const sampled_spectrum<N>& e) noexcept {
        sampled_spectra s;
        s.index = e;
        for (std::size_t k = 0; k < N; ++k) {
            s.index2[k] = e[k] * e[k];
            s.inv_index2[k] = 1.0f / s.index2[k];
        }
        return s;
    }
};

/// \brief Whether BxDF B may read a conductor's complex index (`eta()` and `k()` from
/// per-material tables, when its `has_ior()`); false unless B says so.
template <class B>
inline constexpr bool reads_conductor_v = requires { requires B::reads_conductor; };

/// \brief A BxDF that may carry a thin film (`film()`: the film, or null); its spectra
/// source then also gives the wavelengths (`wavelength()`) and the film's index (`film_eta()`).
template <class B>
inline constexpr bool reads_film_v = requires(const B& b) { b.film(); };

/// \brief A spectra source that gives the wavelengths and a film's index (every source the
/// estimators use; a coat's view of its base does not, and a coat's base has no film).
template <class S>
concept film_source = requires(const S& s) {
    s.wavelength()[0];
    s.film_eta()[0];
};

static_assert(film_source<sampled_spectra<4>>);

/// \brief The BxDF concept of the table above, checked at 4 wavelengths.
template <class B>
concept bxdf = requires(const B& b, const glm::vec3& v, const sampled_wavelengths<4>& wl, const sampled_spectra<4>& s,
                        float u1, glm::vec2 u2, lobe kind) {
    { B::delta } -> std::convertible_to<bool>;
    { B::reads_albedo } -> std::convertible_to<bool>;
    { B::reads_eta } -> std::convertible_to<bool>;
    { b.template f_cos<4>(v, v, s) } -> std::same_as<sampled_spectrum<4>>;
    { b.template pdf<4>(v, v, s) } -> std::same_as<sampled_spectrum<4>>;
    { b.template eval<4>(v, v, s) } -> std::same_as<bsdf_value<4>>;
    { b.template sample<4>(v, wl, u1, u2, s) } -> std::same_as<std::optional<bsdf_sample<4>>>;
    { b.template follow<4>(v, v, kind, s) } -> std::same_as<sampled_spectrum<4>>;
};

/// \brief A BxDF whose f·|cos θi| is its reflectance times `cos_factor(wo, wi)`.
template <class B>
concept separable_bxdf = bxdf<B> && B::reads_albedo && requires(const glm::vec3& v) {
    { B::cos_factor(v, v) } -> std::same_as<float>;
};

/// \brief The common part of the delta BxDFs (mirror, smooth glass): no density for a
/// given ωi, so `f_cos` and `pdf` are zero and light sampling never asks for them.
struct delta_bxdf {
    static constexpr bool delta = true;

    template <std::size_t N, class S>
    sampled_spectrum<N> f_cos(const glm::vec3&, const glm::vec3&, const S&) const noexcept {
        return {};
    }
    template <std::size_t N, class S>
    sampled_spectrum<N> pdf(const glm::vec3&, const glm::vec3&, const S&) const noexcept {
        return {};
    }
    template <std::size_t N, class S>
    bsdf_value<N> eval(const glm::vec3&, const glm::vec3&, const S&) const noexcept {
        return {};
    }
};

/// \brief `f_cos` and `pdf` of a BxDF `D` that computes both at once in its `eval` (the
/// microfacet BxDFs): each is that evaluation's half.
template <class D>
struct parts_of_eval {
    template <std::size_t N, class S>
    sampled_spectrum<N> f_cos(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        return static_cast<const D&>(*this).template eval<N>(wo, wi, s).f_cos;
    }
    template <std::size_t N, class S>
    sampled_spectrum<N> pdf(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        return static_cast<const D&>(*this).template eval<N>(wo, wi, s).pdf;
    }
};

namespace detail {
inline constexpr float inv_pi = std::numbers::inv_pi_v<float>;
}  // namespace detail

}  // namespace iris
