"""Every example in examples/python runs to the end and writes what it says
(small beam counts; the CPU reference)."""

import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "python"


def run(script, *args):
    done = subprocess.run([sys.executable, str(EXAMPLES / script), *args], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def is_png(path):
    return path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_blackbody_sweep(tmp_path):
    out = tmp_path / "sweep.png"
    run("blackbody_sweep.py", "--out", str(out), "--beams", "20000", "--device", "cpu")
    assert is_png(out)


def test_spectral_cube_slice(tmp_path):
    out = tmp_path / "slice.png"
    run("spectral_cube_slice.py", "--out", str(out), "--beams", "100000", "--device", "cpu")
    assert is_png(out)


def test_shard_and_merge(tmp_path):
    run("shard_and_merge.py", "--shards", "3", "--beams", "60000", "--dir", str(tmp_path), "--device", "cpu")
    assert len(list(tmp_path.glob("*.state"))) == 3
