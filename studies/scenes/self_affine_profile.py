#!/usr/bin/env python3
"""A self-affine rough profile scene for `rhabel solve -`: N samples on [0, 1) of a profile
synthesised by FFT with the power spectrum C(q) ~ q^-(1 + 2H) (Hurst exponent H, default 0.8)
for wavenumbers 2 pi k, k = 1 .. N/2, uniform random phases from the seed, scaled to the rms
height (default 1e-3) and shifted so that its highest sample is at z = 0; alpha 0.3, nu 0,
E1 = 1, speed 1, body load P.

    python3 studies/scenes/self_affine_profile.py N SEED LOAD [--hurst H] [--rms R] [--alpha A] [--periodic]

With --periodic the scene carries profile.period = 1 (the samples are one period); without it
the same samples are a finite window. The profile is deterministic in (N, SEED, H, R): NumPy's
default_rng(SEED).
"""
import argparse
import json
import sys

import numpy as np


def self_affine(n, seed, hurst, rms):
    """Samples z_i at x_i = i/n, i = 0 .. n-1, of a periodic self-affine profile."""
    rng = np.random.default_rng(seed)
    k = np.arange(1, n // 2 + 1)
    amplitude = k ** (-(1 + 2 * hurst) / 2)
    phase = rng.uniform(0, 2 * np.pi, k.size)
    spectrum = np.zeros(n // 2 + 1, dtype=complex)
    spectrum[1:] = amplitude * np.exp(1j * phase)
    if n % 2 == 0:
        spectrum[-1] = spectrum[-1].real  # the Nyquist mode of a real signal is real
    z = np.fft.irfft(spectrum, n)
    z *= rms / np.sqrt(np.mean(z ** 2))
    return np.arange(n) / n, z - z.max()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("samples", type=int)
    ap.add_argument("seed", type=int)
    ap.add_argument("load", type=float)
    ap.add_argument("--hurst", type=float, default=0.8)
    ap.add_argument("--rms", type=float, default=1e-3)
    ap.add_argument("--alpha", type=float, default=0.3)
    ap.add_argument("--periodic", action="store_true")
    a = ap.parse_args()
    x, z = self_affine(a.samples, a.seed, a.hurst, a.rms)
    profile = {"x": x.tolist(), "z": z.tolist()}
    if a.periodic:
        profile["period"] = 1.0
    json.dump({"description": f"self-affine profile H = {a.hurst}, {a.samples} samples, seed {a.seed}",
               "material": {"alpha": a.alpha, "E1": 1.0, "nu": 0.0, "coulomb": 0.0}, "speed": 1.0,
               "body": {"load": a.load}, "profile": profile}, sys.stdout)


if __name__ == "__main__":
    main()
