"""The Python examples of README.md and docs/python.md run as shown (from the source tree's root)."""

import os
import re
import subprocess

import pytest

from conftest import ROOT


def python_blocks(path, after=None):
    text = (ROOT / path).read_text(encoding="utf-8")
    if after:
        text = text[text.index(after):]
        following = text.find("\n## ", len(after))
        text = text[:following if following >= 0 else None]
    return re.findall(r"```python\n(.*?)```", text, re.S)


def sh_lines(path, after):
    text = (ROOT / path).read_text(encoding="utf-8")
    text = text[text.index(after):]
    text = text[:text.find("\n## ", len(after))]
    return [l for b in re.findall(r"```sh\n(.*?)```", text, re.S) for l in b.splitlines() if l.strip()]


def run_blocks(blocks, name):
    assert blocks
    here = os.getcwd()
    os.chdir(ROOT)  # paths in the examples are relative to the source tree
    namespace = {"__name__": "docs_example"}  # the blocks of a page continue one session
    try:
        for code in blocks:
            exec(compile(code, name, "exec"), namespace)
    finally:
        os.chdir(here)


def test_readme_python_section(capsys):
    run_blocks(python_blocks("README.md", "## Python"), "README.md")
    out = capsys.readouterr().out
    assert "tests/data/bad/nan.off line 4 coordinate is NaN" in out


def test_readme_python_shell_lines(tmp_path):
    # The shell lines of README's Python section, with the build tree this suite runs from.
    build = os.path.dirname(os.environ["PYTHONPATH"].split(os.pathsep)[0])
    prefix = tmp_path / "prefix"
    for line in sh_lines("README.md", "## Python"):
        line = line.split("  #")[0].replace("build/python", os.path.join(build, "python"))
        line = line.replace("cmake --install build", f"cmake --install {build}").replace("/tmp/minksum-prefix", str(prefix))
        r = subprocess.run(line, shell=True, cwd=ROOT, capture_output=True, text=True)
        assert r.returncode == 0, (line, r.stderr)
    assert (prefix / "lib" / "python3.11" / "dist-packages" / "minksum" / "__init__.py").exists()


def test_docs_python_page_examples():
    run_blocks(python_blocks("docs/python.md"), "docs/python.md")


def test_stubs_declare_every_public_name():
    import minksum._minksum as m

    stub = (ROOT / "python" / "minksum" / "_minksum.pyi").read_text(encoding="utf-8")
    for name in (n for n in dir(m) if not n.startswith("_")):
        assert f"class {name}" in stub or f"def {name}(" in stub or f"{name}:" in stub, name
        obj = getattr(m, name)
        if isinstance(obj, type):
            for member in (a for a in dir(obj) if not a.startswith("_")):
                assert f"def {member}(" in stub, f"{name}.{member}"
            assert obj.__doc__, name
        elif callable(obj):
            assert obj.__doc__ and len(obj.__doc__) > 80, name
