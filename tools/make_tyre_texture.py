#!/usr/bin/env python3
"""Write data/tyre_texture.dat, the road texture of data/tyre_patch.nml.

A deterministic, isotropic random surface: the sum of 400 plane waves
h(x, y) = sum_k a_k * cos(2*pi*(x*cos(theta_k) + y*sin(theta_k))/lambda_k + phi_k),
wavelengths lambda_k log-uniform from 10 mm to 0.5 m, directions theta_k and phases phi_k
uniform, amplitudes a_k proportional to lambda_k (a height spectrum falling as the wavenumber,
the texture slope of a dense asphalt in round numbers), scaled to an rms height of 1.0 mm.
Sampled every 5 mm along x (0 to 3 m) and across y (-0.12 to 0.12 m), in the format of
src/greenconv/model/road_texture.f90: the first data line the lateral positions y [m], then
every line x [m] and the heights [m] at each y.

    python3 tools/make_tyre_texture.py [OUTPUT]     (default data/tyre_texture.dat)

Python's random.Random(seed).random() is the same sequence on every platform and version
(Mersenne Twister), so the file is reproduced exactly.
"""
import math
import random
import sys

SEED = 25
N_WAVES = 400
RMS = 1.0e-3
DX = 0.005
X_END = 3.0
Y_HALF = 0.12


def main():
    output = sys.argv[1] if len(sys.argv) > 1 else "data/tyre_texture.dat"
    rng = random.Random(SEED)
    waves = []
    for _ in range(N_WAVES):
        wavelength = 0.010 * (0.5 / 0.010) ** rng.random()
        theta = 2.0 * math.pi * rng.random()
        phase = 2.0 * math.pi * rng.random()
        waves.append((wavelength, math.cos(theta), math.sin(theta), phase))
    # a sum of cosines with random phases has mean square sum(a_k^2)/2
    weight = [w[0] for w in waves]
    scale = RMS / math.sqrt(sum(a * a for a in weight) / 2.0)
    n_x = int(round(X_END / DX)) + 1
    n_y = int(round(2.0 * Y_HALF / DX)) + 1
    ys = [-Y_HALF + j * DX for j in range(n_y)]
    lines = [
        "# greenconv road texture for data/tyre_patch.nml: heights [m] on an x-y grid (format:",
        "# src/greenconv/model/road_texture.f90). Written by tools/make_tyre_texture.py: an isotropic",
        "# random surface of 400 plane waves, wavelengths 10 mm to 0.5 m, amplitude proportional to the",
        "# wavelength, rms height 1.0 mm, sampled every 5 mm; seed 25.",
        " " * 7 + "".join(f" {y:10.3f}" for y in ys),
    ]
    for i in range(n_x):
        x = i * DX
        row = []
        for y in ys:
            h = 0.0
            for (wavelength, c, s, phase), a in zip(waves, weight):
                h += a * math.cos(2.0 * math.pi * (x * c + y * s) / wavelength + phase)
            row.append(scale * h)
        lines.append(f"{x:7.3f}" + "".join(f" {h:10.3e}" for h in row))
    with open(output + ".part", "w") as f:
        f.write("\n".join(lines) + "\n")
    import os
    os.replace(output + ".part", output)
    print(f"make_tyre_texture: wrote {output} ({n_x} x {n_y} heights)")


if __name__ == "__main__":
    main()
