# SPDX-License-Identifier: BSD-3-Clause
"""The structure test: the module stays small enough to read.

    python3 structure.py <project root> [--max-file-lines N] [--max-function-lines N]

Checks every C++ file under Module/ (the math and the comparison techniques included):
- no file over --max-file-lines (900) lines;
- no function over --max-function-lines (100) lines, from the line its definition begins to its
  closing brace (a definition at namespace scope, as the project's clang-format lays it out:
  its body opens with "{" alone in column 0 and closes with "}" in column 0);
- no circle of includes among the module's units (a unit is a header with its source file, x.h
  and x.cxx, and a class's private xInternals.h), so that no helper includes the orchestrator
  it serves.
Prints each finding and exits 1 when there is one.
"""
import os
import re
import sys

FILE_LIMIT, FUNCTION_LIMIT = 900, 100
args = sys.argv[1:]
root = args.pop(0)
while args:
    flag, value = args.pop(0), int(args.pop(0))
    if flag == "--max-file-lines":
        FILE_LIMIT = value
    elif flag == "--max-function-lines":
        FUNCTION_LIMIT = value
    else:
        sys.exit("structure.py: unknown option " + flag)

sources = []
for folder, _, names in os.walk(os.path.join(root, "Module")):
    sources += [os.path.join(folder, n) for n in names if n.endswith((".h", ".cxx"))]
sources.sort()
problems = []

# Lines that open a braced block at column 0 which is not a function body.
NOT_A_FUNCTION = re.compile(r"^(namespace|extern|struct|class|union|enum)\b|=\s*$")

for path in sources:
    name = os.path.relpath(path, root)
    lines = open(path, encoding="utf-8").read().splitlines()
    if len(lines) > FILE_LIMIT:
        problems.append("%s: %d lines (at most %d)" % (name, len(lines), FILE_LIMIT))
    start, head = None, ""
    for number, line in enumerate(lines, 1):
        if line == "{" and start is None:
            # The definition's first line: the nearest line above in column 0 (a declaration may
            # wrap onto indented lines).
            begin = number - 1
            while begin > 1 and (not lines[begin - 1] or lines[begin - 1][0].isspace()):
                begin -= 1
            head = lines[begin - 1] if begin >= 1 else ""
            if NOT_A_FUNCTION.search(head) or NOT_A_FUNCTION.search(lines[number - 2]):
                continue
            start = begin
        elif start is not None and line.startswith("}"):
            length = number - start + 1
            if length > FUNCTION_LIMIT:
                problems.append("%s:%d: %s: a function of %d lines (at most %d)"
                                % (name, start, head.strip()[:72], length, FUNCTION_LIMIT))
            start = None

# Units and their includes (quoted includes that name a file of the module).
def unit_name(path):
    base = os.path.splitext(os.path.basename(path))[0]
    return base[:-len("Internals")] if base.endswith("Internals") else base


unit_of = {os.path.basename(path): unit_name(path) for path in sources}
units = {}
for path in sources:
    unit = unit_name(path)
    edges = units.setdefault(unit, set())
    for line in open(path, encoding="utf-8"):
        match = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
        if match:
            target = unit_of.get(os.path.basename(match.group(1)))
            if target and target != unit:
                edges.add(target)

# Circles: strongly connected components of more than one unit (Tarjan).
index, low, stack, on_stack, circles, counter = {}, {}, [], set(), [], [0]


def visit(unit):
    index[unit] = low[unit] = counter[0]
    counter[0] += 1
    stack.append(unit)
    on_stack.add(unit)
    for target in sorted(units.get(unit, ())):
        if target not in index:
            visit(target)
            low[unit] = min(low[unit], low[target])
        elif target in on_stack:
            low[unit] = min(low[unit], index[target])
    if low[unit] == index[unit]:
        component = []
        while True:
            top = stack.pop()
            on_stack.discard(top)
            component.append(top)
            if top == unit:
                break
        if len(component) > 1:
            circles.append(sorted(component))


sys.setrecursionlimit(10000)
for unit in sorted(units):
    if unit not in index:
        visit(unit)
for circle in circles:
    problems.append("an include circle among: " + ", ".join(circle))

for problem in problems:
    print("structure: " + problem)
if problems:
    sys.exit(1)
print("structure: %d files, none over %d lines, no function over %d lines, no include circle"
      % (len(sources), FILE_LIMIT, FUNCTION_LIMIT))
