#!/usr/bin/env python3
"""Runs the commands written in the docs, as a reader would.

Every fenced block tagged ```sh in the given Markdown files is run with bash
(-e -o pipefail) from the repository root of a fresh build: a scratch copy of
the root (its top-level entries linked, `build` linking the build directory,
../shared linking the reference material when present), so files a block
writes land in the scratch directory or under build/. A block whose first
line is `# not run: <reason>` is skipped; one whose first line is
`# needs ../shared` is skipped when ../shared is absent. A block that runs a
benchmark or the MPI driver is skipped in a build without them (the checked
build of scripts/checked_build.sh builds neither). Placeholders belong in
```text blocks.

Usage: docs_commands.py --source ROOT --build BUILD [--shared DIR] [--timeout S] DOC...
Exit status 1 when a block fails (its output is shown), else 0.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Optional parts of a build: a block naming one runs only where it was built.
OPTIONAL = [
    (re.compile(r'\bsb_\w+_bench\b|build/bench/'), 'bench', 'the benchmarks are not built here'),
    (re.compile(r'strangebeta-mpi'), 'strangebeta-mpi', 'the MPI driver is not built here'),
]

FENCE = re.compile(r'^(\s*)(```+|~~~+)\s*([\w+-]*)\s*$')


def sh_blocks(path):
    """(first line number, text) of every ```sh block of a Markdown file."""
    lines = open(path).read().split('\n')
    blocks, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, lang = m.group(2), m.group(3)
        j = i + 1
        while j < len(lines):
            t = lines[j].strip()
            if t.startswith(fence) and t == fence[0] * len(t):
                break
            j += 1
        if lang == 'sh':
            blocks.append((i + 2, '\n'.join(lines[i + 1:j]) + '\n'))
        i = j + 1
    return blocks


def scratch_root(source, build, shared):
    """A directory standing for the repository root of a fresh build."""
    tmp = tempfile.mkdtemp(prefix='sb_docs_')
    root = os.path.join(tmp, 'repo')
    os.mkdir(root)
    for entry in os.listdir(source):
        if entry.startswith('.') or entry == 'build' or entry.startswith('build-'):
            continue
        os.symlink(os.path.join(source, entry), os.path.join(root, entry))
    os.symlink(build, os.path.join(root, 'build'))
    if shared and os.path.isdir(shared):
        os.symlink(shared, os.path.join(tmp, 'shared'))
    return tmp, root


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--source', required=True)
    ap.add_argument('--build', required=True)
    ap.add_argument('--shared', default='')
    ap.add_argument('--timeout', type=int, default=120)
    ap.add_argument('docs', nargs='+')
    a = ap.parse_args()
    source, build = os.path.abspath(a.source), os.path.abspath(a.build)
    shared = os.path.abspath(a.shared) if a.shared else ''
    have_shared = bool(shared) and os.path.isdir(shared)
    failed = ran = skipped = 0
    for doc in a.docs:
        rel = os.path.relpath(os.path.abspath(doc), source)
        for line, text in sh_blocks(doc):
            first = text.lstrip().split('\n', 1)[0].strip()
            where = '%s:%d' % (rel, line)
            if first.startswith('# not run:'):
                print('%s: skipped (%s)' % (where, first[len('# not run:'):].strip()))
                skipped += 1
                continue
            if first.startswith('# needs ../shared') and not have_shared:
                print('%s: skipped (../shared is absent)' % where)
                skipped += 1
                continue
            missing = [why for pattern, path, why in OPTIONAL
                       if pattern.search(text) and not os.path.exists(os.path.join(build, path))]
            if missing:
                print('%s: skipped (%s)' % (where, missing[0]))
                skipped += 1
                continue
            tmp, root = scratch_root(source, build, shared)
            try:
                p = subprocess.run(['bash', '-e', '-o', 'pipefail', '-c', text], cwd=root,
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   timeout=a.timeout)
                ok = p.returncode == 0
                out = p.stdout.decode(errors='replace')
            except subprocess.TimeoutExpired:
                ok, out = False, 'timed out after %d s' % a.timeout
            finally:
                shutil.rmtree(tmp, ignore_errors=True)
            ran += 1
            if ok:
                print('%s: ok' % where)
            else:
                failed += 1
                print('%s: FAILED\n--- block ---\n%s--- output ---\n%s' % (where, text, out[-4000:]))
    print('%d blocks run, %d skipped, %d failed' % (ran, skipped, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
