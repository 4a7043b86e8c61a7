#!/usr/bin/env python3
"""Lists the longest functions of src/ and tools/ (issue 11: none longer than ~80
lines). A function is a definition that opens at column 0 and closes with a '}' at column 0, the
house's clang-format layout; lambdas count toward the function that holds them.
    python3 scripts/function-lengths.py [N]     # the N longest (default 10)
"""
import glob, os, re, sys

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
files = [f for d in ('src/**/*.cpp', 'src/**/*.h', 'tools/*.cpp')
         for f in glob.glob(os.path.join(root, d), recursive=True)]
found = []
for path in files:
    lines = open(path, encoding='utf-8').read().split('\n')
    start = None
    for i, line in enumerate(lines):
        if start is None:
            # A definition: a signature at column 0 whose '{' ends it or a following line.
            if re.match(r'^[A-Za-z_].*\(', line) and not line.startswith(('namespace', 'struct', 'class', 'enum', 'union', 'TEST')):
                for j in range(i, min(i + 6, len(lines))):
                    if lines[j].rstrip().endswith(';'):
                        break
                    if lines[j].rstrip().endswith('{'):
                        start = i
                        break
        elif line.startswith('}'):
            found.append((i - start + 1, os.path.relpath(path, root), start + 1, lines[start].strip()[:70]))
            start = None
found.sort(reverse=True)
n = int(sys.argv[1]) if len(sys.argv) > 1 else 10
for length, path, line, head in found[:n]:
    print(f'{length:4d}  {path}:{line}  {head}')
largest = max(files, key=lambda f: sum(1 for _ in open(f, encoding='utf-8')))
print(f'largest file: {os.path.relpath(largest, root)}, {sum(1 for _ in open(largest, encoding="utf-8"))} lines')
