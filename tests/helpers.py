"""Helpers shared by the tests (imported as a plain module: tests/ is on sys.path): a
workflow script loader, the stiffness model with uniform slices
(:class:`pipeline.contact.source.UniformSlices`), the small report and its readers."""

from __future__ import annotations

import importlib.util
import sys
from html.parser import HTMLParser
from pathlib import Path

from gearsets import SMALL

from pipeline.cli import main as cli
from pipeline.contact.source import UniformSlices  # noqa: F401 (the tests' import)

ROOT = Path(__file__).resolve().parents[1]


def load_workflow(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / "workflows" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


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
