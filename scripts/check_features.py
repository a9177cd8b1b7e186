#!/usr/bin/env python3
"""Structure checks of the feature generator (engine/stepnc/src/features, issue 16):

1. no function is longer than --max-lines (120) lines, from the first line of its signature to
   its closing brace (lambdas count with the function they are in);
2. no planner (*_plan.cpp) includes a reader header (reader.hpp, *_read.hpp): planners take
   specs, never the model.

check_features.py FOLDER [--max-lines N]   exit 0 when both hold, 1 (listing each place) if not.
"""
import argparse
import pathlib
import re
import sys

SCOPE = re.compile(r'\b(namespace|class|struct|enum|union)\b')
READER_INCLUDE = re.compile(r'#include\s+"(reader\.hpp|[a-z_]*_read\.hpp)"')


def code_only(text):
    """The text with comments, strings and character literals blanked (lines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i))
            i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == '\\' else 1
            out.append(c + ' ' * (min(j, n) - i - 1) + c)
            i = j + 1
        elif c == '#' and (i == 0 or text[i - 1] == '\n'):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def functions(text):
    """(name, first line, last line) of each function body at namespace or class scope."""
    code = code_only(text)
    found = []
    stack = []  # for each open brace: 'scope' or ('function', start line, head)
    item_start = 0  # where the current declaration began (after the last ; { or } at scope)
    line = 1
    for i, c in enumerate(code):
        if c == '\n':
            line += 1
        if c not in '{};':
            continue
        in_function = any(isinstance(s, tuple) for s in stack)
        if c == ';':
            if not in_function:
                item_start = i + 1
            continue
        if c == '{':
            if in_function:
                stack.append('block')
                continue
            head = code[item_start:i]
            if SCOPE.search(head) and '(' not in head.split('{')[0].split('=')[0]:
                stack.append('scope')
                item_start = i + 1
            elif ')' in head:
                lead = len(head) - len(head.lstrip())  # the blank lines before the signature
                first = code.count('\n', 0, item_start + lead) + 1
                name = re.findall(r'([~\w:]+)\s*\(', head)
                stack.append(('function', first, name[0] if name else '?'))
            else:
                stack.append('block')  # an initializer at namespace scope
            continue
        # c == '}'
        if not stack:
            continue
        top = stack.pop()
        if isinstance(top, tuple):
            found.append((top[2], top[1], line))
        if not any(isinstance(s, tuple) for s in stack):
            item_start = i + 1
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('folder')
    parser.add_argument('--max-lines', type=int, default=120)
    args = parser.parse_args()
    problems = []
    files = sorted(pathlib.Path(args.folder).glob('*.[ch]pp'))
    if not files:
        print(f'no sources in {args.folder}')
        return 1
    for path in files:
        text = path.read_text()
        for name, first, last in functions(text):
            length = last - first + 1
            if length > args.max_lines:
                problems.append(f'{path}:{first}: {name} is {length} lines '
                                f'(at most {args.max_lines})')
        if path.name.endswith('_plan.cpp'):
            for number, source_line in enumerate(text.splitlines(), 1):
                if READER_INCLUDE.search(source_line):
                    problems.append(f'{path}:{number}: a planner includes a reader: '
                                    f'{source_line.strip()}')
    for p in problems:
        print(p)
    print(f'{len(files)} files, {len(problems)} problems')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
