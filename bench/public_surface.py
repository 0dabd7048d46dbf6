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
whose `pub` reaches no further than the crate; `#[cfg(test)]` modules skipped) whose NAME
occurs as a word nowhere in the outside code above, nor in the public face of an item that is
itself public by this rule (a function's signature, a field's type, an enum's or a trait's
body; followed to a fixed point: the type a named function returns is public, so are the
types of its named fields...). A word test is conservative: a name that occurs outside for
another reason (a local variable, a method of another type) stays `pub`. The few items kept
`pub` for a reason the words cannot show are in REVIEWED below, with the reason.
tests/architecture.rs (`public_items_are_named_outside`, with syn) runs the same check and
fails on a new candidate; this script is the quick way to list and fix them.

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

# `pub` items no outside code names and no public face exposes, kept by review: "path:name"
# (the same list as PUBLIC_BY_REVIEW in tests/architecture.rs).
REVIEWED = {
    "src/solver/newton.rs:divergence_ratio",  # struct update `..*settings` needs every field
    "src/solver/newton.rs:stagnation_iterations",
    "src/solver/newton.rs:line_search",
    "src/damage/mod.rs:to_array",  # unused; src/damage is reworked on another branch
    "src/materials/damage.rs:MODES",  # the order damage::Strengths::to_array documents
}

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


def face(lines, i, kind):
    """The text of the public face of the item on line i: what its being public exposes."""
    line = lines[i]
    if kind in ("fn", "type", "const", "static"):
        text = ""
        for line in lines[i:]:
            text += " " + line
            if "{" in line or line.rstrip().endswith(";"):
                break
        return text.split("{")[0] if kind == "fn" else text
    if kind in ("enum", "trait"):
        indent = len(line) - len(line.lstrip())
        text = line
        for line in lines[i + 1 :]:
            text += " " + line
            if line.rstrip() == " " * indent + "}":
                break
        return text
    if kind == "field":
        return line.split(":", 1)[1]
    return line  # struct: its generics, a tuple struct's fields


def pub_items():
    """(path, line index, kind, names, face words) of every `pub` item of the public modules."""
    items = []
    for f in sorted((ROOT / "src").rglob("*.rs")):
        if in_private_module(f):
            continue
        lines = f.read_text().splitlines()
        skip_to = None  # the closing line of a #[cfg(test)] module
        for i, line in enumerate(lines):
            if skip_to is not None:
                if line.rstrip() == skip_to:
                    skip_to = None
                continue
            if line.strip() == "#[cfg(test)]" and i + 1 < len(lines) and re.match(r"\s*(pub(\(crate\))?\s+)?mod \w+ \{", lines[i + 1]):
                skip_to = re.match(r"(\s*)", lines[i + 1]).group(1) + "}"
                continue
            if m := ITEM.match(line):
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
            if kind == "use":  # one entry per name a re-export brings in
                items += [(f, i, kind, [n], {n}) for n in names]
                continue
            words = set(names) if kind == "mod" else set(WORD.findall(face(lines, i, kind)))
            items.append((f, i, kind, names, words))
    return items


def candidates():
    """(path, line index, kind, name) of every `pub` item no outside code names or exposes."""
    public = outside_words()
    items = pub_items()
    grew = True
    while grew:
        grew = False
        for _, _, _, names, words in items:
            if any(n in public for n in names) and not words <= public:
                public |= words
                grew = True
    found = []
    for f, i, kind, names, _ in items:
        rel = f.relative_to(ROOT)
        if any(n in public for n in names) or any(f"{rel}:{n}" in REVIEWED for n in names):
            continue
        found.append((f, i, kind, ",".join(names)))
    return found


def apply(found):
    by_file = {}
    flagged = {(f, i, name) for f, i, _, name in found}
    for f, i, kind, _ in found:
        if kind == "use":  # a re-export group turns only if every name in it is flagged
            leaves = [it[3][0] for it in pub_items() if it[0] == f and it[1] == i]
            if not all((f, i, n) in flagged for n in leaves):
                print(f"{f.relative_to(ROOT)}:{i + 1}: split this re-export by hand", file=sys.stderr)
                continue
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
