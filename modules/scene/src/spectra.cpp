#include "spectra.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "iris/spectrum/blackbody.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/named.hpp"
#include "iris/spectrum/rgb_upsampling.hpp"

namespace iris::scene::detail {
namespace {

constexpr std::size_t max_table_points = 100000;
constexpr double min_kelvin = 100.0;  // below, the visible tail underflows to nothing useful
constexpr double max_kelvin = 1e6;
constexpr double max_ior = 10.0;

/// {"wavelengths": [...], "values": [...]}, values in [lo, hi].
tabulated_spectrum read_table(const reader& r, double lo, double hi, outside mode, std::string_view what) {
    r.expect_object({"wavelengths", "values"}, what);
    const reader wl = r.at("wavelengths"), val = r.at("values");
    if (!wl.is_array() || wl.size() < 2 || wl.size() > max_table_points)
        wl.fail("expected an array of 2 to " + std::to_string(max_table_points) + " wavelengths (nm), got " +
                describe(wl.value()));
    if (!val.is_array() || val.size() != wl.size())
        val.fail("expected an array of " + std::to_string(wl.size()) + " values (one per wavelength), got " +
                 describe(val.value()));
    std::vector<double> l(wl.size()), v(wl.size());
    for (std::size_t i = 0; i < l.size(); ++i) {
        l[i] = wl.at(i).number_in(0.0, 1e5, true, false, "a wavelength in nm");
        if (i > 0 && !(l[i] > l[i - 1]))
            wl.at(i).fail("wavelengths must increase strictly; " + reader::shortest(l[i]) + " follows " +
                          reader::shortest(l[i - 1]));
        v[i] = val.at(i).number_in(lo, hi, false, false, "a value");
    }
    return {std::move(l), std::move(v), mode};
}

tabulated_spectrum constant_reflectance(double v) { return {{360.0, 830.0}, {v, v}, outside::clamp}; }

rgb read_rgb(const reader& r) {
    r.expect_array(3, "a colour [r, g, b]");
    const double c[3] = {r.at(0).number_in(0.0, 1.0, false, false, "a colour component"),
                         r.at(1).number_in(0.0, 1.0, false, false, "a colour component"),
                         r.at(2).number_in(0.0, 1.0, false, false, "a colour component")};
    return {c[0], c[1], c[2]};
}

std::string illuminant_names() {
    std::vector<std::string_view> names;
    for (const auto& i : illuminants) names.push_back(i.name);
    return join(names);
}

named_spd blackbody(const reader& r, double kelvin) {
    if (!(kelvin >= min_kelvin && kelvin <= max_kelvin))
        r.fail("expected a blackbody temperature in [" + reader::shortest(min_kelvin) + ", " +
               reader::shortest(max_kelvin) + "] K, got " + reader::shortest(kelvin));
    const blackbody_spectrum b(kelvin);
    std::vector<double> l(cie::cmf_samples), v(cie::cmf_samples);
    for (std::size_t i = 0; i < l.size(); ++i) {
        l[i] = cie::cmf_lambda_min + static_cast<double>(i);
        v[i] = b(l[i]);
    }
    return {"blackbody:" + reader::shortest(kelvin), tabulated_spectrum(std::move(l), std::move(v))};
}

}  // namespace

double integrate_over(const tabulated_spectrum& s, const domain& d) noexcept {
    double sum = 0.0;
    for (double x = d.min; x < d.max; x += 1.0) {
        const double step = std::min(1.0, d.max - x);
        sum += 0.5 * (s(x) + s(x + step)) * step;
    }
    return sum;
}

tabulated_spectrum read_reflectance(const reader& r) {
    if (r.is_number()) return constant_reflectance(r.number_in(0.0, 1.0, false, false, "a reflectance"));
    if (r.is_object()) {
        if (r.has("srgb")) {
            r.expect_object({"srgb"});
            return reflectance_from_srgb(read_rgb(r.at("srgb")));
        }
        if (r.has("linear_srgb")) {
            r.expect_object({"linear_srgb"});
            return reflectance_from_linear_srgb(read_rgb(r.at("linear_srgb")));
        }
        if (r.has("wavelengths") || r.has("values")) return read_table(r, 0.0, 1.0, outside::clamp, "a reflectance table");
    }
    r.fail("expected a reflectance: a number in [0, 1], {\"srgb\": [r, g, b]}, {\"linear_srgb\": [r, g, b]} or "
           "{\"wavelengths\": [...], \"values\": [...]}; got " + describe(r.value()));
}

tabulated_spectrum read_coefficient(const reader& r, const coefficient& c) {
    constexpr double max_sigma = 1e9;
    const std::string what = c.what;
    if (r.is_number()) {
        const double v = r.number_in(0.0, max_sigma, false, false, what + " (per scene unit)");
        return tabulated_spectrum({360.0, 830.0}, {v, v}, outside::clamp);
    }
    if (r.is_object() && (r.has("wavelengths") || r.has("values")))
        return read_table(r, 0.0, max_sigma, outside::clamp, what + " table (per scene unit)");
    r.fail("expected " + what + " " + c.symbol + " ≥ 0 per scene unit: a number or {\"wavelengths\": [...], "
           "\"values\": [...]}; got " + describe(r.value()));
}

named_spd read_spd(const reader& r) {
    if (r.is_string()) {
        const std::string name = r.string();
        if (const auto ill = find_illuminant(name)) return {name, ill->spectrum()};
        constexpr std::string_view prefix = "blackbody:";
        if (name.rfind(prefix, 0) == 0) {
            const std::string k = name.substr(prefix.size());
            errno = 0;
            char* end = nullptr;
            const double kelvin = std::strtod(k.c_str(), &end);
            if (k.empty() || end != k.c_str() + k.size() || errno == ERANGE || !std::isfinite(kelvin))
                r.fail("expected blackbody:KELVIN with a number after the colon, got '" + name + "'");
            return blackbody(r, kelvin);
        }
        r.fail("unknown spectrum '" + name + "'; expected one of " + illuminant_names() +
               ", blackbody:KELVIN, {\"blackbody\": KELVIN} or {\"wavelengths\": [...], \"values\": [...]}");
    }
    if (r.is_object()) {
        if (r.has("blackbody")) {
            r.expect_object({"blackbody"});
            const reader k = r.at("blackbody");
            return blackbody(k, k.number());
        }
        if (r.has("wavelengths") || r.has("values"))
            return {"tabulated", read_table(r, 0.0, 1e30, outside::zero, "an emission table")};
    }
    r.fail("expected a spectrum: an illuminant name (" + illuminant_names() +
           "), \"blackbody:KELVIN\", {\"blackbody\": KELVIN} or {\"wavelengths\": [...], \"values\": [...]}; got " +
           describe(r.value()));
}

std::optional<material::conductor_ior> read_conductor_ior(const reader& r) {
    if (r.has("metal")) {
        for (const char* key : {"eta", "k", "reflectance"})
            if (r.has(key))
                r.at(key).fail(std::string("'") + key + "' and 'metal' are exclusive: a named metal has its own index");
        const reader m = r.at("metal");
        const std::string name = m.string();
        const auto metal = find_metal(name);
        if (!metal) {
            std::string names;
            for (const auto& x : metals) names += (names.empty() ? "" : ", ") + std::string(x.name);
            m.fail("unknown metal '" + name + "'; expected one of " + names);
        }
        return material::conductor_ior{name, metal->eta_spectrum(), metal->k_spectrum()};
    }
    if (!r.has("eta") && !r.has("k")) return std::nullopt;
    if (!r.has("eta") || !r.has("k")) r.fail(std::string("a conductor's index needs both 'eta' and 'k'; '") + (r.has("eta") ? "k" : "eta") + "' is missing");
    if (r.has("reflectance")) r.at("reflectance").fail("'reflectance' and 'eta'/'k' are exclusive");
    const auto part = [](const reader& x, double lo, bool lo_open, const char* what) {
        if (x.is_number()) {
            const double v = x.number_in(lo, 100.0, lo_open, false, what);
            return tabulated_spectrum({360.0, 830.0}, {v, v}, outside::clamp);
        }
        if (x.is_object()) {
            auto t = read_table(x, lo, 100.0, outside::clamp, std::string(what) + " table");
            if (lo_open)
                for (std::size_t i = 0; i < t.values().size(); ++i)
                    if (!(t.values()[i] > 0.0)) x.at("values").at(i).fail(std::string("expected ") + what + " > 0");
            return t;
        }
        x.fail(std::string("expected ") + what + ": a number or {\"wavelengths\": [...], \"values\": [...]}; got " + describe(x.value()));
    };
    return material::conductor_ior{"tabulated", part(r.at("eta"), 0.0, true, "a conductor's real index eta"),
                         part(r.at("k"), 0.0, false, "a conductor's extinction coefficient k")};
}

ior_model read_ior(const reader& r, const domain& d) {
    ior_model m;
    if (r.is_number()) {
        m = constant_ior{r.number_in(1.0, max_ior, false, false, "an index of refraction (IOR)")};
    } else if (r.is_string() || (r.is_object() && r.has("glass"))) {
        std::string name, model = "sellmeier";
        reader at = r;
        if (r.is_string()) {
            name = r.string();
        } else {
            r.expect_object({"glass", "model"});
            at = r.at("glass");
            name = at.string();
            if (r.has("model")) {
                model = r.at("model").string();
                if (model != "sellmeier" && model != "cauchy")
                    r.at("model").fail("unknown IOR model '" + model + "'; expected one of sellmeier, cauchy");
            }
        }
        const auto g = find_glass(name);
        if (!g) {
            std::vector<std::string_view> names;
            for (const auto& x : glasses) names.push_back(x.name);
            at.fail("unknown glass '" + name + "'; expected one of " + join(names));
        }
        if (model == "cauchy") m = g->cauchy;
        else m = g->sellmeier;
    } else if (r.is_object() && r.has("cauchy")) {
        r.expect_object({"cauchy"});
        const reader c = r.at("cauchy");
        c.expect_array(2, "Cauchy coefficients [A, B] (B in µm²)");
        m = cauchy_ior{c.at(0).number_in(1.0, max_ior, false, false, "Cauchy A (the IOR at infinite wavelength)"),
                       c.at(1).number_in(-1.0, 1.0, false, false, "Cauchy B in µm²")};
    } else if (r.is_object() && r.has("sellmeier")) {
        r.expect_object({"sellmeier"});
        const reader s = r.at("sellmeier");
        s.expect_object({"B", "C"}, "Sellmeier coefficients {\"B\": [B1, B2, B3], \"C\": [C1, C2, C3]} (C in µm²)");
        const reader b = s.at("B"), c = s.at("C");
        b.expect_array(3, "Sellmeier B1, B2, B3");
        c.expect_array(3, "Sellmeier C1, C2, C3 in µm²");
        sellmeier_ior x;
        double* bs[3] = {&x.b1, &x.b2, &x.b3};
        double* cs[3] = {&x.c1, &x.c2, &x.c3};
        for (std::size_t i = 0; i < 3; ++i) {
            *bs[i] = b.at(i).number_in(-1e3, 1e3, false, false, "a Sellmeier B coefficient");
            *cs[i] = c.at(i).number_in(-1e6, 1e6, false, false, "a Sellmeier C coefficient in µm²");
        }
        m = x;
    } else {
        r.fail("expected an IOR: a number >= 1, a glass name, {\"glass\": NAME, \"model\": \"sellmeier\"|\"cauchy\"}, "
               "{\"cauchy\": [A, B]} or {\"sellmeier\": {\"B\": [...], \"C\": [...]}}; got " + describe(r.value()));
    }
    // n(λ) must be a physical IOR everywhere the renderer may sample (1 nm grid + the ends)
    for (double l = d.min;; l = std::min(l + 1.0, d.max)) {
        const double n = refractive_index(m, l);
        if (!std::isfinite(n) || n < 1.0 || n > max_ior)
            r.fail("IOR must be in [1, " + reader::shortest(max_ior) + "] over the spectral domain [" +
                   reader::shortest(d.min) + ", " + reader::shortest(d.max) + "] nm, but n(" + reader::shortest(l) +
                   " nm) = " + reader::shortest(n));
        if (l >= d.max) break;
    }
    return m;
}

/// The three emission basis spectra of an environment image: the reflectance basis of
/// iris/spectrum/rgb_upsampling.hpp times D65 at luminance 1, so that a texel of linear sRGB
/// (1, 1, 1) is D65 with Y = 1 and any texel's colour is its RGB (1 nm over 360–830 nm).
std::array<tabulated_spectrum, 3> environment_basis(const tabulated_spectrum& d65) {
    const double k = white_normalisation(d65);
    std::array<std::vector<double>, 3> v;
    std::vector<double> lambda;
    for (int l = 360; l <= 830; ++l) {
        const double x = l;
        lambda.push_back(x);
        const double e = k * d65(x);
        v[0].push_back(e * rgb_upsampling::red_basis(x));
        v[1].push_back(e * rgb_upsampling::green_basis(x));
        v[2].push_back(e * rgb_upsampling::blue_basis(x));
    }
    return {tabulated_spectrum(lambda, v[0], outside::zero), tabulated_spectrum(lambda, v[1], outside::zero),
            tabulated_spectrum(lambda, v[2], outside::zero)};
}

}  // namespace iris::scene::detail
