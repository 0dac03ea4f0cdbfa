// Must not compile: automatic placement moves multi_box windows; a single box has none to place.
#include <iris/sampling/integrator_config.hpp>
int main() {
    return static_cast<int>(iris::integrator_config<iris::restriction::box, iris::relaxation::linear, 4,
                                                    iris::bias::propagate_unused, iris::spectral_pdf::uniform,
                                                    iris::placement::emitters>::wavelength_count);
}
