#pragma once
/// \file
/// \brief Catalogue of bias policies (concept: `BiasPolicy`) and the B term's bins.
///
/// | model | use it when | cost per sample | bias it brings |
/// |---|---|---|---|
/// | `none` | to see what the restriction alone does (paper Figs. 5–6) | nothing | E[F] = ∫ r_α f: dim and tinted until α = 1 |
/// | `scaled_pdf` | the paper's "scaling PDFs" (Fig. 7): right brightness for flat spectra | one divide | E[F] = ∫ r_α f / Z_α: a colour bias set by where the windows sit, until α = 1 |
/// | `propagate_unused` | the paper's method: clean early frames that are not dim | one `sampled_spectrum<Bins>` evaluation of every material on the hero path while α < 1 | none in scenes without specular dispersion (docs/method.md §4, U1); at specular dispersive events λ outside the restriction follow the hero's direction; never grows with α (U3) and is 0 from N_thold on (U2) |
///
/// `bin_layout` places the B term's wavelengths (default 5 nm bins, one jittered λ per bin).

#include "iris/sampling/bias/bin_layout.hpp"
#include "iris/sampling/bias/concept.hpp"
#include "iris/sampling/bias/policies.hpp"
