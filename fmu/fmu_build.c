/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Building a model into an instance's block (fmu_instance.h): plan, allocate through the
 * importer's memory functions, build. One routine for the glue (ExitInitializationMode) and the
 * serialiser (a deserialised state rebuilds its filters from its parameters), below both, so
 * neither calls the other for it.
 */
#include <stdio.h>

#include "fmu_instance.h"

int fmu_build(const fmu_host *host, void *model, void **mem, size_t *bytes, char *msg,
              size_t len)
{
    size_t need = 0;
    void *block;
    int built;
    if (fmu_model_plan(model, &need, msg, len) != 0)
        return 1;
    block = host->alloc(need > 0 ? need : 1, 1);
    if (block == NULL)
        return snprintf(msg, len, "out of memory: the filters need %lu bytes",
                        (unsigned long)need), 1;
    built = fmu_model_build(model, block, need, msg, len);
    if (built > 0) {
        host->release(block);
        return 1;
    }
    if (*mem != NULL)
        host->release(*mem);
    *mem = block;
    *bytes = need;
    return built < 0 ? -1 : 0;
}
