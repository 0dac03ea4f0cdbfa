// The Python module's sampling layer and spectral data (docs/python.md): the presets, the
// restricted wavelength pdf p_α and its hero-rotated draws (as `iris-spectrum pdf|sample`),
// the illuminants, glasses and metals compiled into iris.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "iris/renderer/renderer.hpp"
#include "iris/sampling/presets.hpp"
#include "iris/sampling/random.hpp"
#include "iris/spectrum/blackbody.hpp"
#include "iris/spectrum/named.hpp"
#include "module.hpp"

namespace py = pybind11;

namespace iris::python {
namespace {

float checked_alpha(double alpha) {
    if (!(alpha >= 0.0 && alpha <= 1.0)) throw py::value_error(fmt::format("alpha must be in [0, 1], got {}", alpha));
    return static_cast<float>(alpha);
}

/// \brief λ = min, min + step, … ≤ max on a preset's domain (as iris-spectrum's grid).
std::vector<double> grid(const spectral_domain& d, double step) {
    if (!(step >= 1e-3 && step <= 400.0)) throw py::value_error(fmt::format("step must be in [0.001, 400] nm, got {}", step));
    std::vector<double> l;
    const double w = static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm);
    for (std::uint64_t k = 0; static_cast<double>(k) * step <= w + 1e-9; ++k)
        l.push_back(static_cast<double>(d.min_nm) + static_cast<double>(k) * step);
    return l;
}

std::vector<double> wavelengths_or_grid(const std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>>& given,
                                        const spectral_domain& d, double step) {
    if (!given) return grid(d, step);
    if (given->ndim() != 1) throw py::value_error(fmt::format("wavelengths must be a 1-D array, got {} dimensions", given->ndim()));
    std::vector<double> l(given->data(), given->data() + given->size());
    for (double x : l)
        if (!std::isfinite(x)) throw py::value_error("wavelengths must be finite");
    return l;
}

using wavelength_array = std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>>;

py::tuple pdf(const std::string& preset, double alpha, const wavelength_array& wavelengths, double step) {
    const float a = checked_alpha(alpha);
    return dispatch_preset(preset, [&]<class P>() {
        P cfg;
        const auto dist = cfg.distribution(a);
        const std::vector<double> l = wavelengths_or_grid(wavelengths, cfg.params.domain, step);
        py::array_t<double> lam(static_cast<py::ssize_t>(l.size())), p(static_cast<py::ssize_t>(l.size()));
        for (std::size_t i = 0; i < l.size(); ++i) {
            lam.mutable_data()[i] = l[i];
            p.mutable_data()[i] = dist.pdf(static_cast<float>(l[i]));
        }
        return py::make_tuple(lam, p);
    });
}

py::tuple sample_wavelengths(const std::string& preset, double alpha, std::int64_t count, std::uint64_t seed) {
    const float a = checked_alpha(alpha);
    if (count < 1 || count > 100000000) throw py::value_error(fmt::format("n must be in 1..100000000, got {}", count));
    return dispatch_preset(preset, [&]<class P>() {
        constexpr std::size_t C = P::wavelength_count;
        P cfg;
        const auto dist = cfg.distribution(a);
        py::array_t<float> lam({static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(C)});
        py::array_t<float> p({static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(C)});
        float* lp = lam.mutable_data();
        float* pp = p.mutable_data();
        {
            py::gil_scoped_release unlocked;
            counter_rng rng(seed);  // the stream iris-spectrum sample --seed draws
            for (std::int64_t n = 0; n < count; ++n) {
                const auto wl = dist.template sample_wavelengths<C>(rng.next());
                for (std::size_t j = 0; j < C; ++j) {
                    lp[static_cast<std::size_t>(n) * C + j] = wl[j];
                    pp[static_cast<std::size_t>(n) * C + j] = wl.pdf(j);
                }
            }
        }
        return py::make_tuple(lam, p);
    });
}

py::tuple spectrum(const std::string& name, const wavelength_array& wavelengths, double step) {
    const spectral_domain visible{};
    std::vector<double> l = wavelengths_or_grid(wavelengths, visible, step);
    py::array_t<double> lam(static_cast<py::ssize_t>(l.size())), v(static_cast<py::ssize_t>(l.size()));
    std::function<double(double)> f;
    if (const auto ill = find_illuminant(name)) {
        f = [t = ill->spectrum()](double x) { return t(x); };
    } else if (name.rfind("blackbody:", 0) == 0) {
        const std::string k_text = name.substr(10);
        char* end = nullptr;
        const double k = std::strtod(k_text.c_str(), &end);
        if (k_text.empty() || *end != '\0' || !(k > 0.0 && k <= 1e6))
            throw py::value_error(fmt::format("blackbody temperature must be a number in (0, 1e6] K, got '{}'", k_text));
        f = [b = blackbody_spectrum(k)](double x) { return b(x); };
    } else {
        std::string names;
        for (const auto& i : illuminants) names += std::string(i.name) + ", ";
        throw py::value_error(fmt::format("unknown spectrum '{}'; accepted: {}or blackbody:KELVIN", name, names));
    }
    for (std::size_t i = 0; i < l.size(); ++i) {
        lam.mutable_data()[i] = l[i];
        v.mutable_data()[i] = f(l[i]);
    }
    return py::make_tuple(lam, v);
}

named_glass glass(const std::string& name) {
    if (const auto g = find_glass(name)) return *g;
    std::string names;
    for (const auto& g : glasses) names += (names.empty() ? "" : ", ") + std::string(g.name);
    throw py::value_error(fmt::format("unknown glass '{}'; accepted: {}", name, names));
}

}  // namespace

void add_sampling(py::module_& m) {
    m.def("presets", [] {
        py::list l;
        for (const auto& p : renderer::presets()) {
            py::dict d;
            d["name"] = p.name;
            d["config"] = p.config;
            d["wavelengths"] = p.wavelengths;
            d["unbiased_before_nthold"] = p.unbiased_before_nthold;
            d["fades"] = p.fades;
            l.append(d);
        }
        return l;
    }, "The presets (docs/method.md) as dicts: name (CLI), config (kernel/curve/C/bias), wavelengths (C), ...");
    m.def("samplers", [] { return std::vector<std::string>{"sobol", "zsobol", "independent"}; },
          "The samplers a Renderer accepts (the first is the default).");
    m.def("estimators", [] { return std::vector<std::string>{"nee-mis", "bdpt", "light", "bsdf-only"}; },
          "The estimators a Renderer accepts (the first is the default).");
    m.def("pdf", &pdf, py::arg("preset"), py::arg("alpha"), py::arg("wavelengths") = py::none(), py::kw_only(),
          py::arg("step") = 1.0,
          "(λ, p_α(λ)) of a preset's restricted wavelength pdf: at the given wavelengths (nm), else every `step` nm "
          "over its domain (380-780 nm). As `iris-spectrum pdf`.");
    m.def("sample_wavelengths", &sample_wavelengths, py::arg("preset"), py::arg("alpha"), py::arg("n"), py::kw_only(),
          py::arg("seed") = 1,
          "n hero-rotated draws from p_α: (λ, pdf), each float32 (n, C), the hero first. As `iris-spectrum sample`.");
    m.def("spectrum", &spectrum, py::arg("name"), py::arg("wavelengths") = py::none(), py::kw_only(), py::arg("step") = 1.0,
          "(λ, value) of an illuminant (iris.illuminants()) or blackbody:KELVIN (peak 1), every `step` nm on 380-780 nm "
          "or at the given wavelengths.");
    m.def("illuminants", [] {
        py::list l;
        for (const auto& i : illuminants) l.append(py::make_tuple(std::string(i.name), std::string(i.description)));
        return l;
    }, "The built-in illuminants as (name, description).");
    m.def("glasses", [] {
        std::vector<std::string> v;
        for (const auto& g : glasses) v.emplace_back(g.name);
        return v;
    }, "The catalogue glasses.");
    m.def("metals", [] {
        py::list l;
        for (const auto& x : metals) l.append(py::make_tuple(std::string(x.name), std::string(x.description)));
        return l;
    }, "The measured metals as (name, description).");
    m.def("ior", [](const std::string& name, py::array_t<double, py::array::forcecast> nm, const std::string& model) {
        const named_glass g = glass(name);
        if (model != "sellmeier" && model != "cauchy")
            throw py::value_error(fmt::format("unknown model '{}' (expected sellmeier or cauchy)", model));
        const bool cauchy = model == "cauchy";
        return py::vectorize([&](double l) {
            if (!(l > 0.0 && std::isfinite(l))) throw py::value_error(fmt::format("wavelength must be > 0 nm, got {}", l));
            return cauchy ? g.cauchy.n(l) : g.sellmeier.n(l);
        })(nm);
    }, py::arg("glass"), py::arg("nm"), py::kw_only(), py::arg("model") = "sellmeier",
       "Refractive index of a catalogue glass at nm (a number or an array).");
}

}  // namespace iris::python
