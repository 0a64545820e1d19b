/* SPDX-License-Identifier: MIT */
/* hystviz._fast: the Python package's compiled fast path, one call of
 * hy_steady_loop (hystviz.h) per hystviz.steady_loop, without ctypes'
 * per-call argument conversion (issue 35 item 2: the call within 5 us of C).
 *
 * The module does not link libhystviz: hystviz/_lib.py loads the library
 * with ctypes (one copy, found as its docstring says) and hands this module
 * the address of that library's hy_steady_loop through bind(), so the fast
 * path and the ctypes path always call the same library.  Where this module
 * is not built or not importable, the package calls the library through
 * ctypes alone (hystviz/_lib.py chooses, in one place).
 *
 *   bind(address: int) -> None
 *       the address of hy_steady_loop (ctypes.cast(lib.hy_steady_loop,
 *       c_void_p).value); 0 is refused.
 *   steady_loop(name, model, input, model_sets, input_sets, points, out) -> int
 *       name, model, input: bytes (the scene name, the [model] and [input]
 *       texts); model_sets, input_sets: lists (or tuples) of bytes, the
 *       overrides; points: the int passed on; out: a writable C-contiguous
 *       buffer of at least 3 (points + 1) doubles (t, u, y one after the
 *       other).  Returns hy_steady_loop's status (0: out written; else out is
 *       not written and the caller asks for the message with a hy_error).
 *       The GIL is released for the library call.  No allocation per call
 *       but where the overrides are more than SETS_ON_STACK.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include "hystviz.h"

typedef int steady_fn(const char *name, const char *model, const char *input, const char *const *sets,
                      size_t nsets, size_t points, double *t, double *u, double *y, hy_error *err);
/* the prototype above is hy_steady_loop's (checked, not called: no symbol reference) */
_Static_assert(_Generic(&hy_steady_loop, steady_fn * : 1, default : 0), "steady_fn is not hy_steady_loop's type");

#define SETS_ON_STACK 32

static steady_fn *fast__steady; /* the bound hy_steady_loop; NULL until bind() */

/* bind(address): stores the function pointer; returns None, or NULL with
 * ValueError for 0 and TypeError/OverflowError for a non-integer. */
static PyObject *fast__bind(PyObject *self, PyObject *arg)
{
    (void)self;
    void *p = PyLong_AsVoidPtr(arg);
    if (!p && PyErr_Occurred())
        return NULL;
    if (!p) {
        PyErr_SetString(PyExc_ValueError, "hystviz._fast.bind: the address of hy_steady_loop must not be 0");
        return NULL;
    }
    /* an object pointer to a function pointer: POSIX dlsym's guarantee */
    fast__steady = (steady_fn *)(uintptr_t)p;
    Py_RETURN_NONE;
}

/* The bytes of a list or tuple item into sets[at..]; returns the next index,
 * or -1 with TypeError for an item that is not bytes. */
static Py_ssize_t fast__sets(PyObject *seq, const char **sets, Py_ssize_t at, const char *what)
{
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    PyObject **items = PySequence_Fast_ITEMS(seq);
    for (Py_ssize_t i = 0; i < n; i++) {
        if (!PyBytes_Check(items[i])) {
            PyErr_Format(PyExc_TypeError, "hystviz._fast.steady_loop: %s[%zd] must be bytes", what, i);
            return -1;
        }
        sets[at++] = PyBytes_AS_STRING(items[i]);
    }
    return at;
}

/* The library call with the GIL released, out checked for size; returns the
 * status as an int object, or NULL with an exception for bad arguments. */
static PyObject *fast__call(PyObject *const *args, PyObject *ms, PyObject *is, size_t points)
{
    Py_ssize_t nm = PySequence_Fast_GET_SIZE(ms), ni = PySequence_Fast_GET_SIZE(is);
    const char *stack[SETS_ON_STACK];
    const char **sets = nm + ni <= SETS_ON_STACK ? stack : PyMem_New(const char *, (size_t)(nm + ni));
    if (!sets)
        return PyErr_NoMemory();
    Py_buffer view;
    PyObject *res = NULL;
    if (fast__sets(ms, sets, 0, "model_sets") < 0 || fast__sets(is, sets, nm, "input_sets") < 0 ||
        PyObject_GetBuffer(args[6], &view, PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS) < 0)
        goto done;
    size_t n = points + 1;
    if (points >= SIZE_MAX / 24 || (size_t)view.len < 3 * n * sizeof(double)) {
        PyErr_Format(PyExc_ValueError, "hystviz._fast.steady_loop: out has %zd bytes, 3 (points + 1) doubles need more",
                     view.len);
    } else {
        double *t = view.buf;
        const char *name = PyBytes_AS_STRING(args[0]), *model = PyBytes_AS_STRING(args[1]),
                   *input = PyBytes_AS_STRING(args[2]);
        int rc;
        Py_BEGIN_ALLOW_THREADS
        rc = fast__steady(name, model, input, sets, (size_t)(nm + ni), points, t, t + n, t + 2 * n, NULL);
        Py_END_ALLOW_THREADS
        res = PyLong_FromLong(rc);
    }
    PyBuffer_Release(&view);
done:
    if (sets != stack)
        PyMem_Free(sets);
    return res;
}

/* steady_loop(name, model, input, model_sets, input_sets, points, out): see
 * the file's head; returns the status, or NULL with TypeError/ValueError for
 * arguments of the wrong kind and RuntimeError before bind(). */
static PyObject *fast__steady_loop(PyObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    (void)self;
    if (nargs != 7) {
        PyErr_Format(PyExc_TypeError, "hystviz._fast.steady_loop takes 7 arguments, got %zd", nargs);
        return NULL;
    }
    if (!fast__steady) {
        PyErr_SetString(PyExc_RuntimeError, "hystviz._fast.steady_loop: bind() was not called");
        return NULL;
    }
    for (int i = 0; i < 3; i++)
        if (!PyBytes_Check(args[i])) {
            PyErr_Format(PyExc_TypeError, "hystviz._fast.steady_loop: argument %d must be bytes", i + 1);
            return NULL;
        }
    size_t points = PyLong_AsSize_t(args[5]);
    if (points == (size_t)-1 && PyErr_Occurred())
        return NULL;
    PyObject *ms = PySequence_Fast(args[3], "hystviz._fast.steady_loop: model_sets must be a list or tuple");
    if (!ms)
        return NULL;
    PyObject *is = PySequence_Fast(args[4], "hystviz._fast.steady_loop: input_sets must be a list or tuple");
    PyObject *res = is ? fast__call(args, ms, is, points) : NULL;
    Py_XDECREF(is);
    Py_DECREF(ms);
    return res;
}

static PyMethodDef fast__methods[] = {
    {"bind", fast__bind, METH_O, "bind(address): the address of libhystviz's hy_steady_loop (from ctypes)."},
    {"steady_loop", (PyCFunction)(void (*)(void))fast__steady_loop, METH_FASTCALL,
     "steady_loop(name, model, input, model_sets, input_sets, points, out) -> status: hy_steady_loop into out "
     "(t, u, y, each points + 1 doubles), the GIL released."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef fast__module = {
    PyModuleDef_HEAD_INIT, "hystviz._fast", "hystviz's compiled fast path for steady_loop (src/python/_fast.c).",
    -1, fast__methods, NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__fast(void)
{
    return PyModule_Create(&fast__module);
}
