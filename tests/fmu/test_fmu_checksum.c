/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The FMU states' checksum, fmu_xxh64(), against the xxHash library's XXH64 (seed 0) for every
 * path of the algorithm: below and above one 32-byte stripe, and every tail (8-, 4- and 1-byte
 * steps). A serialised state is always a multiple of 8 bytes long, so the FMU tests
 * (tests/python/test_fmu_robustness.py compares whole states with the xxhash package) never
 * reach the 4- and 1-byte tails; this test does. The expected values are the Python xxhash
 * package's, for the bytes (131 i + 17) mod 256:
 *   data = bytes((i * 131 + 17) & 255 for i in range(200))
 *   xxhash.xxh64_intdigest(data[:n])
 */
#include <stdio.h>

#include "fmu_serialize.h"

static const struct { size_t n; uint64_t xxh64; } expected[] = {
    { 0, 0xef46db3751d8e999u },  { 1, 0xad10cd9780ac4ff7u },  { 3, 0x40626d96276e4594u },
    { 4, 0x882207c122c76e23u },  { 5, 0xa3da885eec618bb4u },  { 7, 0xcfc90033aa9dac4fu },
    { 8, 0x90fda2f089fa86deu },  { 9, 0xa80deb192b8c5215u },  { 12, 0x333861b25fd6348bu },
    { 15, 0x59f95bad12d14c9du }, { 31, 0x44cc9efe5d2d0233u }, { 32, 0x0e1aab1d173cf196u },
    { 33, 0x5c820b4b4fe28fdcu }, { 36, 0x4085f13b32c5feb0u }, { 39, 0xd0ab734277760e45u },
    { 40, 0xc0441297b12d2395u }, { 63, 0x1153d36cade87066u }, { 64, 0xd4c20ef54cbc9f67u },
    { 67, 0x087fa05dc97eeebdu }, { 100, 0x7f8375f3e09d8123u }, { 200, 0x18005b73212257b8u },
};

int main(void)
{
    unsigned char data[200];
    unsigned i, failures = 0;
    for (i = 0; i < sizeof data; ++i)
        data[i] = (unsigned char)((i * 131u + 17u) & 255u);
    for (i = 0; i < sizeof expected / sizeof expected[0]; ++i) {
        const uint64_t got = fmu_xxh64(data, expected[i].n);
        if (got != expected[i].xxh64) {
            ++failures;
            fprintf(stderr, "fmu_xxh64 of %lu bytes: got %08lx%08lx, xxHash gives %08lx%08lx\n",
                    (unsigned long)expected[i].n, (unsigned long)(got >> 32),
                    (unsigned long)(got & 0xffffffffu), (unsigned long)(expected[i].xxh64 >> 32),
                    (unsigned long)(expected[i].xxh64 & 0xffffffffu));
        }
    }
    printf("fmu_xxh64: %lu lengths checked against xxHash, %u failures\n",
           (unsigned long)(sizeof expected / sizeof expected[0]), failures);
    return failures == 0 ? 0 : 1;
}
