#!/usr/bin/env python3
"""The layers and the floors inside them, checked against the code's own #include lines.

Every quoted include names its layer ("core/doc/document.h", "gpu/render/...", "ui/inspector/...").
A layer may include only the layers listed for it; inside a layer, a folder may include only its own
folder and folders on lower floors. Exit 0 when every include keeps to that, 1 naming each one that
does not (file, line, the include and the rule it breaks). docs/architecture.md draws the same floors.
"""
import os
import re
import sys

# Which layers each layer may include (its own included).
LAYERS = {
    'core': {'core'},
    'demo': {'demo', 'core'},
    'editor': {'editor', 'core'},
    'gpu': {'gpu', 'core'},
    'ui': {'ui', 'editor', 'core'},
    'app': {'app', 'ui', 'gpu', 'editor', 'demo', 'core'},
}
# Where each layer's files live.
ROOTS = {'core': 'engine/core', 'demo': 'engine/demo', 'editor': 'engine/editor', 'gpu': 'engine/gpu',
         'ui': 'ui', 'app': 'app'}
# Floors inside a layer, lowest first: a folder includes only its own and lower floors' folders.
FLOORS = {
    'core': [['util', 'math'], ['anim', 'rig', 'field', 'camera'], ['blobtree'], ['poly'], ['io'],
             ['standin', 'animorphosis'], ['particles', 'standin_morph'], ['project'], ['scene'],
             ['paint', 'export'], ['doc']],
    'gpu': [['include_shared'], ['vulkan'], ['present'], ['transition'], ['render'], ['polygonizer'], ['frame']],
    'ui': [['widgets'], ['common'], ['timeline', 'viewport', 'curves', 'outliner', 'export'], ['inspector'],
           ['animorphosis'], ['shell']],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def floor_of(layer, folder):
    for i, names in enumerate(FLOORS.get(layer, [])):
        if folder in names:
            return i
    return None


def check(repo):
    problems = []
    for layer, root in ROOTS.items():
        base = os.path.join(repo, root)
        for d, _, files in os.walk(base):
            for f in files:
                if not f.endswith(('.h', '.cpp')):
                    continue
                path = os.path.join(d, f)
                rel = os.path.relpath(path, base)
                folder = rel.split(os.sep)[0] if os.sep in rel else ''
                if layer in FLOORS and folder and floor_of(layer, folder) is None:
                    problems.append(f'{os.path.relpath(path, repo)}: folder {layer}/{folder} is on no floor '
                                    '(add it to FLOORS in tests/layout/check_layers.py and to docs/architecture.md)')
                with open(path, encoding='utf-8', errors='replace') as fh:
                    for n, line in enumerate(fh, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        inc = m.group(1)
                        parts = inc.split('/')
                        if len(parts) < 2 or parts[0] not in LAYERS:
                            if layer == 'gpu' and len(parts) == 1:
                                continue  # include_shared/ headers, shared with GLSL by bare name
                            problems.append(f'{os.path.relpath(path, repo)}:{n}: "{inc}" does not name its layer')
                            continue
                        to_layer = parts[0]
                        if to_layer not in LAYERS[layer]:
                            problems.append(f'{os.path.relpath(path, repo)}:{n}: "{inc}": layer {layer} '
                                            f'may not include {to_layer}')
                            continue
                        if to_layer != layer or layer not in FLOORS or not folder or len(parts) < 3:
                            continue
                        to_folder = parts[1]
                        a, b = floor_of(layer, folder), floor_of(layer, to_folder)
                        if to_folder != folder and (b is None or a is None or b >= a):
                            problems.append(f'{os.path.relpath(path, repo)}:{n}: "{inc}": {layer}/{folder} may '
                                            f'include only lower floors, and {to_folder} is not below it')
    return problems


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', '..')
    problems = check(repo)
    for p in problems:
        print(p)
    print(f'layers: {len(problems)} include(s) break the layering' if problems else 'layers: every include keeps to its layer and floor')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
