#pragma once
/// \file
/// \brief Catalogue of restriction kernels r_α(λ) (concept: `RestrictionKernel`).
///
/// | model | use it when | cost | bias it brings (with `bias::none` / `propagate_unused`) |
/// |---|---|---|---|
/// | `unrestricted` | plain HWSS; the baseline and the end point of every relaxation | nothing | none |
/// | `box` | one window (paper Fig. 5): least colour noise, strong tint early on | one compare per λ | restrict-only: dim outside the window; propagate: none in non-dispersive scenes, the hero's direction for λ outside it at dispersive events |
/// | `multi_box<N>` | N windows, default 3 at the sRGB primaries (paper Fig. 6): the paper's choice | N compares per λ | as `box`, spread over three colours, so the tint is much weaker |
/// | `gaussian` | a smooth kernel (paper Fig. 4); fireflies where r is small, as the paper saw | one `exp` per λ | as `box`, but r is between 0 and 1: the r(λ) factor (docs/method.md §4, fix 2) is essential (the paper's form counts that part twice) |
///
/// Every kernel covers Λ at α = 1 (r_1 ≡ 1 exactly), so all presets end as plain HWSS.

#include "iris/sampling/restriction/box.hpp"
#include "iris/sampling/restriction/concept.hpp"
#include "iris/sampling/restriction/gaussian.hpp"
#include "iris/sampling/restriction/multi_box.hpp"
#include "iris/sampling/restriction/unrestricted.hpp"
