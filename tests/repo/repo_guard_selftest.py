#!/usr/bin/env python3
"""The repo guard can fail: a small tree with one breach of each rule is refused, each breach
named with its file, and the same tree mended passes."""
import os
import subprocess
import sys
import tempfile

GUARD = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'repo_guard.py')


def write(root, path, text):
    full = os.path.join(root, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, 'w', encoding='utf-8') as f:
        f.write(text)


def run(root):
    r = subprocess.run([sys.executable, GUARD, '--root', root], capture_output=True, text=True)
    return r.returncode, r.stdout


def main():
    failures = []
    with tempfile.TemporaryDirectory() as root:
        write(root, 'docs/flavours/pem.md',
              '# PEM\n\n## 1. Maths\n\n## 2. Sources\n\n- Hakura, Snyder, Lengyel 2001.\n')
        write(root, 'docs/design.md', '# Design\n\n## 1. Conventions\n\n## 2. Measuring\n')
        write(root, 'README.md', '[design](docs/design.md) [gone](docs/missing.md)\n')
        write(root, 'engine/long.cpp', '//\n' * 451)
        write(root, 'engine/refs.h', '// docs/design.md §2, Hakura §4, DESIGN §7, '
              'docs/design.md §9\n')
        write(root, 'assetcooker/lib/plan/shared.cpp', 'int PemSamples = 0;\n')
        write(root, 'assetcooker/lib/flavours/pem/ok.cpp', 'int PemSamples = 0;\n')
        write(root, 'assetcooker/lib/a/x.h', '#include "assetcooker/lib/b/y.h"\n')
        write(root, 'assetcooker/lib/b/y.h', '#include "assetcooker/lib/a/x.h"\n')
        code, out = run(root)
        expected = ['engine/long.cpp: 451 lines', 'README.md:1: link to docs/missing.md',
                    'engine/refs.h:1: §7 refers to nothing', 'has no section "9."',
                    'assetcooker/lib/plan/shared.cpp:1: a shared tools file names a flavour',
                    'assetcooker/lib/a/x.h: includes assetcooker/lib/b/y.h',
                    'assetcooker/lib/b/y.h: includes assetcooker/lib/a/x.h']
        if code != 1:
            failures.append(f'breaches: exit {code}, expected 1')
        for e in expected:
            if e not in out:
                failures.append(f'breaches: no line with "{e}" in:\n{out}')
        for wrong in ('docs/design.md §2', 'Hakura', 'flavours/pem/ok.cpp'):
            if any(wrong in l and 'refers' in l for l in out.splitlines()):
                failures.append(f'a valid reference was refused: {wrong}')
        # Mended: every breach fixed or listed as debt.
        write(root, 'README.md', '[design](docs/design.md)\n')
        write(root, 'engine/long.cpp', '//\n' * 450)
        write(root, 'engine/refs.h', '// docs/design.md §2, Hakura §4; docs/design.md §1 and §2\n')
        write(root, 'tests/repo/flavour_debt.txt', '# still to move\nassetcooker/lib/plan/shared.cpp\n')
        write(root, 'tests/repo/cycle_debt.txt',
              'assetcooker/lib/a -> assetcooker/lib/b\nassetcooker/lib/b -> assetcooker/lib/a\n')
        code, out = run(root)
        if code != 0:
            failures.append(f'mended tree: exit {code}, expected 0:\n{out}')
        # Debt that was paid must leave the list.
        write(root, 'assetcooker/lib/plan/shared.cpp', 'int samples = 0;\n')
        code, out = run(root)
        if code != 1 or 'no longer names a flavour' not in out:
            failures.append(f'stale flavour debt not reported:\n{out}')
    for f in failures:
        print(f)
    print('repo guard self-test:', 'FAILED' if failures else 'ok')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
