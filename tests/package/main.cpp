// Uses the installed package the way a researcher would: the umbrella header, a named
// illuminant, and (when the module was installed) an EXR round trip.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <iris/iris.hpp>
#ifdef IRIS_CONSUMER_HAS_EXR
#include <iris/exr/exr.hpp>
#endif

int main() {
    const auto d65 = iris::find_illuminant("D65");
    if (!d65) return 1;
    const iris::xyz c = iris::normalise_y(iris::spectrum_to_xyz(d65->spectrum()));
    std::printf("iris %s: D65 X=%.5f Y=%.5f Z=%.5f\n", iris::version.data(), c.x, c.y, c.z);
    if (std::abs(c.x - 0.95047) > 2e-4 || std::abs(c.z - 1.08883) > 2e-4) return 1;
#ifdef IRIS_CONSUMER_HAS_EXR
    iris::image img(2, 1);
    img(1, 0) = {1.0f, 0.5f, 0.25f};
    const auto path = std::filesystem::temp_directory_path() / "iris-consumer.exr";
    iris::exr::write(path, img, {{"iris:test", "consumer"}});
    const auto back = iris::exr::read(path);
    std::filesystem::remove(path);
    if (!(back.pixels == img) || back.meta.at("iris:test") != "consumer") return 1;
    std::puts("EXR round trip ok");
#endif
    return 0;
}
