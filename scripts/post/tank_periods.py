#!/usr/bin/python3
"""Natural periods of a tank from its response to the recorded ground motion:
the sloshing (convective) period from wave heights, the bulging (impulsive)
period from wall pressures or wall displacements.

Why not the peak of a spectrum: a 20 s record holds three cycles of the ~6 s
sloshing period and its spectrum resolves 1/20 Hz, a third of the period.
Instead a linear single-degree-of-freedom oscillator

    q'' + 2 zeta omega q' + omega^2 q = u(t),   omega = 2 pi / T,

driven by the recorded ground acceleration (each horizontal component its own
input) is fitted to the response by least squares: the response is modelled
as a combination of q and q' of every input (any second-order transfer
function with these poles), the oscillator's free decay (initial state), a
slow drift (settling; the sloshing under bulging) and, if asked, the inputs themselves (the rigid
impulsive pressure) and further oscillators of shorter periods (higher
modes: a wave height holds the second sloshing mode, which, left out, pulled
the first's period up by 2-4 % in trials with a design motion). For given (T, zeta) these are linear and solved exactly;
T and zeta are found by a grid scan and Levenberg-Marquardt (variable
projection). The oscillator is integrated exactly for inputs linear between
samples, so the sampling adds no period error.

The period's uncertainty is the least-squares standard deviation, with the
residuals' autocorrelation allowed for (Newey-West over one period), since
other modes and solver noise leave coloured residuals. A period is refused
(PeriodNotIdentified) rather than guessed when the record holds fewer than
`min_cycles` of the band's periods, when the best oscillator lies at the edge
of the band or needs a damping beyond `max_damping` (no resonance), when it
explains too little of the response, or when its uncertainty is too large.
Measured on synthetic records (tests/tools/test_tank_periods.py and trials
like it): within 0.2 % at 10-30 % noise; at low signal-to-noise (the
oscillator taking 10-20 % of the variance) errors reached 3 standard
deviations in 2 of 10 trials, so the stated deviation can then be low by
up to about half.

Usage:
  tank_periods.py --response RUN/fluid/probes/wave_0deg.csv --column wave_height_m \\
      --ground RUN/ground_acceleration.csv --band 2 18 [--feedthrough]
Prints the period with its standard deviation; exit status 1 when none is identified.
"""
import argparse
import dataclasses
import math
import sys

import numpy as np


# A higher mode's period is below the one before divided by this (the
# cylinder's second sloshing mode: 0.57 of the first for h/R ~ 1).
HIGHER_MODE_RATIO = 1.25


class PeriodNotIdentified(Exception):
    """The record does not determine a period; the message says why."""


@dataclasses.dataclass
class PeriodEstimate:
    period_s: float
    period_std_s: float
    damping_ratio: float
    damping_std: float
    explained_fraction: float  # of the variance left by drift and feedthrough, taken by the oscillator
    cycles: float  # periods the record holds
    fitted: np.ndarray  # the model's response at the record's times
    band_s: tuple


def _expm(matrix):
    """exp(matrix) of a small matrix by scaling and squaring of its Taylor
    series (numpy has no expm; the matrices here are 4x4)."""
    norm = np.linalg.norm(matrix, 1)
    squarings = max(0, int(math.ceil(math.log2(norm))) + 1) if norm > 0.5 else 0
    scaled = matrix / 2.0 ** squarings
    result = np.eye(len(matrix))
    term = np.eye(len(matrix))
    for k in range(1, 20):
        term = term @ scaled / k
        result = result + term
    for _ in range(squarings):
        result = result @ result
    return result


def _oscillator_kernels(period_s, damping_ratios, dt, n):
    """For each damping ratio (Z of them): discrete kernels (Z x 2 x n: q and
    q') of the oscillator's exact response to an input linear between samples,
    x[k] = sum_m W[m] u[k - m], and the free responses of q to unit initial q
    and q' (Z x 2 x n). Needs damping < 1."""
    omega = 2 * math.pi / period_s
    zeta = np.asarray(damping_ratios, dtype=float)
    g1 = np.empty((len(zeta), 2))
    g0 = np.empty((len(zeta), 2))
    for k, z in enumerate(zeta):
        augmented = np.zeros((4, 4))
        augmented[:2, :2] = [[0.0, 1.0], [-omega ** 2, -2 * z * omega]]
        augmented[1, 2] = 1.0  # B = (0, 1): the input drives q''
        augmented[2, 3] = 1.0  # the input's slope over the step
        e = _expm(augmented * dt)
        g1[k] = e[:2, 3] / dt  # weight of u[k+1] in x[k+1]
        g0[k] = e[:2, 2] - g1[k]  # weight of u[k]
    # Phi^m = exp(A m dt) = exp(-zeta omega t) [cos(wd t) I + sin(wd t)/wd (A + zeta omega I)]
    t = dt * np.arange(n + 1)
    zeta = zeta[:, None]
    omega_d = omega * np.sqrt(1 - zeta ** 2)
    decay = np.exp(-zeta * omega * t)
    c = decay * np.cos(omega_d * t)
    s = decay * np.sin(omega_d * t) / omega_d
    zo = zeta * omega
    phi = ((c + s * zo, s), (-omega ** 2 * s, c - s * zo))  # entries (row, column), each Z x (n + 1)
    kernels = np.empty((len(zeta), 2, n))
    for row in range(2):
        # K1[m] = Phi^m g1; K0[m] = Phi^(m-1) g0, m >= 1
        kernels[:, row] = phi[row][0][:, :n] * g1[:, :1] + phi[row][1][:, :n] * g1[:, 1:]
        kernels[:, row, 1:] += phi[row][0][:, :n - 1] * g0[:, :1] + phi[row][1][:, :n - 1] * g0[:, 1:]
    free = np.stack([phi[0][0][:, :n], phi[0][1][:, :n]], axis=1)
    return kernels, free


class _Model:
    """The linear least-squares problem of one record at given (T, zeta)."""

    def __init__(self, time_s, response, dynamic_inputs, feedthrough_inputs, drift_period_s):
        self.dt = (time_s[-1] - time_s[0]) / (len(time_s) - 1)
        self.n = len(time_s)
        self.response = response
        self.nfft = 1 << int(math.ceil(math.log2(2 * self.n)))
        self.input_spectra = [np.fft.rfft(u, self.nfft) for u in dynamic_inputs]
        # Drift: a line and the cosines of periods down to drift_period_s (a
        # high-pass: the sloshing under a bulging record, settling under a wave).
        fraction = (time_s - time_s[0]) / (time_s[-1] - time_s[0])
        cosines = int(2 * (time_s[-1] - time_s[0]) / drift_period_s) if drift_period_s else 0
        null = [np.ones_like(fraction), fraction - 0.5]
        null += [np.cos(math.pi * k * fraction) for k in range(1, cosines + 1)]
        null += list(feedthrough_inputs)
        self.null_basis = np.array(null).T
        # The oscillator's columns are fitted to what the drift and feedthrough
        # leave (Frisch-Waugh: the same least squares, far fewer columns each time).
        q, r = np.linalg.qr(self.null_basis / np.linalg.norm(self.null_basis, axis=0))
        self.null_orthonormal = q[:, np.abs(np.diag(r)) > 1e-10]
        self.null_residual = response - self.null_orthonormal @ (self.null_orthonormal.T @ response)
        self.null_rss = float(self.null_residual @ self.null_residual)
        self.columns_per_oscillator = 2 * len(dynamic_inputs) + 2

    def oscillator_columns(self, period_s, damping_ratios):
        """For each damping ratio: q and q' of each input, then the two free
        responses (Z x n x columns), projected off the drift and feedthrough."""
        kernels, free = _oscillator_kernels(period_s, damping_ratios, self.dt, self.n)
        kernel_spectra = np.fft.rfft(kernels, self.nfft, axis=2)
        columns = []
        # The kernels' term in u[0] alone is a free response: the free columns hold it.
        for spectrum in self.input_spectra:
            columns.append(np.fft.irfft(kernel_spectra * spectrum, self.nfft, axis=2)[:, :, :self.n])
        columns.append(free)
        columns = np.concatenate(columns, axis=1).transpose(0, 2, 1)
        return columns - self.null_orthonormal @ (self.null_orthonormal.T @ columns)

    def fit_columns(self, columns):
        """Residual of the best linear combination of `columns` (n x m, already
        off the drift and feedthrough)."""
        scale = np.linalg.norm(columns, axis=0)
        scale[scale == 0] = 1.0
        coefficients, *_ = np.linalg.lstsq(columns / scale, self.null_residual, rcond=None)
        return self.null_residual - (columns / scale) @ coefficients

    def fit(self, oscillators):
        """Residual and fitted response of the best linear combination of the
        columns of every oscillator [(T, zeta), ...]."""
        residual = self.fit_columns(np.hstack([self.oscillator_columns(p, [z])[0] for p, z in oscillators]))
        return residual, self.response - residual

    def parameters(self, oscillators):
        """Fitted numbers: the linear ones and (T, zeta) of each oscillator."""
        return self.null_orthonormal.shape[1] + oscillators * (self.columns_per_oscillator + 2)


def _levenberg_marquardt(model, oscillators, bands, damping_range):
    """Refines [(T, zeta), ...] from a start, each T within its band; T in log
    so that steps are relative."""
    lower = np.array([b for band in bands for b in (math.log(band[0]), damping_range[0])])
    upper = np.array([b for band in bands for b in (math.log(band[1]), damping_range[1])])

    def unpack(theta):
        return [(math.exp(theta[2 * k]), theta[2 * k + 1]) for k in range(len(bands))]

    def residual(theta):
        return model.fit(unpack(theta))[0]

    theta = np.clip(np.array([x for p, z in oscillators for x in (math.log(p), z)]), lower, upper)
    r = residual(theta)
    cost = r @ r
    mu = 1e-3
    for _ in range(60):
        jacobian = _jacobian(residual, theta, [1e-5] * len(theta))
        gradient = jacobian.T @ r
        normal = jacobian.T @ jacobian
        improved = False
        for _ in range(12):
            step = -np.linalg.solve(normal + mu * np.diag(np.diag(normal) + 1e-30), gradient)
            trial = np.clip(theta + step, lower, upper)
            r_trial = residual(trial)
            if r_trial @ r_trial < cost:
                improved = True
                converged = abs(cost - r_trial @ r_trial) <= 1e-12 * cost or np.all(np.abs(trial - theta) < 1e-9)
                theta, r, cost = trial, r_trial, r_trial @ r_trial
                mu = max(mu / 10, 1e-12)
                break
            mu *= 10
        if not improved or converged:
            break
    return unpack(theta)


def _period_grid(band, duration):
    """Periods across a band in relative steps of an eighth of the record's
    resolution (1 / cycles), between 0.3 % and 2 %."""
    periods = [band[0]]
    while periods[-1] < band[1]:
        periods.append(periods[-1] * (1 + min(0.02, max(0.003, periods[-1] / duration / 8))))
    return np.array(periods[:-1] + [band[1]])


def _scan(model, oscillators, slot, band, duration, dampings, deepest):
    """Grid scan of oscillator `slot`'s (T, zeta) with the others held: the
    grid points of the `deepest` lowest local minima over T, as oscillator
    lists to refine."""
    periods = _period_grid(band, duration)
    # The others' columns are the same at every grid point: made once.
    held = [model.oscillator_columns(o[0], [o[1]])[0] for k, o in enumerate(oscillators) if k != slot]

    def costs_at(period):
        """The residual's sum of squares at each damping of the grid."""
        return [float(np.sum(model.fit_columns(np.hstack(held + [columns])) ** 2))
                for columns in model.oscillator_columns(period, dampings)]

    costs = np.array([costs_at(p) for p in periods])
    best_per_period = costs.min(axis=1)
    padded = np.concatenate([[np.inf], best_per_period, [np.inf]])
    minima = [k for k in range(len(periods)) if padded[k + 1] <= min(padded[k], padded[k + 2])]
    starts = []
    for k in sorted(minima, key=lambda k: best_per_period[k])[:deepest]:
        start = list(oscillators)
        start[slot] = (periods[k], dampings[int(np.argmin(costs[k]))])
        starts.append(start)
    return starts


def _jacobian(residual, theta, steps):
    """Central differences of the residual vector with respect to each parameter."""
    columns = []
    for k in range(len(theta)):
        shifted = theta.copy()
        shifted[k] += steps[k]
        back = theta.copy()
        back[k] -= steps[k]
        columns.append((residual(shifted) - residual(back)) / (2 * steps[k]))
    return np.column_stack(columns)


def _parameter_std(jacobian, residual, dof, lag):
    """Standard deviations of the parameters: the larger of the white-noise
    least-squares figure and the Newey-West (Bartlett, `lag` samples) one."""
    normal_inverse = np.linalg.inv(jacobian.T @ jacobian)
    white = np.diag(normal_inverse) * (residual @ residual) / dof
    scores = jacobian * residual[:, None]
    meat = scores.T @ scores
    for l in range(1, lag + 1):
        weight = 1 - l / (lag + 1)
        cross = scores[l:].T @ scores[:-l]
        meat += weight * (cross + cross.T)
    coloured = np.diag(normal_inverse @ meat @ normal_inverse) * len(residual) / dof
    return np.sqrt(np.maximum(white, coloured))


def uniform_record(time_s, *series):
    """Resamples series onto a uniform time grid of the record's mean spacing
    (a restarted run may repeat or skip a sample)."""
    time_s = np.asarray(time_s, dtype=float)
    order = np.argsort(time_s, kind="stable")
    time_s = time_s[order]
    keep = np.concatenate([[True], np.diff(time_s) > 1e-12])
    time_s = time_s[keep]
    grid = np.linspace(time_s[0], time_s[-1], len(time_s))
    return (grid,) + tuple(np.interp(grid, time_s, np.asarray(s, dtype=float)[order][keep]) for s in series)


def identify_period(time_s, response, dynamic_inputs, band_s, feedthrough_inputs=(), drift_period_s=None,
                    min_cycles=2.0, max_damping=0.3, min_explained=0.05, max_relative_std=0.05, higher_modes=0):
    """Period (s) of the oscillator that best maps `dynamic_inputs` (ground
    accelerations, sampled at `time_s`) onto `response`, searched within
    `band_s` = (shortest, longest); content of periods longer than
    `drift_period_s` (default: none but a line) counts as drift.
    `higher_modes` more oscillators, each of a period below
    1/HIGHER_MODE_RATIO of the one before, are fitted with it (the second
    sloshing mode under the first: left out, its response biases the first's
    period). Returns a PeriodEstimate of the first; raises
    PeriodNotIdentified with the reason when the record does not determine one."""
    time_s = np.asarray(time_s, dtype=float)
    response = np.asarray(response, dtype=float)
    if len(time_s) < 16 or not np.all(np.isfinite(response)):
        raise PeriodNotIdentified(f"the record has {len(time_s)} samples or non-finite values")
    duration = time_s[-1] - time_s[0]
    dt = duration / (len(time_s) - 1)
    shortest = max(band_s[0], 4 * dt)  # four samples per period at least
    longest = min(band_s[1], duration / min_cycles)
    if shortest >= longest:
        raise PeriodNotIdentified(
            f"the record ({duration:.3g} s sampled every {dt:.3g} s) cannot resolve periods of "
            f"{band_s[0]:.3g}-{band_s[1]:.3g} s: it holds {duration / band_s[1]:.2g}-{duration / band_s[0]:.2g} "
            f"cycles of them (at least {min_cycles:g} needed) and resolves periods from {4 * dt:.3g} s")
    band = (shortest, longest)
    inputs = [np.asarray(u, dtype=float) for u in dynamic_inputs]
    if not inputs or all(np.ptp(u) == 0 for u in inputs):
        raise PeriodNotIdentified("the ground acceleration is zero: nothing drives the response")
    model = _Model(time_s, response, inputs, [np.asarray(u, dtype=float) for u in feedthrough_inputs], drift_period_s)
    null_rss = model.null_rss
    if null_rss <= 1e-24 * float(response @ response):
        raise PeriodNotIdentified("the response is constant (or a drift alone)")
    damping_range = (1e-4, 0.6)
    dampings = (0.005, 0.03, 0.1, 0.3)

    def refined(starts, bands):
        """The start that refines to the smallest residual, refined."""
        best = None
        for start in starts:
            oscillators = _levenberg_marquardt(model, start, bands, damping_range)
            rss = float(np.sum(model.fit(oscillators)[0] ** 2))
            if best is None or rss < best[0]:
                best = (rss, oscillators)
        return best[1]

    # One oscillator: the three deepest valleys of a grid scan refined (the
    # deepest on the grid need not be the deepest refined).
    oscillators = refined(_scan(model, [None], 0, band, duration, dampings, 3), [band])
    # Each higher mode below the one before, scanned with the others held;
    # then the first scanned again with them (their responses no longer pull
    # it), and all refined together within the whole band.
    def bands_of(oscillators):
        return [band] + [(shortest, max(shortest * 1.01, oscillators[k][0] / HIGHER_MODE_RATIO))
                         for k in range(len(oscillators) - 1)]

    for _ in range(higher_modes):
        bands = bands_of(oscillators + [None])
        oscillators = refined(_scan(model, oscillators + [None], len(oscillators), bands[-1], duration, dampings, 1),
                              bands)
    if higher_modes:
        # The first moves by a few per cent when the others join: scanned again
        # within a fifth of where it was.
        near = (max(band[0], oscillators[0][0] / 1.2), min(band[1], oscillators[0][0] * 1.2))
        oscillators = refined(_scan(model, oscillators, 0, near, duration, dampings, 3), bands_of(oscillators))
    residual, fitted = model.fit(oscillators)
    rss = float(residual @ residual)
    period, damping = oscillators[0]

    explained = 1 - rss / null_rss
    cycles = duration / period
    if period <= band[0] * 1.01 or period >= band[1] / 1.01:
        raise PeriodNotIdentified(f"the best oscillator ({period:.4g} s) lies at the edge of the band "
                                  f"{band[0]:.4g}-{band[1]:.4g} s: no resonance within it")
    if damping > max_damping:
        raise PeriodNotIdentified(f"the best oscillator ({period:.4g} s) needs damping {damping:.2f} > {max_damping}: "
                                  "no resonance")
    if explained < min_explained:
        raise PeriodNotIdentified(f"the best oscillator ({period:.4g} s) explains {100 * explained:.1f} % of the "
                                  f"response's variance (at least {100 * min_explained:.0f} % needed)")
    theta = np.array([x for oscillator in oscillators for x in oscillator])
    steps = [1e-5 * x if k % 2 == 0 else 1e-5 for k, x in enumerate(theta)]
    jacobian = _jacobian(lambda th: model.fit(list(zip(th[0::2], th[1::2])))[0], theta, steps)
    lag = int(min(len(residual) // 4, round(period / dt)))
    stds = _parameter_std(jacobian, residual, len(residual) - model.parameters(len(oscillators)), lag)
    period_std, damping_std = stds[0], stds[1]
    if not period_std / period <= max_relative_std:
        raise PeriodNotIdentified(
            f"the best oscillator's period {period:.4g} s is uncertain by {100 * period_std / period:.1f} % "
            f"(at most {100 * max_relative_std:.0f} % accepted)")
    return PeriodEstimate(float(period), float(period_std), float(damping), float(damping_std), float(explained),
                          float(cycles), fitted, band)


SPECTRUM_PADDING = 8


def amplitude_spectrum(time_s, values, padding=SPECTRUM_PADDING):
    """Frequencies (Hz) and amplitude spectrum of a record with its linear
    trend removed and a Hann window, zero-padded `padding` times (for plots;
    the padding interpolates, it does not resolve)."""
    time_s = np.asarray(time_s, dtype=float)
    values = np.asarray(values, dtype=float)
    detrended = values - np.polyval(np.polyfit(time_s, values, 1), time_s)
    window = np.hanning(len(values))
    n = padding * len(values)
    dt = (time_s[-1] - time_s[0]) / (len(time_s) - 1)
    amplitude = 2 * np.abs(np.fft.rfft(detrended * window, n)) / window.sum()
    return np.fft.rfftfreq(n, dt), amplitude


def read_csv(path):
    """A probe CSV as a dict of column -> array."""
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {name: np.atleast_1d(data[name]) for name in data.dtype.names}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--response", required=True, help="probe CSV (time_s first)")
    parser.add_argument("--column", required=True, help="column of the response, e.g. wave_height_m")
    parser.add_argument("--ground", required=True, help="ground acceleration CSV (time_s, ax_m_s2, ay_m_s2, az_m_s2)")
    parser.add_argument("--components", default="ax_m_s2,ay_m_s2", help="ground columns that drive the oscillator")
    parser.add_argument("--band", nargs=2, type=float, required=True, metavar=("SHORTEST_S", "LONGEST_S"))
    parser.add_argument("--feedthrough", action="store_true",
                        help="the response holds the inputs themselves too (wall pressure: the rigid impulsive part)")
    parser.add_argument("--min-cycles", type=float, default=2.0)
    parser.add_argument("--higher-modes", type=int, default=0,
                        help="shorter-period oscillators fitted with the first (1 for a wave height: the second "
                             "sloshing mode)")
    args = parser.parse_args()
    record = read_csv(args.response)
    ground = read_csv(args.ground)
    time_s, response = uniform_record(record["time_s"], record[args.column])
    columns = args.components.split(",")
    inputs = [np.interp(time_s, ground["time_s"], ground[c]) for c in columns]
    feedthrough = [np.interp(time_s, ground["time_s"], ground[c]) for c in ("ax_m_s2", "ay_m_s2", "az_m_s2")
                   if c in ground] if args.feedthrough else []
    try:
        estimate = identify_period(time_s, response, inputs, tuple(args.band), feedthrough, min_cycles=args.min_cycles,
                                   higher_modes=args.higher_modes)
    except PeriodNotIdentified as reason:
        print(f"no period identified: {reason}")
        return 1
    print(f"period {estimate.period_s:.5g} s +- {estimate.period_std_s:.2g} s (1 sigma), damping "
          f"{100 * estimate.damping_ratio:.2f} % +- {100 * estimate.damping_std:.2f} %, "
          f"{estimate.cycles:.1f} cycles in the record, "
          f"{100 * estimate.explained_fraction:.1f} % of the variance explained")
    return 0


if __name__ == "__main__":
    sys.exit(main())
