#!/usr/bin/env python3
"""Every relative link and image in README.md, CHANGELOG.md and docs/**/*.md
resolves to a file (or folder) in the repository, and every #anchor into a
Markdown page names one of its headings (GitHub's slug rule). Prints one line
per broken link and exits 1; exits 0 when all resolve. Run by the ctest
`docs.links`. Only the standard library: it runs under any python3."""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HTML = re.compile(r"<(?:img|a)\s[^>]*(?:src|href)=\"([^\"]+)\"")
FENCE = re.compile(r"^\s*(```|~~~)")


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(page):
    out, fenced = set(), False
    for line in page.read_text(encoding="utf-8").splitlines():
        if FENCE.match(line):
            fenced = not fenced
        elif not fenced and line.startswith("#"):
            out.add(slug(line.lstrip("#")))
    return out


def links(page):
    fenced = False
    for n, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if fenced:
            continue
        line = re.sub(r"`[^`]*`", "", line)  # inline code is not a link
        for m in list(LINK.finditer(line)) + list(HTML.finditer(line)):
            yield n, m.group(1)


def main():
    pages = [p for p in [ROOT / "README.md", ROOT / "CHANGELOG.md"] if p.exists()]
    pages += sorted((ROOT / "docs").rglob("*.md"))
    broken, count = [], 0
    for page in pages:
        for n, target in links(page):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("//"):
                continue  # http:, https:, mailto:
            count += 1
            path, _, anchor = target.partition("#")
            dest = page if not path else (page.parent / path).resolve()
            where = f"{page.relative_to(ROOT)}:{n}"
            if not dest.exists():
                broken.append(f"{where}: {target}: no such file")
            elif ROOT.resolve() not in dest.resolve().parents and dest.resolve() != ROOT.resolve():
                broken.append(f"{where}: {target}: outside the repository")
            elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                broken.append(f"{where}: {target}: no heading #{anchor} in {dest.name}")
    for b in broken:
        print(b)
    print(f"docs links: {count} relative links in {len(pages)} pages, {len(broken)} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
