#!/usr/bin/env python3
"""Checks that the project's citations of its own documents resolve.

Code, shaders, scripts and documents cite a section as
`docs/radiosity.md, "The clamp"` (or `design.md, section 2, "Ties"`, or a
Markdown link followed by the quoted title). A cited title must open a
heading of that document or a bold paragraph lead (`**The clamp.**`); the
check ignores case and accepts a title the heading starts with, so
"The march" names "The march (`--ao-method march`)". `section N` must be a
numbered heading `N.` of that document. Relative Markdown links must name a
file that exists. A document moved or a heading renamed without its
citations fails here with one line per broken citation.

Usage: check_doc_citations.py REPO_ROOT
"""
import os
import re
import subprocess
import sys

SOURCE_SUFFIXES = ('.md', '.cpp', '.hpp', '.h', '.glsl', '.frag', '.vert',
                   '.comp', '.py', '.sh', '.txt', '.cmake')

# A citation: a document name, optionally closing a Markdown link, then
# ", " and an optional "section N, " before the quoted title. Comment
# markers at line starts are folded away first, so a citation may wrap.
CITATION = re.compile(
    r'([\w./-]+\.md)\)?,\s*(?:section (\d+),\s*)?"([^"\n]+)"')
SECTION_ONLY = re.compile(r'([\w./-]+\.md)\)?,\s*section (\d+)\b')
LINK = re.compile(r'\]\(([^)#\s]+)(?:#[^)]*)?\)')
HEADING = re.compile(r'^#+\s+(.*?)\s*$')
BOLD_LEAD = re.compile(r'\*\*([^*]+?)\*\*')


def tracked_files(root):
    try:
        out = subprocess.check_output(['git', '-C', root, 'ls-files'],
                                      text=True, stderr=subprocess.DEVNULL)
    except (OSError, subprocess.CalledProcessError):
        print('skipped: not a git checkout, so the tracked files are unknown')
        sys.exit(77)
    return sorted(set(out.split()))  # a file in a merge conflict is listed per stage


def titles_of(path):
    titles = []
    in_code = False
    with open(path, encoding='utf-8') as f:
        for line in f:
            if line.startswith('```'):
                in_code = not in_code
                continue
            if in_code:
                continue
            m = HEADING.match(line)
            if m:
                titles.append(m.group(1))
            titles.extend(b.strip() for b in BOLD_LEAD.findall(line))
    return [normalise(t) for t in titles]


def normalise(text):
    text = re.sub(r'\s+', ' ', text.replace('`', '')).strip().lower()
    return text.rstrip('.:')


def resolve(doc, citing_file, docs):
    """The tracked document a citation names: a path relative to the
    repository or to the citing file, else the one document of that name."""
    for candidate in (doc, os.path.normpath(
            os.path.join(os.path.dirname(citing_file), doc))):
        if candidate in docs:
            return candidate
    matches = [p for p in sorted(docs)
               if os.path.basename(p) == os.path.basename(doc)]
    docs_first = [p for p in matches if p.startswith('docs/')]
    return (docs_first or matches or [None])[0]


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else '.'
    files = tracked_files(root)
    docs = {f for f in files if f.endswith('.md')}
    titles = {}
    problems = []
    checked = 0
    for f in files:
        if not f.endswith(SOURCE_SUFFIXES):
            continue
        try:
            with open(os.path.join(root, f), encoding='utf-8') as fh:
                text = fh.read()
        except (UnicodeDecodeError, FileNotFoundError):
            continue
        folded = re.sub(r'\n[ \t]*(?://+|#+(?=\s)|\*(?=\s)|>)?[ \t]*', ' ',
                        text)
        for m in CITATION.finditer(folded):
            doc, section, title = m.group(1), m.group(2), m.group(3)
            target = resolve(doc, f, docs)
            if target is None:
                continue  # another project's file name, not ours
            if target not in titles:
                titles[target] = titles_of(os.path.join(root, target))
            checked += 1
            wanted = normalise(title)
            if not any(t == wanted or t.startswith(wanted + ' ') or
                       t.startswith(wanted + ',') or
                       t.startswith(wanted + '(') or
                       t.startswith(wanted + ':') or
                       t.startswith(wanted + '.')
                       for t in titles[target]):
                problems.append(f'{f}: {doc}, "{title}": no such heading '
                                f'or bold lead in {target}')
        for m in SECTION_ONLY.finditer(folded):
            target = resolve(m.group(1), f, docs)
            if target is None:
                continue
            if target not in titles:
                titles[target] = titles_of(os.path.join(root, target))
            checked += 1
            if not any(t.startswith(m.group(2) + '. ')
                       for t in titles[target]):
                problems.append(f'{f}: {m.group(1)}, section {m.group(2)}: '
                                f'no numbered heading {m.group(2)} in '
                                f'{target}')
        if f.endswith('.md'):
            for m in LINK.finditer(text):
                link = m.group(1)
                if re.match(r'^[a-z]+:', link):
                    continue  # a URL
                path = os.path.normpath(os.path.join(os.path.dirname(f),
                                                     link))
                checked += 1
                if not os.path.exists(os.path.join(root, path)):
                    problems.append(f'{f}: link to {link}: no such file')
    for p in problems:
        print(p)
    print(f'{checked} citations and links checked, {len(problems)} broken')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
