// Fuzz target: the HWSS MIS weight, the hero rotation, the bias policies' factors and the
// B term's bin layout, on arbitrary floats (NaN, ±Inf, denormals, negatives).
// Properties: the weight is finite and ≥ 0, and where it is not 0 it is the balance
// weight (w · p_α · Σ p = 1 to float precision); rotations lie in [0, 1); policy factors
// are finite and ≥ 0; bins cover the domain with finite, positive widths and every
// jittered wavelength lies in its bin.
#include <array>
#include <cmath>
#include <span>

#include <iris/sampling/bias.hpp>
#include <iris/sampling/hwss.hpp>

#include "fuzz_input.hpp"

using iris::fuzz::fail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    iris::fuzz::input in(data, size);
    const float p_alpha = in.raw<float>();
    const std::size_t n = in.count(0, 32);
    std::array<float, 32> path{};
    for (std::size_t k = 0; k < n; ++k) path[k] = in.raw<float>();
    const float w = iris::hwss_mis_weight(p_alpha, std::span<const float>(path.data(), n));
    if (!(std::isfinite(w) && w >= 0.0f)) fail("MIS weight negative or not finite");
    if (w > 0.0f) {
        double sum = 0.0;
        for (std::size_t k = 0; k < n; ++k) sum += path[k] > 0.0f ? static_cast<double>(path[k]) : 0.0;
        const double one = static_cast<double>(w) * static_cast<double>(p_alpha) * sum;
        if (std::isfinite(one) && std::fabs(one - 1.0) > 1e-6 && static_cast<double>(w) > 1e-30)
            fail("MIS weight is not 1 / (p_alpha * sum)");
    }
    const iris::sampled_spectrum<4> four({path[0], path[1], path[2], path[3]});
    if (!(iris::hwss_mis_weight(p_alpha, four) >= 0.0f)) fail("sampled_spectrum weight negative or NaN");

    const float u = in.raw<float>();
    for (std::size_t c : {1u, 3u, 4u, 32u})
        for (std::size_t j = 0; j < c; ++j) {
            const double x = iris::hwss_rotation(u, j, c);
            if (!(x >= 0.0 && x < 1.0)) fail("rotation outside [0, 1)");
        }

    const float r = in.raw<float>(), z = in.raw<float>();
    for (double f : {iris::bias::none::restricted_factor(r, p_alpha, z), iris::bias::scaled_pdf::restricted_factor(r, p_alpha, z),
                    iris::bias::propagate_unused::restricted_factor(r, p_alpha, z)})
        if (!(std::isfinite(f) && f >= 0.0 && f <= 3.0e38)) fail("bias factor negative or not finite in float");

    iris::spectral_domain d{in.raw<float>(), in.raw<float>()};
    const iris::bias::bin_layout bins(d, in.raw<float>());
    if (bins.count() > iris::bias::bin_layout::max_count) fail("too many bins");
    if (!d.valid() && bins.count() != 0) fail("bins on an invalid domain");
    double covered = 0.0;
    for (std::size_t b = 0; b < bins.count(); ++b) {
        const double width = bins.width(b);
        if (!(width > 0.0 && std::isfinite(width))) fail("bin width not positive and finite");
        covered += width;
        const float l = bins.lambda(b, u);
        if (!(l >= static_cast<float>(bins.lower(b)) && l <= static_cast<float>(bins.lower(b) + width)))
            fail("jittered wavelength outside its bin");
    }
    if (bins.count() > 0 && std::fabs(covered - static_cast<double>(d.width())) > 1e-6 * static_cast<double>(d.width()) + 1e-9)
        fail("bins do not cover the domain");
    const auto wl = bins.jittered<16>(u);
    for (std::size_t b = 0; b < 16; ++b)
        if (!(std::isfinite(wl[b]) && std::isfinite(wl.pdf(b)) && wl.pdf(b) >= 0.0f)) fail("jittered<16> not finite");
    return 0;
}
