"""Every ```python block of README.md and docs/ runs standalone, and the CLI's help texts name the
registered unloading models.

Each block runs as a script of its own, as ``__main__``, in a fresh temporary directory, with a time
limit: a block must hold its own imports and data. The default run executes the blocks not marked
slow one after another in one worker process (``runpy.run_path``: a fresh namespace per block; the
process saves re-importing fastrest); ``-m slow`` runs every block, the slow ones included, as
``python snippet.py`` in a process of its own. An HTML comment on the lines just above
a block (only blank lines between) changes how it runs; the comment is visible in the Markdown
source and invisible on the rendered page:

* ``<!-- no-run: REASON -->``: the block is not run (``test_no_run_blocks_are_listed`` lists
  them and asserts the reason is given);
* ``<!-- slow: REASON -->``: the block runs only with ``-m slow`` (it compiles a lot, or starts a
  Dask cluster);
* ``<!-- setup: COMMAND -->``: COMMAND runs first in the same directory (a ``fastrest ...``
  command line, run as ``python -m fastrest ...``), for blocks that read a file the page's text
  tells the reader to write.

Several markers may share one comment, one per line.
"""
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]

#: Seconds one block may run (a cold Numba cache compiles what it calls).
TIME_LIMIT = 240

FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})(?P<info>[^\n`]*)$")
MARKER = re.compile(r"^\s*(no-run|slow|setup)\s*:\s*(.*?)\s*$")


def markdown_files():
    """README.md and every Markdown page of docs/ (not the build output)."""
    files = [REPO / "README.md"]
    files += sorted(p for p in (REPO / "docs").rglob("*.md") if "_build" not in p.relative_to(REPO).parts)
    return files


def _markers(lines, start):
    """The markers of the HTML comments directly above line ``start`` (blank lines allowed)."""
    found = {}
    i = start - 1
    while i >= 0 and not lines[i].strip():
        i -= 1
    while i >= 0 and lines[i].rstrip().endswith("-->"):
        end = i
        while i >= 0 and "<!--" not in lines[i]:
            i -= 1
        if i < 0:
            break
        comment = "\n".join(lines[i:end + 1]).strip()
        body = comment[comment.index("<!--") + 4:comment.rindex("-->")]
        for line in body.splitlines():
            m = MARKER.match(line)
            if m:
                found.setdefault(m.group(1), []).append(m.group(2))
        i -= 1
        while i >= 0 and not lines[i].strip():
            i -= 1
    return found


def python_blocks(path):
    """(first line number, code, markers) of each ```python block of a Markdown file."""
    lines = path.read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, info, indent = m.group("fence"), m.group("info").strip(), len(m.group("indent"))
        j = i + 1
        while j < len(lines) and not (lines[j].strip().startswith(fence) and lines[j].strip().strip(fence[0]) == ""):
            j += 1
        lang = info.split()[0].lower() if info else ""
        if lang in ("python", "py", "python3", "{code-block}") and (lang != "{code-block}" or "python" in info):
            code = "\n".join(ln[indent:] if ln[:indent].strip() == "" else ln for ln in lines[i + 1:j])
            out.append((i + 1, code + "\n", _markers(lines, i)))
        i = j + 1
    return out


def all_blocks():
    for path in markdown_files():
        for line, code, markers in python_blocks(path):
            yield f"{path.relative_to(REPO).as_posix()}:{line}", code, markers


BLOCKS = list(all_blocks())


def _runnable():
    return [(label, code, markers) for label, code, markers in BLOCKS if "no-run" not in markers]


#: Documentation must not use deprecated names: fastrest's DeprecationWarnings are errors in the blocks.
DEPRECATED = r".*is deprecated and will be removed in fastrest"

#: The worker that runs the default blocks in one process: each block is a script of its own
#: (``runpy.run_path`` as ``__main__``: a fresh namespace), in a fresh directory, with a time limit.
WORKER = r"""
import json, os, runpy, shlex, signal, sys, tempfile, traceback, warnings
warnings.filterwarnings("error", message=DEPRECATED, category=DeprecationWarning)
blocks, limit = json.load(sys.stdin), int(sys.argv[1])
def alarm(signum, frame):
    raise TimeoutError(f"the block ran past {limit} s")
signal.signal(signal.SIGALRM, alarm)
results = {}
for label, code, setups in blocks:
    d = tempfile.mkdtemp(prefix="snippet-")
    os.chdir(d)
    signal.alarm(limit)
    try:
        for command in setups:
            from fastrest import cli
            rc = cli.main(shlex.split(command)[1:])
            if rc not in (0, None):
                raise RuntimeError(f"setup {command!r} exited with {rc}")
        path = os.path.join(d, "snippet.py")
        with open(path, "w", encoding="utf-8") as f:
            f.write(code)
        runpy.run_path(path, run_name="__main__")
        results[label] = None
    except BaseException:
        results[label] = traceback.format_exc()
    finally:
        signal.alarm(0)
print("\n@@RESULTS@@" + json.dumps(results))
"""


def _env(site=None):
    """The blocks' environment; ``site``: a folder whose sitecustomize makes fastrest's
    DeprecationWarnings errors in a script run as ``python snippet.py``."""
    paths = ([str(site)] if site else []) + [str(REPO)]
    if os.environ.get("PYTHONPATH"):
        paths.append(os.environ["PYTHONPATH"])
    return dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=os.pathsep.join(paths))


@pytest.fixture(scope="module")
def default_results():
    """Run every default block (not slow, not no-run) in one worker process; label -> error or None."""
    import json
    blocks = [(label, code, markers.get("setup", [])) for label, code, markers in _runnable()
              if "slow" not in markers]
    for _, _, setups in blocks:
        for command in setups:
            assert shlex.split(command)[0] == "fastrest", f"a setup command runs fastrest: {command!r}"
    r = subprocess.run([sys.executable, "-c", f"DEPRECATED = {DEPRECATED!r}\n" + WORKER, str(TIME_LIMIT)], input=json.dumps(blocks),
                       cwd=REPO, env=_env(), capture_output=True, text=True,
                       timeout=TIME_LIMIT * max(len(blocks), 1))
    assert "@@RESULTS@@" in r.stdout, f"the worker failed:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return json.loads(r.stdout.rsplit("@@RESULTS@@", 1)[1]), r.stdout, r.stderr


def _run_script(code, markers, tmp_path):
    """Run one block as ``python snippet.py`` in ``tmp_path``, after its setup commands."""
    site = tmp_path / "_site"
    site.mkdir()
    (site / "sitecustomize.py").write_text(
        "import warnings\n"
        f"warnings.filterwarnings('error', message={DEPRECATED!r}, category=DeprecationWarning)\n")
    env = _env(site)
    for command in markers.get("setup", []):
        argv = shlex.split(command)
        assert argv and argv[0] == "fastrest", f"a setup command runs fastrest: {command!r}"
        r = subprocess.run([sys.executable, "-m", "fastrest"] + argv[1:], cwd=tmp_path, env=env,
                           capture_output=True, text=True, timeout=TIME_LIMIT)
        assert r.returncode == 0, f"setup {command!r} failed:\n{r.stdout}\n{r.stderr}"
    script = tmp_path / "snippet.py"
    script.write_text(code, encoding="utf-8")
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True,
                       text=True, timeout=TIME_LIMIT)
    assert r.returncode == 0, f"the block failed:\n{code}\n--- stdout\n{r.stdout}\n--- stderr\n{r.stderr}"


@pytest.mark.parametrize("label", [label for label, _, m in _runnable() if "slow" not in m])
def test_block_runs(label, default_results):
    """Default blocks: each a script of its own, run as __main__ in one shared worker process."""
    results, out, err = default_results
    assert label in results, f"{label} was not run:\n{err[-3000:]}"
    code = next(c for lab, c, _ in BLOCKS if lab == label)
    assert results[label] is None, f"{label} failed:\n{code}\n--- traceback\n{results[label]}"


@pytest.mark.slow
@pytest.mark.parametrize("code, markers", [pytest.param(c, m, id=label) for label, c, m in _runnable()])
def test_block_runs_as_script(code, markers, tmp_path):
    """Every runnable block (the slow ones included) as ``python snippet.py`` in its own process."""
    _run_script(code, markers, tmp_path)


def test_blocks_found():
    """The extraction sees the README's quickstart and blocks of the user guide."""
    labels = [label for label, _, _ in BLOCKS]
    assert any(label.startswith("README.md:") for label in labels)
    assert len({label.split(":")[0] for label in labels}) >= 4, labels
    readme = [code for label, code, _ in BLOCKS if label.startswith("README.md:")]
    assert any("fastrest.Impact" in code for code in readme)


def test_no_run_blocks_are_listed():
    """Blocks left out on purpose say why; this is the list (see the test's -rA output)."""
    skipped = [(label, markers["no-run"]) for label, _, markers in BLOCKS if "no-run" in markers]
    for label, reasons in skipped:
        assert all(reason.strip() for reason in reasons), f"{label}: no-run needs a reason"
        print(f"no-run {label}: {'; '.join(reasons)}")
    # Deliberately unrunnable blocks are exceptions: keep them few.
    assert len(skipped) <= 5, skipped


def test_markers_parse(tmp_path):
    md = tmp_path / "page.md"
    md.write_text("text\n\n<!-- no-run: needs a GPU -->\n\n```python\nraise SystemExit(1)\n```\n\n"
                  "<!--\nslow: compiles\nsetup: fastrest info\n-->\n```python\nx = 1\n```\n\n"
                  "```bash\nls\n```\n\n```python\n    y = 2\n```\n", encoding="utf-8")
    blocks = python_blocks(md)
    assert [b[0] for b in blocks] == [5, 13, 21]
    assert blocks[0][2] == {"no-run": ["needs a GPU"]}
    assert blocks[1][2] == {"slow": ["compiles"], "setup": ["fastrest info"]}
    assert blocks[2][2] == {} and blocks[2][1] == "    y = 2\n"


# --- The CLI's help texts against the registered unloading models --------------------------------

def _help(argv, capsys):
    from fastrest import cli
    with pytest.raises(SystemExit) as exc:
        cli.main(argv + ["-h"])
    assert exc.value.code == 0
    return " ".join(capsys.readouterr().out.split())


def _subcommands(text):
    """Subcommand names listed in an argparse help text ('{a,b,c}' or the commands section)."""
    names = set()
    for group in re.findall(r"\{([a-z0-9_,-]+)\}", text):
        names.update(group.split(","))
    return names


def _command_names(argv, capsys):
    from fastrest import cli
    with pytest.raises(SystemExit):
        cli.main(argv + ["-h"])
    raw = capsys.readouterr().out
    names = _subcommands(" ".join(raw.split()))
    section = re.search(r"^commands:\n((?:[ \t]+.*\n?)*)", raw, re.M)
    if section:
        names.update(re.findall(r"^ {2,6}([a-z][a-z0-9_-]*)\b", section.group(1), re.M))
    return sorted(names)


COUNT_WORDS = {1: "one|a single", 2: "two|both", 3: "three", 4: "four", 5: "five"}


def test_cli_help_names_every_unloading_model(capsys):
    from fastrest.unloading import MODELS, NAMES

    commands = _command_names([], capsys)
    assert {"e", "build"} <= set(commands), commands
    argvs = [[c] for c in commands]
    if "export" in commands:
        argvs += [["export", c] for c in _command_names(["export"], capsys)]
    checked = []
    for argv in argvs:
        text = _help(argv, capsys)
        if not re.search(r"unloading", text, re.I):
            continue
        checked.append(" ".join(argv))
        for n, words in COUNT_WORDS.items():
            if n != len(NAMES):
                assert not re.search(rf"\b({words}) (of the )?unloading models\b", text, re.I), (
                    f"`fastrest {' '.join(argv)} -h` speaks of {n} unloading models; "
                    f"{len(NAMES)} are registered ({', '.join(NAMES)})")
        if re.search(r"unloading models\b", text, re.I):   # speaks of all of them: names each
            missing = [m for m in NAMES if MODELS[m].short.lower() not in text.lower() and m not in text.lower()]
            assert not missing, f"`fastrest {' '.join(argv)} -h` does not name {missing}"
    assert {"e", "build"} <= set(checked), checked
