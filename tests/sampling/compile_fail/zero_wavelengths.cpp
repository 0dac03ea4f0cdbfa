// Must not compile: a path needs at least one wavelength.
#include <iris/sampling/integrator_config.hpp>
int main() { return static_cast<int>(iris::integrator_config<iris::restriction::box, iris::relaxation::linear, 0, iris::bias::none>::wavelength_count); }
