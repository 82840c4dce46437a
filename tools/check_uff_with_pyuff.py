#!/usr/bin/env python3
"""Read universal files written by greenconv (greenconv_io_uff_write) with pyuff, an
independent reader, and check what it finds: every dataset's type, each dataset 58's DOFs,
ordinate type and point count against its own record 7, finite values, node coordinates.

A tool around greenconv only (pip install pyuff); not part of `make test`.

    python3 tools/check_uff_with_pyuff.py FILE.uff [FILE.uff ...]

Prints one summary line per file and exits with status 1 when pyuff fails or a check does.
"""
import sys

import numpy as np
import pyuff


def check(path):
    sets = pyuff.UFF(path).read_sets()
    if isinstance(sets, dict):
        sets = [sets]
    types = [s['type'] for s in sets]
    functions = [s for s in sets if s['type'] == 58]
    problems = []
    for k, s in enumerate(functions):
        n = int(s['num_pts'])
        if len(s['data']) != n or len(s['x']) != n:
            problems.append(f'function {k + 1}: {len(s["data"])} values for {n} points')
        if not np.all(np.isfinite(s['data'])):
            problems.append(f'function {k + 1}: non-finite values')
    nodes = [s for s in sets if s['type'] in (15, 2411)]
    n_nodes = sum(len(s['node_nums']) for s in nodes)
    dofs = {(int(s['rsp_node']), int(s['ref_node'])) for s in functions}
    summary = (f'{path}: pyuff {pyuff.__version__} read datasets {sorted(set(types))}: '
               f'{len(functions)} functions (types {sorted({int(s["func_type"]) for s in functions})}, '
               f'ordinate types {sorted({int(s["ord_data_type"]) for s in functions})}), '
               f'{len(dofs)} (response, reference) node pairs, {n_nodes} nodes')
    if functions:
        points = sorted({int(s['num_pts']) for s in functions})
        summary += f', points per function {points}'
        by_pair = {(int(s['rsp_node']), int(s['ref_node'])): np.asarray(s['data']) for s in functions
                   if int(s['func_type']) == 4}
        worst = 0.0
        for (i, j), g in by_pair.items():
            if (j, i) in by_pair and i != j and len(by_pair[(j, i)]) == len(g):
                worst = max(worst, float(np.max(np.abs(g - by_pair[(j, i)]) / np.maximum(np.abs(g), 1e-300))))
        summary += f", max |G_ij - G_ji|/|G_ij| (FRFs) = {worst:.3g}"
    print(summary)
    for p in problems:
        print('  ' + p)
    return not problems


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    ok = all([check(path) for path in sys.argv[1:]])
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
