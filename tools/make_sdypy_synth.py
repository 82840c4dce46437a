#!/usr/bin/env python3
"""Write sdypy-EMA's own synthetic test FRFs as universal files, without sdypy or pyLump.

    pip install numpy pyuff     # tools for this script only, never dependencies of greenconv
    python3 tools/make_sdypy_synth.py [OUTPUT_DIRECTORY]      # default: test/data/sdypy

sdypy-EMA's tests/test_synth_FRF.py identifies the FRFs that tests/test_tools/generate_synth_frf.py
makes (sdypy-EMA 0.31, github.com/sdypy/sdypy-EMA): np.random.seed(6020); five masses
uniform in [0.1, 1] kg, five springs in [500e3, 1e6] N/m, five dampers in [10, 100] N s/m, drawn in
that order; a chain fixed on the left (pyLump's boundaries="left": spring and damper i join mass
i - 1 and mass i, the first to the ground); f_min = round(f_1/4, -1), f_max = round(5*f_5, -2)
(10 and 1700 Hz); freq = np.linspace(f_min, f_max, 5000); H(f) = inv(K - w^2 M + i w C), the
first row: the five FRFs from a force on mass 1 (a point FRF and four transfers, the far ones
rolling off as w^-10, 11 decades below the peak at 1700 Hz). The natural frequencies and damping
ratios sdypy's test compares against are pyLump's: get_eig_freq, called first, gives the undamped
natural frequencies sqrt(eig(K, M))/(2 pi); get_damping_ratios those of the state-space
eigenvalues lambda, xi = -Re(lambda)/|lambda| (the damping is not proportional: |lambda|/(2 pi)
differs from the undamped frequency by up to 0.12 Hz, within the 1 Hz of the criterion). sdypy's criteria (tests/test_tools/closeness_criteria.py): every natural
frequency within 1 Hz or every one within 2 %, and every damping ratio within 2 %.

Written here, as an analyser exports them: synth_receptance.uff and synth_accelerance.uff, five
datasets 58 each (response node j, +X, over the force at node 1, +X), complex single precision
(E13.5, six digits) on the even grid from 10 Hz (record 7's increment 3.38068E-01 rounded, as
any universal file holds it), and synth_truth.txt with the truth to 17 digits.
"""
import os
import sys

import numpy as np
import pyuff

N_DOF = 5
N_LINES = 5000


def chain_left(values):
    """pyLump's _fill_matrix for boundaries="left"."""
    matrix = np.zeros((N_DOF, N_DOF))
    for i in range(N_DOF - 1):
        matrix[i, i] = values[i] + values[i + 1]
        matrix[i, i + 1] = -values[i + 1]
        matrix[i + 1, i] = -values[i + 1]
    matrix[N_DOF - 1, N_DOF - 1] = values[N_DOF - 1]
    return matrix


def system():
    np.random.seed(6020)
    masses = np.random.uniform(0.1, 1, N_DOF)
    stiffnesses = np.random.uniform(500e3, 1e6, N_DOF)
    damping = np.random.uniform(10, 100, N_DOF)
    return np.diag(masses), chain_left(stiffnesses), chain_left(damping)


def modes(m, k, c):
    """sdypy's true natural frequencies [Hz] (undamped), damping ratios and |lambda|/(2 pi) [Hz]."""
    minv = np.linalg.inv(m)
    state = np.block([[np.zeros((N_DOF, N_DOF)), np.eye(N_DOF)], [-minv @ k, -minv @ c]])
    roots = np.linalg.eigvals(state)
    roots = roots[roots.imag > 0]
    roots = roots[np.argsort(np.abs(roots))]
    undamped = np.sqrt(np.sort(np.linalg.eigvals(minv @ k).real)) / (2 * np.pi)
    return undamped, -roots.real / np.abs(roots), np.abs(roots) / (2 * np.pi)


def dataset(j, kind, freq, values):
    numerator = {'receptance': (8, 'm'), 'accelerance': (12, 'm/s^2')}[kind]
    return pyuff.prepare_58(
        id1='sdypy-EMA test_synth_FRF, seed 6020: %s H_%d1' % (kind, j + 1), id2='tools/make_sdypy_synth.py',
        id3='NONE', id4='NONE', id5='NONE', func_type=4, ver_num=0, load_case_id=0, rsp_ent_name='NONE',
        rsp_node=j + 1, rsp_dir=1, ref_ent_name='NONE', ref_node=1, ref_dir=1, ord_data_type=5,
        num_pts=len(freq), abscissa_spacing=1, abscissa_min=freq[0], abscissa_inc=freq[1] - freq[0],
        z_axis_value=0.0, abscissa_spec_data_type=18, abscissa_len_unit_exp=0, abscissa_force_unit_exp=0,
        abscissa_temp_unit_exp=0, abscissa_axis_units_lab='Hz', ordinate_spec_data_type=numerator[0],
        ordinate_len_unit_exp=1, ordinate_force_unit_exp=0, ordinate_temp_unit_exp=0,
        ordinate_axis_units_lab=numerator[1], orddenom_spec_data_type=13, orddenom_len_unit_exp=0,
        orddenom_force_unit_exp=1, orddenom_temp_unit_exp=0, orddenom_axis_units_lab='N',
        z_axis_spec_data_type=0, z_axis_len_unit_exp=0, z_axis_force_unit_exp=0, z_axis_temp_unit_exp=0,
        z_axis_axis_units_lab='NONE', data=np.asarray(values, dtype=complex), x=freq)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join('test', 'data', 'sdypy')
    os.makedirs(directory, exist_ok=True)
    m, k, c = system()
    f_nat, zeta, f_state = modes(m, k, c)
    f_min = np.round(f_nat[0] * 0.25 / 10, 0) * 10
    f_max = np.round(f_nat[-1] * 5.0 / 100, 0) * 100
    freq = np.linspace(f_min, f_max, N_LINES)
    omega = 2 * np.pi * freq
    frf = np.array([np.linalg.inv(k - w**2 * m + 1j * w * c)[0, :] for w in omega]).T
    for kind, factor in (('receptance', 1.0), ('accelerance', -omega**2)):
        path = os.path.join(directory, 'synth_%s.uff' % kind)
        if os.path.exists(path):
            os.remove(path)
        uff = pyuff.UFF(path)
        uff.write_sets([dataset(j, kind, freq, factor * frf[j]) for j in range(N_DOF)], mode='add',
                       force_double=False)
        print('%s: %d bytes' % (path, os.path.getsize(path)))
    with open(os.path.join(directory, 'synth_truth.txt'), 'w') as out:
        out.write('# sdypy-EMA test_synth_FRF (seed 6020), from tools/make_sdypy_synth.py: f_min f_max lines,\n')
        out.write('# then per mode: sdypy\'s true natural frequency (undamped) [Hz], damping ratio,\n')
        out.write('# |lambda|/(2 pi) of the damped system [Hz]\n')
        out.write('%r %r %d\n' % (float(f_min), float(f_max), N_LINES))
        for f, xi, f_l in zip(f_nat, zeta, f_state):
            out.write('%r %r %r\n' % (float(f), float(xi), float(f_l)))


if __name__ == '__main__':
    main()
