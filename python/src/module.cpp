// The Python module `iris` (docs/python.md): its definition, the translation of iris's
// exceptions to Python's, and the image metrics on numpy arrays.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "iris/exr/exr.hpp"
#include "iris/image.hpp"
#include "iris/metrics/bias_variance.hpp"
#include "iris/metrics/flip.hpp"
#include "iris/metrics/mse.hpp"
#include "iris/metrics/ssim.hpp"
#include "iris/renderer/checkpoint.hpp"
#include "iris/scene/error.hpp"
#include "iris/version.hpp"
#include "module.hpp"

namespace py = pybind11;

namespace iris::python {
namespace {

using float_array = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// \brief An (H, W, 3) array as an iris::image, or ValueError naming `what`.
iris::image to_image(const float_array& a, const char* what) {
    if (a.ndim() != 3 || a.shape(2) != 3) {
        std::string shape;
        for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
        throw py::value_error(fmt::format("{} must be an (H, W, 3) array of RGB, got shape ({})", what, shape));
    }
    if (a.shape(0) > (1 << 20) || a.shape(1) > (1 << 20))
        throw py::value_error(fmt::format("{} is too large: {}x{}", what, a.shape(1), a.shape(0)));
    iris::image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
    const float* p = a.data();
    for (std::size_t i = 0; i < img.pixels().size(); ++i) img.pixels()[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    return img;
}

}  // namespace

void add_metrics(py::module_& m) {
    m.def("mse", [](const float_array& a, const float_array& b) { return mse(to_image(a, "a"), to_image(b, "b")); },
          py::arg("a"), py::arg("b"), "Mean squared error over pixels and channels (docs/metrics.md; as iris-image diff).");
    m.def("relmse", [](const float_array& a, const float_array& ref, double eps) {
        return relmse(to_image(a, "a"), to_image(ref, "reference"), eps);
    }, py::arg("a"), py::arg("reference"), py::arg("epsilon") = relmse_default_epsilon,
       "Relative MSE: mean of (a − ref)² / (ref² + ε) (docs/metrics.md).");
    m.def("ssim", [](const float_array& a, const float_array& b) { return ssim(to_image(a, "a"), to_image(b, "b")); },
          py::arg("a"), py::arg("b"),
          "Mean SSIM of the sRGB-encoded channels (Gaussian window σ 1.5; docs/metrics.md; as iris-image diff).");
    m.def("flip", [](const float_array& a, const float_array& ref, bool hdr, std::optional<double> ppd) {
        const double p = ppd ? *ppd : flip_default_ppd;
        return hdr ? flip_hdr(to_image(a, "a"), to_image(ref, "reference"), p) : flip(to_image(a, "a"), to_image(ref, "reference"), p);
    }, py::arg("a"), py::arg("reference"), py::kw_only(), py::arg("hdr") = true, py::arg("ppd") = py::none(),
       "Mean FLIP perceptual error (Andersson et al. 2020, 2021; docs/metrics.md): HDR-FLIP of linear sRGB (exposures "
       "from the reference), or LDR-FLIP of the images clamped to [0, 1] (hdr=False). ppd: pixels per degree "
       "(default 67.02: 3840 pixels across 0.7 m seen from 0.7 m). As `iris-image flip`.");
    m.def("flip_map", [](const float_array& a, const float_array& ref, bool hdr, std::optional<double> ppd) {
        const double p = ppd ? *ppd : flip_default_ppd;
        const iris::image ia = to_image(a, "a"), ir = to_image(ref, "reference");
        const std::vector<float> map = hdr ? flip_hdr_map(ia, ir, p) : flip_map(ia, ir, p);
        py::array_t<float> out({static_cast<py::ssize_t>(ia.height()), static_cast<py::ssize_t>(ia.width())});
        std::copy(map.begin(), map.end(), out.mutable_data());
        return out;
    }, py::arg("a"), py::arg("reference"), py::kw_only(), py::arg("hdr") = true, py::arg("ppd") = py::none(),
       "The per-pixel FLIP error, float32 (H, W) in [0, 1].");
    m.def("bias_variance", [](const std::vector<float_array>& runs, const float_array& ref) {
        std::vector<iris::image> images;
        for (std::size_t i = 0; i < runs.size(); ++i) images.push_back(to_image(runs[i], "each run"));
        const auto s = bias_variance(images, to_image(ref, "reference"));
        py::dict d;
        d["mse"] = s.mse;
        d["variance"] = s.variance;
        d["bias_sq"] = s.bias_sq;
        d["bias_sq_se"] = s.bias_sq_se;
        d["runs"] = s.runs;
        return d;
    }, py::arg("runs"), py::arg("reference"),
       "Split the MSE of independent runs into variance and squared bias (docs/metrics.md): a dict.");
}

}  // namespace iris::python

PYBIND11_MODULE(iris, m) {
    m.doc() = "iris: progressive spectral rendering (hero wavelengths restricted, relaxed and propagated). "
              "Scenes load once (iris.load), renderers add passes (iris.Renderer.step) and give numpy images; "
              "the sampling layer and the image metrics are here too. docs/python.md.";
    m.attr("__version__") = std::string(iris::version);
    // iris's errors carry the command line's messages: bad input is a ValueError, a file
    // that cannot be used a RuntimeError (FileNotFoundError is raised where a path is checked)
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const iris::scene::error& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const iris::renderer::checkpoint_error& e) {
            PyErr_SetString(PyExc_RuntimeError, e.what());
        } catch (const iris::exr::error& e) {
            PyErr_SetString(PyExc_RuntimeError, e.what());
        }
    });
    iris::python::add_render(m);
    iris::python::add_sampling(m);
    iris::python::add_metrics(m);
}
