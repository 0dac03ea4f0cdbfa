#pragma once
/// \file
/// \brief Everything of iris/sampling: base pdfs, restriction kernels, relaxation curves,
/// bias policies, the restricted distribution, HWSS rotation and MIS weight, the
/// spectral-level estimator, integrator_config and the presets. Method: docs/method.md.

#include "iris/sampling/bias.hpp"
#include "iris/sampling/domain.hpp"
#include "iris/sampling/estimator.hpp"
#include "iris/sampling/hwss.hpp"
#include "iris/sampling/integrator_config.hpp"
#include "iris/sampling/presets.hpp"
#include "iris/sampling/random.hpp"
#include "iris/sampling/relaxation.hpp"
#include "iris/sampling/restricted_distribution.hpp"
#include "iris/sampling/restriction.hpp"
#include "iris/sampling/spectral_pdf.hpp"
