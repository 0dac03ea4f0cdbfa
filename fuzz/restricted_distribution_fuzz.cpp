// Fuzz target: restricted_distribution built from arbitrary kernel parameters (NaN, Inf,
// negative widths, centres anywhere), α (any float), domain (any floats, or sane ones),
// grid cell size and base pdf (uniform, visible, or a table decoded from the bytes).
// Properties: construction throws std::invalid_argument only for an invalid domain or
// table; otherwise Z_α is in (0, 1], pdf/restriction/base_pdf/cdf are finite and in range
// for any float λ, and every sample — from `sample`, `sample_with_pdf` and the C = 4
// hero rotation, for any float u — lies inside the domain with pdf(λ) > 0.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include <iris/sampling/restricted_distribution.hpp>
#include <iris/sampling/restriction.hpp>
#include <iris/sampling/spectral_pdf.hpp>

#include "fuzz_input.hpp"

namespace {

using iris::fuzz::fail;

float any_or(iris::fuzz::input& in, double lo, double hi) {
    return in.flag() ? in.raw<float>() : static_cast<float>(in.in_range(lo, hi));
}

template <class Base, class Kernel>
void check(const Base& base, const Kernel& kernel, float alpha, iris::spectral_domain d, float cell,
           iris::fuzz::input& in) {
    // (a unique_ptr, not an optional: GCC 12 warns "may be used uninitialized" about an
    // optional holding the distribution's shared table)
    std::unique_ptr<iris::restricted_distribution<Base, Kernel>> dist;
    try {
        dist = std::make_unique<iris::restricted_distribution<Base, Kernel>>(base, kernel, alpha, d, cell);
    } catch (const std::invalid_argument&) {
        if (d.valid()) fail("a valid domain was rejected");
        return;
    }
    if (!d.valid()) fail("an invalid domain was accepted");
    const float z = dist->normalisation();
    if (!(z > 0.0f && z <= 1.0f + 1e-5f)) fail("Z_alpha outside (0, 1]");
    for (int k = 0; k < 12; ++k) {
        const float l = k < 4 ? (k < 2 ? d.min_nm : d.max_nm) : in.raw<float>();
        const float p = dist->pdf(l), r = dist->restriction(l), b = dist->base_pdf(l);
        if (!(std::isfinite(p) && p >= 0.0f)) fail("pdf negative or not finite");
        if (!(r >= 0.0f && r <= 1.0f)) fail("restriction outside [0, 1]");
        if (!(std::isfinite(b) && b >= 0.0f)) fail("base pdf negative or not finite");
        const double c = dist->cdf(l);
        if (!(c >= 0.0 && c <= 1.0)) fail("cdf outside [0, 1]");
    }
    for (int k = 0; k < 8; ++k) {
        const float u = k == 0 ? 0.0f : k == 1 ? 0x1.fffffep-1f : in.raw<float>();
        const iris::wavelength_sample s = dist->sample_with_pdf(u);
        if (!d.contains(s.lambda)) fail("sample outside the domain");
        if (!(s.pdf > 0.0f && std::isfinite(s.pdf))) fail("sample carries a zero or non-finite pdf");
        if (!(dist->pdf(s.lambda) > 0.0f)) fail("pdf(sample(u)) is 0");
        if (s.lambda != dist->sample(u)) fail("sample and sample_with_pdf disagree");
        const auto wl = dist->template sample_wavelengths<4>(u);
        for (std::size_t j = 0; j < 4; ++j) {
            if (!d.contains(wl[j])) fail("rotated wavelength outside the domain");
            if (!(wl.pdf(j) > 0.0f && std::isfinite(wl.pdf(j)))) fail("rotated wavelength with a zero pdf");
            if (!(dist->pdf(wl[j]) > 0.0f)) fail("pdf of a rotated wavelength is 0");
        }
    }
}

template <class Base>
void with_kernel(const Base& base, iris::fuzz::input& in, float alpha, iris::spectral_domain d, float cell) {
    switch (in.count(0, 3)) {
    case 0: check(base, iris::restriction::unrestricted{}, alpha, d, cell, in); break;
    case 1: {
        const iris::restriction::box k{any_or(in, 0, 1000), any_or(in, 0, 100)};
        check(base, k, alpha, d, cell, in);
        break;
    }
    case 2: {
        iris::restriction::multi_box<3> k;
        for (std::size_t i = 0; i < 3; ++i) {
            k.centres_nm[i] = any_or(in, 0, 1000);
            k.widths_nm[i] = any_or(in, 0, 100);
        }
        check(base, k, alpha, d, cell, in);
        break;
    }
    default: {
        const iris::restriction::gaussian k{any_or(in, 0, 1000), any_or(in, 0, 100)};
        check(base, k, alpha, d, cell, in);
        break;
    }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    iris::fuzz::input in(data, size);
    iris::spectral_domain d;
    if (in.flag()) {
        d.min_nm = in.raw<float>();
        d.max_nm = in.raw<float>();
    } else {
        d.min_nm = static_cast<float>(in.in_range(0.0, 1000.0));
        d.max_nm = d.min_nm + static_cast<float>(in.in_range(0.001, 1000.0));
    }
    const float alpha = any_or(in, 0.0, 1.0);
    const float cell = in.flag() ? in.raw<float>() : 1.0f;
    switch (in.count(0, 2)) {
    case 0: with_kernel(iris::spectral_pdf::uniform{}, in, alpha, d, cell); break;
    case 1: with_kernel(iris::spectral_pdf::visible{}, in, alpha, d, cell); break;
    default: {
        const std::size_t n = in.count(0, 32);
        std::vector<double> l(n), v(n);
        double x = in.in_range(0.0, 1000.0);
        for (std::size_t i = 0; i < n; ++i) {
            l[i] = x;
            x += in.flag() ? in.any_double() : in.in_range(0.0, 50.0);
            v[i] = in.flag() ? in.any_double() : in.in_range(0.0, 10.0);
        }
        try {
            const iris::spectral_pdf::tabulated table(l, v);
            with_kernel(table, in, alpha, d, cell);
        } catch (const std::invalid_argument&) {
            // a bad table is rejected with a message: fine (the domain check is above)
        }
        break;
    }
    }
    return 0;
}
