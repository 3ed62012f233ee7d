# Tests of the Python module (src/python/module.cpp, docs/python.md): loading and its errors,
# rendering with keyword options and their validation, arrays' shapes and dtypes, layers and AOVs,
# bit-identity with `phos render`, determinism over seeds and threads, progress callbacks, Ctrl-C,
# the GIL released while rendering, several renders in one process, read / write / diff, and the
# photon maps as arrays. Run by ctest (Python.pytest) with PYTHONPATH at build/python.
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import phos

SOURCE = os.environ.get("PHOS_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("PHOS_BINARY", os.path.join(SOURCE, "build", "phos"))
CORNELL = os.path.join(SOURCE, "scenes", "cornell-diffuse.scn")
SMALL = dict(width=32, height=32, quiet=True)


@pytest.fixture(scope="module")
def cornell():
    return phos.load(CORNELL)


def test_load_gives_a_scene(cornell):
    assert cornell.path == CORNELL
    assert "cornell-diffuse.scn" in repr(cornell)


def test_a_malformed_scene_raises_scene_error_with_its_location(tmp_path):
    bad = tmp_path / "bad.scn"
    bad.write_text("camera 0 0 5  0 0 0  0 1 0  0.5\nsphere 0 0 0 oops\n")
    with pytest.raises(phos.SceneError) as e:
        phos.load(str(bad))
    assert e.value.file.endswith("bad.scn")
    assert e.value.line == 2
    assert e.value.column > 0
    assert e.value.message
    assert str(e.value).startswith(e.value.file + ":2:")


def test_a_missing_scene_raises_scene_error(tmp_path):
    with pytest.raises(phos.SceneError) as e:
        phos.load(str(tmp_path / "nowhere.scn"))
    assert "nowhere.scn" in str(e.value)


def test_render_returns_a_float32_image_and_statistics(cornell):
    r = phos.render(cornell, integrator="path", spp=2, **SMALL)
    assert r.image.shape == (32, 32, 3)
    assert r.image.dtype == np.float32
    assert np.isfinite(r.image).all() and r.image.mean() > 0
    assert r.integrator == "path"
    assert r.spp == 2 and r.iterations is None
    assert r.time > 0
    assert r.rays["camera"] >= 32 * 32 * 2
    assert not r.interrupted


def test_progressive_integrators_count_iterations_and_photons(cornell):
    r = phos.render(cornell, integrator="sppm", iterations=3, photons_per_iter=5000, **SMALL)
    assert r.iterations == 3 and r.spp is None
    # The photons of the estimate: sppm's first pass is a pilot that only sets the radii.
    assert r.photons in (2 * 5000, 3 * 5000)


def test_layers_and_aovs_come_back_as_arrays(cornell):
    r = phos.render(cornell, integrator="photonmap", spp=1, layers=True, aov=["albedo", "normal"], **SMALL)
    assert {"direct", "indirect", "albedo", "normal"} <= set(r.layers)
    for name, a in r.layers.items():
        assert a.shape == (32, 32, 3) and a.dtype == np.float32, name
    # The components sum to the image.
    parts = [a for n, a in r.layers.items() if n not in ("albedo", "normal")]
    assert np.allclose(sum(parts), r.image, rtol=1e-4, atol=1e-5)


def test_unknown_options_and_bad_values_raise_value_error_naming_the_option(cornell):
    with pytest.raises(ValueError, match="no_such_option"):
        phos.render(cornell, no_such_option=3)
    with pytest.raises(ValueError, match="--spp"):
        phos.render(cornell, spp=-4, **SMALL)
    with pytest.raises(ValueError, match="--integrator"):
        phos.render(cornell, integrator="raytracer", **SMALL)
    with pytest.raises(ValueError, match="--layers"):
        phos.render(cornell, layers="yes", **SMALL)


def test_a_render_is_bit_identical_to_the_command_line(cornell, tmp_path):
    out = tmp_path / "cli.pfm"
    subprocess.run([BINARY, "render", CORNELL, "--integrator", "photonmap", "--spp", "2", "--width", "32",
                    "--height", "32", "--seed", "9", "-q", "-o", str(out)], check=True)
    r = phos.render(cornell, integrator="photonmap", spp=2, seed=9, **SMALL)
    assert np.array_equal(phos.read(str(out)), r.image)


def test_renders_are_deterministic_over_runs_and_threads(cornell):
    a = phos.render(cornell, integrator="sppm", iterations=2, seed=3, threads=1, **SMALL).image
    b = phos.render(cornell, integrator="sppm", iterations=2, seed=3, threads=2, **SMALL).image
    c = phos.render(cornell, integrator="sppm", iterations=2, seed=4, threads=2, **SMALL).image
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_progress_reaches_the_callback(cornell):
    seen = []
    phos.render(cornell, integrator="path", spp=64, width=64, height=64, quiet=True,
                progress=lambda f, label: seen.append((f, label)))
    assert seen, "the callback was called"
    fractions = [f for f, _ in seen if f >= 0]
    assert all(0 <= f <= 1 for f in fractions)
    assert fractions == sorted(fractions) or len({l for _, l in seen}) > 1


def test_an_exception_in_the_callback_stops_the_render_and_is_raised(cornell):
    def stop(fraction, label):
        raise RuntimeError("enough")

    t0 = time.monotonic()
    with pytest.raises(RuntimeError, match="enough"):
        phos.render(cornell, integrator="path", time=30, width=64, height=64, quiet=True, progress=stop)
    assert time.monotonic() - t0 < 20


def test_ctrl_c_stops_the_render_and_returns_what_was_done(cornell):
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    r = phos.render(cornell, integrator="sppm", time=60, width=64, height=64, quiet=True)
    timer.join()
    assert time.monotonic() - t0 < 30
    assert r.interrupted
    assert r.image is not None and r.image.shape == (64, 64, 3) and r.image.mean() > 0
    # The next render runs normally.
    assert not phos.render(cornell, integrator="path", spp=1, **SMALL).interrupted


def test_the_gil_is_released_while_rendering(cornell):
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    phos.render(cornell, integrator="path", time=1.5, width=64, height=64, quiet=True)
    stop.set()
    t.join()
    assert len(ticks) > 100


def test_write_read_round_trips(tmp_path):
    rng = np.random.default_rng(1)
    a = rng.random((5, 7, 3), dtype=np.float32) * 4
    for ext in ("exr", "pfm"):
        path = str(tmp_path / ("x." + ext))
        phos.write(a, path)
        back = phos.read(path)
        assert back.shape == (5, 7, 3) and back.dtype == np.float32
        assert np.allclose(back, a, rtol=1e-3 if ext == "exr" else 0, atol=0), ext
    png = str(tmp_path / "x.png")
    phos.write(a / 8, png)
    assert phos.read(png).shape == (5, 7, 3)
    with pytest.raises(ValueError):
        phos.write(a, str(tmp_path / "x.unknown"))
    with pytest.raises(ValueError):
        phos.write(np.zeros((4, 4, 2)), str(tmp_path / "y.exr"))
    with pytest.raises(ValueError):
        phos.read(str(tmp_path / "missing.exr"))


def test_diff_gives_relmse_and_mean_ratio(tmp_path):
    a = np.full((4, 4, 3), 0.5, dtype=np.float32)
    d = phos.diff(a, a)
    assert d.relmse == 0 and d.mean_ratio == 1
    assert phos.diff(2 * a, a).mean_ratio == pytest.approx(2)
    path = str(tmp_path / "a.pfm")
    phos.write(a, path)
    assert phos.diff(path, a).relmse == 0
    with pytest.raises(ValueError):
        phos.diff(a, np.zeros((3, 3, 3)))


def test_photons_come_back_as_arrays(cornell):
    p = phos.photons(cornell, photons=20000)
    n = len(p.position)
    assert n > 0
    assert p.position.shape == (n, 3) and p.position.dtype == np.float32
    assert p.direction.shape == (n, 3) and p.power.shape == (n, 3)
    assert p.map.shape == (n,) and p.bounces.shape == (n,)
    assert np.allclose(np.linalg.norm(p.direction, axis=1), 1, atol=1e-2)
    # A photon's power is the colour of its four wavelengths' power: a channel may be negative
    # (a spectrum outside the sRGB gamut), its luminance Y never.
    luminance = p.power @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)
    assert (luminance >= -1e-6 * np.abs(p.power).max()).all()
    assert p.power.sum() > 0
    assert set(np.unique(p.map)) <= set(range(len(p.map_names)))
    global_only = phos.photons(cornell, maps="global", photons=20000)
    assert set(np.unique(global_only.map)) == {p.map_names.index("global")}
    with pytest.raises(ValueError):
        phos.photons(cornell, maps="nonsense")


def test_load_keeps_its_options_for_every_render():
    small = phos.load(CORNELL, width=16, height=8)
    assert phos.render(small, integrator="path", spp=1, quiet=True).image.shape == (8, 16, 3)


def test_options_and_integrators_are_listed():
    assert "photons_per_iter" in phos.options()
    assert {"path", "photonmap", "sppm", "vcm"} <= set(phos.integrators())
