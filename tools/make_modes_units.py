#!/usr/bin/env python3
"""Write test/data/uff/modes_plate_mm.uff and modes_plate_mm_unit.uff: the plate of
tools/make_modes_plate.py (the same nodes and modes), written by pyuff (an independent writer)
in the unit system "MN: mm (newton)" that their dataset 164 states, for the modes_file model's
tests of units (test/model/test_modesfile_mod.f90).

    pip install pyuff          # a tool for this script only, never a dependency of greenconv
    python3 tools/make_modes_units.py [OUTPUT_DIRECTORY]     # default: test/data/uff

Dataset 164 (Units): record 1 the units code (10: mm, newton), record 2 the factors that convert
the file's units to SI by division: length 1000 (mm per m), force 1. A mass is then in
N*s^2/mm = 1000 kg, so the modal mass written is the plate's in kg divided by 1000, and the
nodes are at their coordinates in mm. modes_plate_mm.uff gives the modal masses with unit
shapes; modes_plate_mm_unit.uff gives them as 0 with mass-normalised shapes, in that file's
units: phi = w/sqrt(m_kg/1000) [1/sqrt(N*s^2/mm)]. Read in SI both must give the modes of
modes_plate.uff: the same coordinates in m and phi_i*phi_j/m_k in 1/kg.
"""
import os
import sys

import numpy as np
import pyuff

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_modes_plate import A, B, MASS, modes, nodes, fresh  # noqa: E402

LENGTH, FORCE = 1000.0, 1.0   # dataset 164 factors: SI = file value / factor
MASS_UNIT = FORCE/LENGTH     # a mass in the file's units is mass_kg*FORCE/LENGTH


def write(path, normalised):
    labels, x, y = nodes()
    uff = pyuff.UFF(path)
    uff.write_sets({'type': 164, 'units_code': 10, 'units_description': 'mm (newton)', 'temp_mode': 2,
                    'length': LENGTH, 'force': FORCE, 'temp': 1.0, 'temp_offset': 273.15}, mode='add')
    uff.write_sets({'type': 15, 'node_nums': labels, 'def_cs': np.zeros(9), 'disp_cs': np.zeros(9),
                    'color': np.ones(9), 'x': x*LENGTH, 'y': y*LENGTH, 'z': np.zeros(9)}, mode='add')
    mass = MASS*MASS_UNIT
    for k, (f, m, n) in enumerate(modes()):
        km, kn = m*np.pi/A, n*np.pi/B
        w = np.sin(km*x)*np.sin(kn*y)
        scale = 1.0/np.sqrt(mass) if normalised else 1.0
        uff.write_sets({'type': 55, 'analysis_type': 2, 'data_ch': 2, 'spec_data_type': 8, 'load_case': 1,
                        'mode_n': k + 1, 'freq': f, 'modal_m': 0.0 if normalised else mass,
                        'modal_damp_vis': 0.02 if k % 2 == 0 else 0.0, 'modal_damp_his': 0.0,
                        'node_nums': labels, 'id1': 'plate %d,%d in mm' % (m, n),
                        'r1': np.zeros(9), 'r2': np.zeros(9), 'r3': w*scale}, mode='add')


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else 'test/data/uff'
    write(fresh(out, 'modes_plate_mm.uff'), False)
    write(fresh(out, 'modes_plate_mm_unit.uff'), True)


if __name__ == '__main__':
    main()
