"""spectrace from Python: render scenes given as dicts, JSON text or files, and
read their images and spectra as numpy arrays.

    import spectrace
    result = spectrace.render("scenes/default.json", beams=1_000_000, device="cpu")
    result.xyz          # (H, W, 3) float32, Y in lux: the EXR's XYZ channels
    result.write_exr("out/default.exr")

The work is done by the C++ library the CLI uses (spectrace._spectrace): the
same scene reader, devices, film and resolve, so the arrays equal the CLI's
EXR channels bit for bit. This file only shapes arguments and errors.
"""

from __future__ import annotations

import errno
import itertools
import json
import os
from typing import Any, Callable, Iterator, Mapping, Optional, Sequence, Union

from . import _spectrace

__version__: str = _spectrace.__version__

__all__ = [
    "__version__",
    "render",
    "Session",
    "Result",
    "State",
    "load_state",
    "merge",
    "devices",
    "SceneError",
    "DeviceError",
    "StateError",
]

SceneLike = Union[Mapping[str, Any], str, "os.PathLike[str]"]
Progress = Callable[[int, int], None]


class SceneError(ValueError):
    """A scene that cannot be rendered: the CLI's message, with its parts.

    ``file`` names the scene (a path, or ``<dict>``/``<json>`` under
    ``base_dir`` for scenes given in Python), ``pointer`` the JSON pointer of
    the field at fault (``None`` when the fault is the whole file) and
    ``message`` what is wrong.
    """

    def __init__(self, text: str, file: Optional[str] = None, pointer: Optional[str] = None,
                 message: Optional[str] = None):
        super().__init__(text)
        self.file = file
        self.pointer = pointer
        self.message = message if message is not None else text

    @classmethod
    def _from_message(cls, text: str) -> "SceneError":
        # "<file>: <pointer>: <what>" (json_fields.h); the pointer starts with "/".
        file, sep, rest = text.partition(": /")
        if sep:
            pointer, sep2, what = ("/" + rest).partition(": ")
            if sep2:
                return cls(text, file, pointer, what)
        file, sep, what = text.partition(": ")
        return cls(text, file if sep else None, None, what if sep else text)


class DeviceError(RuntimeError):
    """A device failed while rendering (or could not be opened)."""


class StateError(ValueError):
    """A render state that cannot be read, merged or developed."""


def _scene_source(scene: SceneLike, base_dir: Optional[Union[str, "os.PathLike[str]"]]):
    """(source, is_file, virtual file name) for the native render."""
    folder = os.path.abspath(os.fspath(base_dir)) if base_dir is not None else os.getcwd()
    if isinstance(scene, Mapping):
        return json.dumps(scene), False, os.path.join(folder, "<dict>")
    if isinstance(scene, os.PathLike):
        return _existing_file(os.fspath(scene), "scene file"), True, ""
    if isinstance(scene, str):
        if scene.lstrip().startswith("{"):
            return scene, False, os.path.join(folder, "<json>")
        return _existing_file(scene, "scene file"), True, ""
    raise TypeError(f"scene must be a dict, a JSON string or a path, not {type(scene).__name__}")


def _existing_file(path: str, what: str) -> str:
    # Missing files are OSErrors, as Python's own open() raises them.
    if not os.path.isfile(path):
        raise FileNotFoundError(errno.ENOENT, f"no such {what}", path)
    return path


def _overrides(values: Mapping[str, Any]):
    return [(pointer, json.dumps(value)) for pointer, value in values.items()]


class State:
    """The exact render state: the film's integer counters and what traced them.

    States of disjoint beam ranges of one scene and seed merge exactly
    (:func:`merge`); ``develop`` turns one into an image.
    """

    def __init__(self, native):
        self._native = native

    @property
    def beams(self) -> int:
        return _spectrace._state_beams(self._native)

    @property
    def ranges(self) -> list:
        """The beam ranges held, as (first, count) pairs."""
        return _spectrace._state_ranges(self._native)

    @property
    def counts(self):
        """The bin counters, (H, W, bins) uint64, read-only; (H, W, bins, 2),
        low word first, for films that count weighted beams in 128 bits."""
        return _spectrace._state_counts(self._native, self._native)

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        _spectrace._save_state(self._native, os.fspath(path))

    def develop(self, device: str = "auto", spectral: bool = False) -> "Result":
        with Session(device) as session:
            return session.develop(self, spectral=spectral)


class Result:
    """A render's image, as float32 arrays equal to the CLI's EXR channels."""

    def __init__(self, native):
        self._native = native

    xyz = property(lambda self: self._native.xyz, doc="(H, W, 3) CIE XYZ, Y in lux")
    rgb = property(lambda self: self._native.rgb, doc="(H, W, 3) linear sRGB")
    irradiance = property(lambda self: self._native.irradiance, doc="(H, W) W/m^2")
    error = property(lambda self: self._native.error, doc="(H, W) standard error of irradiance, W/m^2")
    spectral = property(lambda self: self._native.spectral,
                        doc="(H, W, bins) W m^-2 nm^-1 when asked for (spectral=True), else None")
    wavelengths_nm = property(lambda self: self._native.wavelengths_nm, doc="bin centres (nm), or None")
    beams = property(lambda self: self._native.beams, doc="beams traced")
    seed = property(lambda self: self._native.seed)
    first_beam = property(lambda self: self._native.first_beam)
    seconds = property(lambda self: self._native.seconds, doc="wall time of the render")
    device = property(lambda self: self._native.device, doc="the device's name and kind")

    @property
    def state(self) -> State:
        return State(self._native._state)

    def write_exr(self, path: Union[str, "os.PathLike[str]"], png: bool = True) -> None:
        """Writes the image as the CLI does (the PNG preview beside it)."""
        self._native._write_exr(os.fspath(path), png)

    def __repr__(self) -> str:
        h, w = self.irradiance.shape
        return f"<spectrace.Result {w}x{h}, {self.beams} beams on {self.device}>"


class Session:
    """A device opened once for many renders, as ``spectrace batch`` does.

    ``device`` is "auto", "gpu" or "cpu" (another word: ValueError); a
    device that cannot be opened raises DeviceError.
    """

    def __init__(self, device: str = "auto"):
        self._native = _spectrace._Session(device)

    def __enter__(self) -> "Session":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        self._native.close()

    @property
    def device(self) -> str:
        return self._native.device

    def render(self, scene: SceneLike, *, beams: Optional[int] = None, seed: Optional[int] = None,
               spectral: bool = False, first_beam: int = 0,
               base_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
               progress: Optional[Progress] = None, overrides: Optional[Mapping[str, Any]] = None) -> Result:
        source, is_file, file = _scene_source(scene, base_dir)
        native = self._native.render(source, is_file, file, _overrides(overrides or {}), beams, seed, first_beam,
                                     spectral, progress)
        return Result(native)

    def sweep(self, scene: SceneLike, axes: Mapping[str, Sequence[Any]], *, beams: Optional[int] = None,
              seed: Optional[int] = None, spectral: bool = False, first_beam: int = 0,
              base_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
              progress: Optional[Progress] = None) -> Iterator[tuple]:
        """Renders every combination of the axes' values (the Cartesian
        product, the last axis fastest), each as JSON-pointer overrides of
        the scene, and yields (overrides, Result) in order."""
        pointers = list(axes)
        for values in itertools.product(*(axes[p] for p in pointers)):
            overrides = dict(zip(pointers, values))
            yield overrides, self.render(scene, beams=beams, seed=seed, spectral=spectral, first_beam=first_beam,
                                         base_dir=base_dir, progress=progress, overrides=overrides)

    def develop(self, state: State, spectral: bool = False) -> Result:
        return Result(self._native.develop(state._native, spectral))


def render(scene: SceneLike, *, beams: Optional[int] = None, seed: Optional[int] = None, device: str = "auto",
           spectral: bool = False, first_beam: int = 0, base_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
           progress: Optional[Progress] = None) -> Result:
    """Renders a scene (a dict in the JSON schema, a JSON string or a path).

    Relative files named in a dict or string resolve against ``base_dir``
    (default: the current folder); in a file, against the file's folder.
    """
    with Session(device) as session:
        return session.render(scene, beams=beams, seed=seed, spectral=spectral, first_beam=first_beam,
                              base_dir=base_dir, progress=progress)


def load_state(path: Union[str, "os.PathLike[str]"]) -> State:
    return State(_spectrace._load_state(_existing_file(os.fspath(path), "state file")))


def merge(states: Sequence[State]) -> State:
    """The exact sum of states of disjoint beam ranges of one render; raises
    StateError, as ``spectrace merge`` refuses, for anything else."""
    return State(_spectrace._merge([s._native for s in states]))


def devices() -> list:
    """What ``spectrace devices`` lists, one dict a device (the CPU reference last)."""
    return json.loads(_spectrace._devices_json())
