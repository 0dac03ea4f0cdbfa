// Must not compile: with no restriction there is nothing for a bias policy to replace.
#include <iris/sampling/integrator_config.hpp>
int main() { return static_cast<int>(iris::integrator_config<iris::restriction::unrestricted, iris::relaxation::none, 4, iris::bias::propagate_unused>::wavelength_count); }
