#pragma once
/// \file
/// \brief Catalogue of base wavelength pdfs p(λ) (concept: `SpectralPdf`).
///
/// | model | use it when | cost per rebuild | bias |
/// |---|---|---|---|
/// | `uniform` | the baseline; the paper and Wilkie et al.'s HWSS | one subtraction per cell | none |
/// | `visible` | general scenes: fewer samples where the CMFs are near 0 (pbrt-v4's choice) | one `tanh` per cell edge | none (p > 0 on every finite domain) |
/// | `illuminant` | one dominant emitter, spiky SPDs (LEDs): samples follow SPD × ȳ | a table lookup per cell edge; building it: 471 points once per scene | none where p > 0; **zero where every emitter is 0**, so light that reaches the eye only through fluorescence-like shifts would be missed (iris has none) |
/// | `tabulated` | any measured or designed shape; the fuzz targets | as `illuminant` | none where p > 0; 0 where the table is 0 |
///
/// None of them is restricted: the restriction r_α is applied on top of any of them by
/// `restricted_distribution`. A distribution divides by p's mass on its domain, so a
/// model only gives the shape (`density`) and its integral (`primitive`).

#include "iris/sampling/spectral_pdf/concept.hpp"
#include "iris/sampling/spectral_pdf/tabulated.hpp"
#include "iris/sampling/spectral_pdf/uniform.hpp"
#include "iris/sampling/spectral_pdf/visible.hpp"
