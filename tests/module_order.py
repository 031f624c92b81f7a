#!/usr/bin/env python3
"""Checks every #include in src/ against the module order (cmake/module_levels.txt)
and the dependencies each module declares in CMake. Prints file:line: reason
for each violation and exits 1 when there is one.

Usage: module_order.py ROOT             check the tree at ROOT
       module_order.py --self-test ROOT  check that a scratch copy of ROOT with
                                         deliberate violations is refused
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def read_table(root):
    levels, owners, confined, seams, seam_files = {}, [], [], [], []
    with open(os.path.join(root, 'cmake', 'module_levels.txt')) as f:
        for n, line in enumerate(f, 1):
            words = line.split('#', 1)[0].split()
            if not words:
                continue
            if words[0] == 'module' and len(words) == 3:
                levels[words[1]] = int(words[2])
            elif words[0] == 'header' and len(words) == 3:
                owners.append((words[1], words[2]))
            elif words[0] == 'confined' and len(words) == 3:
                confined.append((words[1], words[2]))
            elif words[0] == 'seam' and len(words) == 3:
                seams.append((words[1], words[2]))
            elif words[0] == 'seam-file' and len(words) == 3:
                seam_files.append((words[1], words[2]))
            else:
                sys.exit('cmake/module_levels.txt:%d: cannot read %r' % (n, line.strip()))
    return levels, owners, confined, seams, seam_files


def cmake_calls(text, name):
    """The argument texts of every call `name(...)` in a CMake file."""
    text = re.sub(r'#[^\n]*', '', text)
    out = []
    for m in re.finditer(r'\b%s\s*\(' % re.escape(name), text):
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += {'(': 1, ')': -1}.get(text[i], 0)
            i += 1
        out.append(text[m.end():i - 1])
    return out


def declared_deps(root, module, levels):
    """(DEPS, TEST_DEPS) of a module: the sb_<m> names it links."""
    path = os.path.join(root, 'src', module, 'CMakeLists.txt')
    deps, test_deps = set(), set()
    if not os.path.exists(path):
        return deps, test_deps
    text = open(path).read()
    for args in cmake_calls(text, 'sb_module'):
        section = None
        for word in args.split()[1:]:
            if word in ('SOURCES', 'DEPS', 'TEST_DEPS'):
                section = word
                continue
            m = re.fullmatch(r'sb_(\w+)', word)
            if m and m.group(1) in levels:
                (test_deps if section == 'TEST_DEPS' else deps if section == 'DEPS' else set()).add(
                    m.group(1))
    for args in cmake_calls(text, 'target_link_libraries'):
        words = args.split()
        if words and words[0] == 'sb_' + module:
            for w in words[1:]:
                m = re.fullmatch(r'sb_(\w+)', w)
                if m and m.group(1) in levels:
                    deps.add(m.group(1))
    return deps, test_deps


def check(root):
    levels, owners, confined, seams, seam_files = read_table(root)
    src = os.path.join(root, 'src')
    errors = []
    folders = sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
    for d in folders:
        if d not in levels:
            errors.append('src/%s: a module missing from cmake/module_levels.txt' % d)
    for module in folders:
        if module not in levels:
            continue
        deps, test_deps = declared_deps(root, module, levels)
        # Modules this one reaches only through a module between (seam lines):
        # never included nor named as `M::`, tests included, whatever DEPS say.
        hidden = [m for (user, m) in seams if user == module]
        named = re.compile(r'\b(%s)::' % '|'.join(map(re.escape, hidden))) if hidden else None
        for dirpath, _, files in os.walk(os.path.join(src, module)):
            for name in sorted(files):
                if not name.endswith(('.h', '.cc', '.inc')):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                is_test = name.endswith('_test.cc') or name.endswith('_test_util.h')
                file_hidden = [m for (only, m) in seam_files if only == rel]
                allowed = deps | (test_deps if is_test else set())
                with open(path, errors='replace') as f:
                    for n, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            code = re.sub(r'"(\\.|[^"\\])*"', '""', line).split('//', 1)[0]
                            if named and named.search(code):
                                errors.append('%s:%d: names %s:: types (%s reaches %s only '
                                              'through app; seam in cmake/module_levels.txt)' %
                                              (rel, n, named.search(code).group(1), module,
                                               named.search(code).group(1)))
                            continue
                        kind, inc = m.groups()
                        where = '%s:%d: #include %s%s%s' % (rel, n, kind, inc,
                                                              '"' if kind == '"' else '>')
                        if kind == '"' and '/' in inc:
                            target = inc.split('/', 1)[0]
                            if target == module:
                                continue
                            if target in file_hidden:
                                errors.append('%s: %s may not include %s (seam-file in '
                                              'cmake/module_levels.txt)' % (where, rel, target))
                                continue
                            if target in hidden:
                                errors.append('%s: %s may not include %s (seam in '
                                              'cmake/module_levels.txt: through app only)' %
                                              (where, module, target))
                                continue
                            if target not in levels:
                                errors.append('%s: unknown module "%s"' % (where, target))
                            elif levels[target] > levels[module]:
                                errors.append('%s: %s (level %d) is above %s (level %d)' %
                                              (where, target, levels[target], module,
                                               levels[module]))
                            elif target not in allowed:
                                errors.append('%s: %s does not declare sb_%s in its CMake DEPS' %
                                              (where, module, target))
                        elif kind == '<':
                            for prefix, owner in owners:
                                if inc.startswith(prefix) and name.endswith('.h') and \
                                        owner != module and not is_test:
                                    errors.append('%s: a %s type in a header of %s (owned by %s)' %
                                                  (where, prefix, module, owner))
                            for header, only in confined:
                                if inc == header and rel != only and not is_test:
                                    errors.append('%s: %s is confined to %s' % (where, header, only))
    return errors


def self_test(root):
    """Copies the tree, adds violations one at a time, and expects each refused."""
    cases = [
        ('src/crdl/route.cc', '#include "web/server.h"\n', 'src/crdl/route.cc:', 'is above crdl'),
        ('src/chaos/variation.cc', '#include "markov/model.h"\n', 'src/chaos/variation.cc:',
         'does not declare sb_markov'),
        ('src/plan/plan.h', '#include <nlohmann/json.hpp>\n', 'src/plan/plan.h:',
         'a nlohmann/ type in a header of plan'),
        ('src/web/server.cc', '#include <httplib.h>\n', 'src/web/server.cc:',
         'confined to src/web/http_transport.cc'),
        # Issue 21: web and cli reach the database through app only.
        ('src/web/server.cc', '#include "store/store.h"\n', 'src/web/server.cc:',
         'web may not include store'),
        ('src/cli/cmd_db.cc', '#include "store/open.h"\n', 'src/cli/cmd_db.cc:',
         'cli may not include store'),
        ('src/web/api_test_util.h', '#include "store/store_test_util.h"\n',
         'src/web/api_test_util.h:', 'web may not include store'),
        ('src/web/pages.cc', 'static store::RouteRecord* unused = nullptr;\n', 'src/web/pages.cc:',
         'names store:: types'),
        ('src/app/types.h', '#include "store/store.h"\n', 'src/app/types.h:',
         'src/app/types.h may not include store'),
    ]
    failures = []
    for path, line, where, why in cases:
        tmp = tempfile.mkdtemp(prefix='sb_module_order_')
        try:
            for d in ('src', 'cmake'):
                shutil.copytree(os.path.join(root, d), os.path.join(tmp, d))
            target = os.path.join(tmp, path)
            text = open(target).read()
            # After the first include, so the line number is a real one.
            i = text.index('#include')
            i = text.index('\n', i) + 1
            open(target, 'w').write(text[:i] + line + text[i:])
            errors = check(tmp)
            if not any(e.startswith(where) and why in e for e in errors):
                failures.append('%s with %s was not refused (got: %s)' %
                                (path, line.strip(), errors))
            else:
                print('refused as expected: %s' % [e for e in errors if e.startswith(where)][0])
        finally:
            shutil.rmtree(tmp)
    # A folder missing from the table.
    tmp = tempfile.mkdtemp(prefix='sb_module_order_')
    try:
        for d in ('src', 'cmake'):
            shutil.copytree(os.path.join(root, d), os.path.join(tmp, d))
        os.mkdir(os.path.join(tmp, 'src', 'stray'))
        errors = check(tmp)
        if not any('src/stray' in e for e in errors):
            failures.append('an unlisted src/stray was not refused')
        else:
            print('refused as expected: src/stray missing from the table')
    finally:
        shutil.rmtree(tmp)
    return failures


def main():
    args = sys.argv[1:]
    if args and args[0] == '--self-test':
        failures = self_test(args[1])
        for f in failures:
            print(f)
        return 1 if failures else 0
    errors = check(args[0] if args else '.')
    for e in errors:
        print(e)
    if not errors:
        print('module order: every include follows cmake/module_levels.txt and the declared DEPS')
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main())
