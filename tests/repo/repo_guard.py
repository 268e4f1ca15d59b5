#!/usr/bin/env python3
"""Guards the shape of the repository (issue 37): fails, naming the file and line, when

  - a source file is longer than --max-lines (450),
  - a relative link in a Markdown file points at nothing,
  - a "§" reference does not resolve: `docs/x.md §N` needs a heading "## N." in that file; a
    reference after a paper's author (listed under "Sources" in docs/flavours/*.md) cites the
    paper; anything else (such as the old "DESIGN §4") dangles,
  - an include closes a cycle between folders of the tools (assetcooker/lib/*, sandbox/lib/*,
    one node per folder), unless listed in tests/repo/cycle_debt.txt (which may only shrink),
  - a shared file of the tools (assetcooker/ or sandbox/ outside their flavours/ folders) names
    a flavour, unless it is on the list of files still to move (FLAVOUR_DEBT below, which may
    only shrink: a listed file that no longer names a flavour is an error too, so the list
    stays true).

Reads the files git tracks under --root (or, outside a git checkout, every file).
"""
import argparse
import os
import re
import subprocess
import sys

SOURCE_EXT = ('.h', '.cpp', '.glsl', '.frag', '.vert', '.comp', '.py')
TEXT_EXT = SOURCE_EXT + ('.md', '.txt', '.cmake', '.sh')
TOOL_WINGS = ('assetcooker/', 'sandbox/')
# The one place per wing that lists the flavours (the registration table).
REGISTRATION = ('assetcooker/lib/flavours/flavours.cpp', 'sandbox/lib/flavours/flavours.cpp')

# A flavour named in code: its types, its headers, its name as a string.
FLAVOUR_WORDS = re.compile(
    r'\b(Pem\w*|PEM\w*|pem_\w+|LightField\w*|lightfield\w*|lightField\w*|light_field\w*'
    r'|Distance(Probe|Method|Level|Bake|Host|Asset|Gpu|Layer|Glossy)\w*|CpuDistance\w*'
    r'|distance_(probe|level|bake|lookup|params|glossy|host|asset|layer)\w*)\b'
    r'|"(pem|lightfield|distance)"')

# Shared tools files that still name a flavour: the work issue 37 item 1 has left. Shrinks only.
FLAVOUR_DEBT_FILE = 'tests/repo/flavour_debt.txt'


def tracked_files(root):
    try:
        out = subprocess.run(['git', '-C', root, 'ls-files'], check=True, capture_output=True,
                             text=True).stdout
        return [f for f in out.splitlines() if os.path.isfile(os.path.join(root, f))]
    except (OSError, subprocess.CalledProcessError):
        found = []
        for d, _, names in os.walk(root):
            for n in names:
                found.append(os.path.relpath(os.path.join(d, n), root))
        return found


def read(root, f):
    try:
        with open(os.path.join(root, f), encoding='utf-8') as h:
            return h.read()
    except (UnicodeDecodeError, OSError):
        return None


def headings(text):
    return {m.group(1) for m in re.finditer(r'^#+\s+(\d+[a-z]?)\.\s', text, re.M)}


def paper_authors(root, files):
    authors = set()
    for f in files:
        if not (f.startswith('docs/flavours/') and f.endswith('.md')):
            continue
        text = read(root, f) or ''
        m = re.search(r'^##\s+\d+[a-z]?\.\s+Sources\s*$(.*?)(?=^## |\Z)', text, re.M | re.S)
        if m:
            for line in m.group(1).splitlines():
                w = re.match(r'\s*[-*]\s+([A-Z][a-z]+)', line)
                if w:
                    authors.add(w.group(1))
    return authors


def check_lengths(root, files, max_lines, errors):
    for f in files:
        if not f.endswith(SOURCE_EXT):
            continue
        text = read(root, f)
        if text is None:
            continue
        n = text.count('\n')
        if n > max_lines:
            errors.append(f'{f}: {n} lines, more than {max_lines}: split it by concern')


def check_links(root, files, errors):
    link = re.compile(r'\[[^\]]*\]\(([^)\s]+)\)')
    for f in files:
        if not f.endswith('.md'):
            continue
        text = read(root, f) or ''
        for lineno, line in enumerate(text.splitlines(), 1):
            for m in link.finditer(line):
                target = m.group(1).split('#')[0]
                if not target or re.match(r'^[a-z]+:', target):
                    continue
                path = os.path.normpath(os.path.join(os.path.dirname(f), target))
                if not os.path.exists(os.path.join(root, path)):
                    errors.append(f'{f}:{lineno}: link to {m.group(1)}: no such file')


def check_sections(root, files, errors):
    authors = paper_authors(root, files)
    ref = re.compile(r'§\s?(\d+[a-z]?)')
    cache = {}
    for f in files:
        if not f.endswith(TEXT_EXT) or f.startswith('tests/repo/'):
            continue
        text = read(root, f)
        if text is None or '§' not in text:
            continue
        lines = text.splitlines()
        for i, line in enumerate(lines):
            for m in ref.finditer(line):
                before = line[:m.start()]
                # "docs/x.md §4, §9": a list of sections after one doc names that doc.
                doc = re.search(r'([\w./-]+\.md)(?:\s*§\s?\d+[a-z]?\s*(?:,|and|or)\s*)*\W*$',
                                before)
                if doc:
                    path = os.path.normpath(os.path.join(root, doc.group(1)))
                    if not os.path.exists(path):
                        path = os.path.normpath(os.path.join(root, os.path.dirname(f),
                                                             doc.group(1)))
                    if path not in cache:
                        cache[path] = headings(read(root, path) or '') if os.path.exists(
                            path) else None
                    if cache[path] is None:
                        errors.append(f'{f}:{i + 1}: §{m.group(1)} of {doc.group(1)}: '
                                      'no such file')
                    elif m.group(1) not in cache[path]:
                        errors.append(f'{f}:{i + 1}: {doc.group(1)} has no section '
                                      f'"{m.group(1)}."')
                    continue
                # The author must name this reference: the text since the previous reference
                # or clause on the line (or, at its start, the previous line's end).
                cut = max(before.rfind('§'), before.rfind(';'))
                context = before[cut + 1:] if cut >= 0 else (
                    (lines[i - 1] if i > 0 else '') + ' ' + before)
                if any(re.search(r'\b' + a + r'\b', context) for a in authors):
                    continue  # a section of a paper the flavour docs list
                errors.append(f'{f}:{i + 1}: §{m.group(1)} refers to nothing in the repo: '
                              'name the doc (docs/design.md §N) or the paper\'s author')


CYCLE_DEBT_FILE = 'tests/repo/cycle_debt.txt'
INCLUDE = re.compile(r'^\s*#\s*include\s+"((?:assetcooker|sandbox)/[^"]+)"', re.M)


def include_graph(root, files):
    """Folder -> folder -> the first (file, included) that makes the edge."""
    graph = {}
    for f in files:
        if not (f.startswith(TOOL_WINGS) and f.endswith(('.h', '.cpp'))):
            continue
        for m in INCLUDE.finditer(read(root, f) or ''):
            a, b = os.path.dirname(f), os.path.dirname(m.group(1))
            if a != b:
                graph.setdefault(a, {}).setdefault(b, (f, m.group(1)))
    return graph


def reaches(graph, start, goal):
    seen, todo = set(), [start]
    while todo:
        n = todo.pop()
        if n == goal:
            return True
        if n not in seen:
            seen.add(n)
            todo.extend(graph.get(n, {}))
    return False


def check_cycles(root, files, errors):
    debt_text = read(root, CYCLE_DEBT_FILE) or ''
    debt = {tuple(l.split(' -> ')) for l in debt_text.splitlines()
            if ' -> ' in l and not l.startswith('#')}
    graph = include_graph(root, files)
    cyclic = set()
    for a, edges in sorted(graph.items()):
        for b, (f, inc) in sorted(edges.items()):
            if reaches(graph, b, a):
                cyclic.add((a, b))
                if (a, b) not in debt:
                    errors.append(f'{f}: includes {inc}, and {b}/ already reaches {a}/: '
                                  'an include cycle between folders')
    for a, b in sorted(debt - cyclic):
        errors.append(f'{CYCLE_DEBT_FILE}: {a} -> {b} no longer closes a cycle: take it off')
    return len(cyclic)


def shared_tools_file(f):
    return (f.startswith(TOOL_WINGS) and '/flavours/' not in f and f not in REGISTRATION
            and f.endswith(('.h', '.cpp')))


def check_flavour_names(root, files, errors):
    debt_text = read(root, FLAVOUR_DEBT_FILE) or ''
    debt = {l.strip() for l in debt_text.splitlines() if l.strip() and not l.startswith('#')}
    naming = set()
    for f in files:
        if not shared_tools_file(f):
            continue
        text = read(root, f) or ''
        for lineno, line in enumerate(text.splitlines(), 1):
            m = FLAVOUR_WORDS.search(line)
            if m:
                naming.add(f)
                if f not in debt:
                    errors.append(f'{f}:{lineno}: a shared tools file names a flavour '
                                  f'("{m.group(0)}"): move it into the flavour\'s folder and '
                                  'register it in the wing\'s flavours.cpp')
                break
    for f in sorted(debt - naming):
        errors.append(f'{FLAVOUR_DEBT_FILE}: {f} no longer names a flavour (or is gone): '
                      'take it off the list')
    return len(naming)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--root', default=os.path.join(os.path.dirname(__file__), '..', '..'))
    ap.add_argument('--max-lines', type=int, default=450)
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    files = tracked_files(root)
    errors = []
    check_lengths(root, files, args.max_lines, errors)
    check_links(root, files, errors)
    check_sections(root, files, errors)
    naming = check_flavour_names(root, files, errors)
    cycles = check_cycles(root, files, errors)
    shared = sum(1 for f in files if shared_tools_file(f))
    print(f'repo guard: {len(files)} files; {naming} of {shared} shared tools files name a '
          f'flavour (tests/repo/flavour_debt.txt); {cycles} folder includes close a cycle '
          '(tests/repo/cycle_debt.txt)')
    for e in errors:
        print(e)
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main())
