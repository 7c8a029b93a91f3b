/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The serialised FMU state (fmu_serialize.c, which documents the byte format): what the glue's
 * SerializedFMUstateSize / SerializeFMUstate / DeSerializeFMUstate (FMI 3.0: ...FMUState)
 * call. Reading a
 * state rebuilds the model through fmu_build() (fmu_instance.h), never through the glue.
 */
#ifndef FMU_SERIALIZE_H
#define FMU_SERIALIZE_H

#include <stddef.h>
#include <stdint.h>
#include "fmu_instance.h"

/** XXH64 (seed 0) of p[0..n-1], the states' checksum: the reference algorithm of Y. Collet's
 * xxHash (64-bit variant), any n (tests/fmu/test_fmu_checksum.c compares it with the xxHash
 * library's values, every tail length). */
uint64_t fmu_xxh64(const unsigned char *p, size_t n);

/** Make (or refresh) img from model's current settable values: the bytes fmu_serialize()
 * writes for them. Memory through host. @return 0, or non-zero (out of memory, or more inputs
 * than FMU_MAX_IMAGE_INPUTS): img then stays invalid and states are read value by value. */
int fmu_values_image_make(fmu_values_image *img, const void *model, const fmu_host *host);
/** Release img's memory. */
void fmu_values_image_free(fmu_values_image *img, const fmu_host *host);

/** Bytes fmu_serialize() writes for this snapshot. */
size_t fmu_serialized_size(const fmu_snapshot *s);
/** Write the snapshot into out[0..size-1] (size from fmu_serialized_size); the model's state
 * vector is written in place when the host stores doubles as the format does and out puts them
 * at an address aligned for double, else it passes through scratch memory from host.
 * @return 0, or non-zero when out of memory. */
int fmu_serialize(const fmu_snapshot *s, const fmu_host *host, unsigned char *out);
/**
 * Parse a serialised state into dst (whose model struct is allocated, fmu_model_size() bytes;
 * its block is allocated here through host). The filters are rebuilt from the state's
 * parameters, unless they equal those of `like` (the instance the state is read for, if built:
 * NULL for none), whose built filters are copied instead, which a build would give bit for bit
 * and costs no design: the fixed cost of reading a state of the instance's own configuration.
 * When like->values is valid, a state whose settable values equal it outside the inputs (one
 * memcmp per run between inputs) takes that path without reading the values one by one: only
 * its inputs are read (and must be finite).
 * @return 0 on success, else non-zero with msg saying why (foreign, other precision, truncated,
 *         corrupted, clock and tick count disagreeing, invalid parameters); dst then holds no
 *         block and must only be freed.
 */
int fmu_deserialize(const unsigned char *in, size_t size, fmu_snapshot *dst,
                    const fmu_instance *like, const fmu_host *host, char *msg, size_t len);

#endif
