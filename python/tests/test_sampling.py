"""The sampling layer, spectra and metrics from Python: the same numbers as the command
line's tools (docs/python.md)."""
import json
import os
import subprocess

import numpy as np
import pytest

import iris

IRIS_SPECTRUM = os.environ.get("IRIS_SPECTRUM", "iris-spectrum")
IRIS_IMAGE = os.environ.get("IRIS_IMAGE", "iris-image")
IRIS_RENDER = os.environ.get("IRIS_RENDER", "iris-render")


def csv(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout.splitlines()[1:]
    return np.array([[float(x) for x in line.split(",")] for line in out])


def test_presets_and_samplers():
    names = [p["name"] for p in iris.presets()]
    assert names[:2] == ["hwss", "paper"]
    paper = iris.presets()[1]
    assert paper["config"] == "multibox3/linear/C4/propagate" and paper["wavelengths"] == 4
    assert iris.samplers()[0] == "sobol" and "zsobol" in iris.samplers()
    assert iris.estimators()[0] == "nee-mis"


@pytest.mark.parametrize("preset,alpha", [("paper", 0.0), ("paper", 0.4), ("gaussian", 0.7), ("hwss", 1.0)])
def test_pdf_is_iris_spectrum_pdf(preset, alpha):
    lam, p = iris.pdf(preset, alpha)
    ref = csv([IRIS_SPECTRUM, "pdf", "--preset", preset, "--alpha", str(alpha)])
    assert np.array_equal(lam, ref[:, 0])
    assert np.allclose(p, ref[:, 1], rtol=1e-6, atol=0)  # the CLI prints 6+ digits
    # a density on 380–780 nm: midpoint sums at 0.01 nm (each of the ≤ 6 box edges adds at
    # most height · 0.005 nm ≤ 1e-4 of error)
    mid = np.arange(380.005, 780.0, 0.01)
    _, fine = iris.pdf(preset, alpha, mid)
    assert abs(fine.sum() * 0.01 - 1.0) < 1e-3
    lam2, p2 = iris.pdf(preset, alpha, [500.0, 610.0])
    assert np.array_equal(lam2, [500.0, 610.0]) and np.allclose(p2, np.interp(lam2, lam, p), rtol=1e-6)


def test_sample_wavelengths_are_iris_spectrum_sample():
    lam, pdf = iris.sample_wavelengths("paper", 0.5, 3, seed=3)
    assert lam.shape == (3, 4) and lam.dtype == np.float32
    ref = csv([IRIS_SPECTRUM, "sample", "--preset", "paper", "--alpha", "0.5", "--count", "3", "--seed", "3"])
    assert np.allclose(lam.ravel(), ref[:, 0], rtol=1e-7)
    assert np.allclose(pdf.ravel(), ref[:, 1], rtol=1e-6)


def test_sampling_arguments_are_checked():
    with pytest.raises(ValueError, match="alpha must be in"):
        iris.pdf("paper", 1.5)
    with pytest.raises(ValueError, match="unknown preset 'nope'"):
        iris.pdf("nope", 0.5)
    with pytest.raises(ValueError, match="n must be in"):
        iris.sample_wavelengths("paper", 0.5, 0)
    with pytest.raises(ValueError, match="1-D"):
        iris.pdf("paper", 0.5, [[500.0]])


def test_spectra_and_glasses():
    lam, d65 = iris.spectrum("D65")
    assert lam[0] == 380 and lam[-1] == 780 and len(lam) == 401
    assert d65[lam == 560][0] == pytest.approx(100.0, rel=1e-3)  # D65 is 100 at 560 nm
    _, bb = iris.spectrum("blackbody:5000", [300.0, 579.5, 900.0])
    assert bb.max() == pytest.approx(1.0, rel=1e-3)  # peak-normalised: Wien's peak at 579.6 nm
    assert iris.ior("N-BK7", 587.5618) == pytest.approx(1.5168, abs=1e-4)
    n = iris.ior("N-BK7", np.array([450.0, 650.0]))
    assert n.shape == (2,) and n[0] > n[1]
    assert "N-BK7" in iris.glasses() and ("Au", "gold (Johnson & Christy 1972)") in iris.metals()
    with pytest.raises(ValueError, match="unknown glass 'BK-7'"):
        iris.ior("BK-7", 500.0)
    with pytest.raises(ValueError, match="unknown spectrum 'D66'"):
        iris.spectrum("D66")
    with pytest.raises(ValueError, match="blackbody temperature"):
        iris.spectrum("blackbody:hot")


def test_metrics_are_iris_image_diff(tmp_path):
    paths = []
    for seed in (1, 2):
        p = tmp_path / f"s{seed}.exr"
        subprocess.run([IRIS_RENDER, "cornell", "--spp", "2", "--width", "48", "--height", "36", "--seed", str(seed),
                        "-o", str(p)], check=True, capture_output=True)
        paths.append(p)
    ref = json.loads(subprocess.run([IRIS_IMAGE, "diff", str(paths[0]), str(paths[1]), "--json"], check=True,
                                    capture_output=True, text=True).stdout)
    a, _ = iris.read_image(paths[0])
    b, _ = iris.read_image(paths[1])
    assert iris.mse(a, b) == pytest.approx(ref["mse"], rel=1e-12)
    assert iris.relmse(a, b) == pytest.approx(ref["relmse"], rel=1e-12)
    assert iris.ssim(a, b) == pytest.approx(ref["ssim"], rel=1e-12)
    assert iris.mse(a, a) == 0.0 and iris.ssim(a, a) == pytest.approx(1.0)
    split = iris.bias_variance([a, b], (a + b) / 2)
    assert split["runs"] == 2 and split["variance"] > 0
    assert iris.mse(a.astype(np.float64), b) == iris.mse(a, b)  # any float array, converted


def test_metric_arguments_are_checked():
    a = np.zeros((12, 12, 3), np.float32)
    with pytest.raises(ValueError, match=r"\(H, W, 3\) array of RGB, got shape \(12, 12\)"):
        iris.mse(a[:, :, 0], a)
    with pytest.raises(ValueError, match="size"):
        iris.mse(a, np.zeros((12, 13, 3)))
    with pytest.raises(TypeError):
        iris.ssim("a", a)
    with pytest.raises(ValueError, match="at least 2 runs"):
        iris.bias_variance([a], a)
