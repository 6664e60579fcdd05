"""The examples of the user guide (docs/**/*.md) and of README.md run, and print what they say.

How an example is marked in a page's Markdown source:

- A fenced block marked ``sh`` whose commands all start with ``gjklab `` (or
  ``build/release/gjklab ``, ``./build/release/gjklab ``) is an example. Its commands run one
  after the other (a line ending in a backslash continues on the next), each through bash with
  the leading ``gjklab`` replaced by the built program, and each must exit with status 0.
- A fenced block marked ``python`` is an example, run with this Python and the module of the
  build (PYTHONPATH, as ctest sets it).
- HTML comments on the lines just above the block's fence add to it:
  ``<!-- example: expect TEXT -->`` asks for TEXT (quotes around it are dropped) in the block's
  output, stdout and stderr of all its commands together; one comment per text.
  ``<!-- example: skip REASON -->`` leaves the block out: it needs MPI, or takes minutes.
- A block marked ``sh`` that mixes ``gjklab`` commands with other commands (set-up, tools,
  shell loops) must be marked ``skip``; blocks with no ``gjklab`` command at all are not
  examples. Usage synopses are written in blocks marked ``text``, which are never run.

Each example runs in a fresh temporary folder holding copies of experiments/, examples/ and
tests/data/, an empty build/, and results/ with links to the committed files (so an example
reads the reference archives but writes nothing into the source tree). A command may take at
most COMMAND_SECONDS. The examples are kept small: all of them together take well under a
minute on 2 cores.

The test also checks that mkdocs.yml's nav lists every page of docs/, and that CITATION.cff
names the project version of CMakeLists.txt.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import BINARY, SOURCE_DIR

DOCS = SOURCE_DIR / "docs"
PAGES = sorted(DOCS.rglob("*.md")) + [SOURCE_DIR / "README.md"]
PROGRAM_PREFIXES = ("gjklab", "build/release/gjklab", "./build/release/gjklab")
COMMAND_SECONDS = 120
MARKER = re.compile(r"^<!--\s*example:\s*(expect|skip)\b\s*(.*?)\s*-->\s*$")
FENCE_OPEN = re.compile(r"^```\s*([\w+-]*)\s*$")


class Block:
    """One fenced block of a page: its language, lines, and the markers above it."""

    def __init__(self, page, line, language, lines, markers):
        self.page, self.line, self.language, self.lines = page, line, language, lines
        self.expect = [text for kind, text in markers if kind == "expect"]
        self.skip = [text for kind, text in markers if kind == "skip"]

    @property
    def name(self):
        return f"{self.page.relative_to(SOURCE_DIR)}:{self.line}"

    def commands(self):
        """The block's commands: continuation lines joined, blank and comment lines dropped."""
        commands, current = [], ""
        for raw in self.lines:
            current += raw.rstrip()
            if current.endswith("\\"):
                current = current[:-1] + " "
                continue
            if current.strip() and not current.lstrip().startswith("#"):
                commands.append(current.strip())
            current = ""
        if current.strip():
            commands.append(current.strip())
        return commands


def program_command(command):
    """The command with the built program in place of its leading `gjklab`, or None when the
    command does not start with the program."""
    first, _, rest = command.partition(" ")
    if first not in PROGRAM_PREFIXES:
        return None
    return shlex.quote(str(BINARY)) + " " + rest


def read_blocks(page):
    blocks, markers, lines = [], [], page.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        marker = MARKER.match(lines[i])
        fence = FENCE_OPEN.match(lines[i])
        if marker:
            markers.append((marker.group(1), marker.group(2).strip().strip('"')))
        elif fence:
            start, body = i + 1, []
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i])
                i += 1
            blocks.append(Block(page, start, fence.group(1), body, markers))
            markers = []
        else:
            markers = []
        i += 1
    return blocks


ALL_BLOCKS = [block for page in PAGES for block in read_blocks(page)]


def is_shell_example(block):
    if block.language != "sh":
        return False
    commands = block.commands()
    return bool(commands) and all(program_command(c) for c in commands)


SHELL_EXAMPLES = [b for b in ALL_BLOCKS if is_shell_example(b) and not b.skip]
PYTHON_EXAMPLES = [b for b in ALL_BLOCKS if b.language == "python" and not b.skip]


def workspace(tmp_path):
    """A folder like the repository's root, for one example."""
    for part in ("experiments", "examples", os.path.join("tests", "data")):
        shutil.copytree(SOURCE_DIR / part, tmp_path / part)
    (tmp_path / "build").mkdir()
    results = SOURCE_DIR / "results"
    for folder, _, files in os.walk(results):
        target = tmp_path / "results" / Path(folder).relative_to(results)
        target.mkdir(parents=True, exist_ok=True)
        for f in files:
            (target / f).symlink_to(Path(folder) / f)
    return tmp_path


def check_expectations(block, output):
    for text in block.expect:
        assert text in output, f"{block.name}: expected {text!r} in the output:\n{output[-3000:]}"


def test_examples_are_found():
    """The markers are read: the guide has both kinds of examples, and every marker belongs
    to a block that is an example."""
    assert len(SHELL_EXAMPLES) >= 20 and PYTHON_EXAMPLES
    for block in ALL_BLOCKS:
        if block.expect or block.skip:
            assert block.language in ("sh", "python"), f"{block.name}: marker on a {block.language!r} block"


def test_mixed_blocks_are_marked():
    """A sh block with gjklab commands and other commands is either all program commands or
    marked skip: no gjklab command in the guide goes untested unnoticed."""
    for block in ALL_BLOCKS:
        if block.language != "sh" or block.skip:
            continue
        commands = block.commands()
        mixed = any(program_command(c) for c in commands) and not all(
            program_command(c) for c in commands)
        assert not mixed, (f"{block.name}: mixes gjklab commands with others; "
                           "mark it <!-- example: skip REASON --> or split it")


def test_nav_lists_every_page():
    nav = set(re.findall(r"([\w/.-]+\.md)\s*$", (SOURCE_DIR / "mkdocs.yml").read_text(), re.M))
    pages = {str(p.relative_to(DOCS)) for p in DOCS.rglob("*.md")}
    assert pages == nav, f"pages not in nav: {sorted(pages - nav)}; nav without a page: {sorted(nav - pages)}"


@pytest.mark.parametrize("block", SHELL_EXAMPLES, ids=lambda b: b.name)
def test_shell_example(block, tmp_path):
    if not BINARY.exists():
        pytest.skip(f"no gjklab program at {BINARY}")
    cwd = workspace(tmp_path)
    output = ""
    for command in block.commands():
        done = subprocess.run(["bash", "-c", program_command(command)], cwd=cwd,
                              capture_output=True, text=True, timeout=COMMAND_SECONDS)
        output += done.stdout + done.stderr
        assert done.returncode == 0, (
            f"{block.name}: `{command}` exited with status {done.returncode}:\n"
            f"{done.stdout[-2000:]}\n{done.stderr[-2000:]}")
        assert done.stdout.strip() or done.stderr.strip(), f"{block.name}: `{command}` printed nothing"
    check_expectations(block, output)


@pytest.mark.parametrize("block", PYTHON_EXAMPLES, ids=lambda b: b.name)
def test_python_example(block, tmp_path):
    pytest.importorskip("gjklab")
    cwd = workspace(tmp_path)
    script = cwd / "example.py"
    script.write_text("\n".join(block.lines) + "\n", encoding="utf-8")
    done = subprocess.run([sys.executable, str(script)], cwd=cwd, capture_output=True, text=True,
                          timeout=COMMAND_SECONDS)
    output = done.stdout + done.stderr
    assert done.returncode == 0, f"{block.name}: the example failed:\n{output[-3000:]}"
    check_expectations(block, output)


def test_citation_names_the_project_version():
    """CITATION.cff's version is CMakeLists.txt's project version."""
    project = re.search(r"project\(gjklab VERSION ([\d.]+)", (SOURCE_DIR / "CMakeLists.txt").read_text())
    citation = re.search(r"^version: ([\d.]+)\s*$", (SOURCE_DIR / "CITATION.cff").read_text(), re.M)
    assert project and citation and project.group(1) == citation.group(1)
