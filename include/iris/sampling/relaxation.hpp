#pragma once
/// \file
/// \brief Catalogue of relaxation curves (concept: `RelaxationCurve`).
///
/// | model | use it when | cost | bias it brings |
/// |---|---|---|---|
/// | `linear` | the paper's evaluation (N_thold = 512) | one multiply per sample index | the restriction's bias (see restriction.hpp), fading linearly until N_thold |
/// | `quadratic` | the paper's future-work suggestion: clean early frames for longer | one more multiply | as `linear`, held longer (α = ¼ at half of N_thold) |
/// | `none` | plain HWSS, or to switch a restricting preset off | nothing | none (α ≡ 1) |
///
/// The running mean keeps every sample, so whatever bias the first N_thold samples carry
/// decays as N_thold / N afterwards (docs/method.md §2, Bias fade).

#include "iris/sampling/relaxation/concept.hpp"
#include "iris/sampling/relaxation/curves.hpp"
