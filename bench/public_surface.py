#!/usr/bin/env python3
"""The core crate's public surface: `pub` items of src/ that nothing outside the crate names.

ARCHITECTURE.md ("The core's public surface") says an item of the core crate (src/) is `pub`
only if something outside the crate names it: the other crates (crates/*/src), the Python
package (python/src), the integration tests (tests/, crates/*/tests) or the doc examples (the
code blocks of src/'s doc comments), or a public item's signature needs it (the compiler's
`private_interfaces` lint). This script lists the candidates that break the first half: a

    pub fn|struct|enum|trait|const|static|type|mod|use NAME     (items and re-exports)
    pub NAME: TYPE                                              (struct fields)

of src/ (outside the crate-private modules `assembly`, `elements`, `interfaces`, `kinematics`,
whose `pub` reaches no further than the crate) whose NAME occurs as a word nowhere in the
outside code above. A word test is conservative: a name that occurs outside for another
reason (a local variable, a method of another type) stays `pub`. Items kept `pub` only
because a public signature needs them are listed in ALLOWED below, each with the item whose
signature needs it; tests/architecture.rs (`public_items_are_named_outside`) runs the same
check and fails on a new candidate.

    python3 bench/public_surface.py            # list the candidates (path:line kind name)
    python3 bench/public_surface.py --apply    # turn them to `pub(crate)` in place
    python3 bench/public_surface.py --check    # exit 1 if any candidate is left

Exit status 0 with --check means the claim of ARCHITECTURE.md holds for the word test.
"""

import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
PRIVATE_MODULES = ("assembly", "elements", "interfaces", "kinematics")

# `pub` items no outside code names, kept because a public item's signature exposes them
# (the compiler's private_interfaces lint): "path:name".
ALLOWED = set()

ITEM = re.compile(
    r"^(\s*)pub\s+(?:unsafe\s+|const\s+(?=fn)|async\s+)*"
    r"(fn|struct|enum|trait|const|static|type|mod)\s+(?:mut\s+)?([A-Za-z_][A-Za-z0-9_]*)"
)
FIELD = re.compile(r"^(\s*)pub\s+([a-z_][a-z0-9_]*)\s*:(?!:)")
USE = re.compile(r"^(\s*)pub\s+use\s+([^;]*);")
WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
DOC_FENCE = re.compile(r"^\s*//[/!]\s?```")


def outside_words():
    """Every word of the code outside the crate, and of src/'s doc-comment code blocks."""
    words = set()
    roots = [ROOT / "tests", ROOT / "python" / "src"]
    roots += [p for p in (ROOT / "crates").glob("*/src")]
    roots += [p for p in (ROOT / "crates").glob("*/tests")]
    for root in roots:
        for f in root.rglob("*.rs"):
            words.update(WORD.findall(f.read_text()))
    for f in (ROOT / "src").rglob("*.rs"):
        inside = False
        for line in f.read_text().splitlines():
            if DOC_FENCE.match(line):
                inside = not inside
            elif inside:
                words.update(WORD.findall(line))
    return words


def in_private_module(path):
    rel = path.relative_to(ROOT / "src")
    top = rel.parts[0].removesuffix(".rs")
    return top in PRIVATE_MODULES


def candidates():
    """(path, line index, kind, name) of every `pub` item of src/ no outside code names."""
    words = outside_words()
    found = []
    for f in sorted((ROOT / "src").rglob("*.rs")):
        if in_private_module(f):
            continue
        rel = f.relative_to(ROOT)
        for i, line in enumerate(f.read_text().splitlines()):
            m = ITEM.match(line)
            if m:
                kind, names = m.group(2), [m.group(3)]
            elif (m := FIELD.match(line)) and not line.lstrip().startswith("pub fn"):
                kind, names = "field", [m.group(2)]
            elif m := USE.match(line):
                kind = "use"
                leaves = re.sub(r"\w+\s+as\s+", "", m.group(2))
                leaves = leaves.split("{")[-1] if "{" in leaves else leaves.split("::")[-1]
                names = [w for w in WORD.findall(leaves) if w not in ("self", "super", "crate")]
                if "*" in m.group(2) or not names:
                    continue
            else:
                continue
            if any(n in words for n in names):
                continue
            if any(f"{rel}:{n}" in ALLOWED for n in names):
                continue
            found.append((f, i, kind, ",".join(names)))
    return found


def apply(found):
    by_file = {}
    for f, i, _, _ in found:
        by_file.setdefault(f, []).append(i)
    for f, lines in by_file.items():
        text = f.read_text().split("\n")
        for i in lines:
            text[i] = re.sub(r"^(\s*)pub\b(?!\()", r"\1pub(crate)", text[i], count=1)
        f.write_text("\n".join(text))


def main():
    found = candidates()
    for f, i, kind, name in found:
        print(f"{f.relative_to(ROOT)}:{i + 1} {kind} {name}")
    if "--apply" in sys.argv:
        apply(found)
        print(f"{len(found)} items turned to pub(crate)", file=sys.stderr)
    else:
        print(f"{len(found)} candidates", file=sys.stderr)
    if "--check" in sys.argv and found:
        sys.exit(1)


if __name__ == "__main__":
    main()
