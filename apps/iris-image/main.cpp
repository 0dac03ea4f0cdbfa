// iris-image — compare, convert and crop the EXR images iris renders.
//
//   iris-image diff IMAGE REFERENCE [--json]
//       mse, relmse (ε = 0.01, REFERENCE in the denominator), ssim (sRGB-encoded, 11×11
//       Gaussian window; "nan"/null below 11×11), max_abs and the pixel count, as one line
//       `mse=… relmse=… ssim=… max_abs=… pixels=…`, or with --json as a JSON object with
//       those keys plus width and height. Definitions: docs/metrics.md.
//   iris-image bias RUN RUN... --reference REFERENCE [--json]
//       the MSE of independent runs (the same render, other seeds) against REFERENCE split
//       into the runs' variance and the squared bias (with the reference's own error), and
//       the bias's standard error: `runs=… mse=… variance=… bias_sq=… bias_sq_se=…`.
//   iris-image regions IMAGE REFERENCE [--size N=20] [--floor F=0.01] [--json]
//       per N×N block, the relative difference of the means (IMAGE − REFERENCE) / REFERENCE of
//       each channel (a near-black channel against the block's luminance), over the blocks
//       whose reference luminance is at least F × the image's mean: `regions=… compared=…
//       max_rel=… mean_abs_rel=… mean_rel=… worst=X,Y` (comparing two renderers).
//   iris-image convert IMAGE -o OUT.png [--exposure E]
//       8-bit sRGB PNG of IMAGE scaled by 2^E (E in stops; default 0).
//   iris-image crop IMAGE --rect X,Y,W,H -o OUT.exr
//       the W×H pixels whose top-left is (X, Y) (top row is y = 0), as a float EXR that
//       keeps IMAGE's string metadata; the rectangle must lie inside IMAGE.
//   iris-image error-map IMAGE REFERENCE -o OUT.png [--scale S]
//       false-colour PNG of the per-pixel error e = 0.2126|ΔR| + 0.7152|ΔG| + 0.0722|ΔB|
//       (luminance of |IMAGE − REFERENCE|) mapped through a CIELAB ramp (error_ramp.hpp)
//       with e = S at its top; default S: the 99th percentile of e (nearest rank; the
//       maximum if that is 0, 1 if the images are equal). Prints the scale used.
//   iris-image spectrum IMAGE X Y [--radius R] [--json]
//       the spectral channels (S0.<λ>nm, iris-render --spectral) of pixel (X, Y), or their
//       mean over the (2R + 1)² pixels around it: one `wavelength_nm value` line each.
//   iris-image info IMAGE
//       width, height, the spectral channels and the string metadata of IMAGE.
//
// Inputs are EXRs with R, G and B channels. Missing, unreadable or non-EXR files,
// different sizes, NaN/Inf pixels, bad options: one line on stderr, exit status 2, and no
// output file (every writer replaces its target atomically).
#include <iris/version.hpp>

#include "cli.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
    CLI::App app{"iris-image: compare, convert and crop EXR images", "iris-image"};
    app.set_version_flag("--version", std::string(iris::version));
    app.require_subcommand(1);
    iris::app::add_image_commands(app);
    return iris::app::run(app, argc, argv);
}
