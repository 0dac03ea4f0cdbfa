// rgb2spec_measure: the measurements of docs/rgb-upsampling.md — Jakob & Hanika's sigmoid
// polynomials (iris/spectrum/rgb_sigmoid.hpp) against the logistic basis of
// iris/spectrum/rgb_upsampling.hpp: round-trip error over the sRGB cube, range, smoothness
// and cost per evaluation; optionally the data of docs/rgb-upsampling.png.
//
//   g++ -std=c++20 -O2 -fno-math-errno -fno-trapping-math -I include scripts/rgb2spec_measure.cpp -o /tmp/rgb2spec_measure
//   /tmp/rgb2spec_measure                       # the committed table, all measurements
//   /tmp/rgb2spec_measure --table T.bin         # round trip of a table dumped by rgb2spec_opt RES T.bin
//   /tmp/rgb2spec_measure --plot-data FILE      # spectra for scripts/rgb_upsampling_plot.gp
//
// (-fno-math-errno -fno-trapping-math: the flags the renderer's hot loop is compiled
// with, modules/renderer/CMakeLists.txt; without them GCC keeps a libm call per sqrt.)

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "iris/spectrum/color.hpp"
#include "iris/spectrum/rgb_sigmoid.hpp"
#include "iris/spectrum/rgb_upsampling.hpp"

namespace {

struct loaded_table {
    std::vector<float> z, coeff;
    iris::sigmoid_table view() const { return {z.size(), z, coeff, 360.0, 830.0}; }
};

bool load(const char* path, loaded_table& t) {
    std::ifstream in(path, std::ios::binary);
    std::int32_t res = 0;
    if (!in.read(reinterpret_cast<char*>(&res), sizeof res) || res < 3) return false;
    const auto r = static_cast<std::size_t>(res);
    t.z.resize(r);
    t.coeff.resize(9 * r * r * r);
    in.read(reinterpret_cast<char*>(t.z.data()), static_cast<std::streamsize>(r * sizeof(float)));
    in.read(reinterpret_cast<char*>(t.coeff.data()), static_cast<std::streamsize>(t.coeff.size() * sizeof(float)));
    return static_cast<bool>(in);
}

const iris::xyz white = iris::reflectance_xyz_d65([](double) { return 1.0; });

double lab_f(double v) {
    constexpr double d = 6.0 / 29.0;
    return v > d * d * d ? std::cbrt(v) : v / (3.0 * d * d) + 4.0 / 29.0;
}
std::array<double, 3> lab(const iris::xyz& c) {
    const double fx = lab_f(c.x / white.x), fy = lab_f(c.y / white.y), fz = lab_f(c.z / white.z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}
double delta_e(const iris::xyz& a, const iris::xyz& b) {
    const auto p = lab(a), q = lab(b);
    return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

/// XYZ under D65 with the float evaluation (the renderer's form), sums in double.
iris::xyz reflectance_xyz_d65_float(const iris::sigmoid_polynomial& s) {
    return iris::reflectance_xyz_d65([&](double l) { return static_cast<double>(s(static_cast<float>(l))); });
}

struct stats {
    double max_rgb = 0, sum_rgb = 0, max_de = 0, sum_de = 0;
    double lo = 1e9, hi = -1e9;
    iris::rgb worst{};
    std::size_t n = 0;
    std::vector<double> des;  // every ΔE, for the percentile
    void add(const iris::rgb& in, const iris::xyz& out) {
        const iris::rgb o = iris::xyz_to_linear_srgb(out);
        const double e = std::max({std::abs(o.r - in.r), std::abs(o.g - in.g), std::abs(o.b - in.b)});
        const double de = delta_e(iris::linear_srgb_to_xyz(in), out);
        if (e > max_rgb) worst = in;
        max_rgb = std::max(max_rgb, e);
        sum_rgb += e;
        max_de = std::max(max_de, de);
        sum_de += de;
        des.push_back(de);
        ++n;
    }
    template <class S>
    void range(const S& s) {
        for (int l = 360; l <= 830; ++l) {
            lo = std::min(lo, static_cast<double>(s(static_cast<double>(l))));
            hi = std::max(hi, static_cast<double>(s(static_cast<double>(l))));
        }
    }
    void print(const char* what) const {
        std::vector<double> d = des;
        std::sort(d.begin(), d.end());
        std::printf(
            "  %-32s n=%zu |Δrgb| max %.3g mean %.3g; ΔE76 max %.3g mean %.3g p99 %.3g; S in [%.3g, %.6f]; worst (%.4g "
            "%.4g %.4g)\n",
            what, n, max_rgb, sum_rgb / static_cast<double>(n), max_de, sum_de / static_cast<double>(n),
            d[d.size() * 99 / 100], lo, hi, worst.r, worst.g, worst.b);
    }
};

std::vector<iris::rgb> grid(int n) {
    std::vector<iris::rgb> v;
    for (int r = 0; r < n; ++r)
        for (int g = 0; g < n; ++g)
            for (int b = 0; b < n; ++b) v.push_back({r / double(n - 1), g / double(n - 1), b / double(n - 1)});
    return v;
}
std::vector<iris::rgb> random_colours(std::size_t n) {
    std::mt19937_64 rng(2019);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<iris::rgb> v(n);
    for (auto& c : v) c = {u(rng), u(rng), u(rng)};
    return v;
}

void round_trip(const iris::sigmoid_table& table, bool all) {
    const auto g17 = grid(17), rnd = random_colours(100000);
    stats jh17, jhr, jhf17, lg17, lgr;
    for (const auto& c : g17) {
        const auto s = table.lookup(c);
        jh17.add(c, iris::reflectance_xyz_d65(s));
        jh17.range(s);
        if (all) {
            jhf17.add(c, reflectance_xyz_d65_float(s));
            jhf17.range([&](double l) { return s(static_cast<float>(l)); });
            const auto r = iris::upsample_linear_srgb(c);
            lg17.add(c, iris::reflectance_xyz_d65(r));
            lg17.range(r);
        }
    }
    for (const auto& c : rnd) {
        const auto s = table.lookup(c);
        jhr.add(c, iris::reflectance_xyz_d65(s));
        jhr.range(s);
        if (all) {
            const auto r = iris::upsample_linear_srgb(c);
            lgr.add(c, iris::reflectance_xyz_d65(r));
            lgr.range(r);
        }
    }
    std::printf("round trip (resolution %zu):\n", table.resolution);
    jh17.print("JH, 17^3 grid");
    jhr.print("JH, 1e5 uniform random");
    if (all) {
        jhf17.print("JH float evaluation, 17^3 grid");
        lg17.print("logistic, 17^3 grid");
        lgr.print("logistic, 1e5 uniform random");
    }
}

struct named {
    const char* name;
    iris::rgb c;
};
const std::vector<named> colours = {
    {"red", {1, 0, 0}},
    {"green", {0, 1, 0}},
    {"blue", {0, 0, 1}},
    {"yellow", {1, 1, 0}},
    {"cyan", {0, 1, 1}},
    {"magenta", {1, 0, 1}},
    {"dark red", {0.2, 0.01, 0.01}},
    {"pastel pink", {0.9, 0.6, 0.65}},
    {"pastel green", {0.6, 0.85, 0.6}},
    {"pastel blue", {0.6, 0.7, 0.95}},
    {"skin", {0.6, 0.4, 0.3}},
    {"grey-ish teal", {0.3, 0.45, 0.42}},
};

template <class S>
void smoothness(const S& s, double& max_d, double& tv) {
    max_d = 0.0;
    tv = 0.0;
    for (int l = 380; l < 780; ++l) {
        const double d = std::abs(static_cast<double>(s(double(l + 1))) - static_cast<double>(s(double(l))));
        max_d = std::max(max_d, d);
        tv += d;
    }
}

void smoothness_table() {
    std::printf("smoothness over 380–780 nm (1 nm differences): max |dS/dλ| (1/nm), total variation\n");
    std::printf("  %-14s %10s %8s   %10s %8s\n", "colour", "JH max", "JH TV", "log max", "log TV");
    for (const auto& n : colours) {
        double jm, jt, lm, lt;
        smoothness(iris::rgb_to_sigmoid(n.c), jm, jt);
        smoothness(iris::upsample_linear_srgb(n.c), lm, lt);
        std::printf("  %-14s %10.4f %8.3f   %10.4f %8.3f\n", n.name, jm, jt, lm, lt);
    }
}

template <class F>
double time_ns(F&& eval, const std::vector<float>& lambda, int reps) {
    volatile float sink = 0.0f;
    double best = 1e30;
    for (int rep = 0; rep < 5; ++rep) {
        const auto t0 = std::chrono::steady_clock::now();
        float acc = 0.0f;
        for (int r = 0; r < reps; ++r) acc += eval(lambda);
        const auto t1 = std::chrono::steady_clock::now();
        sink = sink + acc;
        best = std::min(
            best, std::chrono::duration<double, std::nano>(t1 - t0).count() / (double(reps) * double(lambda.size())));
    }
    return best;
}

void cost() {
    std::vector<float> lambda(4096);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(360.0f, 830.0f);
    for (auto& l : lambda) l = u(rng);
    const auto jh = iris::rgb_to_sigmoid({0.6, 0.4, 0.3});
    const auto lg = iris::upsample_linear_srgb({0.6, 0.4, 0.3});
    const auto ill = iris::rgb_illuminant::from_linear_srgb({0.6, 0.4, 0.3});
    const int reps = 2000;
    const double t_jh = time_ns(
        [&](const std::vector<float>& ls) {
            float a = 0.0f;
            for (float l : ls) a += jh(l);
            return a;
        },
        lambda, reps);
    const double t_jh8 = time_ns(  // 8 wavelengths at a time through sample<8> (vectorised)
        [&](const std::vector<float>& ls) {
            iris::sampled_spectrum<8> a(0.0f);
            for (std::size_t i = 0; i + 8 <= ls.size(); i += 8) {
                std::array<float, 8> l8;
                std::copy_n(ls.begin() + static_cast<std::ptrdiff_t>(i), 8, l8.begin());
                a += iris::sample(jh, iris::sampled_wavelengths<8>(l8, l8));
            }
            return a.sum();
        },
        lambda, reps);
    const double t_jhd = time_ns(
        [&](const std::vector<float>& ls) {
            double a = 0.0;
            for (float l : ls) a += jh(static_cast<double>(l));
            return static_cast<float>(a);
        },
        lambda, reps);
    const double t_ill = time_ns(
        [&](const std::vector<float>& ls) {
            float a = 0.0f;
            for (float l : ls) a += ill(l);
            return a;
        },
        lambda, reps);
    const double t_lg = time_ns(
        [&](const std::vector<float>& ls) {
            double a = 0.0;
            for (float l : ls) a += lg(static_cast<double>(l));
            return static_cast<float>(a);
        },
        lambda, reps / 4);
    std::vector<iris::rgb> cs = random_colours(100000);
    const auto t0 = std::chrono::steady_clock::now();
    float acc = 0.0f;
    for (const auto& c : cs) acc += iris::rgb_to_sigmoid(c).c2;
    const auto t1 = std::chrono::steady_clock::now();
    std::printf("cost (best of 5 timing loops over 4096 random λ, one run; scalar loops unless stated):\n");
    std::printf("  JH sigmoid, float          %.2f ns/λ\n", t_jh);
    std::printf("  JH sigmoid, float, sample<8> %.2f ns/λ\n", t_jh8);
    std::printf("  JH sigmoid, double         %.2f ns/λ\n", t_jhd);
    std::printf("  JH rgb_illuminant, float   %.2f ns/λ\n", t_ill);
    std::printf("  logistic basis, double     %.2f ns/λ\n", t_lg);
    std::printf("  rgb_to_sigmoid lookup      %.1f ns/colour (checksum %g)\n",
                std::chrono::duration<double, std::nano>(t1 - t0).count() / double(cs.size()),
                static_cast<double>(acc));
}

void plot_data(const char* path) {
    std::FILE* f = std::fopen(path, "w");
    if (!f) return;
    const std::vector<named> plotted = {colours[0], colours[1], colours[2], colours[3], colours[7], colours[10]};
    std::fprintf(f, "# lambda");
    for (const auto& n : plotted) std::fprintf(f, " \"JH %s\" \"logistic %s\"", n.name, n.name);
    std::fprintf(f, "\n");
    for (int l = 360; l <= 830; ++l) {
        std::fprintf(f, "%d", l);
        for (const auto& n : plotted)
            std::fprintf(f, " %.6f %.6f", iris::rgb_to_sigmoid(n.c)(double(l)),
                         iris::upsample_linear_srgb(n.c)(double(l)));
        std::fprintf(f, "\n");
    }
    std::fclose(f);
}

void illuminant_check() {
    stats s;
    for (const iris::rgb c :
         {iris::rgb{1, 1, 1}, iris::rgb{5, 2, 0.5}, iris::rgb{0.1, 0.3, 3}, iris::rgb{0.9, 0.1, 0.1}}) {
        const auto e = iris::rgb_illuminant::from_linear_srgb(c);
        iris::xyz x = iris::spectrum_to_xyz(e);
        x = {x.x / iris::cie::y_integral, x.y / iris::cie::y_integral, x.z / iris::cie::y_integral};
        const iris::rgb o = iris::xyz_to_linear_srgb(x);
        std::printf("  illuminant (%g %g %g) → (%.5f %.5f %.5f)\n", c.r, c.g, c.b, o.r, o.g, o.b);
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 3 && std::strcmp(argv[1], "--table") == 0) {
        loaded_table t;
        if (!load(argv[2], t)) {
            std::fprintf(stderr, "cannot read %s\n", argv[2]);
            return 2;
        }
        round_trip(t.view(), false);
        return 0;
    }
    if (argc == 3 && std::strcmp(argv[1], "--plot-data") == 0) {
        plot_data(argv[2]);
        return 0;
    }
    round_trip(iris::srgb_sigmoid_table, true);
    smoothness_table();
    illuminant_check();
    cost();
    return 0;
}
