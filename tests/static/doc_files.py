#!/usr/bin/env python3
"""doc_files.py - docs/architecture.md names every file of rt/, tools/scenec/ and
tools/modrt/ in the first column of its table, and names no file that is not there.

Each directory's table is the first one after its marker line; a file is named when it
appears in backticks in a row's first cell. Usage: doc_files.py [docs/architecture.md]."""
import os
import re
import sys

TABLES = [  # directory, the line its table follows
    ('rt', '## Files of `rt/`'),
    ('tools/scenec', '| file of `tools/scenec/` |'),
    ('tools/modrt', '## Files of `tools/modrt/`'),
]


def table_names(lines, marker):
    """the backticked names of the first cells of the table after the marker line"""
    try:
        i = next(k for k, l in enumerate(lines) if l.startswith(marker))
    except StopIteration:
        return None
    if not marker.startswith('|'):  # a heading: its table starts at the next row
        while i < len(lines) and not lines[i].startswith('|'):
            i += 1
    names = set()
    while i < len(lines) and lines[i].startswith('|'):
        first = lines[i].split('|')[1]
        names.update(re.findall(r'`([^`]+)`', first))
        i += 1
    return names


def main(argv):
    doc = argv[0] if argv else 'docs/architecture.md'
    lines = open(doc, encoding='utf-8').read().split('\n')
    passed = failed = 0
    for d, marker in TABLES:
        files = {f for f in os.listdir(d) if f.endswith(('.c', '.h'))}
        names = table_names(lines, marker)
        if names is None:
            print('doc_files: %s: no table after "%s"' % (doc, marker))
            failed += 1
            continue
        names = {n for n in names if n.endswith(('.c', '.h', '.mk'))}
        missing = sorted(files - names)
        gone = sorted(n for n in names if not os.path.exists(os.path.join(d, n)))
        if missing:
            print('doc_files: %s: files of %s/ not in its table: %s'
                  % (doc, d, ', '.join(missing)))
        if gone:
            print('doc_files: %s: its table of %s/ names files that do not exist: %s'
                  % (doc, d, ', '.join(gone)))
        ok = not missing and not gone
        passed += ok
        failed += not ok
    print('doc_files: %d passed, %d failed' % (passed, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
