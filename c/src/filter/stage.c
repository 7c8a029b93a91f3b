/* SPDX-License-Identifier: Apache-2.0 */
/* One interface over the three implementation families: each stage's memory layout (instance,
 * tap table, delay line, each on a cell boundary) and dispatch; no filtering here. */
#include <stdint.h>
#include "smoothshaper/coeffs.h"
#include "filter/coeffs_check.h"
#include "core/kind.h"
#include "filter/shaper_designs.h"
#include "filter/input_smoother.h"

sms_stage_config sms_stage_config_default(sms_kind kind)
{
    sms_stage_config c;
    unsigned m;
    c.kind = kind;
    c.timing = SMS_TIMING_EXACT;
    c.T = 0.0;
    c.sigma = 0.0;
    c.k = 1u;
    c.wn = 0.0;
    c.zeta = 0.0;
    c.order = kind == SMS_SHAPER_GMZV ? 3u : 1u;   /* GMZV: 3 impulses over 0.75 Td = MZV */
    c.tolerance = 0.05;
    c.duration = 0.75;
    if (kind == SMS_SHAPER_SI)                    /* 3 impulses, between ZV and EI */
        c.order = 3u;
    if (kind == SMS_SHAPER_IMPULSES)
        c.order = 0u;                             /* the impulses must be set */
    c.notch_pole_zeta = 0.7;
    for (m = 0; m < SMS_SHAPER_MAX_IMPULSES; ++m)
        c.amplitudes[m] = c.times[m] = 0.0;
    return c;
}

/* Where the parts of a stage lie in its memory, in cells from its start. */
typedef struct layout {
    size_t table;   /* shaper tap table (after the instance) */
    size_t ring;    /* delay line */
    size_t total;   /* cells in all */
} layout;

static size_t cells_of_bytes(size_t bytes)
{
    return bytes / sizeof(sms_memory_cell) + (bytes % sizeof(sms_memory_cell) != 0);
}

/* The layout of a stage of family fam with n_taps tap entries and n_reals delay-line reals;
 * 0 if the total overflows size_t. A cell holds a whole number of reals (it holds a double). */
static int plan(sms_family fam, size_t n_taps, size_t n_reals, layout *out)
{
    const size_t per_cell = sizeof(sms_memory_cell) / sizeof(sms_real);
    size_t instance, table, ring;
    switch (fam) {
    case SMS_FAMILY_SMOOTHER: instance = cells_of_bytes(sizeof(sms_smoother)); break;
    case SMS_FAMILY_SHAPER: instance = cells_of_bytes(sizeof(sms_shaper)); break;
    default: instance = cells_of_bytes(sizeof(sms_notch)); break;
    }
    /* n_taps <= SMS_SHAPER_MAX_TAPS, or an input smoother's <= 2^20: no overflow */
    table = cells_of_bytes(n_taps * sizeof(sms_shaper_tap));
    ring = n_reals / per_cell + (n_reals % per_cell != 0);
    if (ring > SIZE_MAX - instance - table)
        return 0;
    out->table = instance;
    out->ring = instance + table;
    out->total = instance + table + ring;
    return 1;
}

/* Validate a config; its delay-line reals and tap-table entries. */
static sms_status stage_sizes(const sms_stage_config *config, double Ts, size_t *n_reals,
                              size_t *n_taps)
{
    *n_reals = 0;
    *n_taps = 0;
    switch (sms_family_of(config->kind)) {
    case SMS_FAMILY_SMOOTHER:
        return sms_smoother_buffer_size(config, Ts, n_reals);
    case SMS_FAMILY_SHAPER:
        return sms_shaper_sizes(config, Ts, n_reals, n_taps);
    case SMS_FAMILY_NOTCH: {
        sms_notch probe;
        return sms_notch_init(&probe, config, Ts);
    }
    case SMS_FAMILY_NONE:
        break;
    }
    return SMS_ERR_KIND;
}

/* Validate a config and lay out its memory. */
static sms_status stage_layout(const sms_stage_config *config, double Ts, layout *out)
{
    size_t n_reals, n_taps;
    sms_status st = stage_sizes(config, Ts, &n_reals, &n_taps);
    if (st != SMS_OK)
        return st;
    return plan(sms_family_of(config->kind), n_taps, n_reals, out) ? SMS_OK : SMS_ERR_TOO_LONG;
}

sms_status sms_stage_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals)
{
    size_t n_taps, reals;
    sms_status st;
    if (config == NULL || n_reals == NULL)
        return SMS_ERR_NULL;
    st = stage_sizes(config, Ts, &reals, &n_taps);
    if (st == SMS_OK)
        *n_reals = reals;
    return st;
}

sms_status sms_stage_memory_size(const sms_stage_config *config, double Ts, size_t *n_cells)
{
    layout lay;
    sms_status st;
    if (config == NULL || n_cells == NULL)
        return SMS_ERR_NULL;
    st = stage_layout(config, Ts, &lay);
    if (st == SMS_OK)
        *n_cells = lay.total;
    return st;
}

sms_status sms_stage_config_validate(const sms_stage_config *config, double Ts)
{
    size_t unused;
    return sms_stage_memory_size(config, Ts, &unused);
}

sms_status sms_stage_init(sms_stage *stage, const sms_stage_config *config, double Ts,
                          sms_memory_cell *memory, size_t n_cells)
{
    sms_shaper_tap taps[SMS_SHAPER_MAX_TAPS], *table = taps;
    size_t n_taps = SMS_SHAPER_MAX_TAPS;
    sms_stage_coeffs coeffs;
    sms_status st;
    if (stage == NULL || config == NULL)
        return SMS_ERR_NULL;
    if (sms_is_input_smoother(config->kind)) {
        /* A tap per sample of the window, up to 2^20: designed straight into the stage's own
         * tap table, which sms_shaper_init_coeffs then keeps in place. */
        layout lay;
        st = stage_layout(config, Ts, &lay);
        if (st != SMS_OK)
            return st;
        if (memory == NULL)
            return SMS_ERR_NULL;
        if (n_cells < lay.total)
            return SMS_ERR_BUFFER_TOO_SMALL;
        table = (sms_shaper_tap *)(void *)&memory[lay.table];
        n_taps = (lay.ring - lay.table) * sizeof(sms_memory_cell) / sizeof(sms_shaper_tap);
    }
    /* Design once, then build the stage from its coefficients as a target does. */
    st = sms_stage_coeffs_make(config, Ts, &coeffs, table, n_taps);
    if (st != SMS_OK)
        return st;
    return sms_stage_init_coeffs(stage, &coeffs, memory, n_cells);
}

/* ---- the firmware path (coeffs.h) ---- */

sms_status sms_stage_coeffs_make(const sms_stage_config *config, double Ts,
                                 sms_stage_coeffs *coeffs, sms_shaper_tap *taps, size_t n_taps)
{
    sms_stage_coeffs made;
    sms_status st;
    if (config == NULL || coeffs == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(config->kind)) {
    case SMS_FAMILY_SMOOTHER: st = sms_smoother_coeffs_make(config, Ts, &made); break;
    case SMS_FAMILY_SHAPER: st = sms_shaper_coeffs_make(config, Ts, &made, taps, n_taps); break;
    case SMS_FAMILY_NOTCH: st = sms_notch_coeffs_make(config, Ts, &made); break;
    default: return stage_sizes(config, Ts, &n_taps, &n_taps); /* the status of a bad config */
    }
    if (st == SMS_OK)
        *coeffs = made;
    return st;
}

/* Check coefficients and lay out the stage built from them. */
static sms_status coeffs_layout(const sms_stage_coeffs *coeffs, layout *out)
{
    const sms_family fam = sms_family_of(coeffs->kind);
    sms_status st;
    size_t n_taps = 0, n_reals = 0;
    switch (fam) {
    case SMS_FAMILY_SMOOTHER:
        st = sms_smoother_coeffs_check(coeffs);
        n_reals = coeffs->u.smoother.window;
        break;
    case SMS_FAMILY_SHAPER:
        st = sms_shaper_coeffs_check(coeffs);
        n_taps = coeffs->u.shaper.n_taps;
        n_reals = coeffs->u.shaper.length;
        break;
    case SMS_FAMILY_NOTCH: st = sms_notch_coeffs_check(coeffs); break;
    default: return SMS_ERR_KIND;
    }
    if (st != SMS_OK)
        return st;
    return plan(fam, n_taps, n_reals, out) ? SMS_OK : SMS_ERR_TOO_LONG;
}

sms_status sms_stage_coeffs_memory_size(const sms_stage_coeffs *coeffs, size_t *n_cells)
{
    layout lay;
    sms_status st;
    if (coeffs == NULL || n_cells == NULL)
        return SMS_ERR_NULL;
    st = coeffs_layout(coeffs, &lay);
    if (st == SMS_OK)
        *n_cells = lay.total;
    return st;
}

sms_status sms_stage_init_coeffs(sms_stage *stage, const sms_stage_coeffs *coeffs,
                                 sms_memory_cell *memory, size_t n_cells)
{
    sms_stage built;
    layout lay;
    size_t ring_reals;
    sms_status st;
    if (stage == NULL || coeffs == NULL)
        return SMS_ERR_NULL;
    st = coeffs_layout(coeffs, &lay);
    if (st != SMS_OK)
        return st;
    if (memory == NULL)
        return SMS_ERR_NULL;
    if (n_cells < lay.total)
        return SMS_ERR_BUFFER_TOO_SMALL;
    /* Checked and large enough: the family init below succeeds. */
    built.kind = coeffs->kind;
    ring_reals = (lay.total - lay.ring) * (sizeof(sms_memory_cell) / sizeof(sms_real));
    switch (sms_family_of(coeffs->kind)) {
    case SMS_FAMILY_SMOOTHER:
        built.u.smoother = (sms_smoother *)(void *)memory;
        st = sms_smoother_init_coeffs(built.u.smoother, coeffs, &memory[lay.ring].r, ring_reals);
        break;
    case SMS_FAMILY_SHAPER:
        built.u.shaper = (sms_shaper *)(void *)memory;
        st = sms_shaper_init_coeffs(built.u.shaper, coeffs,
                                    (sms_shaper_tap *)(void *)&memory[lay.table],
                                    (lay.ring - lay.table) * sizeof(sms_memory_cell)
                                        / sizeof(sms_shaper_tap),
                                    &memory[lay.ring].r, ring_reals);
        break;
    default:
        built.u.notch = (sms_notch *)(void *)memory;
        st = sms_notch_init_coeffs(built.u.notch, coeffs);
        break;
    }
    if (st != SMS_OK)
        return st;
    *stage = built;
    return SMS_OK;
}

void sms_stage_reset(sms_stage *stage, sms_real rest)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_reset(stage->u.smoother, rest); break;
    case SMS_FAMILY_SHAPER: sms_shaper_reset(stage->u.shaper, rest); break;
    case SMS_FAMILY_NOTCH: sms_notch_reset(stage->u.notch, rest); break;
    case SMS_FAMILY_NONE: break;
    }
}

void sms_stage_process(sms_stage *stage, const sms_real *in, sms_real *out, size_t n)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_process(stage->u.smoother, in, out, n); break;
    case SMS_FAMILY_SHAPER: sms_shaper_process(stage->u.shaper, in, out, n); break;
    case SMS_FAMILY_NOTCH: sms_notch_process(stage->u.notch, in, out, n); break;
    case SMS_FAMILY_NONE: break;
    }
}

size_t sms_stage_length(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return stage->u.smoother->length;
    case SMS_FAMILY_SHAPER: return stage->u.shaper->length;
    default: return 0;
    }
}

size_t sms_stage_state_count(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return sms_smoother_state_count(stage->u.smoother);
    case SMS_FAMILY_SHAPER: return sms_shaper_state_count(stage->u.shaper);
    case SMS_FAMILY_NOTCH: return sms_notch_state_count(stage->u.notch);
    case SMS_FAMILY_NONE: break;
    }
    return 0;
}

void sms_stage_get_state(const sms_stage *stage, double *dst)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_get_state(stage->u.smoother, dst); break;
    case SMS_FAMILY_SHAPER: sms_shaper_get_state(stage->u.shaper, dst); break;
    case SMS_FAMILY_NOTCH: sms_notch_get_state(stage->u.notch, dst); break;
    case SMS_FAMILY_NONE: break;
    }
}

sms_status sms_stage_set_state(sms_stage *stage, const double *src, size_t n)
{
    if (stage == NULL || src == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return sms_smoother_set_state(stage->u.smoother, src, n);
    case SMS_FAMILY_SHAPER: return sms_shaper_set_state(stage->u.shaper, src, n);
    case SMS_FAMILY_NOTCH: return sms_notch_set_state(stage->u.notch, src, n);
    case SMS_FAMILY_NONE: break;
    }
    return SMS_ERR_KIND;
}

sms_status sms_stage_check_state(const sms_stage *stage, const double *src, size_t n)
{
    if (stage == NULL || src == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return sms_smoother_check_state(stage->u.smoother, src, n);
    case SMS_FAMILY_SHAPER: return sms_shaper_check_state(stage->u.shaper, src, n);
    case SMS_FAMILY_NOTCH: return sms_notch_check_state(stage->u.notch, src, n);
    case SMS_FAMILY_NONE: break;
    }
    return SMS_ERR_KIND;
}

/* The layout of a built stage (it fitted when it was built, so plan() succeeds). */
static layout built_layout(const sms_stage *stage)
{
    layout lay = {0, 0, 0};
    sms_family fam = sms_family_of(stage->kind);
    switch (fam) {
    case SMS_FAMILY_SMOOTHER: (void)plan(fam, 0, stage->u.smoother->history_len, &lay); break;
    case SMS_FAMILY_SHAPER:
        (void)plan(fam, stage->u.shaper->n_taps, stage->u.shaper->history_len, &lay);
        break;
    case SMS_FAMILY_NOTCH: (void)plan(fam, 0, 0, &lay); break;
    case SMS_FAMILY_NONE: break;
    }
    return lay;
}

size_t sms_stage_memory_len(const sms_stage *stage)
{
    return built_layout(stage).total;
}

void sms_stage_rebind(sms_stage *stage, sms_memory_cell *memory)
{
    layout lay;
    /* The instance first: the layout is read from the copy, never from the original memory. */
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER:
        stage->u.smoother = (sms_smoother *)(void *)memory;
        lay = built_layout(stage);
        stage->u.smoother->history = &memory[lay.ring].r;
        break;
    case SMS_FAMILY_SHAPER:
        stage->u.shaper = (sms_shaper *)(void *)memory;
        lay = built_layout(stage);
        stage->u.shaper->taps = (sms_shaper_tap *)(void *)&memory[lay.table];
        stage->u.shaper->history = &memory[lay.ring].r;
        break;
    case SMS_FAMILY_NOTCH: stage->u.notch = (sms_notch *)(void *)memory; break;
    case SMS_FAMILY_NONE: break;
    }
}
