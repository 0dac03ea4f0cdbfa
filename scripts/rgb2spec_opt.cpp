// rgb2spec_opt: fits the coefficient table of Jakob & Hanika's sigmoid-polynomial
// spectra ("A Low-Dimensional Function Space for Efficient Spectral Upsampling",
// Computer Graphics Forum 38(2), 2019) for linear sRGB under D65, and writes it as the
// generated header include/iris/spectrum/data/rgb2spec_srgb.hpp.
//
// Regenerate (from the repository root; one core, about 3 s at resolution 32, 20 s at 64):
//
//   g++ -std=c++20 -O2 -I include scripts/rgb2spec_opt.cpp -o /tmp/rgb2spec_opt && /tmp/rgb2spec_opt 32 include/iris/spectrum/data/rgb2spec_srgb.hpp
//
// Usage: rgb2spec_opt RES OUTPUT. OUTPUT ending in ".bin" gets a raw dump instead of a
// header (int32 res, float z[res], float (a, b, c)[3·res³], native byte order), which
// scripts/rgb2spec_measure.cpp reads to compare resolutions without compiling them.
// The method, the choice of resolution and the measurements: docs/rgb-upsampling.md.
//
// What is fitted. A reflectance S(λ) = σ(x(λ)), x a quadratic, σ(x) = 1/2 + x/(2√(1+x²)).
// The optimiser works on the normalised wavelength t = (λ − 360 nm)/470 nm ∈ [0, 1] (the
// CMF table's range, which is also the range of the project's colour sums) with
// x = a·t² + b·t + c. The header stores (a, b, c) as float (well scaled, so shorter as
// text than the same quadratic in nm); the lookup interpolates them and converts the
// result to x = c0·λ² + c1·λ + c2 (λ in nm), which is what the runtime evaluates.
// The colour of S is computed exactly as `reflectance_xyz_d65` (rgb_upsampling.hpp) does:
// 1 nm sums over 360–830 nm of S·D65·(x̄, ȳ, z̄), divided by Σ D65·ȳ. The target of a
// linear sRGB colour is `linear_srgb_to_xyz` of it (color.hpp), so the round trip the
// tests measure (`xyz_to_linear_srgb` of the spectrum's XYZ) is the quantity minimised.
// The residual is the difference in CIELAB (CIE 1976 L*a*b*, white = the XYZ of the flat
// spectrum 1 under the tabulated D65), i.e. CIE76 ΔE, minimised by Levenberg–Marquardt
// (a damped Gauss–Newton step with the analytic 3×3 Jacobian).
//
// The table (the paper's parametrisation). For each slice l ∈ {0, 1, 2} (which of r, g, b
// is largest), the colour of entry (i, j, k) has component l equal to z_k and components
// (l+1) mod 3 and (l+2) mod 3 equal to x_i·z_k and y_j·z_k, with x_i = i/(res−1),
// y_j = j/(res−1) and z_k = s(s(k/(res−1))), s(u) = 3u² − 2u³ (smoothstep of smoothstep:
// nodes crowd near black and near full brightness, where the coefficients change fastest).
// Layout of the coefficient array: [l][k][j][i][a, b, c].
//
// Order of the fits (as in the paper: start where the answer is known and walk outwards,
// each fit starting from an already fitted neighbour). Per slice, the first entry is the
// grey i = j = res−1 at the middle brightness k = res/2 (close to the flat spectrum 1/2,
// coefficients 0); a breadth-first walk over the 6-neighbours then fits every entry from
// the solution of the neighbour it was reached from. An entry whose ΔE stays above 1e-4
// is refitted from each of its fitted neighbours and from 0, keeping the best.
// Two kinds of entries are set rather than fitted:
//   - the greys (i = j = res−1) hold the exact flat spectrum z: a = b = 0,
//     c = (z − 1/2)/√(z(1 − z)), the same spectrum the lookup returns for an exact grey,
//     so the lookup is continuous at the grey axis (flat z's colour is z·(1, 1, 1) to
//     2.5e-6, the difference between the tabulated D65 white and sRGB's); white (z = 1,
//     c = +∞) holds c = 1000, σ = 1 − 2.5e-7 (`white_cap`);
//   - the entries at k = 0 (z = 0: black, where the fit would run off to x → −∞) copy
//     their k = 1 neighbour; z_1 is tiny (≈ 2.8e-5 at res 32), which bounds the error there.
//
// Dependencies: the standard library and the project's CIE tables (cie1931.hpp,
// cie_d65.hpp) and sRGB matrices (color.hpp). Single-threaded.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "iris/spectrum/color.hpp"
#include "iris/spectrum/data/cie1931.hpp"
#include "iris/spectrum/data/cie_d65.hpp"

namespace {

constexpr double lambda_min = 360.0;
constexpr double lambda_range = 470.0;  // 360–830 nm
constexpr std::size_t samples = 471;    // 1 nm

using vec3 = std::array<double, 3>;
using mat3 = std::array<vec3, 3>;

/// Colour-matching weights: D65·(x̄, ȳ, z̄) / Σ D65·ȳ at each 1 nm sample, and t, t².
struct observer {
    std::array<vec3, samples> w{};
    std::array<double, samples> t{}, t2{};
    vec3 white{};  // XYZ of the flat spectrum 1
};

observer make_observer() {
    observer o;
    const auto& d65 = iris::data::cie_d65::values;
    double norm = 0.0;
    for (std::size_t i = 0; i < samples; ++i) {
        const double lambda = lambda_min + static_cast<double>(i);
        const auto k = static_cast<std::size_t>(
            std::lround((lambda - iris::data::cie_d65::lambda_min) / iris::data::cie_d65::lambda_step));
        const double e = k < d65.size() ? d65[k] : 0.0;
        o.w[i] = {e * iris::data::cie1931::x_bar[i], e * iris::data::cie1931::y_bar[i],
                  e * iris::data::cie1931::z_bar[i]};
        norm += o.w[i][1];
        o.t[i] = (lambda - lambda_min) / lambda_range;
        o.t2[i] = o.t[i] * o.t[i];
    }
    for (auto& w : o.w)
        for (auto& v : w) v /= norm;
    for (const auto& w : o.w)
        for (int c = 0; c < 3; ++c) o.white[c] += w[c];
    return o;
}

// CIELAB's f and its derivative (CIE 15: cube root above (6/29)³, linear below).
constexpr double delta = 6.0 / 29.0;
double lab_f(double v) { return v > delta * delta * delta ? std::cbrt(v) : v / (3.0 * delta * delta) + 4.0 / 29.0; }
double lab_df(double v) {
    if (v > delta * delta * delta) {
        const double c = std::cbrt(v);
        return 1.0 / (3.0 * c * c);
    }
    return 1.0 / (3.0 * delta * delta);
}

vec3 xyz_to_lab(const vec3& c, const vec3& white) {
    const double fx = lab_f(c[0] / white[0]), fy = lab_f(c[1] / white[1]), fz = lab_f(c[2] / white[2]);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

/// Lab of the sigmoid polynomial with normalised coefficients p, and (if jac) d Lab / d p.
vec3 evaluate(const observer& o, const vec3& p, mat3* jac) {
    vec3 xyz{};
    mat3 dxyz{};  // dxyz[c][q]: d XYZ_c / d p_q
    for (std::size_t i = 0; i < samples; ++i) {
        const double x = p[0] * o.t2[i] + p[1] * o.t[i] + p[2];
        const double r = 1.0 / std::sqrt(1.0 + x * x);
        const double s = 0.5 + 0.5 * x * r;
        const double ds = 0.5 * r * r * r;  // σ'(x) = 1 / (2 (1 + x²)^{3/2})
        const double g[3] = {ds * o.t2[i], ds * o.t[i], ds};
        for (int c = 0; c < 3; ++c) {
            xyz[c] += s * o.w[i][c];
            for (int q = 0; q < 3; ++q) dxyz[c][q] += g[q] * o.w[i][c];
        }
    }
    if (jac) {
        double df[3];
        for (int c = 0; c < 3; ++c) df[c] = lab_df(xyz[c] / o.white[c]) / o.white[c];
        for (int q = 0; q < 3; ++q) {
            const double fx = df[0] * dxyz[0][q], fy = df[1] * dxyz[1][q], fz = df[2] * dxyz[2][q];
            (*jac)[0][q] = 116.0 * fy;
            (*jac)[1][q] = 500.0 * (fx - fy);
            (*jac)[2][q] = 200.0 * (fy - fz);
        }
    }
    return xyz_to_lab(xyz, o.white);
}

double norm2(const vec3& v) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; }
vec3 operator-(const vec3& a, const vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

/// x of the white node, which would be +∞: σ(1000) = 1 − 2.5e-7 (the runtime returns the
/// exact flat 1 for white itself; this value only enters interpolation near white).
constexpr double white_cap = 1000.0;

/// Solves a·x = b (Gaussian elimination with partial pivoting); false if singular.
bool solve3(mat3 a, vec3 b, vec3& x) {
    for (int col = 0; col < 3; ++col) {
        int piv = col;
        for (int r = col + 1; r < 3; ++r)
            if (std::abs(a[r][col]) > std::abs(a[piv][col])) piv = r;
        if (!(std::abs(a[piv][col]) > 1e-300)) return false;
        std::swap(a[piv], a[col]);
        std::swap(b[piv], b[col]);
        for (int r = col + 1; r < 3; ++r) {
            const double f = a[r][col] / a[col][col];
            for (int c = col; c < 3; ++c) a[r][c] -= f * a[col][c];
            b[r] -= f * b[col];
        }
    }
    for (int r = 2; r >= 0; --r) {
        double s = b[r];
        for (int c = r + 1; c < 3; ++c) s -= a[r][c] * x[c];
        x[r] = s / a[r][r];
    }
    return true;
}

/// Levenberg–Marquardt on ‖Lab(p) − target‖; returns the final ΔE, p updated in place.
double fit(const observer& o, const vec3& target_lab, vec3& p) {
    mat3 j{};
    vec3 lab = evaluate(o, p, &j);
    vec3 r{lab[0] - target_lab[0], lab[1] - target_lab[1], lab[2] - target_lab[2]};
    double err = norm2(r);
    double mu = 1e-3;
    for (int it = 0; it < 300 && err > 1e-14; ++it) {
        // normal equations: (JᵀJ + μ·diag(JᵀJ)) Δ = −Jᵀr
        mat3 a{};
        vec3 g{};
        for (int q = 0; q < 3; ++q) {
            for (int s = 0; s < 3; ++s)
                for (int c = 0; c < 3; ++c) a[q][s] += j[c][q] * j[c][s];
            for (int c = 0; c < 3; ++c) g[q] -= j[c][q] * r[c];
        }
        bool improved = false;
        for (int tries = 0; tries < 30 && !improved; ++tries) {
            mat3 damped = a;
            for (int q = 0; q < 3; ++q) damped[q][q] += mu * std::max(a[q][q], 1e-12);
            vec3 step{};
            if (!solve3(damped, g, step)) {
                mu *= 10.0;
                continue;
            }
            const vec3 trial{p[0] + step[0], p[1] + step[1], p[2] + step[2]};
            mat3 jt{};
            const vec3 lt = evaluate(o, trial, &jt);
            const vec3 rt{lt[0] - target_lab[0], lt[1] - target_lab[1], lt[2] - target_lab[2]};
            const double et = norm2(rt);
            if (std::isfinite(et) && et < err) {
                p = trial;
                j = jt;
                r = rt;
                const bool tiny = err - et < 1e-12 * err && norm2(step) < 1e-20 * (1.0 + norm2(p));
                err = et;
                mu = std::max(mu / 3.0, 1e-9);
                improved = true;
                if (tiny) return std::sqrt(err);
            } else {
                mu *= 8.0;
            }
        }
        if (!improved) break;  // no damping helps: a (local) minimum
    }
    return std::sqrt(err);
}

double smoothstep(double u) { return u * u * (3.0 - 2.0 * u); }

struct table {
    int res = 0;
    std::vector<double> z;
    std::vector<double> coeff;  // normalised (a, b, c), layout [l][k][j][i][3]
    std::vector<double> error;  // ΔE of each entry's fit
    std::size_t index(int l, int k, int j, int i) const {
        return ((static_cast<std::size_t>(l) * res + k) * res + j) * res + i;
    }
};

table optimise(int res) {
    const observer o = make_observer();
    table t;
    t.res = res;
    for (int k = 0; k < res; ++k) t.z.push_back(smoothstep(smoothstep(k / static_cast<double>(res - 1))));
    const std::size_t n = 3 * static_cast<std::size_t>(res) * res * res;
    t.coeff.assign(3 * n, 0.0);
    t.error.assign(n, 0.0);

    auto target = [&](int l, int k, int j, int i) {
        const double z = t.z[k], x = i / static_cast<double>(res - 1), y = j / static_cast<double>(res - 1);
        double c[3];
        c[l] = z;
        c[(l + 1) % 3] = x * z;
        c[(l + 2) % 3] = y * z;
        const iris::xyz v = iris::linear_srgb_to_xyz({c[0], c[1], c[2]});
        return xyz_to_lab({v.x, v.y, v.z}, o.white);
    };
    std::size_t refits = 0;
    for (int l = 0; l < 3; ++l) {
        std::vector<char> done(static_cast<std::size_t>(res) * res * res, 0);
        auto local = [&](int k, int j, int i) { return (static_cast<std::size_t>(k) * res + j) * res + i; };
        struct node {
            int k, j, i;
            vec3 start;
        };
        std::deque<node> queue;
        queue.push_back({res / 2, res - 1, res - 1, {0.0, 0.0, 0.0}});
        done[local(res / 2, res - 1, res - 1)] = 1;
        while (!queue.empty()) {
            const node nd = queue.front();
            queue.pop_front();
            vec3 p = nd.start;
            double err = 0.0;
            const std::array<std::array<int, 3>, 6> steps{
                {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
            if (nd.i == res - 1 && nd.j == res - 1) {  // grey: the flat spectrum (see the file comment)
                const double z = t.z[nd.k];
                p = {0.0, 0.0, z >= 1.0 ? white_cap : (z - 0.5) / std::sqrt(z * (1.0 - z))};
                err = std::sqrt(norm2(evaluate(o, p, nullptr) - target(l, nd.k, nd.j, nd.i)));
            } else if (nd.k > 0) {
                const vec3 lab = target(l, nd.k, nd.j, nd.i);
                err = fit(o, lab, p);
                if (err > 1e-4) {  // retry from every fitted neighbour and from 0
                    ++refits;
                    std::vector<vec3> starts{{0.0, 0.0, 0.0}};
                    for (const auto& s : steps) {
                        const int k = nd.k + s[0], j = nd.j + s[1], i = nd.i + s[2];
                        if (k < 1 || j < 0 || i < 0 || k >= res || j >= res || i >= res) continue;
                        if (done[local(k, j, i)] != 2) continue;
                        const std::size_t g = t.index(l, k, j, i);
                        starts.push_back({t.coeff[3 * g], t.coeff[3 * g + 1], t.coeff[3 * g + 2]});
                    }
                    for (vec3 q : starts) {
                        const double e = fit(o, lab, q);
                        if (e < err) {
                            err = e;
                            p = q;
                        }
                    }
                }
            }
            const std::size_t g = t.index(l, nd.k, nd.j, nd.i);
            for (int c = 0; c < 3; ++c) t.coeff[3 * g + c] = p[c];
            t.error[g] = err;
            done[local(nd.k, nd.j, nd.i)] = 2;
            for (const auto& s : steps) {
                const int k = nd.k + s[0], j = nd.j + s[1], i = nd.i + s[2];
                if (k < 0 || j < 0 || i < 0 || k >= res || j >= res || i >= res) continue;
                if (done[local(k, j, i)]) continue;
                done[local(k, j, i)] = 1;
                queue.push_back({k, j, i, p});
            }
        }
        // z = 0 (black): copy the k = 1 entry of the same chromaticity (see the file comment)
        for (int j = 0; j < res; ++j)
            for (int i = 0; i < res; ++i) {
                const std::size_t d = t.index(l, 0, j, i), s = t.index(l, 1, j, i);
                for (int c = 0; c < 3; ++c) t.coeff[3 * d + c] = t.coeff[3 * s + c];
                t.error[d] = 0.0;
            }
    }
    double max_err = 0.0, sum_err = 0.0;
    std::size_t above = 0;
    for (double e : t.error) {
        max_err = std::max(max_err, e);
        sum_err += e;
        above += e > 1e-3;
    }
    std::fprintf(stderr, "res %d: %zu entries, fit ΔE max %.3g mean %.3g, %zu above 1e-3, %zu refitted\n", res,
                 t.error.size(), max_err, sum_err / static_cast<double>(t.error.size()), above, refits);
    return t;
}

/// The shortest decimal form that reads back as v, as a float literal (the 'f' keeps the
/// project's -Wconversion quiet and makes the compiler round the decimal straight to v).
std::string shortest(float v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    std::string s(buf, r.ptr);
    if (s.find_first_of(".e") == std::string::npos) s += ".";  // 1 → "1.f": a floating literal
    return s + "f";
}

void write_header(const table& t, const std::string& path, const std::string& command) {
    std::ofstream out(path);
    out << "// Generated by scripts/rgb2spec_opt.cpp: do not edit.\n"
        << "// Command: " << command << "\n"
        << "// Jakob & Hanika (2019) sigmoid-polynomial coefficients for linear sRGB under D65;\n"
        << "// the parametrisation and layout are described in scripts/rgb2spec_opt.cpp and\n"
        << "// docs/rgb-upsampling.md, the lookup is iris/spectrum/rgb_sigmoid.hpp.\n"
        << "#pragma once\n\n#include <array>\n#include <cstddef>\n\n"
        << "namespace iris::data::rgb2spec_srgb {\n\n"
        << "/// \\brief Entries per axis of each of the three slices.\n"
        << "inline constexpr std::size_t resolution = " << t.res << ";\n\n"
        << "/// \\brief The fitting range: t = (λ − lambda_min)/(lambda_max − lambda_min) ∈ [0, 1].\n"
        << "inline constexpr double lambda_min = " << lambda_min << ";\n"
        << "inline constexpr double lambda_max = " << lambda_min + lambda_range << ";\n\n"
        << "/// \\brief Brightness nodes z_k = s(s(k/(res−1))), s(u) = 3u² − 2u³.\n"
        << "inline constexpr std::array<float, " << t.res << "> z_nodes = {";
    for (int k = 0; k < t.res; ++k) out << (k % 6 == 0 ? "\n    " : " ") << shortest(static_cast<float>(t.z[k])) << ",";
    const std::size_t n = t.coeff.size();
    out << "\n};\n\n"
        << "/// \\brief (a, b, c) of x = a·t² + b·t + c (t as above), layout [l][k][j][i][3]:\n"
        << "/// slice l = index of the largest component, k the brightness node, j and i the\n"
        << "/// components (l+2) mod 3 and (l+1) mod 3 divided by the largest, at j/(res−1), i/(res−1).\n"
        << "inline constexpr std::array<float, " << n << "> coefficients = {";
    for (std::size_t g = 0; g < n; ++g)
        out << (g % 12 == 0 ? "\n    " : "") << shortest(static_cast<float>(t.coeff[g])) << ",";
    out << "\n};\n\n}  // namespace iris::data::rgb2spec_srgb\n";
}

void write_binary(const table& t, const std::string& path) {
    std::ofstream out(path, std::ios::binary);
    const std::int32_t res = t.res;
    out.write(reinterpret_cast<const char*>(&res), sizeof res);
    for (double z : t.z) {
        const float f = static_cast<float>(z);
        out.write(reinterpret_cast<const char*>(&f), sizeof f);
    }
    for (double c : t.coeff) {
        const float f = static_cast<float>(c);
        out.write(reinterpret_cast<const char*>(&f), sizeof f);
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: rgb2spec_opt RES OUTPUT(.hpp|.bin)\n";
        return 2;
    }
    const int res = std::atoi(argv[1]);
    if (res < 3 || res > 256) {
        std::cerr << "rgb2spec_opt: RES must be in [3, 256]\n";
        return 2;
    }
    const std::string path = argv[2];
    const table t = optimise(res);
    if (path.size() > 4 && path.compare(path.size() - 4, 4, ".bin") == 0) {
        write_binary(t, path);
    } else {
        write_header(
            t, path,
            "g++ -std=c++20 -O2 -I include scripts/rgb2spec_opt.cpp -o /tmp/rgb2spec_opt && /tmp/rgb2spec_opt " +
                std::to_string(res) + " include/iris/spectrum/data/rgb2spec_srgb.hpp");
    }
    return 0;
}
