#pragma once
/// \file
/// \brief The `RelaxationCurve` concept: maps the progress t = min(1, i / N_thold) of a
/// pixel's sample index i to the restriction extent α_i = curve(t) (docs/method.md §1).
/// Models: `relaxation::linear`, `relaxation::quadratic`, `relaxation::none`
/// (catalogue: relaxation.hpp).
///
/// Required, for a `const R& c` and `float t` in [0, 1]:
/// - `R::name`   a `std::string_view`;
/// - `c(t)`      → float α in [0, 1]; non-decreasing; curve(1) = 1; curve(0) = 0 except
///               for `none`, which is α ≡ 1 by definition (the HWSS baseline).
/// `relaxation::alpha_at(c, i, n_thold)` does the t = min(1, i / N_thold) part once.

#include <concepts>
#include <cstdint>
#include <string_view>

namespace iris {

template <class R>
concept RelaxationCurve = std::copyable<R> && requires(const R& c, float t) {
    { R::name } -> std::convertible_to<std::string_view>;
    { c(t) } -> std::same_as<float>;
};

namespace relaxation {

/// \brief α_i = curve(min(1, i / N_thold)), clamped to [0, 1]. N_thold = 0 counts as
/// "already relaxed" (t = 1); a curve that returns NaN yields 1 (no restriction).
template <RelaxationCurve R>
constexpr float alpha_at(const R& curve, std::uint64_t i, std::uint64_t n_thold) noexcept {
    const float t = n_thold == 0 || i >= n_thold
                        ? 1.0f
                        : static_cast<float>(static_cast<double>(i) / static_cast<double>(n_thold));
    const float a = curve(t);
    if (!(a >= 0.0f)) return a < 0.0f ? 0.0f : 1.0f;
    return a > 1.0f ? 1.0f : a;
}

}  // namespace relaxation
}  // namespace iris
