"""Builds an hsr of its own from the checkout with some of its files replaced, without
touching the checkout or its build: the replacements are written to an overlay folder,
every translation unit of hsr that reads one of them (its .o.d lists it) is compiled
again with the build's own command (compile_commands.json) and the overlay first on the
include path, new source files with the command of a neighbour in the same folder, and
hsr is linked again (CMakeFiles/hsr.dir/link.txt) with those objects in their
originals' places or, for one inside a library, ahead of the libraries, so that the
linker takes theirs and leaves the originals in the archives.

bugs/mutant.py builds each bug of the catalogue this way, and folder_build.py a
student's algorithm folder.
"""
import concurrent.futures
import json
import os
import pathlib
import shlex
import subprocess
import sys

SOURCE = pathlib.Path(__file__).resolve().parents[1]


def fail(message):
    print(f'{pathlib.Path(sys.argv[0]).name}: error: {message}', file=sys.stderr)
    sys.exit(2)


def output_of(entry):
    words = shlex.split(entry['command'])
    return words[words.index('-o') + 1]


def objects_of_hsr(build, link, commands):
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


def reads_any(entry, relatives):
    """Whether the translation unit is, or its last compile read, one of these files."""
    if any(pathlib.Path(entry['file']) == SOURCE / r for r in relatives):
        return True
    depfile = pathlib.Path(entry['directory']) / (output_of(entry) + '.d')
    if not depfile.exists():
        return False
    depends = depfile.read_text()
    return any(('/' + r) in depends for r in relatives)


def compile_in(entry, source, overlay, objects):
    """The entry's command on `source` (its own file, or the overlay's), the overlay
    first on the include path, into an object of its own."""
    words = shlex.split(entry['command'])
    out = words.index('-o')
    original = os.path.normpath(os.path.join(entry['directory'], words[out + 1]))
    mutant = objects / (os.path.normpath(str(source)).replace('/', '_') + '.o')
    words[out + 1] = str(mutant)
    words[words.index(entry['file'])] = str(source)
    words.insert(1, f'-I{overlay}')  # a replaced header before the include views that hold the original
    # At -O1, which compiles about a fifth faster than the build's -O3 (a student waits on
    # it, an instructor sixty times): the bits do not depend on it (-ffp-contract=off).
    words.append('-O1')
    done = subprocess.run(words, cwd=entry['directory'], capture_output=True, text=True)
    if done.returncode != 0:
        fail(f'compiling {source}:\n{done.stderr[-3000:]}')
    return original, str(mutant)


def build_with(replacements, build, out):
    """hsr built into OUT/hsr with `replacements` ({path relative to the checkout: its
    text}); returns how many translation units were compiled."""
    build, out = build.resolve(), out.resolve()
    overlay, objects = out / 'overlay', out / 'objects'
    objects.mkdir(parents=True, exist_ok=True)
    for relative, text in replacements.items():
        (overlay / relative).parent.mkdir(parents=True, exist_ok=True)
        (overlay / relative).write_text(text)
    with open(build / 'compile_commands.json') as f:
        commands = json.load(f)
    link = shlex.split((build / 'CMakeFiles' / 'hsr.dir' / 'link.txt').read_text())
    own = objects_of_hsr(build, link, commands)
    jobs = []  # (compile command entry, source to compile)
    for entry in own:
        if reads_any(entry, replacements):
            replaced = os.path.relpath(entry['file'], SOURCE)
            jobs.append((entry, overlay / replaced if replaced in replacements else pathlib.Path(entry['file'])))
    # A source file the checkout does not have: compiled as its folder's neighbours are.
    for relative in replacements:
        if relative.endswith('.cpp') and not (SOURCE / relative).exists():
            folder = str(SOURCE / pathlib.Path(relative).parent) + '/'
            neighbour = next((e for e in own if e['file'].startswith(folder)), None)
            if neighbour is None:
                fail(f'{relative}: no file of hsr is compiled from its folder, so nothing says how to compile it')
            jobs.append((dict(neighbour, command=neighbour['command']), overlay / relative, relative))
    if not jobs:
        fail('no translation unit of hsr reads ' + ', '.join(replacements))
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        compiled = list(pool.map(lambda job: compile_in(job[0], job[1], overlay, objects), jobs))
    replaced = {}
    added = []
    for job, (original, mutant) in zip(jobs, compiled):
        if len(job) == 3:
            added.append(mutant)  # a new file: its object joins the link, replacing none
        else:
            replaced[original] = mutant
    link = [replaced.pop(os.path.normpath(os.path.join(build, w)), w) for w in link]
    at = link.index('-o')
    link[at + 1] = str(out / 'hsr')
    link[at:at] = list(replaced.values()) + added
    done = subprocess.run(link, cwd=build, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f'linking hsr:\n{done.stderr[-3000:]}')
    return len(jobs)
