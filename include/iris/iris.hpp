#pragma once
/// \file
/// \brief Umbrella header: the whole header-only core of iris.

#include "iris/version.hpp"

#include "iris/image.hpp"

#include "iris/spectrum/blackbody.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/ior.hpp"
#include "iris/spectrum/named.hpp"
#include "iris/spectrum/rgb_upsampling.hpp"
#include "iris/spectrum/sampled.hpp"
#include "iris/spectrum/spectrum.hpp"
#include "iris/spectrum/tabulated.hpp"

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

#include "iris/render/bsdf.hpp"
#include "iris/render/camera.hpp"
#include "iris/render/film.hpp"
#include "iris/render/frame.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/lights.hpp"
#include "iris/render/random.hpp"
#include "iris/render/scene.hpp"

#include "iris/metrics/metrics.hpp"
