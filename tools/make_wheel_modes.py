#!/usr/bin/env python3
"""Write test/data/uff/wheel_modes.uff, a wheel's normal modes written by pyuff (an independent
writer), for the wheel_rail model's wheel from a universal file (test/scene/test_wheelrail_mod.f90).

    pip install pyuff          # a tool for this script only, never a dependency of greenconv
    python3 tools/make_wheel_modes.py [OUTPUT_DIRECTORY]     # default: test/data/uff

Two nodes (dataset 15): 7, the contact, and 9. Two modes (dataset 55, analysis type 2, 6 DOF
per node, the Z translation the one normal to the rail):

- mode 1, the wheel mass on its primary suspension: f = 6.5 Hz, modal mass 600 kg, viscous
  damping ratio 0.4, shape 1 at both nodes (the closed form 1/(k - M w^2 + i w c) with
  k = M (2 pi f)^2 and c = 2 xi M 2 pi f);
- mode 2, a radial mode of the wheel: f = 2500 Hz, modal mass 150 kg, damping ratio 0 (the
  scene's damping_ratio applies), shape 0.8 at node 7 and 0 at node 9 (so node 9 sees the mass
  on its suspension alone).

Every value has at most 6 significant digits, what the file's E13.5 fields hold exactly.
"""
import os
import sys

import numpy as np
import pyuff

MODES = [  # frequency [Hz], modal mass [kg], damping ratio, Z shape at nodes 7 and 9
    (6.5, 600.0, 0.4, [1.0, 1.0]),
    (2500.0, 150.0, 0.0, [0.8, 0.0]),
]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else 'test/data/uff'
    path = os.path.join(out, 'wheel_modes.uff')
    if os.path.exists(path):
        os.remove(path)  # pyuff appends
    labels = np.array([7, 9])
    uff = pyuff.UFF(path)
    uff.write_sets({'type': 15, 'node_nums': labels, 'def_cs': np.zeros(2), 'disp_cs': np.zeros(2),
                    'color': np.ones(2), 'x': np.array([0.0, 0.46]), 'y': np.zeros(2), 'z': np.zeros(2)},
                   mode='add')
    for k, (f, mass, xi, shape) in enumerate(MODES):
        uff.write_sets({'type': 55, 'analysis_type': 2, 'data_ch': 3, 'spec_data_type': 8, 'load_case': 1,
                        'mode_n': k + 1, 'freq': f, 'modal_m': mass, 'modal_damp_vis': xi, 'modal_damp_his': 0.0,
                        'node_nums': labels, 'id1': 'wheel mode %d' % (k + 1), 'r1': np.zeros(2),
                        'r2': np.zeros(2), 'r3': np.array(shape), 'r4': np.zeros(2), 'r5': np.zeros(2),
                        'r6': np.zeros(2)}, mode='add')


if __name__ == '__main__':
    main()
