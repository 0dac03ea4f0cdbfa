#pragma once
/// \file
/// \brief `integrator_config<Kernel, Curve, C, Bias, BasePdf, Placement, Accumulation>`: one
/// choice of sampling policies, checked once, with a readable name
/// (`multibox3/linear/C4/propagate`; the base pdf is appended when it is not uniform:
/// `unrestricted/none/C4/none/visible`; an automatic placement marks the kernel:
/// `multibox3-auto/linear/C4/propagate`; a fading accumulation is appended last:
/// `multibox3/linear/C4/propagate/fade`).
///
/// The types are the compile-time part; `parameters` holds the numbers (kernel centres
/// and widths, N_thold, domain, distribution cell size). An integrator
/// asks it for α_i (`alpha(i)`), the restricted distribution of a pass
/// (`distribution(alpha, base_pdf)`) and the B term's bins (`bins()`).

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <type_traits>

#include "iris/sampling/accumulation.hpp"
#include "iris/sampling/bias.hpp"
#include "iris/sampling/detail/name.hpp"
#include "iris/sampling/domain.hpp"
#include "iris/sampling/placement.hpp"
#include "iris/sampling/relaxation.hpp"
#include "iris/sampling/restricted_distribution.hpp"
#include "iris/sampling/restriction.hpp"
#include "iris/sampling/spectral_pdf.hpp"

namespace iris {

namespace detail {
template <class K, class R, std::size_t C, class B, class P, class L, class A>
constexpr name_buffer config_name() noexcept {
    name_buffer b;
    b.append(K::name);
    if constexpr (L::automatic) b.append("-").append(L::name);
    b.append("/").append(R::name).append("/C").append_number(C).append("/").append(B::name);
    if (std::string_view(P::name) != spectral_pdf::uniform::name) b.append("/").append(P::name);
    if constexpr (A::fades) b.append("/").append(A::name);
    return b;
}
template <class K, class R, std::size_t C, class B, class P, class L, class A>
inline constexpr name_buffer config_name_v = config_name<K, R, C, B, P, L, A>();

template <class K>
inline constexpr bool is_multi_box = false;
template <std::size_t N>
inline constexpr bool is_multi_box<restriction::multi_box<N>> = true;
}  // namespace detail

template <class Kernel, class Curve, std::size_t C, class Bias, class BasePdf = spectral_pdf::uniform,
          class WindowPlacement = placement::fixed, class Accumulation = accumulation::running_mean>
struct integrator_config {
    static_assert(RestrictionKernel<Kernel>,
                  "Kernel must be a restriction kernel (iris/sampling/restriction.hpp): a value type with "
                  "`name`, `max_intervals` and `bind(alpha, domain)`");
    static_assert(RelaxationCurve<Curve>,
                  "Curve must be a relaxation curve (iris/sampling/relaxation.hpp): `name` and `float operator()(float t)`");
    static_assert(BiasPolicy<Bias>,
                  "Bias must be a bias policy (iris/sampling/bias.hpp): `name`, `propagates`, `scales_pdf` and "
                  "`restricted_factor`, and not both propagating and scaling");
    static_assert(SpectralPdf<BasePdf>,
                  "BasePdf must be a base wavelength pdf (iris/sampling/spectral_pdf.hpp): `name`, `density` and `primitive`");
    static_assert(placement::Placement<WindowPlacement>,
                  "WindowPlacement must be a placement policy (iris/sampling/placement.hpp): placement::fixed or "
                  "placement::emitters");
    static_assert(accumulation::Accumulation<Accumulation>,
                  "Accumulation must be an accumulation policy (iris/sampling/accumulation.hpp): "
                  "accumulation::running_mean or accumulation::fade");
    static_assert(!Accumulation::fades || !std::is_same_v<Kernel, restriction::unrestricted>,
                  "accumulation::fade separates the samples taken while alpha < 1 from the rest; an unrestricted "
                  "kernel has no such samples: use accumulation::running_mean");
    static_assert(!WindowPlacement::automatic || detail::is_multi_box<Kernel>,
                  "automatic window placement places the windows of restriction::multi_box<N>; this kernel has none");
    static_assert(C >= 1, "a path needs at least one wavelength (C >= 1)");
    static_assert(C <= 64, "more than 64 wavelengths per path: sampled_spectrum<C> would outgrow the registers for no gain");
    static_assert(!std::is_same_v<Curve, relaxation::none> || std::is_same_v<Kernel, restriction::unrestricted>,
                  "relaxation::none keeps alpha at 1, so this kernel would never restrict anything: "
                  "use restriction::unrestricted, or a relaxing curve (linear, quadratic)");
    static_assert(std::is_same_v<Curve, relaxation::none> || !std::is_same_v<Kernel, restriction::unrestricted>,
                  "restriction::unrestricted ignores alpha: pair it with relaxation::none");
    static_assert(!std::is_same_v<Kernel, restriction::unrestricted> || std::is_same_v<Bias, bias::none>,
                  "restriction::unrestricted samples the whole spectrum, so a bias policy has nothing to replace: "
                  "use bias::none");

    using kernel_type = Kernel;
    using curve_type = Curve;
    using bias_type = Bias;
    using base_pdf_type = BasePdf;
    using placement_type = WindowPlacement;
    using accumulation_type = Accumulation;
    using distribution_type = restricted_distribution<BasePdf, Kernel>;
    static constexpr std::size_t wavelength_count = C;
    /// \brief e.g. `multibox3/linear/C4/propagate`: used in CLIs, CSVs, EXR metadata, benchmarks.
    static constexpr std::string_view name = detail::config_name_v<Kernel, Curve, C, Bias, BasePdf, WindowPlacement, Accumulation>.view();

    /// \brief The runtime numbers of a configuration.
    struct parameters {
        Kernel kernel{};                ///< centres, widths (nm)
        Curve curve{};
        std::uint32_t n_thold = 512;    ///< relaxation length in samples per pixel (the paper's 512)
        spectral_domain domain{};       ///< Λ, default 380–780 nm
        float cell_nm = distribution_resolution::default_cell_nm; ///< distribution grid, default 1 nm
    };
    parameters params{};

    constexpr integrator_config() = default;
    constexpr explicit integrator_config(const parameters& p) : params(p) {}

    /// \brief α_i = curve(min(1, i / N_thold)) for the 0-based sample index i of a pixel.
    constexpr float alpha(std::uint64_t i) const noexcept { return relaxation::alpha_at(params.curve, i, params.n_thold); }

    /// \brief p_α on the configured domain. \throws std::invalid_argument for an invalid domain.
    distribution_type distribution(float alpha, const BasePdf& base) const {
        return distribution_type(base, params.kernel, alpha, params.domain, params.cell_nm);
    }
    /// \brief The same with a default-constructed base pdf (uniform, visible).
    distribution_type distribution(float alpha) const
        requires std::default_initializable<BasePdf>
    {
        return distribution(alpha, BasePdf{});
    }

    /// \brief The B term's bins on the configured domain: the bias policy's count of equal
    /// bins (80 for `propagate_unused`, 5 nm on 380–780 nm; B for `propagate_coarse<B>`),
    /// the bins the renderer's `bin_lattice` (iris/render/bins.hpp) is built from, whose λ_b
    /// are this layout's `lambda`, bit for bit; 5 nm bins for a policy without a count.
    constexpr bias::bin_layout bins() const noexcept {
        if constexpr (requires { Bias::bins; }) return bias::bin_layout::with_count(params.domain, Bias::bins);
        else return bias::bin_layout(params.domain);
    }
};

}  // namespace iris
