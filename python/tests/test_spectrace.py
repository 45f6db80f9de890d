"""The Python module against the CLI: the same numbers, errors, states,
sessions and interrupts. Run by ctest (python_tests) with PYTHONPATH at
build/python and SPECTRACE_CLI at the CLI built beside it."""

import json
import os
import resource
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

import spectrace

REPO = Path(__file__).resolve().parents[2]
CLI = os.environ.get("SPECTRACE_CLI", str(REPO / "build" / "spectrace"))
LAMP = REPO / "scenes" / "batch" / "lamp.json"
DEVICES = ["cpu", "gpu"]


def lamp_dict():
    return json.loads(LAMP.read_text())


def cli_render(tmp_path, scene, device, *extra):
    out = tmp_path / f"cli_{device}.exr"
    subprocess.run([CLI, "render", str(scene), "--device", device, "-o", str(out), "--no-png", *extra],
                   check=True, capture_output=True)
    return spectrace._spectrace._read_exr(str(out))


def assert_same_image(result, exr, spectral=False):
    for name in ("xyz", "rgb", "irradiance", "error"):
        a, b = getattr(result, name), getattr(exr, name)
        assert a.dtype == np.float32 and a.shape == b.shape, name
        # Bit for bit: the same float32 bits, NaN never expected.
        assert np.array_equal(a.view(np.uint32), b.view(np.uint32)), name
    if spectral:
        assert np.array_equal(result.spectral.view(np.uint32), exr.spectral.view(np.uint32))
        assert np.array_equal(result.wavelengths_nm, exr.wavelengths_nm)


@pytest.mark.parametrize("device", DEVICES)
def test_file_scene_equals_the_cli_exr_bit_for_bit(tmp_path, device):
    exr = cli_render(tmp_path, LAMP, device, "--beams", "100000", "--seed", "7", "--spectral")
    result = spectrace.render(LAMP, beams=100000, seed=7, device=device, spectral=True)
    assert result.beams == 100000 and result.seed == 7
    assert result.irradiance.shape == (64, 96) and result.xyz.shape == (64, 96, 3)
    assert result.spectral.shape == (64, 96, 40) and result.wavelengths_nm.shape == (40,)
    assert result.irradiance.sum() > 0
    assert_same_image(result, exr, spectral=True)


@pytest.mark.parametrize("device", DEVICES)
def test_dict_scene_equals_the_cli_exr_bit_for_bit(tmp_path, device):
    scene = lamp_dict()
    scene["lights"][0]["spd"] = {"blackbody_k": 5000}
    path = tmp_path / "lamp5000.json"
    path.write_text(json.dumps(scene))
    exr = cli_render(tmp_path, path, device, "--beams", "50000")
    assert_same_image(spectrace.render(scene, beams=50000, device=device), exr)


def test_write_exr_writes_what_the_cli_writes(tmp_path):
    result = spectrace.render(str(LAMP), beams=20000, device="cpu")
    out = tmp_path / "sub" / "lamp.exr"
    result.write_exr(out)
    assert out.exists() and out.with_suffix(".png").exists()
    assert_same_image(result, spectrace._spectrace._read_exr(str(out)))
    with pytest.raises(OSError):
        result.write_exr(LAMP.with_suffix(".exr").parent / "lamp.json")  # an input, and not .exr


def test_a_bad_dict_raises_scene_error_naming_the_field(tmp_path):
    scene = lamp_dict()
    scene["lights"][0]["power_w"] = -1
    with pytest.raises(spectrace.SceneError) as caught:
        spectrace.render(scene, beams=1000, device="cpu", base_dir=tmp_path)
    error = caught.value
    assert isinstance(error, ValueError)
    assert error.pointer == "/lights/0/power_w"
    assert "power_w" not in error.message and error.message  # what is wrong, without the pointer
    assert error.file.endswith("<dict>")
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_scene_errors_have_the_cli_text(tmp_path):
    path = tmp_path / "bad.json"
    scene = lamp_dict()
    scene["camera"]["sensor"]["pixels"] = [0, 64]
    path.write_text(json.dumps(scene))
    cli = subprocess.run([CLI, "render", str(path), "--device", "cpu"], capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(spectrace.SceneError) as caught:
        spectrace.render(path, device="cpu")
    assert str(caught.value) in cli.stderr
    assert caught.value.pointer == "/camera/sensor/pixels/0"


def test_missing_files_are_os_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        spectrace.render(tmp_path / "none.json", device="cpu")
    with pytest.raises(FileNotFoundError):
        spectrace.load_state(str(tmp_path / "none.state"))
    (tmp_path / "bad.state").write_bytes(b"not a state")
    with pytest.raises(spectrace.StateError):
        spectrace.load_state(tmp_path / "bad.state")


def test_relative_files_in_a_dict_resolve_against_base_dir(tmp_path):
    (tmp_path / "flat.csv").write_text("wavelength_nm,value\n380,1\n780,1\n")
    scene = lamp_dict()
    scene["lights"][0]["spd"] = {"csv": "flat.csv"}
    result = spectrace.render(scene, beams=2000, device="cpu", base_dir=tmp_path)
    assert result.beams == 2000
    with pytest.raises(spectrace.SceneError):
        spectrace.render(scene, beams=2000, device="cpu", base_dir=REPO)


def test_json_text_renders_like_the_dict():
    scene = lamp_dict()
    a = spectrace.render(json.dumps(scene), beams=20000, device="cpu")
    b = spectrace.render(scene, beams=20000, device="cpu")
    assert np.array_equal(a.xyz, b.xyz)


def test_arrays_are_read_only_and_outlive_their_result():
    xyz = spectrace.render(LAMP, beams=5000, device="cpu").xyz
    assert not xyz.flags.writeable
    assert np.isfinite(xyz).all()


def test_sweep_yields_the_product_in_order_as_the_cli_set_renders_it(tmp_path):
    temps, powers = [2000, 6500], [1, 2]
    with spectrace.Session("cpu") as session:
        results = list(session.sweep(LAMP, {"/lights/0/spd/blackbody_k": temps, "/lights/0/power_w": powers},
                                     beams=20000))
    assert [o for o, _ in results] == [{"/lights/0/spd/blackbody_k": t, "/lights/0/power_w": p}
                                       for t in temps for p in powers]
    # Twice the power, the same beams: exactly twice the irradiance.
    assert np.array_equal(results[1][1].irradiance, 2 * results[0][1].irradiance)
    exr = cli_render(tmp_path, LAMP, "cpu", "--beams", "20000", "--set", "/lights/0/spd/blackbody_k=6500",
                     "--set", "/lights/0/power_w=2")
    assert_same_image(results[3][1], exr)


def test_state_saves_loads_and_develops_to_the_same_image(tmp_path):
    result = spectrace.render(LAMP, beams=30000, device="cpu")
    state = result.state
    assert state.beams == 30000 and state.ranges == [(0, 30000)]
    counts = state.counts
    assert counts.dtype == np.uint64 and counts.shape[:3] == (64, 96, 40) and not counts.flags.writeable
    assert counts.sum() > 0
    state.save(tmp_path / "a.state")
    loaded = spectrace.load_state(tmp_path / "a.state")
    assert np.array_equal(loaded.counts, counts)
    assert_same_image(loaded.develop(device="cpu"), result)


def test_shards_merge_exactly_and_overlaps_are_refused():
    with spectrace.Session("cpu") as session:
        whole = session.render(LAMP, beams=40000)
        first = session.render(LAMP, beams=25000)
        second = session.render(LAMP, beams=15000, first_beam=25000)
        merged = spectrace.merge([second.state, first.state])
        assert merged.ranges == [(0, 25000), (25000, 15000)] and merged.beams == 40000
        assert np.array_equal(merged.counts, whole.state.counts)
        assert_same_image(session.develop(merged), whole)
        with pytest.raises(spectrace.StateError):
            spectrace.merge([first.state, whole.state])  # beams 0..25000 twice


def test_devices_lists_the_cpu_reference_last():
    listed = spectrace.devices()
    assert listed[-1]["kind"] == "cpu" and listed[-1]["usable"]
    assert sum(d["used_by_device_auto"] for d in listed) == 1


def test_progress_is_called_between_batches():
    calls = []
    spectrace.render(LAMP, beams=200000, device="cpu", progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (200000, 200000)
    assert all(b[0] >= a[0] for a, b in zip(calls, calls[1:]))


def test_an_exception_in_progress_stops_the_render_and_the_session_stays_usable():
    def stop(done, total):
        raise RuntimeError("stop here")

    with spectrace.Session("cpu") as session:
        with pytest.raises(RuntimeError, match="stop here"):
            session.render(LAMP, beams=10**9, progress=stop)
        assert session.render(LAMP, beams=1000).beams == 1000


def test_ctrl_c_stops_a_render_within_a_second(tmp_path):
    script = textwrap.dedent(f"""
        import sys, time, spectrace
        session = spectrace.Session("cpu")
        print("ready", flush=True)
        start = time.monotonic()
        try:
            session.render({str(LAMP)!r}, beams=10**12)
        except KeyboardInterrupt:
            print("interrupted after", time.monotonic() - start, flush=True)
        print("after", session.render({str(LAMP)!r}, beams=1000).beams, flush=True)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                             env=dict(os.environ))
    assert child.stdout.readline().strip() == "ready"
    time.sleep(1.5)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert "interrupted after" in out, out
    assert time.monotonic() - sent < 5.0  # "about a second", with the machine's noise
    assert "after 1000" in out


def test_a_thousand_renders_grow_memory_by_less_than_10_mib():
    scene = lamp_dict()
    scene["camera"]["sensor"]["pixels"] = [16, 16]
    with spectrace.Session("cpu") as session:
        for _ in range(50):  # allocator pools and caches settle first
            session.render(scene, beams=1000).xyz
        before = resident_bytes()
        for _ in range(1000):
            session.render(scene, beams=1000).xyz
        grown = resident_bytes() - before
    assert grown < 10 * 2**20, f"{grown / 2**20:.1f} MiB"


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()


def test_version():
    assert spectrace.__version__.count(".") == 2
