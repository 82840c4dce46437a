#!/usr/bin/env python3
"""Identification benchmark (issue 13): greenconv's maximum-likelihood fit against sdypy-EMA's
LSCE and LSCF on the same noisy receptances, errors in units of the Cramer-Rao bound.

Files: the 12-mode receptance of data/noisy_receptance.uff (example/write_noisy_receptance.f90:
8193 lines to 5 kHz, a close pair 412/418 Hz, xi 0.003-0.2, mixed signs) at 0.1, 1 and 3 %
complex noise of |G|, seeds 13, 14, 15. For each file and each tool it prints the modes
missed and spurious, the worst error of f and of xi in CRB standard deviations (the bound
computed here from the model's Jacobian at the true parameters) and the CPU/wall time.

greenconv chooses the order itself (MDL) and is timed by its own summary line (CPU of the
identification). The peer gets what a user picking poles by hand would: pol_order_high = 60
and its poles closest to the TRUE natural frequencies (select_closest_poles), so it can
invent no mode; a mode counts as missed when its pole is more than 1 % off in f. Its time
is the wall time of get_poles + select_closest_poles.

Run from the repository root after `make lib` (it builds the generator against
build/make): python3 bench/ident_peer.py   (sdypy-EMA is pip-installed into
build/ident_peer/venv on the first run; a tool around greenconv, not a dependency).
"""
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORK = os.path.join(ROOT, 'build', 'ident_peer')
VENV = os.path.join(WORK, 'venv')

F = [95.0, 412.0, 418.0, 730.0, 1150.0, 1600.0, 2100.0, 2650.0, 3200.0, 3800.0, 4300.0, 4750.0]
XI = [0.01, 0.003, 0.005, 0.02, 0.12, 0.008, 0.05, 0.2, 0.015, 0.03, 0.006, 0.04]
C = [1.0, -0.6, 0.8, 1.5, -2.0, 0.7, 3.0, -4.0, 1.2, -0.9, 0.5, 2.0]
CASES = [(0.001, 13), (0.01, 14), (0.03, 15)]


def in_venv():
    """Re-run this script inside a venv holding numpy and sdypy-EMA."""
    python = os.path.join(VENV, 'bin', 'python')
    if os.path.abspath(sys.prefix) == os.path.abspath(VENV):
        return
    if not os.path.exists(python):
        print('ident_peer: installing sdypy-EMA into ' + VENV, flush=True)
        subprocess.run([sys.executable, '-m', 'venv', VENV], check=True)
        subprocess.run([python, '-m', 'pip', 'install', '--quiet', 'sdypy-EMA', 'numpy'], check=True)
    os.execv(python, [python] + sys.argv)


def run(cmd, **kw):
    return subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True, **kw).stdout


def truth():
    import numpy as np
    w = 2 * np.pi * np.array(F)
    xi = np.array(XI)
    a = 1e-6 * np.array(C) * xi * w**2          # paper form A_k, eq. (6)
    wd = w * np.sqrt(1 - xi**2)
    pole = -xi * w + 1j * wd
    residue = a / (2j * wd)                       # A/(w^2 - W^2 + 2i xi w W) = r/(iW - l) + conj
    return pole, residue


def receptance(theta, omega):
    """G at omega for theta = (f, xi, Re r, Im r) per mode."""
    import numpy as np
    g = np.zeros_like(omega, dtype=complex)
    for f, xi, rr, ri in theta.reshape(-1, 4):
        lam = 2 * np.pi * f * (-xi + 1j * np.sqrt(1 - xi**2))
        r = rr + 1j * ri
        g += r / (1j * omega - lam) + np.conj(r) / (1j * omega - np.conj(lam))
    return g


def cramer_rao(omega, level):
    """CRB standard deviations of f [Hz] and xi per mode, noise level*|G| (complex Gaussian)."""
    import numpy as np
    pole, residue = truth()
    theta = np.ravel([[abs(p) / (2 * np.pi), -p.real / abs(p), r.real, r.imag] for p, r in zip(pole, residue)])
    jac = np.empty((omega.size, theta.size), dtype=complex)
    for i in range(theta.size):
        h = 1e-6 * (abs(theta[i]) if i % 4 < 2 else abs(residue[i // 4]))
        e = np.zeros_like(theta)
        e[i] = h
        jac[:, i] = (receptance(theta + e, omega) - receptance(theta - e, omega)) / (2 * h)
    weight = 2.0 / (level * abs(receptance(theta, omega)))**2
    fisher = (jac.conj().T * weight) @ jac
    fisher = fisher.real
    scale = np.sqrt(np.diag(fisher))
    cov = np.linalg.inv(fisher / np.outer(scale, scale)) / np.outer(scale, scale)
    sd = np.sqrt(np.diag(cov))
    return sd[0::4], sd[1::4]


def score(found_f, found_xi, sigma_f, sigma_xi):
    """Missed, spurious, worst |error|/sigma of f and xi over the matched modes."""
    import numpy as np
    found_f = np.asarray(found_f)
    found_xi = np.asarray(found_xi)
    match = [int(np.argmin(abs(found_f - f))) if found_f.size else -1 for f in F]
    missed, worst_f, worst_xi = 0, 0.0, 0.0
    for k, m in enumerate(match):
        if m < 0 or match.count(m) > 1 or abs(found_f[m] - F[k]) > 0.01 * F[k]:
            missed += 1
            continue
        worst_f = max(worst_f, abs(found_f[m] - F[k]) / sigma_f[k])
        worst_xi = max(worst_xi, abs(found_xi[m] - XI[k]) / sigma_xi[k])
    spurious = found_f.size - (len(F) - missed)
    return missed, spurious, worst_f, worst_xi


def main():
    in_venv()
    import numpy as np
    from sdypy import EMA
    os.makedirs(WORK, exist_ok=True)
    generator = os.path.join(WORK, 'write_noisy_receptance')
    run(['gfortran', '-O2', '-Ibuild/make/include', '-J' + WORK, 'example/write_noisy_receptance.f90',
         'build/make/libgreenconv.a', '-llapack', '-lblas', '-lfftw3', '-fopenmp', '-o', generator])
    print('%-28s %-14s %6s %8s %10s %10s %9s' % ('file', 'tool', 'missed', 'spurious', 'f err/CRB',
                                                 'xi err/CRB', 'time [s]'))
    for level, seed in CASES:
        name = 'noisy_%g_%d' % (100 * level, seed)
        uff = os.path.join(WORK, name + '.uff')
        run([generator, str(level), str(seed), uff])
        scene = os.path.join(WORK, name + '.nml')
        with open(scene, 'w') as out:
            out.write("&scene task = 'identify', name = '%s', output_dir = '%s' /\n" % (name, WORK))
            out.write("&structure model = 'frf_file', frf_file = '%s' /\n" % uff)
            out.write("&identification max_order = 30 /\n")
        summary = run(['build/make/greenconv', scene])
        cpu = float(re.search(r'CPU ([0-9.E+-]+) s', summary).group(1))
        modes = np.loadtxt(os.path.join(WORK, name + '_modes.dat'), ndmin=2)
        data = np.loadtxt(os.path.join(WORK, name + '_frf.dat'))
        freq, g = data[:, 0], data[:, 1] + 1j * data[:, 2]
        sigma_f, sigma_xi = cramer_rao(2 * np.pi * freq[1:], level)
        rows = [('greenconv ML',) + score(modes[:, 0], modes[:, 2], sigma_f, sigma_xi) + (cpu,)]
        for method in ('lsce', 'lscf'):
            try:
                start = time.perf_counter()
                model = EMA.Model(g[None, 1:], freq[1:], lower=freq[1], upper=freq[-1], pol_order_high=60,
                                  frf_type='receptance')
                model.get_poles(method=method, show_progress=False)
                model.select_closest_poles(F)
                elapsed = time.perf_counter() - start
                rows.append(('sdypy-EMA ' + method.upper(),) +
                            score(model.nat_freq, model.nat_xi, sigma_f, sigma_xi) + (elapsed,))
            except Exception as failure:      # a method the installed version does not offer
                print('%-28s %-14s not run: %s' % (name, 'sdypy ' + method, failure))
        for tool, missed, spurious, worst_f, worst_xi, seconds in rows:
            print('%-28s %-14s %6d %8d %10.2f %10.2f %9.2f' % (name, tool, missed, spurious, worst_f, worst_xi,
                                                                seconds), flush=True)


if __name__ == '__main__':
    main()
