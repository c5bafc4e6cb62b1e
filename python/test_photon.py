"""The Python module against photon-render: the same image bit for bit, scenes as dicts and JSON
text, the CLI's messages as exceptions, progressive rendering. Run by ctest (python/CMakeLists.txt)
with PYTHONPATH at the module and PHOTON_RENDER, PHOTON_SCENES_DIR set."""
import json
import os
import signal
import subprocess

import numpy as np
import pytest

import photon

SCENES = os.environ.get("PHOTON_SCENES_DIR", os.path.join(os.path.dirname(__file__), "..", "scenes"))
CORNELL = os.path.join(SCENES, "cornell.json")
SMALL = dict(backend="cpu", width=48, height=36, photons=4000, frames=2, deterministic=True, seed=7)


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    assert kind == b"PF"
    return data.reshape(height, width, 3)[::-1]  # PFM rows run from the bottom


def test_render_equals_photon_render_bit_for_bit(tmp_path):
    image = photon.render(CORNELL, **SMALL)
    assert image.shape == (36, 48, 3) and image.dtype == np.float32
    # A view of the readback's own vec4 pixels (no copy after it): strided, its base the owner.
    assert image.strides == (48 * 16, 16, 4) and not image.flags.c_contiguous and not image.flags.owndata
    assert image.base is not None
    out = tmp_path / "cli.pfm"
    args = [os.environ["PHOTON_RENDER"], CORNELL, "-q", "-o", str(out)]
    for key, value in SMALL.items():
        flag = "--" + key.replace("_", "-")
        args += [flag] if value is True else [flag, str(value)]
    subprocess.run(args, check=True)
    assert np.array_equal(image, read_pfm(out))


def test_a_dict_and_json_text_equal_the_file():
    with open(CORNELL) as f:
        scene = json.load(f)
    from_file = photon.render(CORNELL, **SMALL)
    assert np.array_equal(photon.render(scene, **SMALL), from_file)
    assert np.array_equal(photon.render(json.dumps(scene), **SMALL), from_file)


@pytest.mark.parametrize(
    "scene, kwargs, message",
    [
        (CORNELL, dict(photons=-1), "photons: must be"),
        (CORNELL, dict(estimator="nearest"), "estimator: unknown value"),
        (CORNELL, dict(colour=3), "colour: no such keyword"),
        (CORNELL, dict(width=0), "width: must be"),  # the keyword, not the CLI's --width
        (CORNELL, dict(environment_intensity=2), "environment_intensity: only with environment"),
        (CORNELL, dict(environment=""), "environment: the path is empty"),
        (CORNELL, dict(environment="/dev/zero"), "a character device, not an environment map"),
        (CORNELL, dict(validation="maybe"), "validation: expected True or False"),
        ({"render": {"photons": float("nan")}}, {}, "<dict>/render/photons: not a finite number"),
        ({"render": {"photons": {1, 2}}}, {}, "<dict>/render/photons: a set is no JSON value"),
        ("scenes/cornell.json\0.txt", {}, "scene: the path holds a NUL character"),
        (CORNELL, dict(backend="quantum"), "unknown backend 'quantum'"),
        (CORNELL, dict(time="soon"), "time: must be a number"),
        ("no/such/scene.json", {}, "no/such/scene.json: cannot open"),
        ({"camera": {}}, {}, "<dict>: /camera"),
        ("{ not json", {}, "<json>: line 1"),
        (42, {}, "scene: expected a path, JSON text, a dict or None"),
    ],
)
def test_bad_input_raises_value_error_with_the_cli_message(scene, kwargs, message):
    with pytest.raises(ValueError, match=None) as error:
        photon.render(scene, **dict(SMALL, **kwargs))
    assert message in str(error.value)


def test_a_backend_that_cannot_run_raises_runtime_error():
    # Not compiled in, or compiled in on a machine without an NVIDIA GPU: RuntimeError naming CUDA.
    try:
        image = photon.render(CORNELL, **dict(SMALL, backend="cuda"))
    except RuntimeError as error:
        assert "CUDA" in str(error)
    else:
        assert image.shape == (36, 48, 3)  # a GPU is here


def test_ctrl_c_stops_after_the_frame_and_the_renderer_goes_on():
    renderer = photon.Renderer(CORNELL, **dict(SMALL, frames=1000))
    interrupt = lambda done, of: os.kill(os.getpid(), signal.SIGINT) if done == 2 else None
    with pytest.raises(KeyboardInterrupt):
        renderer.step(5, progress=interrupt)
    assert renderer.stats()["frames"] == 2, "the frame in flight finished; none after it"
    assert renderer.step(1) == 3


def test_progressive_steps_continue_where_they_stopped():
    settings = dict(SMALL, frames=1000)
    renderer = photon.Renderer(CORNELL, **settings)
    seen = []
    assert renderer.step(2, progress=lambda done, of: seen.append((done, of))) == 2
    assert seen == [(1, 2), (2, 2)]
    assert renderer.step(1) == 3
    whole = photon.Renderer(CORNELL, **settings)
    whole.step(3)
    assert np.array_equal(renderer.image(), whole.image()), "2 frames, then 1 more, are the 3 frames"
    stats = renderer.stats()
    assert stats["frames"] == 3 and stats["backend"] == "cpu"
    assert stats["photons"]["global"]["stored"] > 0
    assert stats["grid"]["global"]["occupied"] > 0, "the --stats file's grid statistics too"
    assert stats["scene_stats"] and "gather" in stats["stage_ms"]
    with pytest.raises(ValueError, match="aov=True"):
        renderer.aovs()
    aovs = photon.Renderer(CORNELL, **dict(settings, aov=True))
    aovs.step(1)
    assert set(aovs.aovs()) == {"albedo", "normal", "depth", "variance"}


def test_render_calls_progress_after_each_frame_and_false_cancels():
    seen = []
    image = photon.render(CORNELL, progress=lambda done, seconds: seen.append((done, seconds)), **SMALL)
    assert [done for done, _ in seen] == [1, 2]
    assert 0 < seen[0][1] <= seen[1][1], "seconds since the start, growing"
    # Returning None, 0 or [] goes on: only False itself cancels.
    falsy = iter([None, 0, []])
    assert np.array_equal(photon.render(CORNELL, progress=lambda d, s: next(falsy), **dict(SMALL, frames=3)),
                          photon.render(CORNELL, **dict(SMALL, frames=3)))
    # False after the second frame: the image of 2 frames, as the progressive renderer's after step(2).
    settings = dict(SMALL, frames=1000)
    calls = []
    cancelled = photon.render(CORNELL, progress=lambda done, s: calls.append(done) or done < 2, **settings)
    assert calls == [1, 2]
    two = photon.Renderer(CORNELL, **settings)
    assert two.step(2) == 2
    assert np.array_equal(cancelled, two.image()), "cancelled after 2 frames = the mean of 2 frames, bit for bit"
    assert not np.array_equal(cancelled, photon.render(CORNELL, **dict(SMALL, frames=3)))


def test_an_exception_in_progress_ends_the_render_and_comes_through():
    def progress(done, seconds):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        photon.render(CORNELL, progress=progress, **SMALL)


def test_step_progress_false_ends_the_step():
    renderer = photon.Renderer(CORNELL, **dict(SMALL, frames=1000))
    assert renderer.step(5, progress=lambda done, of: done < 2) == 2
    assert renderer.step(1, progress=lambda done, of: False) == 3


def test_aovs_are_views_that_outlive_the_renderer():
    renderer = photon.Renderer(CORNELL, **dict(SMALL, frames=1000, aov=True))
    renderer.step(1)
    aovs = renderer.aovs()
    del renderer
    albedo = aovs["albedo"]
    assert albedo.shape == (36, 48, 3) and albedo.strides == (48 * 16, 16, 4)
    assert np.isfinite(albedo).all() and albedo.max() > 0 and albedo.max() <= 1


def test_an_on_off_setting_takes_a_bool():
    assert np.array_equal(photon.render(CORNELL, **dict(SMALL, denoise=False)),
                          photon.render(CORNELL, **dict(SMALL, denoise="off")))
    assert np.array_equal(photon.render(CORNELL, **dict(SMALL, denoise=True)),
                          photon.render(CORNELL, **dict(SMALL, denoise="on")))


def test_write_image_writes_what_photon_render_reads(tmp_path):
    image = photon.render(CORNELL, **SMALL)
    photon.write_image(str(tmp_path / "a.pfm"), image)  # the strided view, read in place
    assert np.array_equal(read_pfm(tmp_path / "a.pfm"), image)
    assert np.array_equal(photon.read_image(str(tmp_path / "a.pfm")), image)
    photon.write_image(str(tmp_path / "a.exr"), np.ascontiguousarray(image[::-1]))  # any layout
    assert np.array_equal(photon.read_image(str(tmp_path / "a.exr")), image[::-1])
    with pytest.raises(ValueError, match="a.bmp"):
        photon.read_image(str(tmp_path / "a.bmp"))
    photon.write_image(str(tmp_path / "a.png"), image)
    assert (tmp_path / "a.png").stat().st_size > 0
    with pytest.raises(ValueError, match="unknown image format"):
        photon.write_image(str(tmp_path / "a.bmp"), image)
    with pytest.raises(ValueError, match="the image path is empty"):
        photon.write_image("", image)
    with pytest.raises(ValueError, match="not finite"):
        photon.write_image(str(tmp_path / "nan.pfm"), np.full((2, 2, 3), np.nan, np.float32))
    assert not (tmp_path / "nan.pfm").exists()
    with pytest.raises(ValueError, match=r"shape \(height, width, 3\)"):
        photon.write_image(str(tmp_path / "flat.pfm"), np.zeros((4, 4), np.float32))


def test_write_image_refuses_what_it_would_write_wrongly(tmp_path):
    rgb = np.ones((4, 4, 3), np.float32)
    for image, message in [(np.ones((4, 4, 3), np.uint8), "floats, linear radiance .got uint8"),
                           (np.ones((4, 4, 3), complex), "got complex128"),
                           (np.ones((4, 4, 4), np.float32), "got 4 channels"),
                           (np.ones((4, 4, 3), np.float16), None)]:
        if message is None:
            photon.write_image(str(tmp_path / "half.pfm"), image)  # floats of any width
        else:
            with pytest.raises(ValueError, match=message):
                photon.write_image(str(tmp_path / "x.png"), image)
    for exposure in (float("nan"), float("inf"), -1e9):
        with pytest.raises(ValueError, match="exposure: must be"):
            photon.write_image(str(tmp_path / "x.png"), rgb, exposure)
    with pytest.raises(ValueError, match="NUL"):
        photon.write_image(str(tmp_path / "x\0.png"), rgb)
    assert not (tmp_path / "x.png").exists()


def test_a_renderer_shared_by_threads_takes_turns():
    import threading
    renderer = photon.Renderer(CORNELL, **dict(SMALL, aov=True))
    errors = []

    def steps():
        try:
            for _ in range(12):
                renderer.step(1)
        except Exception as error:  # noqa: BLE001: any error fails the test below
            errors.append(error)

    worker = threading.Thread(target=steps)
    worker.start()
    reads = 0
    while worker.is_alive() or reads == 0:
        assert renderer.image().shape == (36, 48, 3)
        assert renderer.aovs()["albedo"].shape == (36, 48, 3)
        renderer.stats()
        reads += 1
    worker.join()
    assert not errors and renderer.stats()["frames"] == 12
    # Steps from two threads at once: every frame counted once.
    workers = [threading.Thread(target=lambda: renderer.step(3)) for _ in range(2)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    assert renderer.stats()["frames"] == 18


def test_a_renderer_converges_unless_told_otherwise():
    settings = {k: v for k, v in SMALL.items() if k != "frames"}
    plain, sppm, radius = (photon.Renderer(CORNELL, **dict(settings, **extra))
                           for extra in ({}, dict(estimator="sppm"), dict(estimator="radius")))
    for r in (plain, sppm, radius):
        r.step(3)
    assert np.array_equal(plain.image(), sppm.image()), "a stepped renderer takes sppm"
    assert not np.array_equal(plain.image(), radius.image())
    with pytest.raises(ValueError, match="time: a Renderer renders the frames step"):
        photon.Renderer(CORNELL, time=1)


def test_keywords_the_cli_has(tmp_path):
    # The flag's name as well as the scene-file key; environment maps; the built-in scene.
    assert np.array_equal(photon.render(CORNELL, **dict(SMALL, max_depth=3)),
                          photon.render(CORNELL, **dict(SMALL, max_eye_depth=3)))
    sky = tmp_path / "sky.exr"
    photon.write_image(str(sky), np.full((8, 16, 3), 0.5, np.float32))
    lit = photon.render(CORNELL, **dict(SMALL, environment=sky))
    brighter = photon.render(CORNELL, **dict(SMALL, environment=str(sky), environment_intensity=4))
    assert brighter.mean() > lit.mean() > 0
    out = tmp_path / "builtin.pfm"
    args = [os.environ["PHOTON_RENDER"], "-q", "-o", str(out)]
    for key, value in SMALL.items():
        args += ["--" + key] if value is True else ["--" + key, str(value)]
    subprocess.run(args, check=True)
    assert np.array_equal(photon.render(None, **SMALL), read_pfm(out)), "None: the built-in Cornell box"
    assert photon.__version__.count(".") == 2


def test_numpy_values_in_a_dict_scene():
    with open(CORNELL) as f:
        scene = json.load(f)
    scene["camera"]["fov"] = np.float32(scene["camera"]["fov"])
    scene["camera"]["position"] = np.array(scene["camera"]["position"], np.float64)
    assert np.array_equal(photon.render(scene, **SMALL), photon.render(CORNELL, **SMALL))


def test_what_the_loaders_notice_comes_as_warnings(tmp_path):
    model = tmp_path / "sliver.obj"
    model.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n")  # the second has no area
    with pytest.warns(UserWarning, match="dropped"):
        photon.render(str(model), **SMALL)
    with pytest.warns(UserWarning, match="nearly black"):
        photon.render(CORNELL, **dict(SMALL, exposure=-40))


def test_progress_numpy_false_cancels_and_ctrl_c_keeps_the_image():
    settings = dict(SMALL, frames=1000)
    calls = []
    photon.render(CORNELL, progress=lambda done, s: calls.append(done) or np.bool_(done < 2), **settings)
    assert calls == [1, 2]
    interrupt = lambda done, s: os.kill(os.getpid(), signal.SIGINT) if done == 2 else None
    with pytest.raises(KeyboardInterrupt) as stopped:
        photon.render(CORNELL, progress=interrupt, **settings)
    two = photon.Renderer(CORNELL, **settings)
    two.step(2)
    assert np.array_equal(stopped.value.image, two.image()), "the interrupted render's frames, on the exception"


def test_devices_lists_the_cpu():
    assert "cpu" in photon.devices()
