// Fuzz target: tabulated_spectrum built from arbitrary tables (any doubles, including
// NaN/Inf, unsorted, duplicated). Properties: construction either throws
// std::invalid_argument or yields a spectrum whose values at any wavelength are finite
// (constructors reject non-finite tables) and lie within the table's [min, max] value range (linear interpolation never overshoots).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <iris/spectrum/tabulated.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    iris::fuzz::input in(data, size);
    const std::size_t n = in.count(0, 64);
    const bool clamp = in.flag();
    std::vector<double> lambda(n), value(n);
    for (std::size_t i = 0; i < n; ++i) {
        lambda[i] = in.any_double();
        value[i] = in.any_double();
    }
    try {
        const iris::tabulated_spectrum s(lambda, value, clamp ? iris::outside::clamp : iris::outside::zero);
        const double lo = std::min(0.0, *std::min_element(value.begin(), value.end()));
        const double hi = std::max(0.0, *std::max_element(value.begin(), value.end()));
        for (int k = 0; k < 16; ++k) {
            const double l = in.any_double();
            const double v = s(l);
            if (!std::isfinite(v)) iris::fuzz::fail("non-finite value from a finite table");
            if (v < lo || v > hi) iris::fuzz::fail("interpolation overshoots the table's values");
        }
    } catch (const std::invalid_argument&) {
        // rejected with a message: fine
    }
    return 0;
}
