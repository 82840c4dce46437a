#!/usr/bin/env python3
"""Write test/data/uff/modes_plate_2414.uff: the plate of tools/make_modes_plate.py (its modes
and its 3 x 3 nodes) as an FE code exports it, the nodes as dataset 2411 and every mode as a
dataset 2414 (analysis data at nodes), with pyuff's own 2414 writer, for the modes_file
model's test that both files give the same modes (test/model/test_modesfile_mod.f90).

    pip install pyuff          # a tool for this script only, never a dependency of greenconv
    python3 tools/make_modes_2414.py [OUTPUT_DIRECTORY]     # default: test/data/uff

Dataset 2414 as written here: record 3 dataset location 1 (data at nodes); record 9 model
type 1 (structural), analysis type 2 (normal mode), data characteristic 3 (6 DOF), result
type 8 (displacement), data type 2 (real single), 6 values per node; record 10 the load set 1
and the mode number (fields 5, 6); record 12 the frequency [Hz], the eigenvalue omega**2,
the modal mass and the viscous damping ratio (fields 2 to 5; 0 for the even modes, as in the
dataset-55 file); records 14 and 15 the node label and its six values X, Y, Z, RX, RY, RZ.
"""
import math
import os
import sys

import numpy as np
import pyuff

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_modes_plate import A, B, MASS, fresh, modes, nodes  # noqa: E402  (the same plate and modes)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else 'test/data/uff'
    labels, x, y = nodes()
    uff = pyuff.UFF(fresh(out, 'modes_plate_2414.uff'))
    uff.write_sets({'type': 2411, 'node_nums': labels, 'def_cs': np.zeros(9, dtype=int),
                    'disp_cs': np.zeros(9, dtype=int), 'color': np.ones(9, dtype=int), 'x': x, 'y': y,
                    'z': np.zeros(9)}, mode='add')
    for k, (f, m, n) in enumerate(modes()):
        km, kn = m*math.pi/A, n*math.pi/B
        w = np.sin(km*x)*np.sin(kn*y)
        values = [np.array([0.0, 0.0, w[i], kn*math.sin(km*x[i])*math.cos(kn*y[i]),
                            -km*math.cos(km*x[i])*math.sin(kn*y[i]), 0.0]) for i in range(9)]
        uff.write_sets({'type': 2414, 'analysis_dataset_label': k + 1, 'analysis_dataset_name': 'plate %d,%d' % (m, n),
                        'dataset_location': 1, 'id1': 'plate', 'id2': 'NONE', 'id3': 'NONE', 'id4': 'LOAD SET 1',
                        'id5': 'MODE %d FREQUENCY %.5e' % (k + 1, f), 'model_type': 1, 'analysis_type': 2,
                        'data_characteristic': 3, 'result_type': 8, 'data_type': 2,
                        'number_of_data_values_for_the_data_component': 6,
                        'record10_field5': 1, 'record10_field6': k + 1,
                        'record12_field2': f, 'record12_field3': (2.0*math.pi*f)**2, 'record12_field4': MASS,
                        'record12_field5': 0.02 if k % 2 == 0 else 0.0,
                        'node_nums': labels, 'data_at_node': values}, mode='add')


if __name__ == '__main__':
    main()
