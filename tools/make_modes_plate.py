#!/usr/bin/env python3
"""Write test/data/uff/modes_plate.uff, the normal modes of a plate greenconv does not ship, with
pyuff (an independent writer), for the modes_file model's tests (test/model/test_modesfile_mod.f90).

    pip install pyuff          # a tool for this script only, never a dependency of greenconv
    python3 tools/make_modes_plate.py [OUTPUT_DIRECTORY]     # default: test/data/uff

The plate: aluminium, 0.5 m x 0.4 m x 5 mm, simply supported on all four edges (model/plate.f90
is periodic along x and simply supported across, with other constants). Closed form:
    w_mn(x, y) = sin(m*pi*x/a)*sin(n*pi*y/b),  modal mass rho*h*a*b/4,
    omega_mn = pi**2*sqrt(D/(rho*h))*((m/a)**2 + (n/b)**2),  D = E*h**3/(12*(1 - nu**2)).
Every mode up to F_MAX Hz is written as a dataset 55 of 6 DOF per node (X, Y translations 0, Z
the deflection, the rotations the slopes), modal mass in record 8, a viscous damping ratio
0.02 for odd modes and 0 (none: the scene's applies) for even ones. Nodes (dataset 15): a
3 x 3 grid, 30 mm apart, around (0.2, 0.17) m.

modes_plate.expected holds what the file holds, written with 17 significant digits after
parsing the file's fields back in Python (so that the Fortran reader is compared with another
parser, to 1e-12):
    node LABEL X Y Z
    mode NUMBER FREQUENCY_HZ MODAL_MASS DAMPING_RATIO
    shape LABEL Z_VALUE            (one per node after each mode line)
"""
import math
import os
import sys

import numpy as np
import pyuff

E, NU, RHO = 70.0e9, 0.33, 2700.0
A, B, H = 0.5, 0.4, 0.005
F_MAX = 3000.0
D = E*H**3/(12.0*(1.0 - NU**2))
MASS = RHO*H*A*B/4.0


def modes():
    found = []
    for m in range(1, 40):
        for n in range(1, 40):
            omega = math.pi**2*math.sqrt(D/(RHO*H))*((m/A)**2 + (n/B)**2)
            if omega/(2.0*math.pi) <= F_MAX:
                found.append((omega/(2.0*math.pi), m, n))
    return sorted(found)


def nodes():
    """Labels and x, y [m] of the 3 x 3 nodes, 30 mm apart, around (0.2, 0.17) m."""
    labels = np.arange(1, 10) + 100
    x = np.array([0.17 + 0.03*(i % 3) for i in range(9)])
    y = np.array([0.14 + 0.03*(i // 3) for i in range(9)])
    return labels, x, y


def fresh(out, name):
    """The path of a file to write in `out`, removed first (pyuff appends)."""
    path = os.path.join(out, name)
    if os.path.exists(path):
        os.remove(path)
    return path


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else 'test/data/uff'
    path = fresh(out, 'modes_plate.uff')
    labels, x, y = nodes()
    uff = pyuff.UFF(path)
    uff.write_sets({'type': 15, 'node_nums': labels, 'def_cs': np.zeros(9), 'disp_cs': np.zeros(9),
                    'color': np.ones(9), 'x': x, 'y': y, 'z': np.zeros(9)}, mode='add')
    for k, (f, m, n) in enumerate(modes()):
        km, kn = m*math.pi/A, n*math.pi/B
        w = np.sin(km*x)*np.sin(kn*y)
        uff.write_sets({'type': 55, 'analysis_type': 2, 'data_ch': 3, 'spec_data_type': 8, 'load_case': 1,
                        'mode_n': k + 1, 'freq': f, 'modal_m': MASS, 'modal_damp_vis': 0.02 if k % 2 == 0 else 0.0,
                        'modal_damp_his': 0.0, 'node_nums': labels, 'id1': 'plate %d,%d' % (m, n),
                        'r1': np.zeros(9), 'r2': np.zeros(9), 'r3': w,
                        'r4': kn*np.sin(km*x)*np.cos(kn*y), 'r5': -km*np.cos(km*x)*np.sin(kn*y),
                        'r6': np.zeros(9)}, mode='add')
    # what the file holds, parsed back here by Python
    lines = open(path).read().split('\n')
    with open(os.path.join(out, 'modes_plate.expected'), 'w') as f:
        f.write('# tools/make_modes_plate.py: the fields of modes_plate.uff parsed by Python\n')
        i = 0
        while i < len(lines):
            if lines[i].strip() == '-1' and i + 1 < len(lines) and lines[i + 1].strip():
                number = int(lines[i + 1][:6])
                j = i + 2
                if number == 15:
                    while lines[j].strip() != '-1':
                        t = lines[j]
                        f.write('node %d %.17g %.17g %.17g\n' % (int(t[:10]), float(t[40:53]), float(t[53:66]),
                                                                 float(t[66:79])))
                        j += 1
                elif number == 55:
                    r8 = lines[i + 9]
                    f.write('mode %d %.17g %.17g %.17g\n' % (int(lines[i + 8][30:40]), float(r8[:13]),
                                                              float(r8[13:26]), float(r8[26:39])))
                    j = i + 10
                    while lines[j].strip() != '-1':
                        f.write('shape %d %.17g\n' % (int(lines[j][:10]), float(lines[j + 1][26:39])))
                        j += 2
                i = j + 1
            else:
                i += 1


if __name__ == '__main__':
    main()
