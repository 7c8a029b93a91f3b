/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The clock of an instance (fmu_instance.h): which ticks a communication step contains (the
 * slack, fmu_clock_slack() in fmu_instance.h), and whether a loaded clock is one a run could have
 * reached. Used by the glue's doStep and by the serialiser, below both.
 *
 * A step of length h advances the time since the last tick to s + h and contains the ticks
 * n = floor((s + h + slack) / Ts): a tick up to `slack` after the step's end belongs to it, so
 * the rounding of the importer's times never loses or doubles one. That rounding has two
 * sources. A host that accumulates t += h passes exact step lengths: their sum is exact here,
 * whatever its t does. A host that computes t_k = t0 + k h passes steps t_k+1 - t_k, each off
 * by the rounding of two times: |t_k - (t0 + k h)| <= 2^-53 (|t_k| + |k h|) <= 2^-53 3 M with
 * M = max(|t_k|, |t0|), which telescopes (the time advanced over k steps is off by one such
 * error, never their sum). So slack = 1e-6 Ts + 2^-51 M covers it with room; near 1.7e9 s one
 * ulp of t is 2.4e-7 s (2.4e-4 Ts at Ts = 1 ms) and the steps alternate between 0.99993 and
 * 1.00017 ms, near 1e12 s the steps are multiples of 1.2e-4 s. The slack is at most Ts/2, so a
 * step of h = Ts exact never holds two ticks; beyond M = 2^50 Ts (about 1.1e12 s at 1 ms) the
 * importer's times cannot place a tick and only exact step lengths keep one tick per step.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "fmu_instance.h"

/* Relative disagreement of t and t0 + ticks*Ts a loaded state may show: a host doing t += h
 * drifts by about 2e-8 t over 1e9 steps of 1 ms. */
#define CLOCK_REL_SLACK 1e-6

int fmu_clock_check(const fmu_clock *k, double Ts, char *msg, size_t len)
{
    const double ticks = (double)k->ticks, at = k->start_time + ticks * Ts + k->since_tick;
    /* One step of h counts floor(h/Ts) ticks, off by a few ulp of h/Ts: up to 1e-4 Ts after a
     * step of 1e12 ticks; the time since the last tick may then fall that far outside. */
    const double rounding = 4.0 * DBL_EPSILON * (ticks + 1.0) * Ts;
    const double slack = fmu_clock_slack(Ts, k->start_time, k->time);
    if (!(ticks < FMU_MAX_TICK_INDEX) || !(k->since_tick >= -2.0 * slack - rounding)
        || !(k->since_tick < Ts + rounding)) {
        snprintf(msg, len, "the state's clock is inconsistent (ticks %.17g, time since the last "
                 "tick %.17g s, Ts %.17g s)", ticks, k->since_tick, Ts);
        return -1;
    }
    if (!(fabs(k->time - at) <= FMU_TICK_SLACK * Ts + CLOCK_REL_SLACK * fabs(k->time))) {
        snprintf(msg, len, "the state's time %.17g s disagrees with its tick count (%.17g ticks "
                 "of %.17g s from t0 = %.17g s end at %.17g s)", k->time, ticks, Ts,
                 k->start_time, at);
        return -1;
    }
    return 0;
}
