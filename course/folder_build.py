#!/usr/bin/env python3
"""Builds a student's algorithm folder into an hsr of its own, in place of the shipped
folder of the same name (the add-an-algorithm interface: README, "How to add an
algorithm"): each of its .cpp and .hpp files replaces the shipped one or joins it.
The checkout and its build are left as they were (overlay.py says how).

    python3 course/folder_build.py FOLDER --algorithm NAME [--build build] --out DIR   # DIR/hsr

hsr grade runs it as the `make build` of a C++ algorithm folder.
"""
import argparse
import pathlib
import shutil

from overlay import SOURCE, build_with, fail

if __name__ == '__main__':
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('folder', type=pathlib.Path)
    parser.add_argument('--algorithm', required=True)
    parser.add_argument('--build', type=pathlib.Path, default=SOURCE / 'build')
    parser.add_argument('--out', type=pathlib.Path, required=True)
    arguments = parser.parse_args()
    shipped = SOURCE / 'algorithms' / arguments.algorithm
    if not shipped.is_dir():
        fail(f'{arguments.algorithm}: no folder algorithms/{arguments.algorithm} to replace')
    sources = [path for path in sorted(arguments.folder.iterdir()) if path.suffix in ('.cpp', '.hpp')]
    if not sources:
        fail(f'{arguments.folder}: no .cpp or .hpp file; expected an algorithm folder')
    # Only what differs from the shipped folder is compiled again.
    replacements = {}
    for path in sources:
        relative = f'algorithms/{arguments.algorithm}/{path.name}'
        shipped_file = SOURCE / relative
        if not shipped_file.exists() or shipped_file.read_text() != path.read_text():
            replacements[relative] = path.read_text()
    if replacements:
        count = build_with(replacements, arguments.build, arguments.out)
    else:
        arguments.out.mkdir(parents=True, exist_ok=True)
        shutil.copy2(arguments.build / 'hsr', arguments.out / 'hsr')
        count = 0
    print(f'{arguments.folder}: {len(replacements)} file(s) differ from algorithms/{arguments.algorithm}/, '
          f'{count} translation unit(s) compiled; {arguments.out / "hsr"} built')
