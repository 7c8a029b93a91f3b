/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The refusals every model's fmu_model_plan() words the same way (fmu_model.h): a configuration
 * beyond the state limit (FMU_MAX_REALS) or beyond the filtering a long step may need
 * (FMU_MAX_HOLD_SAMPLES). Below the models: they call these, and nothing here calls back.
 */
#include <stdio.h>

#include "fmu_model.h"

int fmu_refuse_size(char *msg, size_t len, const char *parameters, double need, const char *fix)
{
    snprintf(msg, len, "%s: needs %.0f reals of delay lines and tables (%.1f MiB in double), more "
             "than the limit of %lu reals (%lu MiB) per instance that keeps every call on the "
             "state well under 100 ms: %s", parameters, need, need * 8.0 / 1048576.0,
             (unsigned long)FMU_MAX_REALS, (unsigned long)(FMU_MAX_REALS * 8u >> 20), fix);
    return 1;
}

int fmu_refuse_hold(char *msg, size_t len, const char *parameters, double need,
                    const char *slowest, const char *fix)
{
    snprintf(msg, len, "%s: absorbing a held input needs %.4g stage-samples of filtering (%s), "
             "more than the limit of %.0f that keeps a doStep of any length well under "
             "100 ms: %s", parameters, need, slowest, FMU_MAX_HOLD_SAMPLES, fix);
    return 1;
}
