#!/usr/bin/env python3
"""file_graph.py - the include-and-call graph between the files of a C directory; fails
on a circle (a strongly connected component of more than one file).

An edge A -> B: A includes B (a quoted #include), or A names a function B defines inside
a body or an initializer (a call, or its address in a table; a prototype is no edge). A static function is its own file's; an inline
function defined in a header is the header's. Usage: file_graph.py DIR... (each DIR on
its own: its .c and .h files are the nodes); -v prints the edges."""
import os
import re
import sys

TOKEN = re.compile(r'[A-Za-z_]\w*|[{}();=,]')


def strip(src):
    """the source without comments, strings, character constants and preprocessor
    lines other than #include (their names are no calls)"""
    src = re.sub(r'/\*.*?\*/', ' ', src, flags=re.S)
    src = re.sub(r'//[^\n]*', ' ', src)
    src = re.sub(r'"(\\.|[^"\\\n])*"', '""', src)
    src = re.sub(r"'(\\.|[^'\\\n])*'", "''", src)
    src = re.sub(r'\\\n', ' ', src)
    return '\n'.join(l for l in src.split('\n') if not l.lstrip().startswith('#'))


def bodies(code):
    """the text inside braces at any depth (function bodies and table initializers):
    where a name is a call or an address, not a prototype"""
    out, depth, start = [], 0, 0
    for m in re.finditer(r'[{}]', code):
        if m.group() == '{':
            if depth == 0:
                start = m.end()
            depth += 1
        else:
            depth -= 1
            if depth == 0:
                out.append(code[start:m.start()])
    return ' '.join(out)


def definitions(code):
    """the functions a file defines: (name, static), from a name followed by a
    parenthesised list and a body at file scope"""
    toks = TOKEN.findall(code)
    out, depth, i = [], 0, 0
    while i < len(toks):
        t = toks[i]
        if t == '{':
            depth += 1
        elif t == '}':
            depth -= 1
        elif depth == 0 and t == '(' and i > 0 and re.match(r'[A-Za-z_]', toks[i - 1]):
            j, par = i, 0
            while j < len(toks):
                par += toks[j] == '('
                par -= toks[j] == ')'
                if par == 0:
                    break
                j += 1
            if j + 1 < len(toks) and toks[j + 1] == '{':
                k = i - 2  # back to the start of the declaration
                while k >= 0 and toks[k] not in (';', '}', '{', ')'):
                    k -= 1
                static = 'static' in toks[k + 1:i - 1]
                out.append((toks[i - 1], static))
        i += 1
    return out


def graph(d):
    files = sorted(f for f in os.listdir(d) if f.endswith(('.c', '.h')))
    code, incs = {}, {}
    for f in files:
        raw = open(os.path.join(d, f), encoding='utf-8').read()
        incs[f] = [m for m in re.findall(r'^\s*#\s*include\s+"([^"]+)"', raw, re.M)
                   if m in files]
        code[f] = strip(raw)
    owner, local = {}, {}
    for f in files:
        local[f] = set()
        for name, static in definitions(code[f]):
            if static and f.endswith('.c'):
                local[f].add(name)
            else:
                owner.setdefault(name, f)
    edges = {f: set(incs[f]) - {f} for f in files}
    for f in files:
        for name in set(re.findall(r'[A-Za-z_]\w*', bodies(code[f]))):
            g = owner.get(name)
            if g and g != f and name not in local[f]:
                edges[f].add(g)
    return files, edges


def circles(files, edges):
    """strongly connected components of more than one file (Tarjan)"""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in files:
        if v not in index:
            visit(v)
    return out


def main(argv):
    verbose = '-v' in argv
    dirs = [a for a in argv if a != '-v']
    bad = failed = 0
    for d in dirs:
        files, edges = graph(d)
        if verbose:
            for f in files:
                print('%s/%s -> %s' % (d, f, ' '.join(sorted(edges[f]))))
        found = circles(files, edges)
        n = sum(len(e) for e in edges.values())
        for comp in found:
            bad = 1
            print('file_graph: %s: files that call or include each other in a circle: %s'
                  % (d, ', '.join(comp)))
            for f in comp:
                print('    %s -> %s' % (f, ', '.join(sorted(edges[f] & set(comp)))))
        print('file_graph: %s: %d files, %d edges, %d circles' % (d, len(files), n, len(found)))
        failed += len(found) > 0
    print('file_graph: %d passed, %d failed' % (len(dirs) - failed, failed))
    return bad


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
