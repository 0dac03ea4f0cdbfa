#pragma once
/// \file
/// \brief The catalogue of materials: which BxDF (iris/render/materials/bxdf.hpp) renders
/// each alternative of `material_desc`, and `visit_bxdf`, the one place a material's
/// runtime type becomes a compile-time one.
///
/// | `material_desc` alternative | BxDF | header |
/// |---|---|---|
/// | `material::diffuse` | `lambertian` | lambertian.hpp |
/// | `material::conductor`, smooth | `specular_conductor` | conductor.hpp |
/// | `material::conductor`, GGX α ≥ `smooth_alpha` | `rough_conductor` | conductor.hpp |
/// | `material::dielectric`, smooth or index 1 | `smooth_dielectric` | smooth_dielectric.hpp |
/// | `material::dielectric`, GGX α ≥ `smooth_alpha` | `rough_dielectric` | rough_dielectric.hpp |
/// | `material::coated` (a coat over a diffuse or conductor base) | `coated_bxdf` | coated.hpp |
///
/// Adding a material: its data in render/scene.hpp (`material_desc` and the feature
/// summary), its BxDF header here, its branch in `visit_bxdf` (which does not compile
/// without it), its parser branch (modules/scene), its tests. Everything else — the
/// integrator, the independent estimator, the hero and bin tables — reaches it through
/// `visit_bxdf` and the BxDF's members.

#include <cstddef>
#include <type_traits>
#include <variant>

#include "iris/render/materials/bxdf.hpp"
#include "iris/render/materials/coated.hpp"
#include "iris/render/materials/conductor.hpp"
#include "iris/render/materials/fresnel.hpp"
#include "iris/render/materials/lambertian.hpp"
#include "iris/render/materials/rough_dielectric.hpp"
#include "iris/render/materials/smooth_dielectric.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

namespace detail {
template <class>
inline constexpr bool no_bxdf_for = false;

/// \brief A dielectric behaves as a delta BSDF when it is (numerically) smooth, or when
/// its index is exactly 1: an invisible interface, whose microfacet half vector is
/// undefined (ωi = −ωo), so it passes light straight through like smooth glass of η = 1.
inline bool effectively_smooth(const material::dielectric& d) noexcept {
    if (d.roughness < smooth_alpha) return true;
    const auto* c = std::get_if<constant_ior>(&d.ior);
    return c && c->value == 1.0;
}
}  // namespace detail

/// \brief `f(bxdf)` with the BxDF of material `m`; `f` must return the same type for every
/// BxDF. A `material_desc` alternative without a branch here is a compile error.
template <class F>
decltype(auto) visit_bxdf(const material_desc& m, F&& f) {
    return std::visit(
        [&](const auto& data) -> decltype(auto) {
            using D = std::remove_cvref_t<decltype(data)>;
            if constexpr (std::is_same_v<D, material::diffuse>) return f(lambertian{data});
            else if constexpr (std::is_same_v<D, material::conductor>) {
                if (data.roughness < smooth_alpha) return f(specular_conductor{data});
                return f(rough_conductor{data});
            }
            else if constexpr (std::is_same_v<D, material::dielectric>) {
                if (detail::effectively_smooth(data)) return f(smooth_dielectric{data});
                return f(rough_dielectric{data});
            } else if constexpr (std::is_same_v<D, material::coated>) return f(coated_bxdf{data});
            else static_assert(detail::no_bxdf_for<D>, "visit_bxdf: a material_desc alternative without a BxDF");
        },
        m);
}

/// \brief The spectra of BxDF `b` at wavelengths `wl`, from the scene's own tables and
/// index models (the independent estimator and the tests read these; the integrator reads
/// its lattice tables instead, iris/render/bins.hpp).
template <std::size_t N, bxdf B>
sampled_spectra<N> scene_spectra(const B& b, const sampled_wavelengths<N>& wl) noexcept {
    sampled_spectra<N> s;
    if constexpr (B::reads_albedo) s = sampled_spectra<N>::with_albedo(sample(b.reflectance(), wl));
    else if constexpr (B::reads_eta) s = sampled_spectra<N>::with_eta(detail::etas(b.ior(), wl));
    if constexpr (reads_conductor_v<B>)
        if (b.has_ior()) {
            s.index = sample(b.conductor_eta(), wl);
            s.kappa = sample(b.conductor_k(), wl);
        }
    if constexpr (reads_film_v<B>)
        if (const material::thin_film* f = b.film()) {
            for (std::size_t k = 0; k < N; ++k) s.lambda[k] = wl[k];
            s.film_index = detail::etas(f->ior, wl);
        }
    return s;
}

static_assert(separable_bxdf<lambertian> && bxdf<specular_conductor> && bxdf<rough_conductor> &&
              bxdf<smooth_dielectric> && bxdf<rough_dielectric> && bxdf<coated_bxdf>);

}  // namespace iris
