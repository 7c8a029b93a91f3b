/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The clock of an instance (fmu_instance.h): which ticks a communication step contains, and
 * whether a loaded clock is one a run could have reached. Used by the glue's doStep and by the
 * serialiser, below both.
 *
 * A step of length h advances the time since the last tick to s + h and contains the ticks
 * n = floor((s + h)/Ts + 1e-6): a tick up to 1e-6 Ts after the step's end belongs to it.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "fmu_instance.h"

/* Relative disagreement of t and t0 + ticks*Ts a loaded state may show: a host doing t += h
 * drifts by about 2e-8 t over 1e9 steps of 1 ms. */
#define CLOCK_REL_SLACK 1e-6

double fmu_clock_slack(double Ts, double t0, double t)
{
    (void)t0;
    (void)t;
    return FMU_TICK_SLACK * Ts;
}

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
