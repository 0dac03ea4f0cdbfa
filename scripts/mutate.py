#!/usr/bin/env python3
"""Mutation check: inject known bugs one at a time and confirm the test suite catches each.

For every mutation below: apply its text replacements to the source, build the test
targets it names (in build/release, which must be configured: README command 2), run the
CTest entries matching its regex, restore the source, and print CAUGHT (some test failed)
or SURVIVED (all passed). At the end the sources are as before and the targets are rebuilt.

    python3 scripts/mutate.py            # every mutation (about 50 min on 2 cores)
    python3 scripts/mutate.py film ab    # the mutations whose names contain 'film' or 'ab'

A mutation whose text is not found is reported as STALE (the code moved: update its text).

IRIS_MUTATE_BUILD=DIR uses another configured build directory, e.g. one configured with
-DIRIS_ISA_COPIES=OFF, where a mutated render header recompiles a third of the renderer
(the mutations do not depend on the instruction set).
"""
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
BUILD = pathlib.Path(os.environ.get("IRIS_MUTATE_BUILD", ROOT / "build" / "release")).resolve()

# name, [(file, old, new), ...], [targets], ctest regex
MUTATIONS = [
    ("issue-18-shadow-ray-and-offsets",
     [("include/iris/render/frame.hpp",
       "    const glm::vec3 target = offset_ray_origin(q, nq, p.p - q.p);\n    return {o, target - o, 1.0f - 1e-4f};",
       "    (void)nq;\n    return {o, glm::normalize(q.p - p.p), glm::length(q.p - o) * (1.0f - 1e-4f)};"),
      ("include/iris/render/frame.hpp",
       "    const float d = glm::dot(glm::abs(ng), sp.error);",
       "    const float d = 1e-4f * (1.0f + std::fmax(std::fabs(sp.p.x), std::fmax(std::fabs(sp.p.y), std::fabs(sp.p.z))));")],
     ["direct_light_test", "estimators_test", "ray_offset_test"], "DirectLight|Estimators|RayOffset"),
    ("fixed-1e-4-ray-offset",
     [("include/iris/render/frame.hpp",
       "    const float d = glm::dot(glm::abs(ng), sp.error);",
       "    const float d = 1e-4f * (1.0f + std::fmax(std::fabs(sp.p.x), std::fmax(std::fabs(sp.p.y), std::fabs(sp.p.z))));")],
     ["ray_offset_test", "estimators_test"], "RayOffset|Estimators"),
    ("no-floor-under-the-offset",
     [("include/iris/render/frame.hpp",
       "    const float floor = 32.0f * eps * std::fmax(m.x, std::fmax(m.y, m.z));",
       "    const float floor = 0.0f * eps * std::fmax(m.x, std::fmax(m.y, m.z));")],
     ["ray_offset_test", "renderer_core_test"], "RayOffset|RendererCore"),
    ("light-point-barycentrics",
     [("include/iris/render/lights/area.hpp", "const float b1 = u.y * su, b2 = su - b1;", "const float b1 = u.y * su, b2 = 1.0f - su - b1;")],
     ["direct_light_test", "estimators_test"], "DirectLight|Estimators"),
    ("hero-fresnel-x1.05",
     [("include/iris/render/materials/fresnel.hpp", "    return fresnel_walter(std::fabs(cos_i), cos_i < 0.0f ? 1.0f / eta2 : eta2);",
       "    return std::min(1.0f, 1.05f * fresnel_walter(std::fabs(cos_i), cos_i < 0.0f ? 1.0f / eta2 : eta2));")],
     ["render_test"], "Bsdf"),
    ("bins-fresnel-x1.05",
     [("include/iris/render/materials/fresnel.hpp", "        const float f = fresnel_walter(c, ef2);",
       "        const float f = std::min(1.0f, 1.05f * fresnel_walter(c, ef2));")],
     ["render_test"], "Bsdf"),
    ("secondaries-kept-at-dispersive-refraction",
     [("include/iris/render/materials/smooth_dielectric.hpp", "            if (dispersive && k > 0) continue;", "            (void)dispersive;")],
     ["estimators_test"], "Estimators"),
    ("scaled-pdf-without-Z",
     [("include/iris/render/integrator.hpp", "const float z = scales_pdf ? dist.normalisation() : 1.0f;", "const float z = 1.0f;")],
     ["renderer_core_test"], "RendererCore.WhiteFurnace"),
    ("B-term-x1.05",
     [("include/iris/render/propagation.hpp", "        v.y += dl * static_cast<double>(y);", "        v.y += 1.05 * dl * static_cast<double>(y);")],
     ["renderer_core_test"], "RendererCore.WhiteFurnace"),
    ("wavelength-pdf-1%-off",
     [("include/iris/sampling/bias/policies.hpp", "    const double q = num / den;", "    const double q = num / (1.01 * den);")],
     ["renderer_core_test"], "RendererCore.WhiteFurnace"),
    ("thread-keyed-random-stream",
     [("modules/renderer/src/render_loop.hpp", "static_cast<std::uint32_t>(y), pixel, job.sample);",
       "static_cast<std::uint32_t>(y), pixel + static_cast<std::uint64_t>(tbb::this_task_arena::current_thread_index()), job.sample);")],
     ["renderer_core_test"], "RendererCore.Identical"),
    ("relaxation-off-by-one",
     [("modules/renderer/src/instantiation.hpp", "cfg.alpha(static_cast<std::uint64_t>(i))", "cfg.alpha(static_cast<std::uint64_t>(i) + 1)")],
     ["renderer_core_test"], "RendererCore.SampleI"),
    ("film-without-nan-guard",
     [("include/iris/render/film.hpp", "        const bool ok = summable(v.x) && summable(v.y) && summable(v.z);", "        const bool ok = true;")],
     ["film_guard_test"], "FilmGuard"),
    ("non-atomic-image-write",
     [("modules/exr/src/atomic_file.cpp", "    try {\n        write_to(tmp);", "    write_to(target);\n    return;\n    try {\n        write_to(tmp);")],
     ["exr_test"], "ExrTest"),
    ("bsdf-only-steps-only-to-the-self-hit",
     [("include/iris/render/bsdf_only.hpp", "            o += std::fmax(h->t, 0.0f) * d + step * d;", "            o += std::fmax(h->t, 0.0f) * d;")],
     ["estimators_test"], "Estimators.BsdfOnly"),
    # issue 17's further list: window placement, MIS after specular bounces, bin width, light pdf
    ("window-indicator-5nm-off-its-sampling",
     [("include/iris/sampling/restriction/multi_box.hpp",
       "                if (lambda_nm >= w.lo && lambda_nm <= w.hi) return 1.0f;",
       "                if (lambda_nm >= w.lo + 5.0f && lambda_nm <= w.hi + 5.0f) return 1.0f;")],
     ["sampling_test", "sampling_statistical_test", "renderer_core_test"], "Laws|ChiSquare|SpectralEstimator|RendererCore.WhiteFurnace"),
    ("mis-weight-on-emission-after-specular-bounce",
     [("include/iris/render/integrator.hpp", "const float pl = hp.prev_delta ? 0.0f : m_lights.pdf_area(vx.shape, vx.prim)",
       "const float pl = m_lights.pdf_area(vx.shape, vx.prim)"),
      ("include/iris/render/integrator.hpp", "{1.0f, 0.0f, 0.0f}}, !hp.prev_delta, pl, wl, hp, bterm);",
       "{1.0f, 0.0f, 0.0f}}, true, pl, wl, hp, bterm);")],
     ["estimators_test", "renderer_core_test"], "Estimators|RendererCore.WhiteFurnace"),
    ("B-term-bins-5%-narrow",
     [("include/iris/render/bins.hpp", "m_width((lambda_max - lambda_min) / static_cast<float>(Bins))",
       "m_width(0.95f * (lambda_max - lambda_min) / static_cast<float>(Bins))")],
     ["renderer_core_test", "render_test"], "RendererCore.WhiteFurnace|Bins"),
    ("light-pdf-3%-high-in-nee",
     [("include/iris/render/integrator.hpp", "        const float pl = ls->pdf;",
       "        const float pl = 1.03f * ls->pdf;")],
     ["direct_light_test"], "DirectLight"),
    ("light-pdf-doubled-in-mis-of-emission-hits",
     [("include/iris/render/integrator.hpp",
       " : m_lights.pdf_area(vx.shape, vx.prim) * vx.t * vx.t / std::fabs(cos_l);",
       " : 2.0f * m_lights.pdf_area(vx.shape, vx.prim) * vx.t * vx.t / std::fabs(cos_l);")],
     ["direct_light_test"], "DirectLight"),
    ("roulette-on-beta-without-eta-scale",
     [("include/iris/render/integrator.hpp", "const float m = bterm.roulette_max(hp.beta.max_value()) * hp.eta_scale;",
       "const float m = bterm.roulette_max(hp.beta.max_value());")],
     ["render_test"], "Integrator.Roulette"),
    ("film-fixed-point-with-20-fraction-bits",
     [("include/iris/render/film.hpp", "        const double w = v * 0x1p56;",
       "        const double w = std::trunc(v * 0x1p20) * 0x1p36;")],
     ["extreme_test", "render_test"], "Extreme.AMillion|Film"),
    ("film-range-check-missing",
     [("include/iris/render/film.hpp", "    static constexpr bool summable(double v) noexcept { return std::fabs(v) < max_sample; }",
       "    static constexpr bool summable(double v) noexcept { return std::isfinite(v); }")],
     ["render_test"], "Film"),
    ("fixed-1e-4-ray-offset-at-extreme-scales",
     [("include/iris/render/frame.hpp",
       "    const float d = glm::dot(glm::abs(ng), sp.error);",
       "    const float d = 1e-4f * (1.0f + std::fmax(std::fabs(sp.p.x), std::fmax(std::fabs(sp.p.y), std::fabs(sp.p.z))));")],
     ["extreme_test"], "Extreme.SceneScaled"),
    # issue 12: samplers
    ("sobol-shuffle-per-slot (padding)",
     [("include/iris/render/random.hpp",
       "        const std::uint32_t x = sobol::point(static_cast<std::uint32_t>(m_index), d);",
       "        const std::uint32_t x = sobol::point(sobol::shuffle_index(static_cast<std::uint32_t>(m_sample), static_cast<std::uint32_t>(h >> 16)), d);")],
     ["render_test", "sampler_render_test"], "Sampler"),
    ("sobol-slot-reads-dimension-slot+1",
     [("include/iris/render/random.hpp", "        const std::uint32_t d = table[slot];", "        const std::uint32_t d = slot == 0 ? 0 : slot + 1;")],
     ["render_test", "sampler_render_test"], "Sampler"),
    ("sobol-ignores-the-sample-index-past-bit-3",
     [("include/iris/render/random.hpp",
       "            m_index = sobol::shuffle_index(static_cast<std::uint32_t>(sample), shuffle) ^ sobol::shuffle_index(0, shuffle);",
       "            m_index = sobol::shuffle_index(static_cast<std::uint32_t>(sample & 7u), shuffle) ^ sobol::shuffle_index(0, shuffle);")],
     ["render_test", "sampler_render_test"], "Sampler"),
    ("sobol-2d-partner-is-the-next-dimension",
     [("include/iris/render/random.hpp",
       "        return {a, sobol::to_unit(sobol::owen_scramble(sobol::paired(x), static_cast<std::uint32_t>(h >> 32)))};",
       "        return {a, sobol::to_unit(sobol::owen_scramble(sobol::point(static_cast<std::uint32_t>(m_index), d + 1), static_cast<std::uint32_t>(h >> 32)))};")],
     ["render_test", "sampler_render_test"], "Sampler"),
    ("owen-scramble-is-an-xor",
     [("include/iris/sampling/sobol.hpp",
       "    return reverse_bits(laine_karras(reverse_bits(v), seed));",
       "    return v ^ seed;")],
     ["render_test", "sampler_render_test"], "Sampler|Sobol"),
    # issue 14: resume, ranks, checkpoints
    ("rank-ignored (every rank renders the round's first pass)",
     [("modules/renderer/src/render_loop.hpp", "        const int i = round + opt.rank;", "        const int i = round;")],
     ["checkpoint_test", "iris-render"], "Resume|apps.render.mpi"),
    ("resume-restarts-at-pass-0",
     [("modules/renderer/src/render_loop.hpp",
       "    for (int round = opt.start_spp; round < opt.spp; round += opt.ranks) {",
       "    for (int round = 0; round < opt.spp; round += opt.ranks) {")],
     ["checkpoint_test", "iris-render"], "Resume|apps.render.resume"),
    ("checkpoint-checksum-not-checked",
     [("modules/renderer/src/checkpoint.cpp",
       "    if (r.get<std::uint64_t>(\"the checksum\") != fnv1a(bytes.data(), body)) r.fail(\"checksum mismatch\");",
       "    (void)r.get<std::uint64_t>(\"the checksum\");")],
     ["checkpoint_test", "iris-render"], "CheckpointFile|apps.render.resume"),
    ("mpi-reduce-skipped (rank 0 writes its own film)",
     [("apps/iris-render/main.cpp", "        iris::film sum = mpi.reduce(local);", "        iris::film sum = local;")],
     ["iris-render"], "apps.render.mpi"),
    # issue 16: the bias fade (each checked by hand on 2026-12-04: CAUGHT)
    ("fade-weight-is-the-running-mean",
     [("include/iris/render/fade.hpp", "    return std::clamp(s.var_late / denominator, 0.0, 1.0);", "    return running;")],
     ["render_test"], "Fade"),
    ("fade-weight-swapped",
     [("include/iris/render/fade.hpp", "    return std::clamp(s.var_late / denominator, 0.0, 1.0);",
       "    return std::clamp((s.var_both - s.var_late) / denominator, 0.0, 1.0);")],
     ["render_test"], "Fade"),
    ("fade-denominator-without-the-difference",
     [("include/iris/render/fade.hpp", "    const double denominator = std::max(s.diff_sq, s.var_both);",
       "    const double denominator = s.var_both;")],
     ["render_test"], "Fade"),
    ("fade-split-off-by-one",
     [("include/iris/render/film.hpp", "            const bool early = sample < split;", "            const bool early = sample <= split;")],
     ["render_test"], "Fade"),
    # the fade layer in checkpoints and the ranks' reduction (checked by hand 2026-12-04: CAUGHT)
    ("checkpoint-without-the-fade-layer",
     [("modules/renderer/src/checkpoint.cpp", "    const film::fade_parts* fade = f.fade_state();",
       "    const film::fade_parts* fade = nullptr;")],
     ["checkpoint_test", "iris-render"], "CheckpointFile|apps.render.resume"),
    ("mpi-reduce-drops-the-fade-layer",
     [("modules/mpi/src/mpi.cpp", "    if (const film::fade_parts* l = local.fade_state()) {",
       "    if (const film::fade_parts* l = nullptr) {")],
     ["iris-render"], "apps.render.mpi"),
    ("bias-variance-divides-by-k",
     [("include/iris/metrics/bias_variance.hpp", "            const double s2 = ss / (k - 1);",
       "            const double s2 = ss / k;")],
     ["metrics_test"], "BiasVariance"),
    # issue 31: lights in solid angle (each checked by hand on 2026-12-05: caught)
    ("latlong-jacobian-without-sin-theta",
     [("include/iris/render/lights/environment.hpp", "        return 2.0f * pi * pi * std::sin(pi * p.y);",
       "        return 2.0f * pi * pi;")],
     ["render_test"], "LightSampling.*"),
    ("spot-solid-angle-full-falloff",
     [("include/iris/render/lights/point.hpp", "+ 0.5f * (cos_falloff_start - cos_total_width)",
       "+ (cos_falloff_start - cos_total_width)")],
     ["render_test"], "LightSampling.*"),
    ("environment-without-mis",
     [("include/iris/render/integrator.hpp", "        const float pl = hp.prev_delta ? 0.0f : m_lights.pdf_environment(dir);",
       "        const float pl = 0.0f;")],
     ["light_render_test"], "LightRender"),
    ("point-light-inverse-distance",
     [("include/iris/render/lights/point.hpp", "        out.le = {emitter, 1, {s / d2, 0.0f, 0.0f}};",
       "        out.le = {emitter, 1, {s / std::sqrt(d2), 0.0f, 0.0f}};")],
     ["light_render_test"], "LightRender"),
    ("spot-linear-falloff",
     [("include/iris/render/lights/point.hpp", "        return t * t * (3.0f - 2.0f * t);", "        return t;")],
     ["light_render_test"], "LightRender"),
    # issue 31: the surface interaction and textures
    ("shading-normal-not-turned-to-the-windings-side",
     [("include/iris/render/interaction.hpp", "    return glm::dot(ns, ng) < 0.0f ? -ns : ns;", "    return ns;")],
     ["render_test"], "Interaction"),
    ("rough-eval-pdf-is-f",
     [("include/iris/render/materials/rough_dielectric.hpp", "            out.pdf[k] = v.pdf;\n        }\n        return out;",
       "            out.pdf[k] = v.f_cos;\n        }\n        return out;")],
     ["render_test"], "Bsdf"),
    ("texture-v-not-flipped",
     [("include/iris/render/texture.hpp", "    const float fy = (1.0f - uv.y) * static_cast<float>(tex.height) - 0.5f;",
       "    const float fy = uv.y * static_cast<float>(tex.height) - 0.5f;")],
     ["render_test", "light_render_test"], "Texture"),
    ("mirror-wrap-repeats",
     [("include/iris/render/texture.hpp", "            return m < n ? m : period - 1 - m;", "            return m % n;")],
     ["render_test"], "Texture"),
    ("hero-ignores-the-texture",
     [("include/iris/render/integrator.hpp", "texture_weights(m_scene, m_scene.materials[shape.material], vx.uv));",
       "std::nullopt);")],
     ["light_render_test"], "TextureRender"),
    ("bins-mix-the-basis-rows-reversed",
     [("include/iris/render/propagation.hpp", "                const view v = m_t.albedo[albedo.first + i].at(m_bp, m_scratch);",
       "                const view v = m_t.albedo[albedo.first + 2 - i].at(m_bp, m_scratch);")],
     ["light_render_test"], "TextureRender"),
    # issue 31: conductors with a complex index
    ("conductor-fresnel-drops-p-polarisation",
     [("include/iris/render/materials/fresnel.hpp", "    const float f = 0.5f * (rs + rp);", "    const float f = rs;")],
     ["render_test"], "Bsdf"),
    ("bins-read-eta-as-k",
     [("include/iris/render/propagation.hpp", "        view k() const { return p.m_t.k[p.m_material].at(p.m_bp, p.m_k_scratch); }",
       "        view k() const { return p.m_t.eta[p.m_material].at(p.m_bp, p.m_k_scratch); }")],
     ["light_render_test"], "ConductorRender"),
    # issue 31: rough conductors
    ("rough-conductor-pdf-without-jacobian",
     [("include/iris/render/materials/conductor.hpp", "        const float p = m.d_visible(wo, wm) / (4.0f * c);",
       "        const float p = m.d_visible(wo, wm) / 4.0f;")],
     ["render_test"], "Bsdf.RoughConductor*"),
    ("rough-conductor-fresnel-at-the-macro-normal",
     [("include/iris/render/materials/conductor.hpp", "        out.f_cos = fresnel<N>(c, s, geometric);",
       "        out.f_cos = fresnel<N>(std::fabs(wo.z), s, geometric);")],
     ["render_test"], "Bsdf.RoughConductor*"),
    ("rough-conductor-unshadowed",
     [("include/iris/render/materials/conductor.hpp", "        const float geometric = d * m.g(wo, wi) / (4.0f * std::fabs(wo.z));",
       "        const float geometric = d * m.g1(wo) / (4.0f * std::fabs(wo.z));")],
     ["light_render_test"], "ConductorRender.*Rough*"),
    # issue 32's groundwork: a bounce's extra draws must not read the next bounce's slots
    ("stream-overflow-reads-the-next-bounce",
     [("include/iris/render/random.hpp", "        if (m_slot == m_end) [[unlikely]] {",
       "        if (false && m_slot == m_end) [[unlikely]] {")],
     ["render_test"], "Sampler.ABounce*"),
    # issue 31: mesh files with normals and uvs
    ("obj-split-ignores-normals",
     [("modules/geometry/src/load.cpp",
       "                const std::array<long long, 3> key{c.vertex_index, any_normal ? c.normal_index : -1, any_uv ? c.texcoord_index : -1};",
       "                const std::array<long long, 3> key{c.vertex_index, -1, any_uv ? c.texcoord_index : -1};")],
     ["geometry_test"], "LoadMesh.*"),
    ("ply-reads-v-as-u",
     [("modules/geometry/src/load.cpp", "                        if (static_cast<int>(k) == uv[c]) t[c] = v;",
       "                        if (static_cast<int>(k) == uv[0]) t[c] = v;")],
     ["geometry_test"], "LoadMesh.*"),
    # issue 32: light tracing and the film's splats
    ("light-transmission-without-eta2",
     [("include/iris/render/light_tracer.hpp", "                            f[k] *= e * e;", "                            f[k] *= 1.0f + 0.0f * e;")],
     ["light_tracer_test"], "LightTracer.AgreesWithThePathTracer*"),
    ("light-camera-importance-cos4",
     [("include/iris/render/light_tracer.hpp", "        l.g = m_camera.pdf_direction(from_camera) / d2;",
       "        l.g = m_camera.importance(from_camera) / d2;")],
     ["light_tracer_test"], "LightTracer.MatchesTheExact*"),
    ("light-bins-transmission-without-eta2",
     [("include/iris/render/propagation.hpp", "                    for (std::size_t b = 0; b < Bins; ++b) f[b] *= e2[b];",
       "                    (void)e2;")],
     ["light_tracer_test", "bdpt_test"], "LightTracer.TheBTerm|Bdpt.TheBTerm"),
    ("light-without-shading-correction",
     [("include/iris/render/light_tracer.hpp",
       "                const float shading = std::fabs(lo.z) * std::fabs(glm::dot(wi, vx.ng)) / (wo_ng * std::fabs(s->wi.z));",
       "                const float shading = 1.0f;")],
     ["light_tracer_test"], "LightTracer.*"),
    # bidirectional path tracing (iris/render/bdpt.hpp)
    ("bdpt-connection-drops-light-density",
     [("include/iris/render/bdpt.hpp",
       "            ws.path[s].pl = to_area(ye.pdf_fwd, vx.sp.p, vx.ng, y.si.sp.p);\n",
       "")],
     ["bdpt_test", "direct_light_test"], "Bdpt"),
    ("bdpt-light-subpath-without-reverse-density",
     [("include/iris/render/bdpt.hpp",
       "                ws.light[i - 1].pdf_rev = to_area(rev, ws.light[i - 1].si.sp.p, ws.light[i - 1].si.ng, vx.sp.p);",
       "                (void)rev;")],
     ["bdpt_test", "direct_light_test"], "Bdpt"),
    ("bdpt-weight-ignores-wavelength-ratios",
     [("include/iris/render/bdpt.hpp",
       "                const float r = e[i].pe[k] / h;",
       "                const float r = e[i].pe[0] / h;"),
      ("include/iris/render/bdpt.hpp",
       "                const float r = e[sp].pl[k] / h;",
       "                const float r = e[sp].pl[0] / h;")],
     ["bdpt_test", "direct_light_test"], "Bdpt"),
    ("bdpt-counts-strategies-with-a-delta-end",
     [("include/iris/render/bdpt.hpp",
       "            return !e[sp - 1].delta && !e[sp].delta;",
       "            return true;")],
     ["bdpt_test", "direct_light_test"], "Bdpt"),
    ("bdpt-camera-density-per-pixel",
     [("include/iris/render/bdpt.hpp",
       "        sampled_spectrum<C> pdf_dir(m_camera.pdf_direction(dir) * m_inv_paths);",
       "        sampled_spectrum<C> pdf_dir(m_camera.pdf_direction(dir));")],
     ["bdpt_test", "direct_light_test"], "Bdpt"),
    ("bdpt-light-subpath-without-adjoint-eta",
     [("include/iris/render/bdpt.hpp",
       "                            f[k] *= e * e;",
       "                            (void)e;")],
     ["bdpt_test", "direct_light_test"], "Bdpt"),
    # the B term under bdpt (iris/render/propagation.hpp's bidirectional_propagation)
    ("bdpt-bterm-weighted-over-wavelengths",
     [("include/iris/render/bdpt.hpp", "            if (k == 0) out.hero = d;", "            if (k + 1 == C) out.hero = d;")],
     ["bdpt_test"], "Bdpt.TheBTerm"),
    ("bdpt-bterm-camera-connection-without-complement",
     [("include/iris/render/propagation.hpp",
       "        for (std::size_t b = 0; b < Bins; ++b) this->m_mix[b] = this->m_c[b] * this->m_g[b] * k;",
       "        for (std::size_t b = 0; b < Bins; ++b) this->m_mix[b] = this->m_g[b] * k;")],
     ["bdpt_test"], "Bdpt.TheBTerm"),
    ("bdpt-bterm-light-vertex-without-reflectance",
     [("include/iris/render/propagation.hpp",
       "            for (std::size_t b = 0; b < Bins; ++b) this->m_g[b] = t[b] * this->m_refl[b] * g;",
       "            for (std::size_t b = 0; b < Bins; ++b) this->m_g[b] = t[b] * g;")],
     ["bdpt_test"], "Bdpt.TheBTerm"),
    ("bdpt-bterm-light-subpath-without-roulette-division",
     [("include/iris/render/bdpt.hpp",
       "                    beta /= survive;\n                    lterm.survive(survive);",
       "                    beta /= survive;")],
     ["bdpt_test"], "Bdpt.TheBTerm|Bdpt.EveryPresetKeepsTheFurnace"),
    ("film-pass-skips-pixels-without-splats",
     [("include/iris/render/film.hpp", "        for (std::size_t i = 0; i < n; ++i) {\n            ++m_count[i];\n            const exact_xyz& t = m_pass[i];",
       "        for (std::size_t i = 0; i < n; ++i) {\n            if (m_pass[i] == exact_xyz{}) continue;\n            ++m_count[i];\n            const exact_xyz& t = m_pass[i];")],
     ["render_test"], "Film.*"),
    # the pbrt-v4 importer and exporter (docs/pbrt-import.md, docs/pbrt-export.md)
    ("pbrt-import-no-mirror-of-a-left-handed-camera",
     [("modules/scene/src/pbrt_import.cpp",
       "if (glm::dot(glm::cross(dir, up), right) < 0.0) m_mirror",
       "if (glm::dot(glm::cross(dir, up), right) > 1e30) m_mirror")],
     ["scene_test"], "PbrtImport"),
    ("pbrt-import-light-luminance-not-divided-out",
     [("modules/scene/src/pbrt_import.cpp", "            k = scale / y;", "            k = scale;")],
     ["scene_test"], "PbrtImport"),
    ("pbrt-import-reverse-orientation-ignored",
     [("modules/scene/src/pbrt_import.cpp", "        s.flip = m_state.reverse_orientation;", "        s.flip = false;")],
     ["scene_test"], "PbrtImport"),
    ("pbrt-import-roughness-not-remapped",
     [("modules/scene/src/pbrt_import.cpp", "const double alpha = remap ? std::sqrt(x) : x;", "const double alpha = x;\n        (void)remap;")],
     ["scene_test"], "PbrtImport"),
    ("pbrt-import-unread-parameters-accepted",
     [("modules/scene/src/pbrt_import.cpp", "            if (!p.used)\n                fail(p.at,", "            if (false)\n                fail(p.at,")],
     ["scene_test"], "PbrtImport"),
    ("pbrt-export-light-scale-photometric",
     [("modules/scene/src/export_pbrt.cpp", "    const double y = luminance(inside);", "    const double y = spectrum_to_xyz(inside).y;")],
     ["scene_test"], "PbrtExport|PbrtImport"),
    ("pbrt-export-fov-always-vertical",
     [("modules/scene/src/export_pbrt.cpp", "    if (c.height > c.width)\n", "    if (false)\n")],
     ["scene_test"], "PbrtExport"),
]


def run(cmd):
    return subprocess.run(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode


def main():
    wanted = sys.argv[1:]
    chosen = [m for m in MUTATIONS if not wanted or any(w in m[0] for w in wanted)]
    results, touched = [], set()
    for name, edits, targets, regex in chosen:
        originals = {}
        stale = False
        for path, old, new in edits:
            f = ROOT / path
            text = originals.get(path, f.read_text())
            originals.setdefault(path, text)
            current = f.read_text()
            if current.count(old) != 1:
                stale = True
                break
            f.write_text(current.replace(old, new))
        try:
            if stale:
                verdict = "STALE"
            elif run(["cmake", "--build", str(BUILD), "--target", *targets]) != 0:
                verdict = "CAUGHT (does not build)"
            else:
                verdict = "SURVIVED" if run(["ctest", "--test-dir", str(BUILD), "-R", regex]) == 0 else "CAUGHT"
        finally:
            for path, text in originals.items():
                (ROOT / path).write_text(text)
        touched.update(targets)
        results.append((name, verdict, regex))
        print(f"{verdict:24} {name}  (tests: {regex})", flush=True)
    run(["cmake", "--build", str(BUILD), "--target", *sorted(touched)])  # the restored sources
    survived = [r for r in results if r[1] in ("SURVIVED", "STALE")]
    print(f"{len(results) - len(survived)} of {len(results)} caught")
    return 1 if survived else 0


if __name__ == "__main__":
    sys.exit(main())
