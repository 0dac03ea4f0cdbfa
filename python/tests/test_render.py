"""iris.load and iris.Renderer: images equal to the command line's, bit for bit; files;
lifetime and threads; the GIL released; Ctrl-C; bad input (docs/python.md)."""
import _thread
import gc
import os
import subprocess
import threading
import time

import numpy as np
import pytest

import iris

IRIS_RENDER = os.environ.get("IRIS_RENDER", "iris-render")
W, H = 40, 30  # small: every render here takes milliseconds


@pytest.fixture(scope="module")
def cubes():
    return iris.load("falling-cubes")


def cli_render(tmp_path, name, *args):
    out = tmp_path / f"{name}.exr"
    subprocess.run([IRIS_RENDER, "falling-cubes", "--width", str(W), "--height", str(H), "--threads", "2",
                    "-o", str(out), *args], check=True, capture_output=True)
    return iris.read_image(out)


# ---- images: the numpy image is the EXR iris-render writes for the same key ------------

@pytest.mark.parametrize("preset,sampler,steps", [
    ("paper", "sobol", [1, 3]),        # the B term; passes added 1 + 3
    ("hwss", "independent", [2, 2]),
    ("paper-fade", "sobol", [3, 1]),   # a fade layer split at nthold (= 2 here)
])
def test_steps_equal_one_cli_render(tmp_path, cubes, preset, sampler, steps):
    spp = sum(steps)
    pixels, meta = cli_render(tmp_path, preset, "--preset", preset, "--sampler", sampler, "--spp", str(spp),
                              "--nthold", "2", "--seed", "7")
    r = iris.Renderer(cubes, preset=preset, sampler=sampler, seed=7, nthold=2, width=W, height=H, threads=2)
    for n in steps:
        r.step(n)
    assert r.spp == spp
    assert r.stats["samples"] == spp * W * H  # each pass rendered once: a step goes on, it does not start over
    img = r.image()
    assert img.dtype == np.float32 and img.shape == (H, W, 3)
    assert np.array_equal(img, pixels)  # bit for bit
    assert r.metadata == meta           # and the EXR's attributes


def test_zsobol_needs_its_planned_spp(tmp_path, cubes):
    pixels, _ = cli_render(tmp_path, "z", "--sampler", "zsobol", "--spp", "4")
    r = iris.Renderer(cubes, sampler="zsobol", width=W, height=H, planned_spp=4)
    r.step(2)
    r.step(2)
    assert np.array_equal(r.image(), pixels)
    with pytest.raises(ValueError, match="planned_spp"):
        r.step(1)
    with pytest.raises(ValueError, match="give planned_spp"):
        iris.Renderer(cubes, sampler="zsobol")


def test_image_kinds(cubes):
    r = iris.Renderer(cubes, width=W, height=H)
    assert not r.image().any()  # before the first pass: black
    r.step(2)
    lin, srgb, xyz = r.image("linear_srgb"), r.image("srgb"), r.image("xyz")
    assert srgb.min() >= 0.0 and srgb.max() <= 1.0
    # encoded = OETF(clamp(linear)), checked at one mid-grey-ish value
    sel = (lin > 0.01) & (lin < 0.9)
    assert sel.any()
    x = lin[sel].astype(np.float64)
    enc = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
    assert np.allclose(srgb[sel], enc, atol=1e-6)
    # xyz → linear sRGB by the sRGB matrix (IEC 61966-2-1)
    m = np.array([[3.2404542, -1.5371385, -0.4985314], [-0.9692660, 1.8760108, 0.0415560],
                  [0.0556434, -0.2040259, 1.0572252]])
    assert np.allclose(xyz @ m.T, lin, atol=1e-4)
    with pytest.raises(ValueError, match="unknown image kind 'rgb'"):
        r.image("rgb")


def test_save_writes_what_the_cli_writes(tmp_path, cubes):
    pixels, meta = cli_render(tmp_path, "cli", "--spp", "3", "--seed", "5")
    r = iris.Renderer(cubes, seed=5, width=W, height=H)
    r.step(3)
    r.save(tmp_path / "py.exr")
    assert (tmp_path / "py.exr").read_bytes() == (tmp_path / "cli.exr").read_bytes()
    r.save(str(tmp_path / "py.png"))
    assert (tmp_path / "py.png").stat().st_size > 0
    with pytest.raises(ValueError, match=".exr"):
        r.save(tmp_path / "out.tiff")
    with pytest.raises(RuntimeError, match="nothing to save"):
        iris.Renderer(cubes).save(tmp_path / "empty.exr")


def test_checkpoint_resume_equals_uninterrupted(tmp_path, cubes):
    ref = iris.Renderer(cubes, preset="paper-fade", nthold=3, width=W, height=H)
    ref.step(5)
    a = iris.Renderer(cubes, preset="paper-fade", nthold=3, width=W, height=H)
    a.step(2)
    a.save_checkpoint(tmp_path / "a.ckpt")
    c = iris.read_checkpoint(tmp_path / "a.ckpt")
    assert c["spp"] == 2 and c["preset"] == "paper-fade" and c["width"] == W
    assert np.array_equal(c["image"], a.image())
    b = iris.Renderer(cubes, preset="paper-fade", nthold=3, width=W, height=H, resume=tmp_path / "a.ckpt")
    assert b.spp == 2
    b.step(3)
    assert np.array_equal(b.image(), ref.image())
    with pytest.raises(ValueError, match="another render: its seed is 1, this render's is 2"):
        iris.Renderer(cubes, preset="paper-fade", nthold=3, width=W, height=H, seed=2, resume=tmp_path / "a.ckpt")
    (tmp_path / "bad.ckpt").write_bytes(b"not a checkpoint")
    with pytest.raises(RuntimeError, match="bad.ckpt"):
        iris.read_checkpoint(tmp_path / "bad.ckpt")
    with pytest.raises(FileNotFoundError):
        iris.read_checkpoint(tmp_path / "missing.ckpt")


# ---- spectral output -------------------------------------------------------------------

def test_spectral_image_is_what_the_cli_writes(tmp_path, cubes):
    # the numpy spectrum, iris-render --spectral's EXR channels and Renderer.save's file:
    # bit for bit, with the same RGB as without the layer
    cli_render(tmp_path, "spec", "--preset", "paper", "--spp", "3", "--spectral", "8")
    nm_cli, values_cli = iris.read_spectral(tmp_path / "spec.exr")
    r = iris.Renderer(cubes, preset="paper", width=W, height=H, spectral=8)
    assert r.image("spectral").shape == (H, W, 8) and not r.image("spectral").any()  # before the first pass
    r.step(1)
    r.step(2)
    s = r.image("spectral")
    assert s.dtype == np.float32 and s.shape == (H, W, 8)
    assert np.array_equal(r.wavelengths, nm_cli) and nm_cli[0] == 380 + 25 and nm_cli[-1] == 780 - 25
    assert np.array_equal(s, values_cli)
    assert s.min() >= 0 and s.max() > 0
    r.save(tmp_path / "py.exr")
    assert (tmp_path / "py.exr").read_bytes() == (tmp_path / "spec.exr").read_bytes()
    plain = iris.Renderer(cubes, preset="paper", width=W, height=H)
    plain.step(3)
    assert np.array_equal(plain.image(), r.image())
    assert plain.wavelengths is None
    with pytest.raises(ValueError, match="no spectral output"):
        plain.image("spectral")
    with pytest.raises(ValueError, match="no spectral channels"):
        plain.save(tmp_path / "plain.exr")
        iris.read_spectral(tmp_path / "plain.exr")
    r.save_checkpoint(tmp_path / "s.ckpt")
    c = iris.read_checkpoint(tmp_path / "s.ckpt")
    assert c["spectral_bins"] == 8 and np.array_equal(c["spectral"], s)
    b = iris.Renderer(cubes, preset="paper", width=W, height=H, spectral=8, resume=tmp_path / "s.ckpt")
    assert np.array_equal(b.image("spectral"), s)
    with pytest.raises(ValueError, match="its spectral_bins is 8, this render's is 4"):
        iris.Renderer(cubes, preset="paper", width=W, height=H, spectral=4, resume=tmp_path / "s.ckpt")
    with pytest.raises(ValueError, match="splats onto other pixels"):
        iris.Renderer(cubes, estimator="bdpt", spectral=4)
    with pytest.raises(ValueError, match="spectral bins must be 0"):
        iris.Renderer(cubes, spectral=-1)


# ---- one scene, many renders --------------------------------------------------------

def test_scene_outlives_its_name(cubes):
    scene = iris.load("falling-cubes")
    r = iris.Renderer(scene, width=W, height=H)
    ref = iris.Renderer(cubes, width=W, height=H)
    del scene
    gc.collect()
    r.step(2)
    ref.step(2)
    assert np.array_equal(r.image(), ref.image())
    assert r.scene.name == "falling-cubes"


def test_two_renderers_on_one_scene_in_two_threads(cubes):
    keys = [dict(preset="paper", seed=1), dict(preset="hwss", seed=2)]
    alone = []
    for k in keys:
        r = iris.Renderer(cubes, width=W, height=H, threads=1, **k)
        r.step(6)
        alone.append(r.image())
    together = [iris.Renderer(cubes, width=W, height=H, threads=1, **k) for k in keys]
    threads = [threading.Thread(target=lambda r=r: r.step(6)) for r in together]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r, img in zip(together, alone):
        assert np.array_equal(r.image(), img)


def test_the_gil_is_released_while_rendering(cubes):
    count = 0
    stop = False

    def spin():
        nonlocal count
        while not stop:
            count += 1

    r = iris.Renderer(cubes, preset="paper", width=160, height=120, threads=1)
    r.step(1)  # warm
    t = threading.Thread(target=spin)
    t.start()
    time.sleep(0.05)
    before = count
    start = time.perf_counter()
    r.step(8)
    seconds = time.perf_counter() - start
    during = count - before
    stop = True
    t.join()
    # Holding the GIL, step() would let the spinning thread run only at its start (one
    # switch interval, 5 ms): at most a few 10⁴ increments. Released, it spins the whole
    # render (≥ 0.1 s here at ≥ 10⁶ increments/s).
    assert seconds > 0.1, "the render is too short to tell"
    assert during > 100_000 * seconds * 10


def test_keyboard_interrupt_stops_after_the_pass_and_keeps_it(cubes):
    r = iris.Renderer(cubes, width=W, height=H, threads=1)
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        r.step(1_000_000)
    timer.join()
    done = r.spp
    assert 0 < done < 1_000_000
    r.step(1)  # still usable
    ref = iris.Renderer(cubes, width=W, height=H)
    ref.step(done + 1)
    assert np.array_equal(r.image(), ref.image())


def test_a_renderer_is_used_by_one_thread_at_a_time(cubes):
    r = iris.Renderer(cubes, width=160, height=120, threads=1)
    errors = []

    def second():
        time.sleep(0.05)
        for use in (lambda: r.step(1), r.image, lambda: r.stats):  # neither a step nor a read of the film in flight
            try:
                use()
            except RuntimeError as e:
                errors.append(str(e))

    t = threading.Thread(target=second)
    t.start()
    r.step(40)
    t.join()
    assert len(errors) == 3 and all("rendering in another thread" in e for e in errors), errors


# ---- bad input: Python exceptions with the command line's messages -------------------

def test_load_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="neither a scene file nor a built-in scene"):
        iris.load("no-such-scene")
    with pytest.raises(FileNotFoundError):
        iris.load(tmp_path / "missing.json")
    with pytest.raises(TypeError, match="iris.load expects"):
        iris.load(42)
    bad = tmp_path / "bad.json"
    bad.write_text('{"camera": {"fov": "wide"}}')
    with pytest.raises(ValueError, match="bad.json"):
        iris.load(bad)
    with pytest.raises(ValueError, match="<dict>"):
        iris.load({"camera": 3})
    pbrt = tmp_path / "bad.pbrt"
    pbrt.write_text('WorldBegin\nShape "teapot"\n')
    with pytest.raises(ValueError, match=r"bad.pbrt:2:\d+"):
        iris.load(pbrt)


def test_a_dict_scene_renders_like_its_file(tmp_path):
    import json
    here = os.path.dirname(__file__)
    text = open(os.path.join(here, "..", "..", "data", "scenes", "cornell.json")).read()
    from_dict = iris.load(json.loads(text))
    from_name = iris.load("cornell")
    assert from_dict.fingerprint == from_name.fingerprint
    assert from_dict.triangles == from_name.triangles > 0


@pytest.mark.parametrize("kwargs,message", [
    (dict(preset="nope"), "unknown preset 'nope'"),
    (dict(sampler="halton"), "unknown sampler 'halton'"),
    (dict(estimator="mlt"), "unknown estimator 'mlt'"),
    (dict(nthold=0), "nthold must be >= 1"),
    (dict(threads=-1), "threads must be >= 0"),
    (dict(width=10), "width and height"),
    (dict(max_depth=0), "max_depth must be in 1..10000"),
    (dict(isa="avx9"), "unknown instruction set"),
    (dict(planned_spp=-1), "planned_spp must be >= 0"),
])
def test_renderer_arguments_are_checked(cubes, kwargs, message):
    with pytest.raises(ValueError, match=message):
        iris.Renderer(cubes, **kwargs)


def test_wrong_types_are_type_errors(cubes):
    with pytest.raises(TypeError):
        iris.Renderer("falling-cubes")
    with pytest.raises(TypeError):
        iris.Renderer(cubes, seed=-1)
    with pytest.raises(TypeError):
        iris.Renderer(cubes, preset=3)
    r = iris.Renderer(cubes, width=W, height=H)
    with pytest.raises(ValueError, match="spp >= 1"):
        r.step(0)
    with pytest.raises(TypeError):
        r.step("many")


def test_stats(cubes):
    r = iris.Renderer(cubes, preset="paper", width=W, height=H, threads=2)
    r.step(3)
    s = r.stats
    assert s["spp"] == 3 and s["samples"] == 3 * W * H and s["rays"] >= s["samples"]
    assert s["nan_inf"] == 0 and s["seconds"] > 0 and s["config"] == "multibox3/linear/C4/propagate"
    assert s["windows"] == "464:20,549:20,611:20"
