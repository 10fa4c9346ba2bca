"""paperlib.apps: one clean app per method, what `python -m paperlib explore` serves, and the confinement of
a served app's files (issue 22 item 1). The apps in a real browser: tests/test_apps_browser.py."""

from __future__ import annotations

import json
import re
import sys
from datetime import datetime, timezone
from pathlib import Path

import pytest

from paperlib import apps
from paperlib.__main__ import main
from paperlib.widgets.mlts import default_script
from paperlib.widgets import arrangement_explorer, mlts_explorer

VOILA_LAB_TEMPLATE = Path(sys.prefix) / "share" / "jupyter" / "voila" / "templates" / "lab" / "index.html.j2"
OUR_TEMPLATE = Path(apps.__file__).parent / "jupyter" / "voila" / "templates" / "paperlib" / "index.html.j2"

UPLOADED = datetime(2026, 1, 1, tzinfo=timezone.utc)  # what ipywidgets' FileUpload gives for a file's date

#: 64 small squares on a jittered 8 x 8 grid: enough elements for categorize and fit.
SQUARES = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 200">'
           + "".join(f'<rect x="{5 + 24 * (k % 8) + 7 * ((k * 37) % 5) / 4:.1f}" y="{5 + 24 * (k // 8) + (k * 53) % 6:.1f}" '
                     'width="6" height="6"/>' for k in range(64))
           + "</svg>")


def test_every_method_has_a_one_cell_app_notebook_without_outputs():
    for key in apps.APPS:
        notebook = json.loads(apps.app_notebook(key).read_text())
        cells = notebook["cells"]
        assert len(cells) == 1 and cells[0]["cell_type"] == "code"
        assert "".join(cells[0]["source"]) == f'from paperlib.apps import app\n\napp("{key}")'
        assert cells[0]["outputs"] == [] and cells[0]["execution_count"] is None


def test_methods_are_named_by_paper_or_module():
    assert apps.resolve_method("kim2009") == apps.resolve_method("stipple") == "kim2009"
    assert {apps.resolve_method(alias) for alias in apps.ALIASES} == set(apps.APPS)
    with pytest.raises(ValueError, match="method must be one of .*got 'kim'"):
        apps.resolve_method("kim")
    with pytest.raises(TypeError, match="method must be a str"):
        apps.resolve_method(2009)


def test_voila_serves_the_app_on_localhost_with_the_offline_template(tmp_path):
    command = apps.voila_command("sketch", port=8870)
    assert command[:3] == [sys.executable, "-m", "voila"] and command[3] == str(apps.app_notebook("simhon2001"))
    assert {"--Voila.ip=127.0.0.1", "--port=8870", "--template=paperlib", "--no-browser"} <= set(command)
    assert "--browser" in apps.voila_command("kim2009", open_browser=True)
    for port in (80, 70000, "8866", True):
        with pytest.raises(ValueError, match="port must be an integer in \\[1024, 65535\\]"):
            apps.voila_command("kim2009", port=port)
    env = apps.voila_environment(tmp_path)
    assert env[apps.FILE_ROOT_VARIABLE] == str(tmp_path.resolve())
    template_dir = Path(env["JUPYTER_PATH"].split(":")[0]) / "voila" / "templates" / "paperlib"
    assert (template_dir / "index.html.j2").samefile(OUR_TEMPLATE)
    with pytest.raises(ValueError, match="file_root must be an existing folder"):
        apps.voila_environment(tmp_path / "missing")
    with pytest.raises(ValueError, match="file_root names the home of an unknown user"):  # found by a fuzz run
        apps.voila_environment("~no-such-user-of-this-machine/files")


def test_the_offline_template_drops_every_link_voila_fetches_from_outside():
    """If a Voila release changes its CDN links, this fails here instead of in the page's console."""
    links = re.findall(r'<link [^>]*href="https?://[^"]+"[^>]*/>', VOILA_LAB_TEMPLATE.read_text())
    assert links, "Voila's lab template has no external link any more: the paperlib template can go"
    ours = OUR_TEMPLATE.read_text()
    assert all(f"replace('{link}', '')" in ours for link in links), links


def test_the_file_root_defaults_to_build_or_the_variable(tmp_path, monkeypatch):
    monkeypatch.delenv(apps.FILE_ROOT_VARIABLE, raising=False)
    root = apps.default_file_root()
    assert root.parts[-2:] == ("build", "explorer_files") and root.is_dir() and "figures" not in root.parts
    monkeypatch.setenv(apps.FILE_ROOT_VARIABLE, str(tmp_path / "mine"))
    assert apps.default_file_root() == tmp_path / "mine" and (tmp_path / "mine").is_dir()


def test_an_app_opens_clean_with_its_files_in_the_root(tmp_path):
    explorer = apps.app("mlts", file_root=tmp_path)
    assert explorer.error is None and explorer.message == "" and explorer.origin == "initial script"
    assert Path(explorer.output_dir.value) == tmp_path.resolve() and explorer.image.value


def test_a_served_hurtut_explorer_reads_svg_only_inside_its_root_or_uploaded(tmp_path):
    root, elsewhere = tmp_path / "root", tmp_path / "elsewhere"
    root.mkdir(), elsewhere.mkdir()
    (root / "squares.svg").write_text(SQUARES)
    (elsewhere / "squares.svg").write_text(SQUARES)
    explorer = arrangement_explorer(T=1000, file_root=root)
    for outside in (str(elsewhere / "squares.svg"), "../elsewhere/squares.svg"):
        assert explorer.load_svg(outside) is False
        assert "outside the folder this app may use" in explorer.message and explorer.drawing.name != "squares.svg"
    (root / "link.svg").symlink_to(elsewhere / "squares.svg")
    assert explorer.load_svg("link.svg") is False and "outside" in explorer.message
    assert explorer.load_svg("squares.svg") is True and explorer.drawing.name == "squares.svg"

    free = arrangement_explorer(T=1000)  # a notebook on one's own machine: any path
    assert free.load_svg(elsewhere / "squares.svg") is True

    explorer.exemplar.value = "two_category"
    explorer.upload.value = ({"name": "sent.svg", "type": "image/svg+xml", "size": len(SQUARES),
                              "content": memoryview(SQUARES.encode()), "last_modified": UPLOADED},)
    assert explorer.error is None and explorer.drawing.name == "sent.svg" and len(explorer.drawing.elements) == 64


def test_a_served_mlts_explorer_writes_and_reads_only_inside_its_root(tmp_path):
    root, elsewhere = tmp_path / "root", tmp_path / "elsewhere"
    root.mkdir(), elsewhere.mkdir()
    explorer = mlts_explorer(file_root=root)
    assert explorer.save("scripts/a.json") is True and (root / "scripts" / "a.json").is_file()
    assert explorer.save(elsewhere / "b.json") is False and "outside" in explorer.message
    assert not (elsewhere / "b.json").exists()
    assert explorer.load("../elsewhere/b.json") is False and "outside" in explorer.message
    assert explorer.load("scripts/a.json") is True
    assert explorer.export("png") == root.resolve() / "texture.png"
    assert explorer.export("png", folder=str(elsewhere)) is None and "outside" in explorer.message

    script = default_script(96, 64)
    explorer.upload.value = ({"name": "sent.json", "type": "application/json", "size": 1,
                              "content": memoryview(script.to_json().encode()), "last_modified": UPLOADED},)
    assert explorer.error is None and explorer.script == script and "sent.json" in explorer.origin
    explorer.upload.value = ({"name": "bad.json", "type": "application/json", "size": 1,
                              "content": memoryview(b"{not json"), "last_modified": UPLOADED},)
    assert explorer.script == script and "load failed" in explorer.message


def test_explore_names_the_methods_and_refuses_an_unknown_one(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["explore", "--help"])
    assert exit_info.value.code == 0
    shown = capsys.readouterr().out
    assert all(key in shown for key in apps.APPS) and "python -m paperlib explore hurtut2009" in shown
    assert main(["explore", "kim"]) == 2 and "method must be one of" in capsys.readouterr().err
    assert main(["explore", "kim2009", "--port", "80"]) == 2 and "port" in capsys.readouterr().err
