// Must not compile: relaxation::none never restricts, so a box kernel would be dead weight.
#include <iris/sampling/integrator_config.hpp>
int main() { return static_cast<int>(iris::integrator_config<iris::restriction::box, iris::relaxation::none, 4, iris::bias::none>::wavelength_count); }
