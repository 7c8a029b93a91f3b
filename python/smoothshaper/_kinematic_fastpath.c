/* SPDX-License-Identifier: Apache-2.0 */
/* design.kinematic's fast path as a CPython function: plain numbers in, Stage objects out.
 *
 * design.kinematic is called once per move in online planning, where its cost beside the C
 * design matters. Through cffi, a Python function that returns Stage objects pays the keyword
 * call, the cffi call and the objects from Python code: 3x the raw C call at least. Here the
 * argument types are tested, the C design (the solve of sms_kinematic_design /
 * sms_kinematic_configs) runs and the Stage objects are built in one C function.
 *
 * It returns None whenever the fast path does not apply (a type other than a plain number,
 * more than three bounds, a design the C core refuses); design.kinematic then runs its fully
 * checked path, which names the offending argument. The C core checks every value (finite,
 * > 0, ratios in range, zeta in [0, 1)), so only the types are tested here. The Stage objects
 * get the C core's values without re-validation, written straight into their slots (Stage is
 * a slotted dataclass): they equal what Stage(...) builds from the same values
 * (tests/python/test_design.py compares them field by field). */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <structmember.h>

#include <math.h>
#include <string.h>

#include "smoothshaper/smoothshaper.h"
#include "trajectory/trajectory_internal.h"

/* Set once by configure() (design.py at import): Stage, the kind and timing names indexed by
 * the C enumerations, the profile names mapped to sms_profile, the extra number types that
 * convert exactly like float() (NumPy float64, float32, int64). */
static PyObject *stage_type, *kind_names, *timing_names, *profile_index, *extra_numbers;
static PyObject *one;

/* Stage's slots: the byte offset of each field in an instance (from its member descriptors)
 * and the field's default, in field order; the fields this file writes, by index. */
#define MAX_FIELDS 32
static Py_ssize_t field_count, field_offset[MAX_FIELDS];
static PyObject *field_default[MAX_FIELDS];
static Py_ssize_t f_kind = -1, f_T = -1, f_sigma = -1, f_k = -1, f_order = -1, f_timing = -1;

/* When the slots fill the whole instance (no dict, no weak-reference list, nothing else
 * after the object header), a new smoother Stage is that block as a copy of `image` (every
 * default, kind rectangular, order 1, T NULL until set) with one reference more on each
 * object in it (image_objects: the image without the NULL). */
static int use_image;
static Py_ssize_t image_start, image_objects_count;
static PyObject *image[MAX_FIELDS], *image_objects[MAX_FIELDS];

/* The profile names as the profiles dict holds them (interned, as a keyword's constant in a
 * call is) with their sms_profile, matched by identity before the dict is asked. */
#define MAX_PROFILES 8
static Py_ssize_t profile_count;
static PyObject *profile_name[MAX_PROFILES];
static long profile_number[MAX_PROFILES];

/* 1 and *x = its value if o is a plain number cffi would pass as float(o); 0 otherwise,
 * with no exception set (an int too large for a double included: the checked path names it). */
static int plain_number(PyObject *o, double *x)
{
    if (PyFloat_CheckExact(o)) {
        *x = PyFloat_AS_DOUBLE(o);
        return 1;
    }
    if (PyLong_CheckExact(o) ||
        PySequence_Contains(extra_numbers, (PyObject *)Py_TYPE(o)) == 1) {
        /* an int directly: through __float__ it would make and free a float object */
        *x = PyLong_CheckExact(o) ? PyLong_AsDouble(o) : PyFloat_AsDouble(o);
        if (*x == -1.0 && PyErr_Occurred()) {
            PyErr_Clear();
            return 0;
        }
        return 1;
    }
    return 0;
}

#define SLOT(s, i) (*(PyObject **)((char *)(s) + field_offset[i]))

/* Replaces field i of a new Stage by a new reference (stolen); -1 if value is NULL. */
static int set_new(PyObject *s, Py_ssize_t i, PyObject *value)
{
    if (value == NULL)
        return -1;
    Py_XSETREF(SLOT(s, i), value);
    return 0;
}

/* A Stage as Stage(kind, T=T, ...) would build it, from valid values, without running its
 * validation: allocated by its type, every slot its field's default, then kind, T and order
 * (the constructor turns None into 1 for smoothers). New reference or NULL. */
static PyObject *new_stage(PyObject *kind, double T)
{
    PyTypeObject *type = (PyTypeObject *)stage_type;
    PyObject *s;
    Py_ssize_t i;
    if (use_image && kind == image[(field_offset[f_kind] - image_start) / sizeof(PyObject *)]) {
        /* allocated as tp_alloc allocates it, then every byte after the header written
         * before the collector can see it (tracked last, as tp_alloc's caller would find it) */
        PyObject *value = PyFloat_FromDouble(T);
        if (value == NULL)
            return NULL;
        s = (PyObject *)PyObject_GC_New(PyObject, type);
        if (s == NULL) {
            Py_DECREF(value);
            return NULL;
        }
        memcpy((char *)s + image_start, image, (size_t)field_count * sizeof(PyObject *));
        for (i = 0; i < image_objects_count; ++i)
            Py_INCREF(image_objects[i]);
        SLOT(s, f_T) = value;
        PyObject_GC_Track(s);
        return s;
    }
    s = type->tp_alloc(type, 0);
    if (s == NULL)
        return NULL;
    for (i = 0; i < field_count; ++i) {
        Py_INCREF(field_default[i]);
        SLOT(s, i) = field_default[i];
    }
    Py_INCREF(kind);
    Py_SETREF(SLOT(s, f_kind), kind);
    Py_INCREF(one);
    Py_SETREF(SLOT(s, f_order), one);
    if (set_new(s, f_T, PyFloat_FromDouble(T)) < 0) {
        Py_DECREF(s);
        return NULL;
    }
    return s;
}

/* design(h, vmax, amax, jmax, higher, profile, wn, zeta, Ts): the stages, or None. */
static PyObject *design(PyObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    PyObject *amax_o, *jmax_o, *higher, *profile, *wn_o, *Ts_o, *prof, *stages;
    double h, limits[3] = {0.0, 0.0, 0.0}, wn = 0.0, zeta = 0.0, Ts = 0.0;
    double lengths[SMS_KINEMATIC_MAX_ORDER];
    sms_kin_last last;
    sms_status st;
    size_t n, i;
    long profile_value;
    (void)self;
    if (nargs != 9) {
        PyErr_SetString(PyExc_TypeError, "design() takes 9 positional arguments");
        return NULL;
    }
    if (field_count == 0) {
        PyErr_SetString(PyExc_RuntimeError, "configure() has not been called");
        return NULL;
    }
    amax_o = args[2];
    jmax_o = args[3];
    higher = args[4];
    profile = args[5];
    wn_o = args[6];
    Ts_o = args[8];
    /* more bounds than three, or another profile than the three names: the checked path */
    if (!PyTuple_CheckExact(higher) || PyTuple_GET_SIZE(higher) != 0 ||
        !PyUnicode_CheckExact(profile))
        Py_RETURN_NONE;
    for (i = 0; i < (size_t)profile_count && profile_name[i] != profile; ++i)
        ;
    if (i < (size_t)profile_count) {
        profile_value = profile_number[i];
    } else {
        prof = PyDict_GetItemWithError(profile_index, profile);
        if (prof == NULL) {
            if (PyErr_Occurred())
                return NULL;
            Py_RETURN_NONE;
        }
        profile_value = PyLong_AsLong(prof);
    }
    if (!plain_number(args[0], &h) || !plain_number(args[1], &limits[0]))
        Py_RETURN_NONE;
    n = 1;
    if (amax_o != Py_None) {
        if (!plain_number(amax_o, &limits[1]))
            Py_RETURN_NONE;
        n = 2;
        if (jmax_o != Py_None) {
            if (!plain_number(jmax_o, &limits[2]))
                Py_RETURN_NONE;
            n = 3;
        }
    } else if (jmax_o != Py_None) {
        Py_RETURN_NONE; /* jmax without amax: the checked path names it */
    }
    /* zeta is ignored without a mode */
    if (wn_o != Py_None && (!plain_number(wn_o, &wn) || !plain_number(args[7], &zeta) ||
                            !(wn > 0.0)))
        Py_RETURN_NONE;
    if (Ts_o != Py_None && (!plain_number(Ts_o, &Ts) || !(Ts > 0.0)))
        Py_RETURN_NONE;
    if (wn > 0.0 && Ts > 0.0) {
        /* a tuned stage on a grid searches mode multiples (microseconds, up to about 0.1 ms
         * with three bounds): let other threads run */
        Py_BEGIN_ALLOW_THREADS
        st = sms_kin_solve_sampled(h, limits, n, (sms_profile)profile_value, wn, zeta, Ts,
                                   lengths, &last);
        Py_END_ALLOW_THREADS
    } else {
        st = sms_kin_solve_sampled(h, limits, n, (sms_profile)profile_value, wn, zeta, Ts,
                                   lengths, &last);
    }
    if (st != SMS_OK)
        Py_RETURN_NONE; /* the checked path re-runs the design and names the cause */
    stages = PyList_New((Py_ssize_t)n);
    if (stages == NULL)
        return NULL;
    for (i = 0; i < n; ++i) {
        PyObject *s = new_stage(PyTuple_GET_ITEM(kind_names, SMS_RECTANGULAR),
                                lengths[i]);
        if (s == NULL) {
            Py_DECREF(stages);
            return NULL;
        }
        PyList_SET_ITEM(stages, (Py_ssize_t)i, s);
    }
    {
        /* the last stage: its family, decay, mode multiple and timing */
        PyObject *s = PyList_GET_ITEM(stages, (Py_ssize_t)(n - 1));
        if (last.kind != SMS_RECTANGULAR) {
            PyObject *kind = PyTuple_GET_ITEM(kind_names, last.kind);
            Py_INCREF(kind);
            Py_SETREF(SLOT(s, f_kind), kind);
        }
        if (last.timing != SMS_TIMING_EXACT) {
            PyObject *timing = PyTuple_GET_ITEM(timing_names, last.timing);
            Py_INCREF(timing);
            Py_SETREF(SLOT(s, f_timing), timing);
        }
        if ((last.sigma != 0.0 && set_new(s, f_sigma, PyFloat_FromDouble(last.sigma)) < 0) ||
            (last.k != 1u && set_new(s, f_k, PyLong_FromUnsignedLong(last.k)) < 0)) {
            Py_DECREF(stages);
            return NULL;
        }
    }
    return stages;
}

/* kinematic(*, h, vmax, amax=None, jmax=None, higher=(), profile="polynomial", wn=None,
 * zeta=0.0, Ts=None): design.kinematic itself, a builtin so that a call costs no Python frame
 * (about 0.1 us of a 0.6 us call). Keywords only, matched by identity to the interned names
 * (what a call in source code passes) or by value; anything else (a positional argument, an
 * unknown or repeated keyword, a type or value design() declines) calls the Python function
 * given to configure(), which raises the same TypeError or names the argument. */
enum { K_H, K_VMAX, K_AMAX, K_JMAX, K_HIGHER, K_PROFILE, K_WN, K_ZETA, K_TS, K_COUNT };
static const char *const keyword_text[K_COUNT] = {"h", "vmax", "amax", "jmax", "higher",
                                                 "profile", "wn", "zeta", "Ts"};
static PyObject *keyword_names[K_COUNT], *checked_kinematic, *default_profile,
    *default_zeta, *empty_tuple;
static PyMethodDef kinematic_def;

static PyObject *kinematic(PyObject *self, PyObject *const *args, size_t nargsf,
                           PyObject *kwnames)
{
    PyObject *v[K_COUNT], *stages;
    Py_ssize_t nk, i;
    int j;
    (void)self;
    if (PyVectorcall_NARGS(nargsf) != 0 || kwnames == NULL)
        goto checked;
    v[K_H] = v[K_VMAX] = NULL;
    v[K_AMAX] = v[K_JMAX] = v[K_WN] = v[K_TS] = Py_None;
    v[K_HIGHER] = empty_tuple;
    v[K_PROFILE] = default_profile;
    v[K_ZETA] = default_zeta;
    nk = PyTuple_GET_SIZE(kwnames);
    for (i = 0, j = -1; i < nk; ++i) {
        PyObject *name = PyTuple_GET_ITEM(kwnames, i);
        /* the keyword after the last one first (a call in the signature's order), then all */
        if (!(j + 1 < K_COUNT && keyword_names[j + 1] == name))
            for (j = -1; j + 1 < K_COUNT && keyword_names[j + 1] != name; ++j)
                ;
        ++j;
        if (j == K_COUNT) /* not interned (a **dict built at run time): compare the text */
            for (j = 0; j < K_COUNT; ++j)
                if (PyUnicode_Check(name) &&
                    PyUnicode_CompareWithASCIIString(name, keyword_text[j]) == 0)
                    break;
        if (j == K_COUNT)
            goto checked; /* unknown keyword: the Python function's TypeError */
        v[j] = args[i];
    }
    /* a repeated keyword cannot reach here from Python syntax; a missing one is a TypeError */
    if (v[K_H] == NULL || v[K_VMAX] == NULL)
        goto checked;
    stages = design(NULL, v, K_COUNT);
    if (stages != Py_None)
        return stages;
    Py_DECREF(stages);
checked:
    return PyObject_Vectorcall(checked_kinematic, args, nargsf, kwnames);
}

/* configure_kinematic(function, module_name) -> the builtin kinematic with the function's
 * docstring and signature (design.py binds it as design.kinematic). */
static PyObject *configure_kinematic(PyObject *self, PyObject *args)
{
    PyObject *function, *module_name, *doc;
    const char *text;
    char *copy;
    size_t size;
    static const char signature[] =
        "kinematic(*, h, vmax, amax=None, jmax=None, higher=(), "
        "profile='polynomial', wn=None, zeta=0.0, Ts=None)\n--\n\n";
    (void)self;
    if (!PyArg_ParseTuple(args, "OU:configure_kinematic", &function, &module_name))
        return NULL;
    if (kinematic_def.ml_name != NULL) {
        PyErr_SetString(PyExc_RuntimeError, "configure_kinematic(): already configured");
        return NULL;
    }
    doc = PyObject_GetAttrString(function, "__doc__");
    if (doc == NULL)
        return NULL;
    text = doc == Py_None ? "" : PyUnicode_AsUTF8(doc);
    if (text == NULL) {
        Py_DECREF(doc);
        return NULL;
    }
    size = sizeof signature + strlen(text);
    copy = PyMem_RawMalloc(size); /* kept for the life of the process, as a static doc is */
    if (copy == NULL) {
        Py_DECREF(doc);
        return PyErr_NoMemory();
    }
    memcpy(copy, signature, sizeof signature - 1);
    memcpy(copy + sizeof signature - 1, text, strlen(text) + 1);
    Py_DECREF(doc);
    Py_INCREF(function);
    Py_XSETREF(checked_kinematic, function);
    kinematic_def.ml_name = "kinematic";
    kinematic_def.ml_meth = (PyCFunction)(void (*)(void))kinematic;
    kinematic_def.ml_flags = METH_FASTCALL | METH_KEYWORDS;
    kinematic_def.ml_doc = copy;
    return PyCFunction_NewEx(&kinematic_def, NULL, module_name);
}

/* n plain numbers from a list or tuple of length n, or n copies of one plain number; 0 when
 * o is neither (no exception set). */
static int plain_numbers(PyObject *o, double *x, Py_ssize_t n)
{
    Py_ssize_t i;
    if (PyList_CheckExact(o) || PyTuple_CheckExact(o)) {
        if (PySequence_Fast_GET_SIZE(o) != n)
            return 0;
        for (i = 0; i < n; ++i)
            if (!plain_number(PySequence_Fast_GET_ITEM(o, i), &x[i]))
                return 0;
        return 1;
    }
    if (!plain_number(o, &x[0]))
        return 0;
    for (i = 1; i < n; ++i)
        x[i] = x[0];
    return 1;
}

/* The path limits V = min vmax_i/|d_i| (and A, J) stay normal and far from overflow, so the
 * C core's closed form in them is as exact as the time-scale form of the NumPy reference. */
static int moderate(double r)
{
    return r > 0x1p-200 && r < 0x1p200;
}

/* phase_duration(delta, vmax, amax, jmax): sms_multi_phase_duration, or None. */
static PyObject *phase_duration(PyObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    sms_multi_generator_config config;
    double delta[SMS_MULTI_MAX_AXES], T;
    Py_ssize_t n, i;
    (void)self;
    if (nargs != 4) {
        PyErr_SetString(PyExc_TypeError, "phase_duration() takes 4 positional arguments");
        return NULL;
    }
    if (!PyList_CheckExact(args[0]) && !PyTuple_CheckExact(args[0]))
        Py_RETURN_NONE;
    n = PySequence_Fast_GET_SIZE(args[0]);
    if (n < 1 || n > SMS_MULTI_MAX_AXES)
        Py_RETURN_NONE;
    memset(&config, 0, sizeof config);
    config.n_axes = (size_t)n;
    if (!plain_numbers(args[0], delta, n) || !plain_numbers(args[1], config.vmax, n) ||
        !plain_numbers(args[2], config.amax, n) || !plain_numbers(args[3], config.jmax, n))
        Py_RETURN_NONE;
    for (i = 0; i < n; ++i) {
        double d = fabs(delta[i]);
        if (d > 0.0 && !(moderate(config.vmax[i] / d) && moderate(config.amax[i] / d) &&
                         moderate(config.jmax[i] / d)))
            Py_RETURN_NONE;
    }
    /* every value is checked by the C core (finite, limits > 0) */
    if (sms_multi_phase_duration(&config, delta, &T) != SMS_OK || !isfinite(T))
        Py_RETURN_NONE;
    return PyFloat_FromDouble(T);
}

/* Index of the field called name in the (name, default) pairs, or -1. */
static Py_ssize_t field_index(PyObject *defaults, const char *name)
{
    Py_ssize_t i;
    for (i = 0; i < PyTuple_GET_SIZE(defaults); ++i)
        if (PyUnicode_CompareWithASCIIString(
                PyTuple_GET_ITEM(PyTuple_GET_ITEM(defaults, i), 0), name) == 0)
            return i;
    return -1;
}

/* use_image and the image when Stage's instances are its slots after the header. */
static void configure_image(PyTypeObject *type, PyObject *kinds)
{
    Py_ssize_t i, start = PY_SSIZE_T_MAX, size = (Py_ssize_t)sizeof(PyObject *);
    unsigned long other_layouts = 0;
#ifdef Py_TPFLAGS_MANAGED_DICT
    other_layouts |= Py_TPFLAGS_MANAGED_DICT;
#endif
#ifdef Py_TPFLAGS_MANAGED_WEAKREF
    other_layouts |= Py_TPFLAGS_MANAGED_WEAKREF;
#endif
    use_image = 0;
    for (i = 0; i < field_count; ++i)
        if (field_offset[i] < start)
            start = field_offset[i];
    if (type->tp_alloc != PyType_GenericAlloc || !PyType_IS_GC(type) ||
        type->tp_itemsize != 0 || type->tp_dictoffset != 0 || type->tp_weaklistoffset != 0 ||
        (PyType_GetFlags(type) & other_layouts) != 0 || start != (Py_ssize_t)sizeof(PyObject) ||
        type->tp_basicsize != start + field_count * size)
        return;
    memset(image, 0, sizeof image);
    for (i = 0; i < field_count; ++i) {
        Py_ssize_t at = field_offset[i] - start;
        if (at % size != 0 || image[at / size] != NULL)
            return; /* not one pointer per slot, each its own */
        image[at / size] = field_default[i];
    }
    image[(field_offset[f_kind] - start) / size] = PyTuple_GET_ITEM(kinds, SMS_RECTANGULAR);
    image[(field_offset[f_order] - start) / size] = one;
    image[(field_offset[f_T] - start) / size] = NULL;
    image_objects_count = 0;
    for (i = 0; i < field_count; ++i)
        if (image[i] != NULL)
            image_objects[image_objects_count++] = image[i];
    image_start = start;
    use_image = 1;
}

/* The profile names and numbers from the profiles dict (name -> sms_profile). */
static void configure_profiles(PyObject *profiles)
{
    PyObject *key, *value;
    Py_ssize_t pos = 0;
    profile_count = 0;
    while (PyDict_Next(profiles, &pos, &key, &value)) {
        long number = PyLong_AsLong(value);
        if (number == -1 && PyErr_Occurred()) {
            PyErr_Clear(); /* design() asks the dict, which raises it again */
            return;
        }
        if (profile_count == MAX_PROFILES || !PyUnicode_CheckExact(key))
            return; /* the dict alone answers for the rest */
        profile_name[profile_count] = key; /* held by the dict, which configure() keeps */
        profile_number[profile_count++] = number;
    }
}

/* configure(Stage, defaults, KINDS, TIMINGS, profiles, extra_numbers): see the variables
 * above; defaults = Stage's (name, default) pairs in field order, each field a slot. */
static PyObject *configure(PyObject *self, PyObject *args)
{
    PyObject *stage, *defaults, *kinds, *timings, *profiles, *numbers;
    Py_ssize_t i, n;
    (void)self;
    if (!PyArg_ParseTuple(args, "OO!O!O!O!O!:configure", &stage, &PyTuple_Type, &defaults,
                          &PyTuple_Type, &kinds, &PyTuple_Type, &timings, &PyDict_Type,
                          &profiles, &PyTuple_Type, &numbers))
        return NULL;
    n = PyTuple_GET_SIZE(defaults);
    if (!PyType_Check(stage) || PyTuple_GET_SIZE(kinds) != SMS_KIND_COUNT ||
        PyTuple_GET_SIZE(timings) != SMS_TIMING_BOUNDED + 1 || n > MAX_FIELDS ||
        field_count != 0) {
        PyErr_SetString(PyExc_ValueError, "configure(): Stage, KINDS and TIMINGS expected, "
                                          "once");
        return NULL;
    }
    for (i = 0; i < n; ++i) {
        PyObject *pair = PyTuple_GET_ITEM(defaults, i), *descr;
        PyMemberDef *member;
        if (!PyTuple_Check(pair) || PyTuple_GET_SIZE(pair) != 2 ||
            !PyUnicode_Check(PyTuple_GET_ITEM(pair, 0))) {
            PyErr_SetString(PyExc_ValueError, "configure(): (name, default) pairs expected");
            return NULL;
        }
        descr = PyObject_GetAttr(stage, PyTuple_GET_ITEM(pair, 0));
        if (descr == NULL)
            return NULL;
        /* a slot holding any object: only then is the offset ours to write */
        if (Py_TYPE(descr) != &PyMemberDescr_Type ||
            (member = ((PyMemberDescrObject *)descr)->d_member)->type != T_OBJECT_EX) {
            Py_DECREF(descr);
            PyErr_SetString(PyExc_ValueError, "configure(): every Stage field must be a slot");
            return NULL;
        }
        field_offset[i] = member->offset;
        Py_DECREF(descr);
    }
    f_kind = field_index(defaults, "kind");
    f_T = field_index(defaults, "T");
    f_sigma = field_index(defaults, "sigma");
    f_k = field_index(defaults, "k");
    f_order = field_index(defaults, "order");
    f_timing = field_index(defaults, "timing");
    if (f_kind < 0 || f_T < 0 || f_sigma < 0 || f_k < 0 || f_order < 0 || f_timing < 0) {
        PyErr_SetString(PyExc_ValueError, "configure(): a Stage field is missing");
        return NULL;
    }
    for (i = 0; i < n; ++i) {
        field_default[i] = PyTuple_GET_ITEM(PyTuple_GET_ITEM(defaults, i), 1);
        Py_INCREF(field_default[i]);
    }
    field_count = n;
    configure_image((PyTypeObject *)stage, kinds);
    configure_profiles(profiles);
    Py_INCREF(stage);
    Py_INCREF(kinds);
    Py_INCREF(timings);
    Py_INCREF(profiles);
    Py_INCREF(numbers);
    Py_XSETREF(stage_type, stage);
    Py_XSETREF(kind_names, kinds);
    Py_XSETREF(timing_names, timings);
    Py_XSETREF(profile_index, profiles);
    Py_XSETREF(extra_numbers, numbers);
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"design", (PyCFunction)(void (*)(void))design, METH_FASTCALL,
     "design(h, vmax, amax, jmax, higher, profile, wn, zeta, Ts) -> list of Stage or None\n\n"
     "design.kinematic's fast path: the stages for plain numbers and at most three bounds,\n"
     "None where the fully checked path must run (other types, a refused design)."},
    {"phase_duration", (PyCFunction)(void (*)(void))phase_duration, METH_FASTCALL,
     "phase_duration(delta, vmax, amax, jmax) -> float or None\n\n"
     "multi_axis.phase_duration's fast path: the C core's duration for plain numbers (a list\n"
     "or tuple per argument, or one number for every axis), None where the checked path runs."},
    {"configure_kinematic", configure_kinematic, METH_VARARGS,
     "configure_kinematic(function, module_name) -> kinematic: design.kinematic as a builtin\n"
     "that runs design() and calls function (the checked path) where it returns None."},
    {"configure", configure, METH_VARARGS,
     "configure(Stage, defaults, KINDS, TIMINGS, profiles, extra_numbers): the Python objects\n"
     "used (defaults: Stage's (name, default) pairs in field order)."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_kinematic_fastpath",
                                    "design.kinematic's fast path (see design.py).", -1,
                                    methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__kinematic_fastpath(void)
{
    if (one == NULL) {
        one = PyLong_FromLong(1);
        empty_tuple = PyTuple_New(0);
        default_profile = PyUnicode_InternFromString("polynomial");
        default_zeta = PyFloat_FromDouble(0.0);
        if (empty_tuple == NULL || default_profile == NULL || default_zeta == NULL)
            return NULL;
        {
            int j;
            for (j = 0; j < K_COUNT; ++j)
                if ((keyword_names[j] = PyUnicode_InternFromString(keyword_text[j])) == NULL)
                    return NULL;
        }
        if (one == NULL)
            return NULL;
    }
    return PyModule_Create(&module);
}
