/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The FMI callbacks of the FMU benchmarks and of the FMU tests that need no logger of their own
 * (each binary includes this once): memory from calloc/free, as a plain importer gives it, and a
 * logger that prints every message on stderr, so a refusal a run provokes is shown with its text.
 */
#ifndef SMS_TESTS_FMU_TEST_CALLBACKS_H
#define SMS_TESTS_FMU_TEST_CALLBACKS_H

#include <stdio.h>
#include <stdlib.h>

#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    (void)env; (void)status; (void)category;
    fprintf(stderr, "[%s] %s\n", name, message);
}

static const fmi2CallbackFunctions callbacks = { logger, calloc, free, NULL, NULL };

#endif
