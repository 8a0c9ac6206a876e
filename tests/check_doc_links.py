#!/usr/bin/env python3
"""Every relative link and image in the documentation resolves.

  check_doc_links.py ROOT          check README.md, CHANGELOG.md, docs/**/*.md
                                   and the README.md of every top-level folder
  check_doc_links.py --self-test   show that a broken link, image and anchor
                                   are each reported (the check can fail)

A link is `[text](target)` or `![alt](target)` outside code spans and fenced
code blocks. A target with a scheme (https:, mailto:) is not checked. A
relative target must name an existing file or folder (relative to the page);
a `#anchor` (alone, or after a .md target) must be a heading of that page,
slugged as GitHub does: lower case, every character other than a letter, a
digit, a space, `-` or `_` dropped, spaces turned into `-`, and `-1`, `-2`
... appended to repeated headings. Prints one line per broken link
(file:line: target: why) and exits 1 if there is any.
"""
import os
import re
import sys
import tempfile

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^()\s>]+(?:\([^()\s]*\))?)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def strip_code_spans(line):
    return re.sub(r"(`+)(.+?)\1", "", line)


def slug(text):
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading keeps its text
    text = text.replace("`", "").lower()
    text = "".join(ch for ch in text if ch.isalnum() or ch in " -_")
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, found = {}, set()
        in_fence = False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if FENCE.match(line):
                    in_fence = not in_fence
                    continue
                m = None if in_fence else HEADING.match(line)
                if m:
                    s = slug(m.group(2))
                    n = seen.get(s, 0)
                    seen[s] = n + 1
                    found.add(s if n == 0 else f"{s}-{n}")
        cache[path] = found
    return cache[path]


def links(path):
    in_fence = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                in_fence = not in_fence
                continue
            if in_fence or line.startswith("    "):  # fenced or indented code
                continue
            for m in LINK.finditer(strip_code_spans(line)):
                yield number, m.group(1)


def check_file(path, root):
    problems = []
    for number, target in links(path):
        if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
            continue
        where = f"{os.path.relpath(path, root)}:{number}: {target}"
        file_part, _, anchor = target.partition("#")
        resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
        if not os.path.exists(resolved):
            problems.append(f"{where}: no such file")
            continue
        if anchor:
            if not resolved.endswith(".md") or os.path.isdir(resolved):
                problems.append(f"{where}: an anchor on a file that is not a Markdown page")
            elif anchor not in anchors(resolved):
                problems.append(f"{where}: no heading '#{anchor}' in {os.path.relpath(resolved, root)}")
    return problems


def pages(root):
    out = [os.path.join(root, name) for name in ("README.md", "CHANGELOG.md")]
    for name in sorted(os.listdir(root)):
        readme = os.path.join(root, name, "README.md")
        if not name.startswith(".") and name != "build" and os.path.isfile(readme):
            out.append(readme)
    for folder, dirs, files in os.walk(os.path.join(root, "docs")):
        dirs.sort()
        out += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".md")]
    return [p for p in dict.fromkeys(out) if os.path.isfile(p)]


def check(root):
    problems = []
    checked = pages(root)
    for page in checked:
        problems += check_file(page, root)
    return checked, problems


def self_test():
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "docs", "images"))
        open(os.path.join(root, "docs", "images", "a.png"), "wb").close()
        with open(os.path.join(root, "docs", "page.md"), "w") as f:
            f.write("# A page\n\n## The `sph check` section\n")
        with open(os.path.join(root, "README.md"), "w") as f:
            f.write("[ok](docs/page.md) [ok](docs/page.md#the-sph-check-section) ![ok](docs/images/a.png)\n"
                    "[web](https://example.org) `[code](nowhere.md)`\n"
                    "```\n[fenced](nowhere.md)\n```\n"
                    "[missing](docs/gone.md)\n![missing image](docs/images/b.png)\n"
                    "[bad anchor](docs/page.md#no-such-heading)\n")
        _, problems = check(root)
        expected = ["docs/gone.md", "docs/images/b.png", "docs/page.md#no-such-heading"]
        reported = [p.split(": ")[1] for p in problems]
        if reported != expected:
            print(f"FAILED: self-test reported {reported}, expected {expected}")
            return 1
        print(f"self-test: the {len(expected)} broken links were reported, the 5 others were not")
        return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    root = os.path.abspath(sys.argv[1])
    checked, problems = check(root)
    for p in problems:
        print(p)
    print(f"{len(checked)} pages checked, {len(problems)} broken link(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
