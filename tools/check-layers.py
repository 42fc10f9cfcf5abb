#!/usr/bin/env python3
"""Checks that renderer/'s includes keep to the libraries renderer/CMakeLists.txt declares.

Each folder of renderer/ is one library, glint_library(<folder> SOURCES ... DEPS ...). A file of
folder F may include "G/..." for another library G only where G is among F's DEPS, transitively
(an include of a library not among them is upward or sideways: the layering docs/architecture.md
draws is broken). DEPS say exactly what a folder uses: each glint library a folder includes is
named in its own DEPS, and each one named is included. The DEPS must not form a cycle.

Usage: tools/check-layers.py [ROOT]   (ROOT holds renderer/; default: this checkout)
Exits 0 when all holds, 1 naming each file:line, include and missing dependency otherwise,
2 when renderer/CMakeLists.txt cannot be read as expected.
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"(([A-Za-z0-9_]+)/[^"]*)"')
CMAKE_LIST = "renderer/CMakeLists.txt"
LIBRARY_CALL = re.compile(r"\bglint_library\s*\(")


def strip_comments(text):
    # CMake comments run from an unquoted # to the end of the line; the renderer's list has no
    # quoted # and no bracket comments.
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


def declared_libraries(cmake_file):
    """{library: [glint libraries named in its DEPS, in order]} and {library: line}."""
    text = strip_comments(cmake_file.read_text())
    calls = []
    for match in LIBRARY_CALL.finditer(text):
        end = text.find(")", match.end())
        if end < 0:
            raise ValueError(f"{cmake_file}: glint_library( is never closed")
        line = text.count("\n", 0, match.start()) + 1
        calls.append((line, text[match.end():end].split()))
    libraries, lines = {}, {}
    for line, words in calls:
        if not words:
            raise ValueError(f"{cmake_file}:{line}: glint_library() names no library")
        name, deps, section = words[0], [], None
        for word in words[1:]:
            if word in ("SOURCES", "DEPS"):
                section = word
            elif section == "DEPS":
                deps.append(word)
        if name in libraries:
            raise ValueError(f"{cmake_file}:{line}: glint_library({name}) is declared twice")
        libraries[name], lines[name] = deps, line
    # DEPS also name other targets (TBB::tbb, glint_mikktspace): only glint libraries count.
    return {
        name: [d[len("glint_"):] for d in deps if d.startswith("glint_") and d[6:] in libraries]
        for name, deps in libraries.items()
    }, lines


def closure(direct):
    """Every library each one reaches through DEPS, and the cycles met on the way."""
    reached, cycles = {}, []

    def visit(name, path):
        if name in path:
            cycles.append(path[path.index(name):] + [name])
            return set()
        if name not in reached:
            found = set()
            for dep in direct[name]:
                found |= {dep} | visit(dep, path + [name])
            reached[name] = found
        return reached[name]

    for name in direct:
        visit(name, [])
    return reached, cycles


def check(root):
    renderer = root / "renderer"
    direct, lines = declared_libraries(root / CMAKE_LIST)
    reached, cycles = closure(direct)
    errors = []
    for cycle in cycles:
        errors.append(f"{CMAKE_LIST}: DEPS form a cycle: {' -> '.join(cycle)}")
    # The first include of each library a folder reaches only through others, and how many.
    indirect = {}
    included = {name: set() for name in direct}
    for folder in sorted(direct):
        files = sorted(
            p
            for p in (renderer / folder).rglob("*")
            if p.suffix in (".h", ".hpp", ".inl", ".cpp") and p.is_file()
        )
        for path in files:
            for number, text in enumerate(path.read_text(errors="replace").splitlines(), 1):
                match = INCLUDE.match(text)
                if not match or match.group(2) == folder or match.group(2) not in direct:
                    continue
                used = match.group(2)
                included[folder].add(used)
                where = f'{path.relative_to(root)}:{number}: #include "{match.group(1)}"'
                if used not in reached[folder]:
                    errors.append(
                        f"{where}: glint_{folder} does not depend on glint_{used} (not among its "
                        f"DEPS, directly or through others; {CMAKE_LIST}:{lines[folder]})"
                    )
                elif used not in direct[folder]:
                    first, count = indirect.get((folder, used), (where, 0))
                    indirect[(folder, used)] = (first, count + 1)
    for (folder, used), (first, count) in sorted(indirect.items()):
        more = f" (and {count - 1} more)" if count > 1 else ""
        errors.append(
            f"{first}{more}: glint_{used} is reached only through other libraries; name it in "
            f"glint_{folder}'s DEPS ({CMAKE_LIST}:{lines[folder]})"
        )
    for folder in sorted(direct):
        for dep in direct[folder]:
            if dep not in included[folder]:
                errors.append(
                    f"{CMAKE_LIST}:{lines[folder]}: glint_{folder}'s DEPS name "
                    f"glint_{dep}, but no file of renderer/{folder}/ includes it"
                )
    return errors


def main(argv):
    here = pathlib.Path(__file__).resolve().parent.parent
    root = pathlib.Path(argv[1]) if len(argv) > 1 else here
    try:
        errors = check(root)
    except (OSError, ValueError) as error:
        print(f"check-layers: {error}", file=sys.stderr)
        return 2
    for error in errors:
        print(error, file=sys.stderr)
    if errors:
        print(f"check-layers: {len(errors)} mismatch(es) between includes and DEPS "
              "(docs/architecture.md, \"Layout and dependencies\")", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
