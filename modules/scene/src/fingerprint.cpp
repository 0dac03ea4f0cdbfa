// fingerprint(): the scene's content as exact bits through FNV-1a (64 bit).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>
#include <variant>

#include "iris/hash.hpp"
#include "iris/scene/scene.hpp"

namespace iris::scene {
namespace {

/// \brief iris's FNV-1a (iris/hash.hpp) fed the exact bits of a scene's values.
class hasher {
public:
    void bytes(const void* data, std::size_t n) noexcept { m_h.add(data, n); }
    template <class T>
        requires std::is_arithmetic_v<T>
    void operator()(T v) noexcept {
        bytes(&v, sizeof v);
    }
    void operator()(std::string_view s) noexcept {
        (*this)(s.size());
        bytes(s.data(), s.size());
    }
    void operator()(const glm::vec3& v) noexcept {
        (*this)(v.x);
        (*this)(v.y);
        (*this)(v.z);
    }
    template <class T>
    void operator()(std::span<const T> v) noexcept {
        (*this)(v.size());
        for (const auto& x : v) (*this)(x);
    }
    void operator()(const tabulated_spectrum& s) noexcept {
        (*this)(s.wavelengths());
        (*this)(s.values());
    }
    std::uint64_t value() const noexcept { return m_h.value(); }

private:
    fnv1a m_h;
};

/// \brief An index model's parameters (after its alternative's index).
void hash_ior(hasher& h, const ior_model& ior) {
    std::visit(
        [&](const auto& n) {
            using N = std::decay_t<decltype(n)>;
            if constexpr (std::is_same_v<N, constant_ior>) h(n.value);
            else if constexpr (std::is_same_v<N, cauchy_ior>) {
                h(n.a);
                h(n.b_um2);
            } else if constexpr (std::is_same_v<N, sellmeier_ior>) {
                for (double v : {n.b1, n.b2, n.b3, n.c1, n.c2, n.c3}) h(v);
            } else {
                static_assert(std::is_same_v<N, tabulated_ior>, "fingerprint: hash every IOR model");
                h(n.table);
            }
        },
        ior);
}

/// \brief A thin film, when there is one (only then: scenes without keep their fingerprints).
void hash_film(hasher& h, const std::optional<material::thin_film>& f) {
    static_assert(sizeof(material::thin_film) == sizeof(double) + sizeof(ior_model), "fingerprint: hash every field of thin_film");
    if (!f) return;
    h(std::string_view("film"));
    h(f->thickness_nm);
    h(f->ior.index());
    hash_ior(h, f->ior);
}

/// \brief A medium's scattering, when there is one (only then: scenes without keep their fingerprints).
void hash_scattering(hasher& h, const std::optional<medium_scattering>& m) {
    static_assert(sizeof(medium_scattering) == sizeof(tabulated_spectrum) + 8, "fingerprint: hash every field of medium_scattering");
    if (!m) return;
    h(std::string_view("scattering"));
    h(m->sigma_s);
    h(m->g);
}

/// \brief Every field of material `x` (a new field changes its size and stops the build).
template <class T>
void hash_material(hasher& h, const T& x) {
    if constexpr (std::is_same_v<T, material::dielectric>) {
        static_assert(sizeof(T) == sizeof(ior_model) + 8 + sizeof(std::optional<tabulated_spectrum>) +
                                       sizeof(std::optional<medium_scattering>) +
                                       sizeof(std::optional<material::thin_film>),
                      "fingerprint: hash every field of material::dielectric");  // (roughness, padded)
        h(x.roughness);
        h(x.ior.index());
        if (x.absorption) h(*x.absorption);  // (only when present: older scenes keep their fingerprints)
        hash_ior(h, x.ior);
        hash_film(h, x.film);
        hash_scattering(h, x.scattering);
    } else if constexpr (std::is_same_v<T, material::diffuse>) {
        // every field: a new one changes the size and stops the build here
        static_assert(sizeof(T) == sizeof(tabulated_spectrum) + sizeof(std::optional<std::uint32_t>),
                      "fingerprint: hash every field of material::diffuse");
        h(x.reflectance);
        if (x.texture) h(*x.texture);  // only when present: untextured scenes keep their fingerprint
    } else if constexpr (std::is_same_v<T, material::conductor>) {
        static_assert(sizeof(T) == sizeof(tabulated_spectrum) + sizeof(std::optional<material::conductor_ior>) +
                                       sizeof(double) +  // roughness, padded
                                       sizeof(std::optional<material::thin_film>),
                      "fingerprint: hash every field of material::conductor");
        static_assert(sizeof(material::conductor_ior) == sizeof(std::string) + 2 * sizeof(tabulated_spectrum),
                      "fingerprint: hash every field of material::conductor_ior");
        h(x.reflectance);
        if (x.ior) {  // only when present: reflectance-only conductors keep their fingerprint
            h(std::string_view(x.ior->name));
            h(x.ior->eta);
            h(x.ior->k);
        }
        if (x.roughness != 0.0f) h(x.roughness);  // only when rough: smooth conductors keep their fingerprint
        hash_film(h, x.film);
    } else if constexpr (std::is_same_v<T, material::coated>) {
        static_assert(sizeof(T) == sizeof(std::variant<material::diffuse, material::conductor>) + 4 * sizeof(float) +
                                       2 * sizeof(int),
                      "fingerprint: hash every field of material::coated");
        h(x.base.index());
        std::visit([&](const auto& b) { hash_material(h, b); }, x.base);
        for (float v : {x.eta, x.roughness, x.thickness, x.internal_reflectance}) h(v);
        h(x.max_depth);
        h(x.samples);
    } else {
        static_assert(sizeof(T) == 0, "fingerprint: hash every field of a new material type");
    }
}

}  // namespace

std::uint64_t fingerprint(const iris::scene_desc& scene) {
    hasher h;
    const auto& c = scene.camera;
    h(c.position);
    h(c.look_at);
    h(c.up);
    h(c.fov_y_degrees);
    h(c.width);
    h(c.height);
    h(scene.lambda_min);
    h(scene.lambda_max);
    h(scene.materials.size());
    for (const auto& m : scene.materials) {
        h(m.index());
        std::visit([&](const auto& x) { hash_material(h, x); }, m);
    }
    h(scene.emitters.size());
    for (const auto& e : scene.emitters) {
        h(std::string_view(e.spd_name));
        h(e.radiance);
        h(e.two_sided);
    }
    h(scene.shapes.size());
    for (const auto& s : scene.shapes) {
        h(s.mesh.positions.size());
        for (const auto& p : s.mesh.positions) h(p);
        h(s.mesh.triangles.size());
        for (const auto& t : s.mesh.triangles) h.bytes(t.data(), sizeof t);
        if (!s.mesh.normals.empty()) {  // (absent: the fingerprints of meshes without them are unchanged)
            h(s.mesh.normals.size());
            for (const auto& n : s.mesh.normals) h(n);
        }
        if (!scene.textures.empty()) {  // uvs matter only to textures (every quad has them)
            h(s.mesh.uvs.size());
            for (const auto& uv : s.mesh.uvs) h.bytes(&uv, sizeof uv);
        }
        h(s.material);
        h(s.emitter.has_value());
        h(s.emitter.value_or(0));
    }
    h(scene.environment.has_value());
    if (scene.environment) {
        h(std::string_view(scene.environment->spd_name));
        h(scene.environment->radiance);
        if (const auto& m = scene.environment->map) {  // hashed only when present: older scenes keep their fingerprint
            h(static_cast<int>(m->mapping));
            if (m->to_map != glm::mat3(1.0f))  // only when turned: older scenes keep their fingerprint
                for (glm::length_t col = 0; col < 3; ++col) h(m->to_map[col]);
            h(m->width);
            h(m->height);
            for (const auto& w : m->weights) h(w);
            for (const auto& b : scene.environment->basis) h(b);
        }
    }
    if (scene.medium) {  // likewise
        static_assert(sizeof(medium_desc) == sizeof(std::optional<tabulated_spectrum>) + sizeof(std::optional<medium_scattering>),
                      "fingerprint: hash every field of medium_desc");
        h(std::string_view("medium"));
        h(scene.medium->absorption.has_value());
        if (scene.medium->absorption) h(*scene.medium->absorption);
        hash_scattering(h, scene.medium->scattering);
    }
    if (!scene.textures.empty()) {  // likewise
        h(scene.textures.size());
        for (const auto& t : scene.textures) {
            h(t.width);
            h(t.height);
            h(static_cast<int>(t.wrap));
            if (t.uv_scale != glm::vec2(1.0f) || t.uv_offset != glm::vec2(0.0f)) {  // likewise
                h(t.uv_scale.x), h(t.uv_scale.y), h(t.uv_offset.x), h(t.uv_offset.y);
            }
            for (const auto& w : t.weights) h(w);
        }
    }
    if (!scene.lights.empty()) {  // likewise
        h(scene.lights.size());
        for (const auto& l : scene.lights) {
            h(l.index());
            std::visit(
                [&](const auto& x) {
                    using L = std::decay_t<decltype(x)>;
                    h(x.emitter);
                    if constexpr (std::is_same_v<L, light::point>) {
                        h(x.position);
                    } else if constexpr (std::is_same_v<L, light::spot>) {
                        h(x.position);
                        h(x.direction);
                        h(x.cos_falloff_start);
                        h(x.cos_total_width);
                    } else if constexpr (std::is_same_v<L, light::distant>) {
                        h(x.direction);
                    } else {
                        static_assert(sizeof(L) == 0, "fingerprint: hash every field of a new light type");
                    }
                },
                l);
        }
    }
    return h.value();
}

}  // namespace iris::scene
