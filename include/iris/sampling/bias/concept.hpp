#pragma once
/// \file
/// \brief The `BiasPolicy` concept: what replaces the part of the spectrum the
/// restriction does not sample (docs/method.md §2, Bias policies). Models: `bias::none`, `bias::scaled_pdf`,
/// `bias::propagate_unused` (catalogue: bias.hpp).
///
/// Every policy shares the restricted estimate
///     F_R = Σ_j w_j · f(x̄, λ_j) / Σ_k p(x̄ | λ_k)
/// and differs in the factor w_j and in whether the B term is added:
/// - `B::name`                          a `std::string_view`;
/// - `B::propagates`                    true: F = F_R + B, with
///                                      B = Σ_b (1 − r_α(λ_b)) f_h(x̄, λ_b) Δλ_b / p(x̄ | λ_0);
/// - `B::scales_pdf`                    true: w_j is divided by Z_α (each λ_j weighed by the
///                                      base pdf instead of p_α);
/// - `B::restricted_factor(r, p_α, Z)`  → w_j = r_α(λ_j) / p_α(λ_j), or / (p_α Z_α) when
///                                      `scales_pdf`, in double (the path integrator
///                                      weighs each λ_j's radiance by it in double); 0
///                                      (never NaN/Inf) for p_α ≤ 0.
/// A policy never both propagates and scales (that would count the unsampled part twice).

#include <concepts>
#include <string_view>

namespace iris {

template <class B>
concept BiasPolicy = std::copyable<B> && requires(float r, float p, float z) {
    { B::name } -> std::convertible_to<std::string_view>;
    { B::propagates } -> std::convertible_to<bool>;
    { B::scales_pdf } -> std::convertible_to<bool>;
    { B::restricted_factor(r, p, z) } -> std::same_as<double>;
} && !(B::propagates && B::scales_pdf);

}  // namespace iris
