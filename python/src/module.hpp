#pragma once
// The Python module `iris` (internal): its parts, each adding its functions to the module.
#include <string>

#include <pybind11/pybind11.h>

namespace iris::python {

/// \brief Scenes, renderers, images and checkpoints (render.cpp).
void add_render(pybind11::module_& m);
/// \brief Presets, samplers, wavelength pdfs, spectra and glasses (sampling.cpp).
void add_sampling(pybind11::module_& m);
/// \brief Image metrics on numpy arrays (metrics.cpp).
void add_metrics(pybind11::module_& m);

/// \brief Raise FileNotFoundError with `message`.
[[noreturn]] inline void raise_file_not_found(const std::string& message) {
    PyErr_SetString(PyExc_FileNotFoundError, message.c_str());
    throw pybind11::error_already_set();
}

}  // namespace iris::python
