#!/usr/bin/env python3
"""Write the universal-file fixtures of test/io/test_uff_mod.f90 with pyuff, an independent writer.

    pip install pyuff          # a tool for this script only, never a dependency of greenconv
    python3 tools/make_uff_fixtures.py [OUTPUT_DIRECTORY]     # default: test/data/uff

Every NAME.uff comes with NAME.expected: the values the reader must return, computed here
from closed forms (a single-degree-of-freedom oscillator), written with 17 significant
digits so that the Fortran test compares against numbers that did not pass through the
universal file. The abscissa values are chosen with at most six significant digits, so the
E13.5 fields of the format hold them exactly.

The .expected format, one item per line ('#' lines are comments):
    file NAME.uff N_FUNCTIONS N_NODES N_SKIPPED
    function FUNCTION_TYPE RESPONSE_NODE RESPONSE_DIR REFERENCE_NODE REFERENCE_DIR ORDINATE_TYPE KIND N_POINTS
    X RE IM                       (N_POINTS lines after each function line)
    node LABEL DATASET X Y Z
    skipped DATASET
"""
import math
import os
import sys

import numpy as np
import pyuff

# The oscillator: mass [kg], natural frequency [Hz], damping ratio.
MASS = 1.5
F_N = 50.0
ZETA = 0.02
OMEGA_N = 2.0 * math.pi * F_N
STIFFNESS = MASS * OMEGA_N**2
DAMPING = 2.0 * ZETA * MASS * OMEGA_N
OMEGA_D = OMEGA_N * math.sqrt(1.0 - ZETA**2)
# Mode shape at nodes 1, 2, 3 for the matrix file: G_ij = phi_i phi_j H.
PHI = {1: 1.0, 2: -0.5, 3: 0.25}

RECORD_SPEC = {'receptance': (8, 'Displacement', 'm'), 'mobility': (11, 'Velocity', 'm/s'),
               'accelerance': (12, 'Acceleration', 'm/s^2'), 'other': (8, 'Displacement', 'm')}


def receptance(f):
    """H(f) = 1 / (k - m w^2 + i c w) [m/N]."""
    w = 2.0 * math.pi * f
    return 1.0 / complex(STIFFNESS - MASS * w * w, DAMPING * w)


def impulse_response(t):
    """g(t) = exp(-zeta w_n t) sin(w_d t) / (m w_d) [m/(N s)], the inverse transform of H."""
    return math.exp(-ZETA * OMEGA_N * t) * math.sin(OMEGA_D * t) / (MASS * OMEGA_D)


def ordinate(kind, f):
    """The FRF of the given kind at f [Hz]: H, i w H or -w^2 H."""
    w = 2.0 * math.pi * f
    return {'receptance': 1.0, 'mobility': 1j * w, 'accelerance': -w * w}[kind] * receptance(f)


class Fixture:
    """One universal file and its expected values."""

    def __init__(self, name):
        self.name = name
        self.sets = []
        self.functions = []
        self.nodes = []
        self.skipped = []

    def add_function(self, func_type, rsp, ref, ordinate_type, kind, x, y, even):
        """A dataset 58: rsp and ref are (node, direction); y complex or real per ordinate_type."""
        complex_data = ordinate_type in (5, 6)
        data = np.asarray(y, dtype=complex if complex_data else float)
        numerator = RECORD_SPEC[kind]
        time = func_type == 1
        self.sets.append(pyuff.prepare_58(
            id1='greenconv fixture %s function %d' % (self.name, len(self.functions) + 1),
            id2='SDOF m = %g kg, f_n = %g Hz, zeta = %g' % (MASS, F_N, ZETA), id3='NONE', id4='NONE', id5='NONE',
            func_type=func_type, ver_num=0, load_case_id=0, rsp_ent_name='NONE', rsp_node=rsp[0], rsp_dir=rsp[1],
            ref_ent_name='NONE', ref_node=ref[0], ref_dir=ref[1], ord_data_type=ordinate_type, num_pts=len(x),
            abscissa_spacing=1 if even else 0, abscissa_min=x[0], abscissa_inc=x[1] - x[0] if even else 0.0,
            z_axis_value=0.0, abscissa_spec_data_type=17 if time else 18, abscissa_len_unit_exp=0,
            abscissa_force_unit_exp=0, abscissa_temp_unit_exp=0, abscissa_axis_units_lab='s' if time else 'Hz',
            ordinate_spec_data_type=numerator[0], ordinate_len_unit_exp=1, ordinate_force_unit_exp=0,
            ordinate_temp_unit_exp=0, ordinate_axis_units_lab=numerator[2], orddenom_spec_data_type=13,
            orddenom_len_unit_exp=0, orddenom_force_unit_exp=1, orddenom_temp_unit_exp=0,
            orddenom_axis_units_lab='N', z_axis_spec_data_type=0, z_axis_len_unit_exp=0, z_axis_force_unit_exp=0,
            z_axis_temp_unit_exp=0, z_axis_axis_units_lab='NONE', data=data, x=np.asarray(x, dtype=float)))
        self.functions.append((func_type, rsp, ref, ordinate_type, kind, list(x), [complex(v) for v in y]))

    def add_nodes(self, dataset, labels, xyz):
        """Nodes of dataset 15 or 2411: labels and (x, y, z) rows."""
        prepare = pyuff.prepare_15 if dataset == 15 else pyuff.prepare_2411
        columns = list(zip(*xyz))
        zeros = [0] * len(labels)
        self.sets.append(prepare(node_nums=labels, def_cs=zeros, disp_cs=zeros, color=[1] * len(labels),
                                 x=list(columns[0]), y=list(columns[1]), z=list(columns[2])))
        self.nodes += [(label, dataset, p) for label, p in zip(labels, xyz)]

    def add_skipped(self, dataset, dset):
        """A dataset the reader skips."""
        self.sets.append(dset)
        self.skipped.append(dataset)

    def write(self, directory):
        path = os.path.join(directory, self.name + '.uff')
        if os.path.exists(path):
            os.remove(path)
        uff = pyuff.UFF(path)
        # force_double=False keeps each dataset 58's own ordinate data type (2, 4, 5 or 6).
        uff.write_sets(self.sets, mode='add', force_double=False)
        with open(os.path.join(directory, self.name + '.expected'), 'w') as out:
            out.write('# Expected values of %s.uff, from the closed forms of tools/make_uff_fixtures.py\n' % self.name)
            out.write('# (not read back from the .uff); see that script for the format.\n')
            out.write('file %s.uff %d %d %d\n' % (self.name, len(self.functions), len(self.nodes),
                                                  len(self.skipped)))
            for func_type, rsp, ref, ordinate_type, kind, x, y in self.functions:
                out.write('function %d %d %d %d %d %d %s %d\n' % (func_type, rsp[0], rsp[1], ref[0], ref[1],
                                                                  ordinate_type, kind, len(x)))
                for xi, yi in zip(x, y):
                    out.write('%r %r %r\n' % (float(xi), yi.real, yi.imag))
            for label, dataset, p in self.nodes:
                out.write('node %d %d %r %r %r\n' % (label, dataset, float(p[0]), float(p[1]), float(p[2])))
            for dataset in self.skipped:
                out.write('skipped %d\n' % dataset)
        size = os.path.getsize(path)
        assert size < 50_000, '%s is %d bytes; keep fixtures small' % (path, size)
        print('%s: %d bytes' % (path, size))


def even_grid(first, step, n):
    return [first + i * step for i in range(n)]


# Uneven frequencies [Hz] (six significant digits at most) crowding at the resonance.
UNEVEN_F = [5.0, 10.0, 20.0, 30.0, 40.0, 45.0, 47.5, 48.75, 49.5, 50.0, 50.25, 51.0, 52.5, 55.0, 60.0, 70.0,
            85.0, 100.0, 125.5, 150.25]
# Uneven times [s].
UNEVEN_T = [0.0, 0.0005, 0.00125, 0.002, 0.003, 0.0045, 0.006, 0.0075, 0.01, 0.0125, 0.015, 0.02, 0.025, 0.0325,
            0.04]


def fixtures():
    result = []

    frf = Fixture('frf_complex_double_even')  # case 7; 81 points: the last line holds 2 of 4 values
    f = even_grid(0.0, 2.5, 81)
    frf.add_function(4, (3, 3), (7, -3), 6, 'receptance', f, [receptance(v) for v in f], True)
    result.append(frf)

    uneven = Fixture('frf_complex_single_uneven')  # case 4, mobility
    uneven.add_function(4, (12, 2), (12, 2), 5, 'mobility', UNEVEN_F, [ordinate('mobility', v) for v in UNEVEN_F],
                        False)
    result.append(uneven)

    time = Fixture('time_real_single')  # case 1, function type 1; 100 points: the last line holds 4 of 6
    t = even_grid(0.0, 0.001, 100)
    time.add_function(1, (5, 1), (5, 1), 2, 'receptance', t, [impulse_response(v) for v in t], True)
    result.append(time)

    patch = Fixture('patch_geometry')  # nodes 15 + 2411, cases 5, 6, 7, 8
    patch.add_nodes(15, [1, 2], [(0.0, 0.0, 0.0), (0.025, -0.0125, 0.5)])
    patch.add_nodes(2411, [3, 40], [(0.05, 0.0125, -1.0 / 3.0), (1.0e-3, 2.0 / 7.0, 1234.5678901234567)])
    f = even_grid(10.0, 1.25, 61)
    for i, j in [(1, 1), (1, 2), (2, 1)]:
        patch.add_function(4, (i, 3), (j, 3), 6, 'receptance', f, [PHI[i] * PHI[j] * receptance(v) for v in f], True)
    patch.add_function(4, (3, 3), (1, 3), 6, 'accelerance', UNEVEN_F,
                       [PHI[3] * ordinate('accelerance', v) for v in UNEVEN_F], False)
    t = even_grid(0.0, 0.00025, 37)
    patch.add_function(1, (2, 3), (2, 3), 4, 'receptance', t, [PHI[2] ** 2 * impulse_response(v) for v in t], True)
    patch.add_function(1, (1, 3), (3, -3), 4, 'receptance', UNEVEN_T,
                       [PHI[1] * PHI[3] * impulse_response(v) for v in UNEVEN_T], False)
    result.append(patch)

    skipped = Fixture('skipped_datasets')  # datasets 151 and 164 skipped; cases 3 and 2
    skipped.add_skipped(151, pyuff.prepare_151(
        model_name='greenconv fixture', description='datasets the reader skips', db_app='pyuff',
        date_db_created='01-Jan-26', time_db_created='00:00:00', version_db1=0, version_db2=0, file_type=0,
        date_db_saved='01-Jan-26', time_db_saved='00:00:00', program='make_uff_fixtures.py',
        date_db_written='01-Jan-26', time_db_written='00:00:00'))
    skipped.add_skipped(164, pyuff.prepare_164(units_code=1, units_description='SI', temp_mode=1, length=1.0,
                                               force=1.0, temp=1.0, temp_offset=273.15))
    f = even_grid(20.0, 5.0, 13)
    skipped.add_function(4, (1, 1), (2, 2), 5, 'accelerance', f, [ordinate('accelerance', v) for v in f], True)
    skipped.add_function(1, (4, -2), (4, -2), 2, 'receptance', UNEVEN_T, [impulse_response(v) for v in UNEVEN_T],
                         False)
    result.append(skipped)
    return result


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join('test', 'data', 'uff')
    os.makedirs(directory, exist_ok=True)
    for fixture in fixtures():
        fixture.write(directory)


if __name__ == '__main__':
    main()
