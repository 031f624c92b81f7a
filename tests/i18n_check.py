#!/usr/bin/env python3
"""The catalog check (issue 32): every user-visible string of the pages is in
the message catalogs.

1. Extraction: xgettext reads every Tr/TrN/N_ message of src/web (the page
   sources; tests excluded) and every Msg/MsgN/MsgId id of src/app (the
   sentences the app keeps as app::Message, translated by id: a candidate's
   reasons, a report's verdict) into a template; msgcmp then fails for each
   catalog po/<lang>.po that lacks one of them or leaves it untranslated or
   fuzzy, and msgfmt --check fails on a broken placeholder or plural form.
2. Scan: a string literal of a page source with English text between tags
   (`"<h1>Your logbook</h1>"`, `"Please <a href=...>"`) that is not wrapped in
   Tr() fails with file:line. A line meant to stay as it is (a brand name, a
   language's own name) says so with a comment `// i18n: <why>`.
3. The static scripts (web/*.js): every message a script shows is written
   `tr('English text', arg1, ...)` -- one single-quoted literal, "{1}".. for
   the arguments -- and listed under the script's array in
   src/web/script_messages.cc (app.js -> kAppJs, gym_import.js -> kGymImportJs:
   `N_("English text")`), which the page renders translated into its JSON
   message block. The check fails for a tr() message the array lacks (it would
   stay English) and, with file:line, for a string literal that looks shown to
   the user outside tr(): one with two words ("not saved"), a capitalised word
   ("Discarded."), or any word on a line that writes to the user (textContent,
   innerText, title, placeholder, alert, confirm, say, aria-label). Code strings
   (headers, selectors) on such a line say so with `// i18n: <why>`.

  i18n_check.py SOURCE_ROOT            run both checks (the CTest i18n_catalogs)
  i18n_check.py --self-test SOURCE_ROOT
      on a scratch copy with a deliberately unwrapped string and a wrapped one
      missing from the catalogs, the check must fail twice (the CTest
      i18n_catalogs_rejects_unwrapped)
  i18n_check.py --update SOURCE_ROOT   regenerate po/strangebeta.pot and merge it
      into po/*.po (msgmerge; new messages come in untranslated)
  i18n_check.py --pending SOURCE_ROOT  rewrite tests/i18n_pending.txt, the page
      strings not wrapped yet (the check allows those only; the list shrinks)
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

KEYWORDS = ["--keyword=Tr:2", "--keyword=TrN:2,3", "--keyword=N_", "--keyword=NN_:1,2"]
# The app's messages (app/message.h): sentences web translates by id.
APP_KEYWORDS = ["--keyword=Msg:1", "--keyword=MsgN:1,2", "--keyword=MsgId:1",
                # The card's words (plan/card.cc, plan::CardTranslate).
                "--keyword=CardTr:2", "--keyword=CardTrN:2,3"]
LITERAL = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
WORD = re.compile(r"[A-Za-z]{2,}")


JS_TR = re.compile(r"\btr\(\s*'((?:[^'\\\n]|\\.)*)'")
# A count's message: trn('{1} route', '{1} routes', n, ...).
JS_TRN = re.compile(r"\btrn\(\s*'((?:[^'\\\n]|\\.)*)'\s*,\s*'((?:[^'\\\n]|\\.)*)'")
JS_LITERAL = re.compile(r"'((?:[^'\\\n]|\\.)*)'|\"((?:[^\"\\\n]|\\.)*)\"|`([^`]*)`")
JS_SHOWN = re.compile(r"textContent|innerText|\.title\s*=|placeholder|\balert\(|\bconfirm\(|"
                      r"\bsay\(|aria-label")
JS_PROSE = re.compile(r"[A-Za-z]{2,}[,.:;!?]?\s+[A-Za-z(]{2,}|^[A-Z][a-z]+\b")
JS_CODE = re.compile(r"^(?:[#.\[][\w\-.#\[\]=\"' ]*|[a-z]+(?:-[a-z]+)+|[A-Za-z]+(?:-[A-Za-z]+)+:?|"
                     r"/[\w/.\-?=&:]*|use strict)$")
JS_IDENTIFIER = re.compile(r"^[a-z_]+$")
# Code on a line that also shows text: element names, classes, comparisons.
JS_NOT_TEXT = re.compile(r"(?:createElement|closest|querySelector(?:All)?|classList\.\w+|\$)\(\s*'[^']*'|"
                         r"(?:className|type)\s*=\s*'[^']*'|[!=]==\s*'[^']*'|'[^']*'\s*[!=]==|'[^']*'\[")


def js_sources(root):
    return sorted(glob.glob(os.path.join(root, "web", "*.js")))


def js_unescape(text):
    return re.sub(r"\\(.)", r"\1", text)


def js_messages(path):
    """The tr('...') message ids of a script, in order."""
    with open(path, encoding="utf-8") as f:
        return [js_unescape(m.group(1)) for m in JS_TR.finditer(f.read())]


def js_plural_messages(path):
    """The trn('one', 'many') pairs of a script, in order."""
    with open(path, encoding="utf-8") as f:
        return [(js_unescape(m.group(1)), js_unescape(m.group(2)))
                for m in JS_TRN.finditer(f.read())]


def script_array(root, name):
    """The body of array `name` in src/web/script_messages.cc (None: no file or array)."""
    path = os.path.join(root, "src", "web", "script_messages.cc")
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        text = f.read()
    m = re.search(r"\b" + name + r"\[\]\s*=\s*\{(.*?)\n\};", text, re.S)
    return m.group(1) if m else None


def listed_script_plurals(root, name):
    """The NN_() pairs of array `name` in src/web/script_messages.cc (None: no array)."""
    body = script_array(root, name)
    if body is None:
        return None
    return {(re.sub(r"\\(.)", r"\1", a), re.sub(r"\\(.)", r"\1", b)) for a, b in
            re.findall(r'NN_\(\s*"((?:[^"\\]|\\.)*)"\s*,\s*"((?:[^"\\]|\\.)*)"\s*\)', body)}


def script_array_name(path):
    stem = os.path.basename(path)[:-3]
    return "k" + "".join(p.capitalize() for p in stem.split("_")) + "Js"


def listed_script_messages(root, name):
    """The N_() ids of array `name` in src/web/script_messages.cc (None: no array)."""
    body = script_array(root, name)
    if body is None:
        return None
    ids = set()
    for n in re.finditer(r'N_\(((?:\s*"(?:[^"\\]|\\.)*")+)\s*\)', body):
        parts = re.findall(r'"((?:[^"\\]|\\.)*)"', n.group(1))
        ids.add(re.sub(r"\\(.)", r"\1", "".join(parts)))
    return ids


def check_scripts(root):
    """tr() messages of web/*.js missing from their script's array."""
    failures = []
    for js in js_sources(root):
        rel = os.path.relpath(js, root)
        ids = js_messages(js)
        name = script_array_name(js)
        pairs = js_plural_messages(js)
        if pairs:
            listed = listed_script_plurals(root, name + "Plurals") or set()
            for pair in pairs:
                if pair not in listed:
                    failures.append(f"{rel}: trn('{pair[0]}', '{pair[1]}') is not listed in "
                                    f"{name}Plurals (src/web/script_messages.cc): it would "
                                    f"stay English")
        if not ids:
            continue
        listed = listed_script_messages(root, name)
        if listed is None:
            failures.append(f"{rel}: tr() messages but no array {name} in src/web/script_messages.cc")
            continue
        for msg in ids:
            if msg not in listed:
                failures.append(f"{rel}: tr('{msg}') is not listed in {name} "
                                f"(src/web/script_messages.cc): it would stay English")
    return failures


def js_unwrapped_text(path, rel):
    """file:line messages for script strings shown to the user outside tr()."""
    out = []
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    for n, line in enumerate(lines, 1):
        stripped = line.lstrip()
        if "// i18n:" in line or stripped.startswith("//") or stripped.startswith("*") or \
                stripped.startswith("/*"):
            continue
        code = re.sub(r"\s//\s.*$", "", line)
        code = JS_TRN.sub("trn(", code)
        code = JS_TR.sub("tr(", code)
        code = JS_NOT_TEXT.sub("", code)
        shown = JS_SHOWN.search(code) is not None
        for m in JS_LITERAL.finditer(code):
            text = next(g for g in m.groups() if g is not None)
            if not WORD.search(text) or JS_CODE.match(text.strip()):
                continue
            if not shown and JS_IDENTIFIER.match(text.strip()):
                continue
            if shown or JS_PROSE.search(text):
                out.append((rel, n, text.strip()))
    return out


def page_sources(root):
    files = sorted(glob.glob(os.path.join(root, "src", "web", "*.cc")))
    return [f for f in files if not f.endswith("_test.cc")]


def app_sources(root):
    """src/app's sources that build app::Message ids (Msg, MsgN, MsgId), and
    the card's (src/plan/card.cc: CardTr, CardTrN)."""
    out = [os.path.join(root, "src", "plan", "card.cc")]
    out = [f for f in out if os.path.exists(f)]
    for f in sorted(glob.glob(os.path.join(root, "src", "app", "*.cc"))):
        if f.endswith("_test.cc") or f.endswith("message.cc"):
            continue
        with open(f, encoding="utf-8") as fh:
            if re.search(r"\bMsg(N|Id)?\(", fh.read()):
                out.append(f)
    return out


def extract(root, out):
    base = ["xgettext", "--language=C++", "--from-code=UTF-8", "--no-wrap", "--sort-by-file",
            "--add-comments=TRANSLATORS:", "--package-name=strangebeta", "-o", out]
    subprocess.run(base + KEYWORDS + [os.path.relpath(f, root) for f in page_sources(root)],
                   cwd=root, check=True)
    app = [os.path.relpath(f, root) for f in app_sources(root)]
    if app:
        # Joined to the pages' template (-j): the app's ids are page messages too.
        subprocess.run(base + ["-j", "--keyword"] + APP_KEYWORDS + app, cwd=root, check=True)


def check_catalogs(root):
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        pot = os.path.join(tmp, "strangebeta.pot")
        extract(root, pot)
        pos = sorted(glob.glob(os.path.join(root, "po", "*.po")))
        if not pos:
            failures.append("po/: no catalogs")
        for po in pos:
            rel = os.path.relpath(po, root)
            r = subprocess.run(["msgcmp", "-N", po, pot], capture_output=True, text=True)
            if r.returncode != 0:
                with open(pot, encoding="utf-8") as f:
                    pot_lines = f.read().split("\n")
                for m in re.finditer(r"^.*?:(\d+): this message is used but not defined",
                                     r.stderr, re.M):
                    line = int(m.group(1))
                    near = pot_lines[max(0, line - 6):line + 1]
                    where = [x for x in near if x.startswith("#:")]
                    msgid = [x for x in near if x.startswith("msgid ")] or ["?"]
                    failures.append(f"{rel}: not translated: {msgid[-1]} "
                                    f"({' '.join(where).replace('#: ', '')})")
                if not any(f.startswith(rel + ": not translated") for f in failures):
                    failures.append(f"{rel}: msgcmp:\n{r.stderr}")
            r = subprocess.run(["msgfmt", "--check", "--statistics", "-o", os.devnull, po],
                               capture_output=True, text=True)
            if r.returncode != 0:
                failures.append(f"{rel}: msgfmt --check:\n{r.stderr}")
            elif "untranslated" in r.stderr or "fuzzy" in r.stderr:
                failures.append(f"{rel}: {r.stderr.strip()}")
    return failures


def unwrapped_text(path, rel):
    """file:line messages for literal text between tags outside Tr()."""
    out = []
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    in_raw = False
    for n, line in enumerate(lines, 1):
        if in_raw:
            if ')"' in line:
                in_raw = False
            continue
        if 'R"(' in line and ')"' not in line.split('R"(', 1)[1]:
            in_raw = True
            continue
        code = line.split("//", 1)[0] if not line.lstrip().startswith('"') else line
        if "// i18n:" in line or line.lstrip().startswith("//") or line.lstrip().startswith("#"):
            continue
        for m in LITERAL.finditer(code):
            text = m.group(1)
            segments = re.findall(r">([^<>]*)(?=<|$)", text)
            start = re.match(r"([^<>=]*)<", text)
            if start:
                segments.append(start.group(1))
            for seg in segments:
                seg = re.sub(r"&[a-z#0-9]+;|\\n|\\\"", " ", seg)
                if WORD.search(seg):
                    out.append((rel, n, seg.strip()))
    return out


PENDING = os.path.join("tests", "i18n_pending.txt")


def read_pending(root):
    """(file, text) -> count of the strings known to be unwrapped still."""
    counts = {}
    path = os.path.join(root, PENDING)
    if not os.path.exists(path):
        return counts
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            rel, text = line.split("\t", 1)
            counts[(rel, text)] = counts.get((rel, text), 0) + 1
    return counts


def found_unwrapped(root):
    found = []
    for f in page_sources(root):
        found += unwrapped_text(f, os.path.relpath(f, root))
    for f in js_sources(root):
        found += js_unwrapped_text(f, os.path.relpath(f, root))
    return found


def scan(root):
    """Unwrapped text not in the pending list, and pending entries gone."""
    failures = []
    left = read_pending(root)
    for rel, n, text in found_unwrapped(root):
        if left.get((rel, text), 0) > 0:
            left[(rel, text)] -= 1
            continue
        failures.append(f"{rel}:{n}: unwrapped text \"{text}\" (wrap it: Tr(v, \"...\"))")
    for (rel, text), k in sorted(left.items()):
        if k > 0:
            failures.append(f"{PENDING}: \"{text}\" ({rel}) is wrapped now or gone: remove "
                            f"the line (i18n_check.py --pending rewrites the list)")
    return failures


def write_pending(root):
    found = found_unwrapped(root)
    with open(os.path.join(root, PENDING), "w", encoding="utf-8") as f:
        f.write("# Page strings not wrapped in Tr() yet (issue 32): the catalog check\n"
                "# (tests/i18n_check.py) allows these and no others; the list only shrinks.\n"
                "# file<TAB>text, one per occurrence.\n")
        for rel, _, text in found:
            f.write(f"{rel}\t{text}\n")
    print(f"{len(found)} unwrapped strings listed in {PENDING}")
    return 0


def run(root):
    failures = check_catalogs(root) + scan(root) + check_scripts(root)
    for f in failures:
        print(f)
    if failures:
        print(f"i18n_check: {len(failures)} problem(s); see DEVELOPERS.md, \"Translating the UI\"")
        return 1
    print("i18n_check: every page string is wrapped and in po/de.po and po/fr.po")
    return 0


def self_test(root):
    with tempfile.TemporaryDirectory() as tmp:
        copy = os.path.join(tmp, "src")
        os.makedirs(os.path.join(copy, "src"))
        shutil.copytree(os.path.join(root, "src", "web"), os.path.join(copy, "src", "web"))
        shutil.copytree(os.path.join(root, "po"), os.path.join(copy, "po"))
        shutil.copytree(os.path.join(root, "web"), os.path.join(copy, "web"))
        os.makedirs(os.path.join(copy, "tests"))
        if os.path.exists(os.path.join(root, PENDING)):
            shutil.copy(os.path.join(root, PENDING), os.path.join(copy, PENDING))
        if run(copy) != 0:
            print("self-test: the real tree must pass first")
            return 1
        page = os.path.join(copy, "src", "web", "i18n_selftest.cc")
        with open(page, "w", encoding="utf-8") as f:
            f.write('std::string A() { return "<p>Unwrapped words</p>"; }\n')
        scan_fail = scan(copy)
        if not any("i18n_selftest.cc:1" in s for s in scan_fail):
            print("self-test: the unwrapped string was not found")
            return 1
        with open(page, "w", encoding="utf-8") as f:
            f.write('std::string A(const PageViewer& v) { return "<p>" + Tr(v, "A message no '
                    'catalog has") + "</p>"; }\n')
        if scan(copy):
            print("self-test: a wrapped string was reported as unwrapped")
            return 1
        cat_fail = check_catalogs(copy)
        if not any("A message no catalog has" in s for s in cat_fail):
            print("self-test: the message missing from the catalogs was not reported")
            return 1
        # An app message (app::Msg) no catalog has.
        os.makedirs(os.path.join(copy, "src", "app"), exist_ok=True)
        with open(os.path.join(copy, "src", "app", "i18n_selftest.cc"), "w",
                  encoding="utf-8") as f:
            f.write('Message A() { return Msg("An app sentence no catalog has"); }\n')
        if not any("An app sentence no catalog has" in s for s in check_catalogs(copy)):
            print("self-test: the app message missing from the catalogs was not reported")
            return 1
        # The scripts: a message shown outside tr(), and a tr() message the
        # script's array in script_messages.cc lacks.
        script = os.path.join(copy, "web", "app.js")
        with open(script, "a", encoding="utf-8") as f:
            f.write("el.textContent = 'Unwrapped script words';\n"
                    "say(msg, tr('A script message nobody listed'));\n"
                    "say(msg, trn('{1} thing nobody listed', '{1} things nobody listed', n, n));\n")
        if not any("app.js:" in s and "Unwrapped script words" in s for s in scan(copy)):
            print("self-test: the unwrapped script string was not found")
            return 1
        if not any("A script message nobody listed" in s for s in check_scripts(copy)):
            print("self-test: the script message missing from kAppJs was not reported")
            return 1
        if not any("{1} thing nobody listed" in s for s in check_scripts(copy)):
            print("self-test: the script count message missing from kAppJsPlurals was not reported")
            return 1
    print("self-test: unwrapped strings (page and script), an untranslated message (page and "
          "app) and an unlisted script message all fail the check")
    return 0


def update(root):
    pot = os.path.join(root, "po", "strangebeta.pot")
    extract(root, pot)
    for po in sorted(glob.glob(os.path.join(root, "po", "*.po"))):
        subprocess.run(["msgmerge", "--quiet", "--update", "--backup=none", "--no-wrap",
                        "--no-fuzzy-matching", po, pot], check=True)
    print("updated", pot, "and po/*.po")
    return 0


def main(argv):
    if len(argv) == 3 and argv[1] == "--self-test":
        return self_test(argv[2])
    if len(argv) == 3 and argv[1] == "--update":
        return update(argv[2])
    if len(argv) == 3 and argv[1] == "--pending":
        return write_pending(argv[2])
    if len(argv) == 2:
        return run(argv[1])
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
