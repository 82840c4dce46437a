#!/usr/bin/env python3
"""Write pyuff's measured beam accelerances as one universal file (dataset 58), as its README does.

    pip install numpy pyuff     # tools for this script only, never dependencies of greenconv
    python3 tools/make_pyuff_beam.py [DIRECTORY]      # default: test/data/pyuff_beam

The three measured accelerances meas_point_1.txt .. meas_point_3.txt of pyuff's data/ folder
(github.com/ladisk/pyuff, MIT licence, copied unchanged into test/data/pyuff_beam/) hold 1001
complex values each, 0 to 1000 Hz by 1 Hz, in m/s^2/N: a beam excited at points 1, 2, 3 and
measured at point 1 (pyuff's README writes them with rsp_node 1 and ref_node 1, 2, 3). pyuff's
README sets the 0 Hz line to NaN before writing (an accelerance says nothing at 0 Hz); here the
0 Hz line is left out instead, so each dataset is the even grid 1..1000 Hz (1000 lines), written in
single precision (E13.5) with the README's dataset 58 fields: beam_accelerance.uff.
"""
import os
import sys

import numpy as np
import pyuff


def dataset(point, values, freq):
    return pyuff.prepare_58(
        id1='pyuff data/meas_point_%d.txt: measured beam accelerance' % point, id2='tools/make_pyuff_beam.py',
        id3='NONE', id4='NONE', id5='NONE', func_type=4, ver_num=0, load_case_id=0, rsp_ent_name='TestCase',
        rsp_node=1, rsp_dir=1, ref_ent_name='TestCase', ref_node=point, ref_dir=1, ord_data_type=5,
        num_pts=len(freq), abscissa_spacing=1, abscissa_min=freq[0], abscissa_inc=freq[1] - freq[0],
        z_axis_value=0.0, abscissa_spec_data_type=18, abscissa_len_unit_exp=0, abscissa_force_unit_exp=0,
        abscissa_temp_unit_exp=0, abscissa_axis_units_lab='Hz', ordinate_spec_data_type=12,
        ordinate_len_unit_exp=1, ordinate_force_unit_exp=0, ordinate_temp_unit_exp=0,
        ordinate_axis_units_lab='m/s^2', orddenom_spec_data_type=13, orddenom_len_unit_exp=0,
        orddenom_force_unit_exp=1, orddenom_temp_unit_exp=0, orddenom_axis_units_lab='N',
        z_axis_spec_data_type=0, z_axis_len_unit_exp=0, z_axis_force_unit_exp=0, z_axis_temp_unit_exp=0,
        z_axis_axis_units_lab='NONE', data=values, x=freq)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join('test', 'data', 'pyuff_beam')
    sets = []
    for point in (1, 2, 3):
        values = np.genfromtxt(os.path.join(directory, 'meas_point_%d.txt' % point), dtype=complex)
        freq = np.arange(len(values), dtype=float)
        sets.append(dataset(point, values[1:], freq[1:]))
    path = os.path.join(directory, 'beam_accelerance.uff')
    if os.path.exists(path):
        os.remove(path)
    pyuff.UFF(path).write_sets(sets, mode='add', force_double=False)
    print('%s: %d bytes' % (path, os.path.getsize(path)))


if __name__ == '__main__':
    main()
