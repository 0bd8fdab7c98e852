"""Records of a single-degree-of-freedom oscillator driven by a ground
motion, for the tests of the tank post-processing (tank_periods, tank_report):
integrated here with Newmark's average acceleration, independently of the
module's own exact discretisation, which they check."""
import math

import numpy as np


def oscillator_record(time_s, ground, period_s, damping_ratio, substeps=20):
    """q'' + 2 zeta omega q' + omega^2 q = ground(t), ground linear between
    samples, from rest; q at the samples (independent of the module's exact
    discretisation, which it checks)."""
    omega = 2 * math.pi / period_s
    dt = (time_s[1] - time_s[0]) / substeps
    fine = np.interp(np.linspace(time_s[0], time_s[-1], (len(time_s) - 1) * substeps + 1), time_s, ground)
    q = v = 0.0
    a = fine[0]
    out = np.zeros(len(fine))
    stiffness = omega ** 2 + 4 * damping_ratio * omega / dt + 4 / dt ** 2
    for i in range(1, len(fine)):
        q_new = (fine[i] + 4 / dt ** 2 * q + 4 / dt * v + a + 2 * damping_ratio * omega * (2 / dt * q + v)) / stiffness
        v_new = 2 / dt * (q_new - q) - v
        a = 4 / dt ** 2 * (q_new - q) - 4 / dt * v - a
        q, v = q_new, v_new
        out[i] = q
    return out[::substeps]
