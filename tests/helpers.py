"""Helpers shared by the tests (imported as a plain module: tests/ is on sys.path): a
workflow script loader, a stiffness model with uniform slices, the small report and its
readers."""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
from gearsets import SMALL

from pipeline.cli import main as cli
from pipeline.contact.source import ContactPoints
from pipeline.geometry import GearPair

ROOT = Path(__file__).resolve().parents[1]


def load_workflow(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / "workflows" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


@dataclass(frozen=True)
class UniformSlices:
    """A spur pair cut into ``slices`` independent slices of stiffness ``c0`` per unit face
    width per tooth pair (N/m^2): uniform mesh stiffness across the face, on the nominal
    path of contact only (``tip_contact`` False)."""

    pair: GearPair
    slices: int
    c0: float
    tip_contact: bool = False

    def points(self, position: float) -> ContactPoints:
        b = self.pair.face_width
        dz = b / self.slices
        z = (np.arange(self.slices) + 0.5) * dz
        k = self.pair.pair_indices(beyond=False)
        s = position + k * self.pair.base_pitch
        kk = k[(s >= self.pair.s_start) & (s <= self.pair.s_end)]
        return ContactPoints(s=np.repeat(position + kk * self.pair.base_pitch, z.size),
                             z=np.tile(z, kk.size), pair=np.repeat(kk, z.size),
                             width=np.full(kk.size * z.size, dz))

    def matrix(self, position: float) -> np.ndarray:
        pts = self.points(position)
        return np.diag(1.0 / (self.c0 * pts.width))


class Cells(HTMLParser):
    """Table cells with their data-key, image sources, links."""

    def __init__(self) -> None:
        super().__init__()
        self.cells: list[tuple[str | None, str]] = []
        self.images: list[str] = []
        self.links: list[str] = []
        self._in_td: str | None | bool = False
        self._text = ""

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "td":
            self._in_td, self._text = a.get("data-key"), ""
        elif tag == "img":
            self.images.append(a["src"])
        elif tag in ("a", "link", "script"):
            self.links.append(a.get("href") or a.get("src") or "")

    def handle_endtag(self, tag):
        if tag == "td" and self._in_td is not False:
            self.cells.append((self._in_td, self._text))
            self._in_td = False

    def handle_data(self, data):
        if self._in_td is not False:
            self._text += data


def json_value(data: dict, key: str):
    section, name, *column = key.split(".")
    row = data["sections"][section]["quantities"][name]
    return row["values"][column[0]] if column else row["value"]


def small_report(root: Path) -> Path:
    """``gearpipe report`` on the small case into ``root/out`` (cache in ``root/c``)."""
    cfg = root / "small.toml"
    cfg.write_text(SMALL, encoding="utf-8")
    out = root / "out"
    assert cli(["report", str(cfg), "--out", str(out), "--cache-dir", str(root / "c"),
                "--json"]) == 0
    return out
