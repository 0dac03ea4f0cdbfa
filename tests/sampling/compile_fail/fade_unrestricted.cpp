// accumulation::fade with an unrestricted kernel: there are no samples taken while α < 1.
#include <iris/sampling/integrator_config.hpp>

using bad = iris::integrator_config<iris::restriction::unrestricted, iris::relaxation::none, 4, iris::bias::none,
                                    iris::spectral_pdf::uniform, iris::placement::fixed, iris::accumulation::fade>;
bad b;
