#pragma once
// A wavelength distribution written out for the tests, not taken from iris::sampling, so
// that estimators are tested against an independent model of the distribution they are
// given (tests/render/integrator_test.cpp, tests/renderer/light_tracer_test.cpp).
#include <cmath>
#include <cstddef>

#include <iris/spectrum/sampled.hpp>

namespace iris::test {

/// \brief A 0/1 box restriction [a, b] on a uniform base pdf over [lo, hi], hero-rotated: the
/// α = 0 end of a Box kernel, the case where the B term carries everything outside the
/// window. With [a, b] = [lo, hi] it is the unrestricted uniform distribution (r ≡ 1).
struct box_distribution {
    float lo = 380.0f, hi = 780.0f, a = 500.0f, b = 600.0f;
    float restriction(float l) const noexcept { return l >= a && l <= b ? 1.0f : 0.0f; }
    float normalisation() const noexcept { return (b - a) / (hi - lo); }
    template <std::size_t C>
    iris::sampled_wavelengths<C> sample_wavelengths(float u) const noexcept {
        iris::sampled_wavelengths<C> wl;
        for (std::size_t j = 0; j < C; ++j) {
            float uj = u + static_cast<float>(j) / static_cast<float>(C);
            uj -= std::floor(uj);
            wl.lambda(j) = a + uj * (b - a);
            wl.pdf(j) = 1.0f / (b - a);
        }
        return wl;
    }
};

}  // namespace iris::test
