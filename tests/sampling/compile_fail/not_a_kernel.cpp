// Must not compile: int is not a restriction kernel.
#include <iris/sampling/integrator_config.hpp>
int main() { return static_cast<int>(iris::integrator_config<int, iris::relaxation::linear, 4, iris::bias::none>::wavelength_count); }
