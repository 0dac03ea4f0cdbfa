// The Python module's scenes and renderers (docs/python.md): a scene loaded and prepared
// once (iris::renderer::prepared_scene: Embree's BVH and the light sampler), renderers that
// add passes to their film a few at a time with the GIL released, images straight into
// numpy arrays, the EXR and checkpoint files the command line writes.
#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "iris/exr/exr.hpp"
#include "iris/renderer/checkpoint.hpp"
#include "iris/renderer/spectral_output.hpp"
#include "iris/renderer/renderer.hpp"
#include "iris/scene/scene.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/version.hpp"
#include "module.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace iris::python {
namespace {

/// \brief A loaded scene: its description, ray tracer and light sampler, shared by every
/// renderer made on it (each holds a reference, so the scene lives while they do).
struct scene {
    renderer::prepared_scene prepared;
    std::string source;
    double load_seconds = 0.0;
};

/// \brief `path` as a string, or FileNotFoundError naming it.
std::string existing_file(const fs::path& path, const char* what) {
    std::error_code ec;
    if (!fs::exists(path, ec)) raise_file_not_found(fmt::format("{} '{}' does not exist", what, path.string()));
    return path.string();
}

std::shared_ptr<scene> load(const py::object& source, bool strict) {
    const auto start = std::chrono::steady_clock::now();
    iris::scene::pbrt_import_options import;
    import.strict = strict;
    std::optional<scene_desc> desc;
    std::string name;
    if (py::isinstance<py::dict>(source)) {
        // a dict in the JSON format: serialised by Python's json (indented, so that an
        // error's line points at one value) and parsed like a file
        const auto text = py::module_::import("json").attr("dumps")(source, py::arg("indent") = 1).cast<std::string>();
        name = "<dict>";
        py::gil_scoped_release unlocked;
        desc = iris::scene::parse_scene(text, name, fs::current_path());
    } else if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) {
        name = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
        if (!iris::scene::builtin_scene_text(name) && !fs::exists(fs::path(name)))
            raise_file_not_found(fmt::format("'{}' is neither a scene file nor a built-in scene ({})", name,
                                             iris::scene::builtin_scene_names()));
        py::gil_scoped_release unlocked;
        desc = iris::scene::load_scene(name, import);
    } else {
        throw py::type_error(fmt::format("iris.load expects a built-in scene's name, a path (str or os.PathLike) or a "
                                         "dict in the JSON scene format, got {}",
                                         py::str(py::type::of(source).attr("__name__")).cast<std::string>()));
    }
    const double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    py::gil_scoped_release unlocked;
    return std::make_shared<scene>(scene{renderer::prepared_scene(std::move(*desc)), name, load_seconds});
}

/// \brief A numpy float32 array (H, W, channels), C-contiguous, written in place by the caller.
py::array_t<float> new_image(int width, int height, int channels) {
    return py::array_t<float>({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width),
                               static_cast<py::ssize_t>(channels)});
}

/// \brief The film's spectral layer as float32 (H, W, bands): each band's mean spectral
/// radiance (film::spectral_mean).
py::array_t<float> spectral_image(const film& f) {
    const film::spectral_parts* sp = f.spectral_state();
    if (!sp)
        throw py::value_error("this render has no spectral output: make the Renderer with spectral=B (bands) for "
                              "image('spectral')");
    const auto n = static_cast<std::size_t>(sp->bands.count);
    auto out = new_image(f.width(), f.height(), sp->bands.count);
    float* px = out.mutable_data();
    {
        py::gil_scoped_release unlocked;
        std::vector<double> row(n);
        for (std::size_t i = 0; i < f.sums().size(); ++i) {
            f.spectral_mean(i, row.data());
            for (std::size_t o = 0; o < n; ++o) px[i * n + o] = static_cast<float>(row[o]);
        }
    }
    return out;
}

/// \brief The film's image as `kind` ("linear_srgb", "srgb", "xyz", "spectral") into a new
/// array: one pass over the film, written straight into numpy's buffer.
py::array_t<float> film_image(const film& f, std::string_view kind) {
    enum class as { linear, encoded, xyz_values };
    as k;
    if (kind == "linear_srgb") k = as::linear;
    else if (kind == "srgb") k = as::encoded;
    else if (kind == "xyz") k = as::xyz_values;
    else if (kind == "spectral") return spectral_image(f);
    else
        throw py::value_error(fmt::format("unknown image kind '{}' (expected linear_srgb, srgb, xyz or spectral)", kind));
    auto out = new_image(f.width(), f.height(), 3);
    float* px = out.mutable_data();
    {
        py::gil_scoped_release unlocked;
        f.for_each_shown([&](std::size_t i, const xyz& v) {
            float* p = px + 3 * i;
            if (k == as::xyz_values) {
                p[0] = static_cast<float>(v.x), p[1] = static_cast<float>(v.y), p[2] = static_cast<float>(v.z);
                return;
            }
            const rgb c = xyz_to_linear_srgb(v);
            // the EXR's float32 values; srgb: clamped to [0, 1] and encoded, as the PNG and SSIM see them
            const float r = static_cast<float>(c.r), g = static_cast<float>(c.g), b = static_cast<float>(c.b);
            if (k == as::linear) {
                p[0] = r, p[1] = g, p[2] = b;
            } else {
                const auto enc = [](float x) {
                    return static_cast<float>(srgb_encode(std::clamp(static_cast<double>(x), 0.0, 1.0)));
                };
                p[0] = enc(r), p[1] = enc(g), p[2] = enc(b);
            }
        });
    }
    return out;
}

/// \brief A progressive render of one scene with one key (preset, sampler, seed, …).
class progressive {
public:
    progressive(std::shared_ptr<scene> s, renderer::options opt) : m_scene(std::move(s)), m_opt(std::move(opt)) {
        const scene_desc& d = m_scene->prepared.desc();
        m_width = m_opt.width > 0 ? m_opt.width : d.camera.width;
        m_height = m_opt.height > 0 ? m_opt.height : d.camera.height;
        renderer::options probe = m_opt;
        probe.spp = std::max(1, m_opt.planned_spp);
        renderer::check(probe);  // ValueError now, not at the first step
        if (m_width <= 0 || m_height <= 0)
            throw py::value_error(fmt::format("image size must be positive, got {}x{}", m_width, m_height));
        m_status.config_name = m_opt.estimator == "bsdf-only" ? "bsdf-only" : renderer::config_name(m_opt.preset);
        m_status.estimator = m_opt.estimator;
        m_status.sampler = m_opt.sampler;
        m_status.width = m_width;
        m_status.height = m_height;
        m_status.windows = m_opt.estimator == "bsdf-only" ? "" : renderer::windows(d, m_opt.preset);
    }

    /// \brief Resume from a checkpoint: its key must be this renderer's.
    void resume(const fs::path& path) {
        auto c = renderer::read_checkpoint(existing_file(path, "checkpoint"));
        renderer::checkpoint_key wanted = key();
        if (m_opt.planned_spp == 0) wanted.spp = c.key.spp;  // only zsobol's points depend on it
        if (const auto m = renderer::key_mismatch(c.key, wanted))
            throw py::value_error(fmt::format("checkpoint '{}' belongs to another render: {}", path.string(), *m));
        m_film = std::move(c.image);
        m_spp = c.spp_done;
        m_status.spp_done = c.spp_done;
        m_totals.samples = c.samples;
        m_totals.rays = c.rays;
        m_totals.seconds = c.seconds;
        m_status.nan_inf = m_film.dropped();
    }

    /// \brief Add `passes` passes (samples per pixel); the GIL is released while they render.
    /// Ctrl-C stops after the current pass (KeyboardInterrupt; the passes done are kept).
    void step(int passes) {
        if (passes < 1) throw py::value_error(fmt::format("step needs spp >= 1, got {}", passes));
        if (m_opt.planned_spp > 0 && m_spp + passes > m_opt.planned_spp)
            throw py::value_error(fmt::format("{} + {} passes exceed planned_spp = {} (the sampler's sequence is laid out "
                                              "for it)", m_spp, passes, m_opt.planned_spp));
        const auto lock = idle();
        renderer::options opt = m_opt;
        opt.start_spp = m_spp;
        opt.spp = m_spp + passes;
        if (m_spp == 0) m_film = film(0, 0);
        bool interrupted = false;
        renderer::hooks h;
        h.on_pass = [&](const film&, const renderer::status&) {
            py::gil_scoped_acquire locked;
            if (PyErr_CheckSignals() != 0) {  // e.g. KeyboardInterrupt: stop after this pass
                interrupted = true;
                return false;
            }
            return true;
        };
        renderer::status st;
        {
            py::gil_scoped_release unlocked;
            st = renderer::render(m_scene->prepared, opt, m_film, h);
        }
        m_spp = st.spp_done;
        m_totals.samples += st.samples;
        m_totals.rays += st.rays;
        m_totals.seconds += st.seconds;
        st.nan_inf = m_film.dropped();
        m_status = st;
        if (interrupted) throw py::error_already_set();
    }

    py::array_t<float> image(const std::string& kind) const {
        const auto lock = idle();
        if (m_spp == 0) {
            film empty(m_width, m_height);
            if (m_opt.spectral_bins > 0) empty.enable_spectral(bands());
            return film_image(empty, kind);
        }
        return film_image(m_film, kind);
    }

    void save(const fs::path& path) const {
        const auto lock = idle();
        if (m_spp == 0) throw std::runtime_error("nothing to save yet: call step() first");
        std::string ext = path.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (ext != ".exr" && ext != ".png")
            throw py::value_error(fmt::format("'{}': save writes .exr (linear sRGB, float32, metadata) or .png (sRGB)",
                                              path.string()));
        const iris::image img = m_film.to_image();
        py::gil_scoped_release unlocked;
        if (ext == ".png") {
            exr::write_png(path, img);
            return;
        }
        auto meta = renderer::image_metadata(m_scene->prepared.desc().name, m_opt, m_status);
        renderer::add_spectral_metadata(m_film, meta);
        const exr::spectral_image spectral = renderer::spectral_channels(m_film);
        exr::write(path, img, meta, exr::pixel_type::float32, spectral.count() > 0 ? &spectral : nullptr);
    }

    void save_checkpoint(const fs::path& path) const {
        const auto lock = idle();
        if (m_spp == 0) throw std::runtime_error("nothing to checkpoint yet: call step() first");
        renderer::write_checkpoint(path, {key(), m_spp, m_totals.samples, m_totals.rays, m_totals.seconds, m_film});
    }

    py::dict stats() const {
        const auto lock = idle();
        py::dict d;
        d["spp"] = m_spp;
        d["seconds"] = m_totals.seconds;
        d["samples"] = m_totals.samples;
        d["rays"] = m_totals.rays;
        d["nan_inf"] = m_film.dropped();
        d["config"] = m_status.config_name;
        d["estimator"] = m_status.estimator;
        d["sampler"] = m_status.sampler;
        d["isa"] = m_status.isa;
        d["threads"] = m_status.threads;
        d["windows"] = m_status.windows;
        d["width"] = m_width;
        d["height"] = m_height;
        return d;
    }

    int spp() const noexcept { return m_spp; }
    /// \brief The spectral bands (none unless spectral > 0).
    spectral_bands bands() const noexcept {
        const scene_desc& d = m_scene->prepared.desc();
        return {m_opt.spectral_bins, d.lambda_min, d.lambda_max};
    }
    double seconds() const noexcept { return m_totals.seconds; }
    const renderer::options& options() const noexcept { return m_opt; }
    std::shared_ptr<scene> scene_ref() const { return m_scene; }
    std::map<std::string, std::string> metadata() const {
        return renderer::image_metadata(m_scene->prepared.desc().name, m_opt, m_status);
    }

private:
    /// \brief The renderer to itself while the lock lives: a step renders into the film
    /// with the GIL released, so another thread must neither step nor read meanwhile.
    std::unique_lock<std::mutex> idle() const {
        std::unique_lock lock(m_busy, std::try_to_lock);
        if (!lock) throw std::runtime_error("this renderer is rendering in another thread: step, read or save it once that step returns");
        return lock;
    }

    renderer::checkpoint_key key() const {
        const scene_desc& d = m_scene->prepared.desc();
        return {std::string(iris::version), d.name, iris::scene::fingerprint(d), m_opt.preset, m_opt.estimator,
                m_opt.sampler, m_opt.seed, m_opt.nthold, m_opt.path.max_depth,
                m_opt.planned_spp > 0 ? m_opt.planned_spp : std::max(1, m_spp), m_width, m_height, m_opt.spectral_bins};
    }

    std::shared_ptr<scene> m_scene;
    renderer::options m_opt;
    int m_width = 0, m_height = 0;
    int m_spp = 0;
    film m_film{0, 0};
    renderer::status m_status;
    struct {
        std::uint64_t samples = 0, rays = 0;
        double seconds = 0.0;
    } m_totals;
    mutable std::mutex m_busy;
};

std::unique_ptr<progressive> make_renderer(std::shared_ptr<scene> s, const std::string& preset, const std::string& sampler,
                                           std::uint64_t seed, int nthold, int threads, int width, int height,
                                           std::optional<int> max_depth, const std::string& estimator,
                                           const std::string& isa, int planned_spp, int spectral,
                                           std::optional<fs::path> resume) {
    if (!s) throw py::type_error("Renderer needs a scene (iris.load(...))");
    renderer::options opt;
    opt.preset = preset;
    opt.sampler = sampler;
    opt.seed = seed;
    opt.nthold = nthold;
    opt.threads = threads;
    opt.width = width;
    opt.height = height;
    const scene_desc& d = s->prepared.desc();
    // like iris-render: a pbrt-v4 file's Integrator suggests the depth, an argument decides
    opt.path.max_depth = max_depth ? *max_depth : d.default_max_depth > 0 ? std::min(d.default_max_depth, 10000) : 32;
    if (opt.path.max_depth < 1 || opt.path.max_depth > 10000)
        throw py::value_error(fmt::format("max_depth must be in 1..10000, got {}", opt.path.max_depth));
    opt.estimator = estimator;
    opt.isa = isa;
    opt.planned_spp = planned_spp;
    opt.spectral_bins = spectral;
    if (planned_spp < 0) throw py::value_error(fmt::format("planned_spp must be >= 0, got {}", planned_spp));
    if (sampler == "zsobol" && planned_spp == 0)
        throw py::value_error("sampler zsobol lays its points out for a known sample count: give planned_spp (the "
                              "image after that many passes is iris-render --spp planned_spp's)");
    auto r = std::make_unique<progressive>(std::move(s), opt);
    if (resume) r->resume(*resume);
    return r;
}

py::dict read_checkpoint_dict(const fs::path& path) {
    auto c = renderer::read_checkpoint(existing_file(path, "checkpoint"));
    py::dict d;
    d["version"] = c.key.version;
    d["scene"] = c.key.scene;
    d["scene_fingerprint"] = c.key.scene_fingerprint;
    d["preset"] = c.key.preset;
    d["estimator"] = c.key.estimator;
    d["sampler"] = c.key.sampler;
    d["seed"] = c.key.seed;
    d["nthold"] = c.key.nthold;
    d["max_depth"] = c.key.max_depth;
    d["planned_spp"] = c.key.spp;
    d["width"] = c.key.width;
    d["height"] = c.key.height;
    d["spectral_bins"] = c.key.spectral_bins;
    d["spp"] = c.spp_done;
    d["samples"] = c.samples;
    d["rays"] = c.rays;
    d["seconds"] = c.seconds;
    d["image"] = film_image(c.image, "linear_srgb");
    if (c.image.spectral_state()) d["spectral"] = spectral_image(c.image);
    return d;
}

/// \brief An EXR's spectral channels (S0.<λ>nm): wavelengths (nm) and float32 (H, W, B).
py::tuple read_spectral(const fs::path& path) {
    auto loaded = exr::read(existing_file(path, "image"));
    const auto n = loaded.spectral.count();
    if (n == 0)
        throw py::value_error(fmt::format("'{}' has no spectral channels (S0.<wavelength>nm; iris-render --spectral B writes "
                                          "them)", path.string()));
    py::array_t<double> nm(static_cast<py::ssize_t>(n));
    std::copy(loaded.spectral.wavelengths.begin(), loaded.spectral.wavelengths.end(), nm.mutable_data());
    auto out = new_image(loaded.pixels.width(), loaded.pixels.height(), static_cast<int>(n));
    std::copy(loaded.spectral.values.begin(), loaded.spectral.values.end(), out.mutable_data());
    return py::make_tuple(nm, out);
}

py::tuple read_image(const fs::path& path) {
    auto loaded = exr::read(existing_file(path, "image"));
    const iris::image& img = loaded.pixels;
    auto out = new_image(img.width(), img.height(), 3);
    float* px = out.mutable_data();
    for (std::size_t i = 0; i < img.pixels().size(); ++i) {
        px[3 * i] = img.pixels()[i].r, px[3 * i + 1] = img.pixels()[i].g, px[3 * i + 2] = img.pixels()[i].b;
    }
    py::dict meta;
    for (const auto& [k, v] : loaded.meta) meta[py::str(k)] = v;
    return py::make_tuple(out, meta);
}

}  // namespace

void add_render(py::module_& m) {
    py::class_<scene, std::shared_ptr<scene>>(m, "Scene",
        "A loaded scene: its meshes, ray tracer (Embree's BVH) and light sampler, built once by iris.load and "
        "shared by every Renderer made on it.")
        .def_property_readonly("name", [](const scene& s) { return s.prepared.desc().name; })
        .def_property_readonly("source", [](const scene& s) { return s.source; }, "what iris.load was given")
        .def_property_readonly("width", [](const scene& s) { return s.prepared.desc().camera.width; })
        .def_property_readonly("height", [](const scene& s) { return s.prepared.desc().camera.height; })
        .def_property_readonly("fingerprint", [](const scene& s) { return iris::scene::fingerprint(s.prepared.desc()); },
                               "64-bit hash of everything a render depends on (iris-scene info)")
        .def_property_readonly("shapes", [](const scene& s) { return s.prepared.desc().shapes.size(); })
        .def_property_readonly("triangles", [](const scene& s) { return s.prepared.desc().triangle_count(); })
        .def_property_readonly("load_seconds", [](const scene& s) { return s.load_seconds; },
                               "seconds spent reading and meshing the scene")
        .def_property_readonly("build_seconds", [](const scene& s) { return s.prepared.build_seconds(); },
                               "seconds spent building the ray tracer and the light sampler")
        .def_property_readonly("approximations", [](const scene& s) { return iris::scene::approximations(s.prepared.desc()); },
                               "what an imported scene approximates (pbrt-v4 files)")
        .def("__repr__", [](const scene& s) {
            return fmt::format("<iris.Scene '{}' {}x{}, {} shapes>", s.prepared.desc().name, s.prepared.desc().camera.width,
                               s.prepared.desc().camera.height, s.prepared.desc().shapes.size());
        });

    m.def("load", &load, py::arg("source"), py::kw_only(), py::arg("strict") = false,
          "Load a scene: a built-in name (iris.scenes()), a .json or .pbrt file, or a dict in the JSON scene format "
          "(docs/scene-format.md). strict: a pbrt-v4 file's approximations are errors. Raises FileNotFoundError, "
          "ValueError (what is wrong, where) or TypeError.");
    m.def("scenes", [] {
        py::list l;
        for (const auto& b : iris::scene::builtin_scenes()) l.append(py::make_tuple(std::string(b.name), std::string(b.description)));
        return l;
    }, "The built-in scenes as (name, description).");

    py::class_<progressive>(m, "Renderer",
        "A progressive render of a scene with one key. step(spp) adds passes to its film (the GIL released; Ctrl-C stops "
        "after the current pass); image() reads it. The image after n passes equals iris-render's with --spp n and the "
        "same key, bit for bit (zsobol: with planned_spp = n).")
        .def(py::init(&make_renderer), py::arg("scene"), py::kw_only(), py::arg("preset") = "hwss",
             py::arg("sampler") = "sobol", py::arg("seed") = 1, py::arg("nthold") = 512, py::arg("threads") = 0,
             py::arg("width") = 0, py::arg("height") = 0, py::arg("max_depth") = py::none(),
             py::arg("estimator") = "nee-mis", py::arg("isa") = "auto", py::arg("planned_spp") = 0,
             py::arg("spectral") = 0, py::arg("resume") = py::none(),
             "preset: iris.presets(); sampler: sobol, zsobol or independent; width/height 0: the scene's; max_depth "
             "None: the scene file's suggestion or 32; estimator: nee-mis, bdpt, light or bsdf-only; planned_spp: the "
             "sample count zsobol's sequence is laid out for (0: any, not zsobol); spectral: B > 0 keeps the spectral radiance "
             "in B equal bands over the scene's wavelength range (image('spectral'), wavelengths; nee-mis and "
             "bsdf-only); resume: a checkpoint of this key.")
        .def("step", &progressive::step, py::arg("spp") = 1, "Render spp more passes (samples per pixel).")
        .def("image", &progressive::image, py::arg("kind") = "linear_srgb",
             "The image as float32 (H, W, 3): linear_srgb (the EXR's values), srgb (clamped, encoded: the PNG's) or xyz; "
             "or spectral: (H, W, B), each band's mean spectral radiance (Renderer(..., spectral=B)).")
        .def("save", &progressive::save, py::arg("path"),
             "Write the image: .exr (float32 linear sRGB with iris-render's metadata, and the spectral channels with "
             "spectral=B) or .png; atomically.")
        .def("save_checkpoint", &progressive::save_checkpoint, py::arg("path"),
             "Write the exact film (iris-render's checkpoint format); Renderer(..., resume=path) goes on from it.")
        .def_property_readonly("spp", &progressive::spp, "passes done")
        .def_property_readonly("wavelengths", [](const progressive& r) -> py::object {
            const spectral_bands b = r.bands();
            if (b.count == 0) return py::none();
            py::array_t<double> nm(b.count);
            for (int o = 0; o < b.count; ++o) nm.mutable_data()[o] = b.centre(o);
            return nm;
        }, "the spectral bands' centres in nm (None without spectral output)")
        .def_property_readonly("seconds", &progressive::seconds, "seconds spent rendering passes")
        .def_property_readonly("stats", &progressive::stats, "spp, seconds, samples, rays, nan_inf (samples dropped), ...")
        .def_property_readonly("metadata", &progressive::metadata, "the EXR attributes save() writes")
        .def_property_readonly("scene", &progressive::scene_ref)
        .def_property_readonly("preset", [](const progressive& r) { return r.options().preset; })
        .def_property_readonly("sampler", [](const progressive& r) { return r.options().sampler; })
        .def_property_readonly("seed", [](const progressive& r) { return r.options().seed; })
        .def_property_readonly("nthold", [](const progressive& r) { return r.options().nthold; })
        .def_property_readonly("max_depth", [](const progressive& r) { return r.options().path.max_depth; })
        .def_property_readonly("estimator", [](const progressive& r) { return r.options().estimator; })
        .def("__repr__", [](const progressive& r) {
            return fmt::format("<iris.Renderer '{}' preset={} sampler={} seed={} spp={}>", r.scene_ref()->prepared.desc().name,
                               r.options().preset, r.options().sampler, r.options().seed, r.spp());
        });

    m.def("read_checkpoint", &read_checkpoint_dict, py::arg("path"),
          "A checkpoint's key, counts and image (linear sRGB, float32 (H, W, 3)) as a dict.");
    m.def("read_image", &read_image, py::arg("path"), "An EXR's RGB as float32 (H, W, 3) and its string attributes.");
    m.def("read_spectral", &read_spectral, py::arg("path"),
          "An EXR's spectral channels (S0.<wavelength>nm, Fichet et al. 2021) as (wavelengths in nm, float32 (H, W, B)).");
}

}  // namespace iris::python
