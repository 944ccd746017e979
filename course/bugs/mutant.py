#!/usr/bin/env python3
"""Builds one bug of the catalogue (catalogue.toml) into an hsr of its own, without
touching the checkout or its build (course/overlay.py says how).

    python3 course/bugs/mutant.py build NAME [--build build] --out DIR   # DIR/hsr
    python3 course/bugs/mutant.py check                                 # every bug's text is found once

hsr grade --self-check runs it as each bug's `make build`.
"""
import argparse
import pathlib
import sys
import tomllib

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from overlay import SOURCE, build_with, fail  # noqa: E402

CATALOGUE = SOURCE / 'course' / 'bugs' / 'catalogue.toml'


def catalogue():
    with open(CATALOGUE, 'rb') as f:
        return tomllib.load(f)['bug']


def find_bug(name):
    for bug in catalogue():
        if bug['name'] == name:
            return bug
    fail(f'{name}: no such bug in {CATALOGUE.relative_to(SOURCE)}')


def mutated_text(bug):
    """The file with the bug's text replaced: exactly once, or the catalogue has gone stale."""
    text = (SOURCE / bug['file']).read_text()
    count = text.count(bug['find'])
    if count != 1:
        fail(f"{bug['name']}: {bug['file']} holds its find text {count} times; expected exactly once")
    return text.replace(bug['find'], bug['replace'])


def check():
    names = set()
    for bug in catalogue():
        if bug['name'] in names:
            fail(f"{bug['name']}: named twice")
        names.add(bug['name'])
        mutated_text(bug)
    print(f'{len(names)} bugs, each text found exactly once')


if __name__ == '__main__':
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    sub = parser.add_subparsers(dest='command', required=True)
    b = sub.add_parser('build')
    b.add_argument('name')
    b.add_argument('--build', type=pathlib.Path, default=SOURCE / 'build')
    b.add_argument('--out', type=pathlib.Path, required=True)
    sub.add_parser('check')
    arguments = parser.parse_args()
    if arguments.command == 'check':
        check()
    else:
        bug = find_bug(arguments.name)
        count = build_with({bug['file']: mutated_text(bug)}, arguments.build, arguments.out)
        print(f"{arguments.name}: {count} translation unit(s) compiled with {bug['file']} changed; {arguments.out / 'hsr'} built")
