#!/usr/bin/env python3
"""Builds one bug of the catalogue (catalogue.toml) into an hsr of its own, without
touching the checkout or its build: the mutated file is written to an overlay folder,
every translation unit that reads it is compiled again with the build's own command
(compile_commands.json) and the overlay first on the include path, and hsr is linked
again (CMakeFiles/hsr.dir/link.txt) with those objects ahead of the libraries, so the
linker takes theirs and leaves the originals in the archives.

    python3 course/bugs/mutant.py build NAME --build build --out DIR   # DIR/hsr
    python3 course/bugs/mutant.py check [--build build]                 # every bug's text is found once

hsr grade --self-check runs it as each bug's `make build`.
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import shlex
import subprocess
import sys
import tomllib

SOURCE = pathlib.Path(__file__).resolve().parents[2]
CATALOGUE = SOURCE / 'course' / 'bugs' / 'catalogue.toml'


def fail(message):
    print(f'mutant.py: error: {message}', file=sys.stderr)
    sys.exit(2)


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
    path = SOURCE / bug['file']
    text = path.read_text()
    count = text.count(bug['find'])
    if count != 1:
        fail(f"{bug['name']}: {bug['file']} holds its find text {count} times; expected exactly once")
    return text.replace(bug['find'], bug['replace'])


def in_hsr(build, link, commands):
    """The compile commands of hsr's own objects: on its link line, or members of the
    libraries it links (not the tests', benchmarks' or other programs')."""
    members = set()
    for word in link:
        if word.endswith('.a'):
            listed = subprocess.run(['ar', 't', word], cwd=build, capture_output=True, text=True, check=True)
            members.update(listed.stdout.split())
    linked = {os.path.normpath(os.path.join(build, w)) for w in link if w.endswith('.o')}
    elsewhere = (str(build / 'tests') + '/', str(build / 'bench') + '/')
    own = []
    for entry in commands:
        out = os.path.normpath(os.path.join(entry['directory'], output_of(entry)))
        if out in linked or (os.path.basename(out) in members and not out.startswith(elsewhere)):
            own.append(entry)
    return own


def readers_of(build, relative, commands):
    """The translation units whose last compile read the file (their .o.d lists it)."""
    readers = []
    for entry in commands:
        source = pathlib.Path(entry['file'])
        if source == SOURCE / relative:
            readers.append(entry)
            continue
        depfile = pathlib.Path(entry['directory']) / (output_of(entry) + '.d')
        if depfile.exists() and ('/' + relative) in depfile.read_text():
            readers.append(entry)
    return readers


def output_of(entry):
    words = shlex.split(entry['command'])
    return words[words.index('-o') + 1]


def compile_one(entry, overlay, relative, objects):
    words = shlex.split(entry['command'])
    out = words.index('-o')
    original = os.path.normpath(os.path.join(entry['directory'], words[out + 1]))
    mutant = objects / (original.replace('/', '_') + '.o')
    words[out + 1] = str(mutant)
    if pathlib.Path(entry['file']) == SOURCE / relative:
        words[words.index(entry['file'])] = str(overlay / relative)
    words.insert(1, f'-I{overlay}')  # the mutated header before the views that hold the original
    done = subprocess.run(words, cwd=entry['directory'], capture_output=True, text=True)
    if done.returncode != 0:
        fail(f'compiling {entry["file"]} with the bug:\n{done.stderr[-3000:]}')
    return original, str(mutant)


def build(name, build_dir, out):
    bug = find_bug(name)
    build_dir, out = build_dir.resolve(), out.resolve()
    overlay, objects = out / 'overlay', out / 'objects'
    (overlay / bug['file']).parent.mkdir(parents=True, exist_ok=True)
    objects.mkdir(parents=True, exist_ok=True)
    (overlay / bug['file']).write_text(mutated_text(bug))
    with open(build_dir / 'compile_commands.json') as f:
        commands = json.load(f)
    link = shlex.split((build_dir / 'CMakeFiles' / 'hsr.dir' / 'link.txt').read_text())
    readers = readers_of(build_dir, bug['file'], in_hsr(build_dir, link, commands))
    if not readers:
        fail(f"{name}: no translation unit of {build_dir} reads {bug['file']}")
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        replaced = dict(pool.map(lambda entry: compile_one(entry, overlay, bug['file'], objects), readers))
    # The link, with each mutated object in its original's place on the command line or,
    # for one inside a library, ahead of the libraries.
    link = [replaced.pop(os.path.normpath(os.path.join(build_dir, w)), w) for w in link]
    at = link.index('-o')
    link[at + 1] = str(out / 'hsr')
    link[at:at] = list(replaced.values())
    done = subprocess.run(link, cwd=build_dir, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f'linking hsr with the bug:\n{done.stderr[-3000:]}')
    print(f"{name}: {len(readers)} translation unit(s) read {bug['file']}; {out / 'hsr'} built")


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
    if arguments.command == 'build':
        build(arguments.name, arguments.build, arguments.out)
    else:
        check()
