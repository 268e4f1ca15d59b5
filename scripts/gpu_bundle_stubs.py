#!/usr/bin/env python3
"""Stand-in shared libraries for a self-contained tool bundle (scripts/gpu-bench pack).

OpenImageIO links dozens of codec libraries (OpenVDB, FFmpeg, OpenCV, DCMTK, libheif,
LibRaw) that the bench never calls: it reads PNG, JPEG and EXR only. Bundled whole they
weigh ~350 MB, over what a device run may carry. Each left-out library is replaced by a
stand-in with the same soname that defines every symbol the bundled objects import from it
(functions that abort with the symbol's name, zeroed data of the symbol's size), so the
dynamic linker resolves everything (OpenImageIO is linked with BIND_NOW) while nothing of
the real library travels. A stand-in that is ever called aborts loudly.

usage: gpu_bundle_stubs.py OUT_DIR REAL_LIB [REAL_LIB...] -- IMPORTER [IMPORTER...]
  REAL_LIB: the libraries to replace (paths); IMPORTER: the bundled ELF objects.
"""
import os
import re
import subprocess
import sys

# Itanium C++ ABI constructors (C1, C2, C3) and destructors (D0, D1, D2) of a nested name.
STRUCTOR = re.compile(r"^_ZN.*(C[123]|D[012])E")
SYMBOL = re.compile(r"^(?:[0-9a-f]+\s+)?(?:([0-9a-f]+)\s+)?([A-Za-z])\s+(\S+)$")


def dynamic_symbols(path, defined):
    flag = "--defined-only" if defined else "--undefined-only"
    out = subprocess.run(["nm", "-D", "-S", flag, "--with-symbol-versions", path],
                         capture_output=True, text=True, check=True).stdout
    symbols = []
    for line in out.splitlines():
        m = SYMBOL.match(line.strip())
        if not m:
            continue
        size, kind, name = m.group(1), m.group(2), m.group(3)
        symbols.append((name, kind, int(size, 16) if size else 0))
    return symbols


def split_version(name):
    """'f@@V' -> ('f', 'V', True); 'f@V' -> ('f', 'V', False); 'f' -> ('f', None, True)."""
    if "@@" in name:
        base, ver = name.split("@@", 1)
        return base, ver, True
    if "@" in name:
        base, ver = name.split("@", 1)
        return base, ver, False
    return name, None, True


def soname(path):
    out = subprocess.run(["readelf", "-d", path], capture_output=True, text=True,
                         check=True).stdout
    m = re.search(r"\(SONAME\)\s+Library soname: \[([^\]]+)\]", out)
    return m.group(1) if m else os.path.basename(path)


def write_stub(out_dir, real, imported):
    wanted = []
    for name, kind, size in dynamic_symbols(real, defined=True):
        if kind in "Aa":  # version nodes
            continue
        base, ver, default = split_version(name)
        if (base, ver) not in imported and (base, None) not in imported:
            continue
        wanted.append((base, ver, default, kind, size))
    name = soname(real)
    c_lines = ['#include <stdio.h>', '#include <stdlib.h>',
               'static void gone(const char* s) {',
               f'    fprintf(stderr, "{name} stand-in called: %s (not bundled)\\n", s);',
               '    abort();', '}']
    nodes = {}
    for i, (base, ver, default, kind, size) in enumerate(wanted):
        local = f"s{i}"
        exported = base if (ver is None or default) else local
        label = f'__asm__("{exported}")'
        if kind in "TtWiI" and STRUCTOR.match(base):
            # Static objects of the left-out libraries are built and destroyed whether or
            # not they are used: their constructors and destructors do nothing.
            c_lines.append(f"void {local}(void) {label};")
            c_lines.append(f"void {local}(void) {{}}")
        elif kind in "TtWiI" and "version" in base.lower():
            # OpenImageIO lists every plugin's library version when it first opens a file.
            c_lines.append(f"const char* {local}(void) {label};")
            c_lines.append(f'const char* {local}(void) {{ return "not bundled"; }}')
        elif kind in "TtWiI":
            c_lines.append(f"void {local}(void) {label};")
            c_lines.append(f'void {local}(void) {{ gone("{base}"); }}')
        else:
            c_lines.append(f"char {local}[{max(size, 1)}] {label} "
                           "__attribute__((aligned(16))) = {0};")
        if ver is not None and not default:
            c_lines.append(f'__asm__(".symver {local}, {base}@{ver}");')
        if ver is not None:
            nodes.setdefault(ver, []).append(base if default else None)
    # A script either names version nodes or is one anonymous node, never both: unversioned
    # symbols join the first node (an unversioned reference binds to any default version).
    unversioned = [b for b, v, _, _, _ in wanted if v is None]
    script = []
    for i, (ver, names) in enumerate(nodes.items()):
        listed = [n for n in names if n] + (unversioned if i == 0 else [])
        globals_ = ("global: " + "".join(n + "; " for n in listed)) if listed else ""
        script.append(f"{ver} {{ {globals_}{'local: *; ' if i == 0 else ''}}};")
    if not script:
        script.append("{ global: " + "".join(n + "; " for n in unversioned) + "local: *; };")
    stem = os.path.join(out_dir, name + ".stub")
    with open(stem + ".c", "w") as f:
        f.write("\n".join(c_lines) + "\n")
    with open(stem + ".map", "w") as f:
        f.write("\n".join(script) + "\n")
    subprocess.run(["cc", "-shared", "-fPIC", "-O0", "-w", "-o", os.path.join(out_dir, name),
                    stem + ".c", f"-Wl,-soname,{name}", f"-Wl,--version-script={stem}.map"],
                   check=True)
    os.remove(stem + ".c")
    os.remove(stem + ".map")
    return name, len(wanted)


def main(argv):
    if "--" not in argv or len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    sep = argv.index("--")
    out_dir, reals, importers = argv[1], argv[2:sep], argv[sep + 1:]
    imported = set()
    for obj in importers:
        for name, _, _ in dynamic_symbols(obj, defined=False):
            base, ver, _ = split_version(name)
            imported.add((base, ver))
    for real in reals:
        name, count = write_stub(out_dir, real, imported)
        print(f"stand-in {name}: {count} symbols")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
