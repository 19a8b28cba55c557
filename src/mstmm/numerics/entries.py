"""Entry points called from Python: a topology's functions arrive as addresses of their
compiled code, turned into first-class function values (one compiled driver serves every
topology; numba caches it on disk)."""

import math

import numpy as np
from numba import prange, types
from numba.core import cgutils
from numba.core.types import FunctionType
from numba.extending import intrinsic

from mstmm.jit import njit

from .bloch import (
    DET0,
    bloch_waves,
    bloch_work,
    cell_subspace,
    cell_subspace_in,
    closed_stiffness,
    pencil_det,
)
from .doubling import (
    levels_of,
    repeated_search,
    repeated_work,
    structure_at,
)
from .frf import (
    frf_march,
)
from .search import (
    PENDING_WIDTH,
    STATE_CERTIFIED,
    STATE_SIZE,
    bracket_root,
    counts_off_poles,
    evaluate,
    lowest,
    lowest_run,
    lowest_start,
    pole_data,
    refine,
)
from .shapes import (
    mode_shapes,
)

# Entry points called from Python. A topology's functions arrive as the addresses of their
# compiled code (``fa``: pairs (C wrapper, numba entry) in the order of FA_*; see
# ``mstmm.kernels.Kernel``), turned into first-class function values inside: plain
# integers cross the Python boundary in microseconds, and one compiled driver serves
# every topology (numba caches it on disk).
_f8 = types.float64
_i8 = types.int64
_A1 = types.float64[::1]
_A2 = types.float64[:, ::1]
DELTA = FunctionType(types.UniTuple(_f8, 2)(_f8, _A1))
COUNT = FunctionType(_i8(_f8, _A1))
OSC = FunctionType(_A2(_A1))
RIGID = FunctionType(_i8(_A1))
EVENT = FunctionType(types.UniTuple(_i8, 2)(_A1, _i8, _f8, _A2, _A2, _A2, _A2, _A2))
INERTIA = FunctionType(_i8(_A1, _i8, _A2))
_c16 = types.complex128
_C2 = types.complex128[:, ::1]
EVENT_C = FunctionType(types.UniTuple(_i8, 2)(_A1, _i8, _c16, _C2, _C2, _C2, _C2, _A2))
SIZES = FunctionType(types.UniTuple(_i8, 2)(_A1))
#: Position of each function's address pair in ``fa``, and its type.
FA_STABLE = 0
FA_COUNT = 2
FA_OSC = 4
FA_RIGID = 6
FA_PAPER = 8
FA_EVENT = 10
FA_SIZES = 12
FA_EVENT_C = 14
FA_INERTIA = 16
FA_SIZE = 18
FUNCTION_TYPES = {
    "delta_stable": (FA_STABLE, DELTA),
    "count_below": (FA_COUNT, COUNT),
    "oscillator_frequencies": (FA_OSC, OSC),
    "rigid_body_modes": (FA_RIGID, RIGID),
    "delta_paper": (FA_PAPER, DELTA),
    "shape_event": (FA_EVENT, EVENT),
    "shape_sizes": (FA_SIZES, SIZES),
    "shape_event_c": (FA_EVENT_C, EVENT_C),
    "shape_inertia": (FA_INERTIA, INERTIA),
}

#: The entry points ``mstmm.kernels.Kernel`` calls, by name (``entry_<name>``): the function
#: of the numerics each wraps, which the interpreted tier runs as Python (None: compiled
#: only), and the kernel functions it takes, in that function's order. ``delta`` is the
#: characteristic function of the formulation asked for: its entry takes the position of
#: its addresses in ``fa`` (``at``) after ``fa``; the others sit at their FA_* place.
#: Each entry is then ``entry_<name>(fa[, at], *args)`` where the function is
#: ``function(*kernel_functions, *args)``: one contract for every tier.
DRIVERS = {
    "evaluate": ("evaluate", ("delta",)),
    "refine": ("refine", ("delta",)),
    "counts": ("counts_off_poles", ("count_below", "oscillator_frequencies")),
    "lowest": ("lowest", ("delta", "count_below", "oscillator_frequencies", "rigid_body_modes")),
    "lowest_start": ("lowest_start", ("count_below", "rigid_body_modes")),
    "lowest_run": ("lowest_run", ("delta", "count_below", "oscillator_frequencies")),
    "refine_pending": (None, ("delta", "oscillator_frequencies")),
    "sweep_lowest": (
        None,
        ("delta_stable", "count_below", "oscillator_frequencies", "rigid_body_modes"),
    ),
    "mode_shapes": ("mode_shapes", ("shape_event", "shape_inertia", "shape_sizes")),
    "frf": (None, ("shape_event_c", "shape_sizes")),
    "damped_shapes": (None, ("shape_event_c", "shape_sizes")),
    "bloch_waves": (None, ("shape_event_c", "shape_sizes", "shape_event")),
    "closed": (None, ("shape_event", "shape_sizes")),
    "subspace": (None, ("shape_event_c", "shape_sizes")),
    "repeated_at": (None, ("shape_event", "count_below", "shape_sizes")),
    "repeated_search": (
        "repeated_search",
        ("shape_event", "count_below", "shape_sizes", "oscillator_frequencies"),
    ),
}

_I1 = types.int64[::1]
#: The one signature each driver compiled ahead of its call is called with (by
#: ``mstmm.kernels.Kernel``; ``mstmm.compiling`` compiles them in helper processes).
SIGNATURES = {
    "lowest": (_I1, _i8, _A1, _i8, _A1, _I1, _A1, types.boolean, _f8),
    "mode_shapes": (_I1, _I1, _f8, _A1, _i8, _A1, types.float64[:, :, ::1], _A2, _A1, _A2, _A2)
    + (_A1, _A1),
    "damped_shapes": (_I1, _I1, types.boolean, _c16, _A1, _A2, _A2, _C2, _A1),
    "repeated_search": (_I1, _A1, _i8, _I1, _I1, _i8, _i8, _f8, _f8, _f8, _A1, _I1, _I1),
}


def _function_value(ftype):
    """An intrinsic that makes a first-class function value of type ``ftype`` from the
    addresses of its C wrapper and of its numba entry (exceptions propagate through it)."""

    @intrinsic
    def make(typingctx, c_addr, jit_addr):
        def codegen(context, builder, signature, args):
            value = cgutils.create_struct_proxy(ftype)(context, builder)
            voidptr = context.get_value_type(types.voidptr)
            value.c_addr = builder.inttoptr(args[0], voidptr)
            value.py_addr = voidptr(None)
            value.jit_addr = builder.inttoptr(args[1], voidptr)
            return value._getvalue()

        return ftype(types.int64, types.int64), codegen

    return make


as_delta = _function_value(DELTA)
as_count = _function_value(COUNT)
as_osc = _function_value(OSC)
as_rigid = _function_value(RIGID)
as_event = _function_value(EVENT)
as_sizes = _function_value(SIZES)
as_event_c = _function_value(EVENT_C)
as_inertia = _function_value(INERTIA)


@njit(cache=True)
def entry_evaluate(fa, at, omegas, p, mant, logs):
    """``evaluate`` with the characteristic function whose addresses are at fa[at]."""
    evaluate(as_delta(fa[at], fa[at + 1]), omegas, p, mant, logs)


@njit(cache=True)
def entry_refine(fa, at, a, b, p, rtol, maxiter):
    """``refine`` with the characteristic function whose addresses are at fa[at]."""
    return refine(as_delta(fa[at], fa[at + 1]), a, b, p, rtol, maxiter)


@njit(cache=True)
def entry_counts(fa, omegas, p, out):
    """``counts_off_poles`` with the kernel's count and own frequencies."""
    counts_off_poles(
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]), as_osc(fa[FA_OSC], fa[FA_OSC + 1]), omegas, p, out
    )


@njit(cache=True)
def entry_lowest(fa, at, p, modes, out, flags, state, certify, rtol):
    """``lowest`` with the kernel's functions (the characteristic function at fa[at])."""
    return lowest(
        as_delta(fa[at], fa[at + 1]),
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]),
        as_osc(fa[FA_OSC], fa[FA_OSC + 1]),
        as_rigid(fa[FA_RIGID], fa[FA_RIGID + 1]),
        p,
        modes,
        out,
        flags,
        state,
        certify,
        rtol,
    )


@njit(cache=True, parallel=True)
def entry_refine_pending(fa, at, p, state, rows, out, flags, rtol):
    """The roots ``lowest`` left pending (``search.PENDING_WIDTH``: out[k] for each k in
    ``rows``, its bracket in ``state``) refined by Brent's method, in parallel over the
    roots."""
    delta = as_delta(fa[at], fa[at + 1])
    poles = pole_data(as_osc(fa[FA_OSC], fa[FA_OSC + 1])(p))
    for i in prange(rows.shape[0]):
        k = rows[i]
        start = STATE_SIZE + PENDING_WIDTH * k
        root, flag = bracket_root(delta, state[start : start + PENDING_WIDTH], poles, p, rtol)
        out[k] = root
        flags[k] = flag


@njit(cache=True)
def entry_lowest_start(fa, p, modes, out, flags, state, certify):
    """``lowest_start`` with the kernel's functions."""
    return lowest_start(
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]),
        as_rigid(fa[FA_RIGID], fa[FA_RIGID + 1]),
        p,
        modes,
        out,
        flags,
        state,
        certify,
    )


@njit(cache=True)
def entry_lowest_run(fa, at, p, modes, out, flags, state, k_stop, certify, w_stop, rtol):
    """``lowest_run`` with the kernel's functions (the characteristic function at fa[at])."""
    return lowest_run(
        as_delta(fa[at], fa[at + 1]),
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]),
        as_osc(fa[FA_OSC], fa[FA_OSC + 1]),
        p,
        modes,
        out,
        flags,
        state,
        k_stop,
        certify,
        w_stop,
        rtol,
    )


@njit(cache=True, parallel=True)
def entry_sweep_lowest(fa, P, modes, out, certified):
    """``lowest`` (stable) for every parameter vector (row of P), in parallel over the
    rows; a row is certified when the count certifies all its roots and none is flagged."""
    delta = as_delta(fa[FA_STABLE], fa[FA_STABLE + 1])
    count = as_count(fa[FA_COUNT], fa[FA_COUNT + 1])
    osc = as_osc(fa[FA_OSC], fa[FA_OSC + 1])
    rigid = as_rigid(fa[FA_RIGID], fa[FA_RIGID + 1])
    for i in prange(P.shape[0]):
        flags = np.zeros(modes, dtype=np.int64)
        state = np.zeros(STATE_SIZE)
        k = lowest(delta, count, osc, rigid, P[i], modes, out[i], flags, state, True, 0.0)
        trusted = True
        for j in range(modes):
            trusted = trusted and flags[j] == 0
        certified[i] = k == modes and state[STATE_CERTIFIED] == 1.0 and trusted


@njit(cache=True)
def entry_mode_shapes(fa, ends, omega, p, m, xs, Z_out, q_out, q_x, q_mass, gram, part, ratio):
    """``mode_shapes`` with the kernel's descriptor functions."""
    return mode_shapes(
        as_event(fa[FA_EVENT], fa[FA_EVENT + 1]),
        as_inertia(fa[FA_INERTIA], fa[FA_INERTIA + 1]),
        as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1]),
        ends,
        omega,
        p,
        m,
        xs,
        Z_out,
        q_out,
        q_x,
        q_mass,
        gram,
        part,
        ratio,
    )


@njit(cache=True, parallel=True)
def entry_frf(fa, ends, damped, ws, p, inputs, outputs, out):
    """``frf_march`` at every frequency ws[k] (complex, rad/s), in parallel over them:
    out[k, i, j] the response j to the load i."""
    event = as_event_c(fa[FA_EVENT_C], fa[FA_EVENT_C + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    for k in prange(ws.shape[0]):
        singular = np.zeros(inputs.shape[0])
        frf_march(event, sizes, ends, ws[k], p, damped, inputs, outputs, out[k], singular)


@njit(cache=True)
def entry_damped_shapes(fa, ends, damped, w, p, inputs, outputs, out, singular):
    """``frf_march`` without load at the root w: the mode shapes (one per input row,
    FRF_NULL or FRF_NULL2) sampled as ``outputs`` says."""
    event = as_event_c(fa[FA_EVENT_C], fa[FA_EVENT_C + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    frf_march(event, sizes, ends, w, p, damped, inputs, outputs, out, singular)


@njit(cache=True, parallel=True)
def entry_bloch_waves(fa, damped, ws, p, out):
    """``bloch_waves`` of the cell at every frequency ws[k] (complex, rad/s), in parallel
    over chunks (scratch allocated once per chunk): out[k] = (mu_1, mu_2, k_1 L, k_2 L,
    propagating pairs), the more attenuated pair first. An undamped cell at real
    frequencies is marched in real arithmetic (the kernel's real descriptor; fa holds
    it then)."""
    event = as_event_c(fa[FA_EVENT_C], fa[FA_EVENT_C + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    n = ws.shape[0]
    real = not damped
    for k in range(n):
        real = real and ws[k].imag == 0.0
    chunks = min(n, 64)
    if real:
        event_r = as_event(fa[FA_EVENT], fa[FA_EVENT + 1])
        for j in prange(chunks):
            work = bloch_work(p, sizes, np.float64)
            A = np.empty((4, 4))
            for k in range(j * n // chunks, (j + 1) * n // chunks):
                bloch_at(event_r, ws[k].real, p, False, work, A, out[k])
        return
    for j in prange(chunks):
        work = bloch_work(p, sizes, np.complex128)
        A = np.empty((4, 4), dtype=np.complex128)
        for k in range(j * n // chunks, (j + 1) * n // chunks):
            bloch_at(event, ws[k], p, damped, work, A, out[k])


@njit(cache=True)
def bloch_at(event, w, p, damped, work, A, out):
    """out <- ``bloch_waves`` of the cell at w (nan where a component leaves the cell
    fewer than four free parameters)."""
    X = cell_subspace_in(event, w, p, damped, work)
    if X.shape[0] == 8:
        bloch_waves(X, A, work[DET0], not damped and w.imag == 0.0, out)
    else:
        out[:] = complex(math.nan, math.nan)


@njit(cache=True)
def entry_closed(fa, w, p, s, K):
    """At the real frequency w: (det M(s) as (sign, log)) and K <- the closed cell's joint
    stiffness (``closed_stiffness``; s = +1 periodic, -1 antiperiodic); returns (sign,
    log, whether K exists); the real march (the kernel's real descriptor)."""
    event = as_event(fa[FA_EVENT], fa[FA_EVENT + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    X = cell_subspace_in(event, w, p, False, bloch_work(p, sizes, np.float64))
    if X.shape[0] != 8:
        return 0.0, 0.0, False
    ok = closed_stiffness(X, s, K)
    phase, log = pencil_det(X, s, np.empty((4, 4)))
    return phase, log, ok


@njit(cache=True)
def entry_subspace(fa, damped, w, p):
    """The cell's end-state subspace [X0; XL] at the complex frequency w
    (``cell_subspace``)."""
    event = as_event_c(fa[FA_EVENT_C], fa[FA_EVENT_C + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    return cell_subspace(event, sizes, w, p, damped)


@njit(cache=True)
def entry_repeated_at(fa, ws, p, n_cells, ends, free, out):
    """``doubling.structure_at`` of n_cells cells at every real ws[k]: out[k] = (J,
    mantissa, log, ok) (``fa``: the kernel of the cell clamped at both ends)."""
    event = as_event(fa[FA_EVENT], fa[FA_EVENT + 1])
    count = as_count(fa[FA_COUNT], fa[FA_COUNT + 1])
    sizes = as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1])
    work = bloch_work(p, sizes, np.float64)
    mats = repeated_work(levels_of(n_cells))
    for k in range(ws.shape[0]):
        J, fm, fl, ok = structure_at(event, count, ws[k], p, n_cells, ends, free, work, mats)
        out[k, 0] = J
        out[k, 1] = fm
        out[k, 2] = fl
        out[k, 3] = 1.0 if ok else 0.0


@njit(cache=True)
def entry_repeated_search(fa, p, n_cells, ends, free, rigid, want, lo, hi, scale, out, mult, flags):
    """``doubling.repeated_search`` with the cell kernel's functions."""
    return repeated_search(
        as_event(fa[FA_EVENT], fa[FA_EVENT + 1]),
        as_count(fa[FA_COUNT], fa[FA_COUNT + 1]),
        as_sizes(fa[FA_SIZES], fa[FA_SIZES + 1]),
        as_osc(fa[FA_OSC], fa[FA_OSC + 1]),
        p,
        n_cells,
        ends,
        free,
        rigid,
        want,
        lo,
        hi,
        scale,
        out,
        mult,
        flags,
    )
