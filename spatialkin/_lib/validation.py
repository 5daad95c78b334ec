"""Argument checks, written once for spatialkin and planar.

Each check returns the value converted (a float, a float array, a pair) or raises ``ValueError`` naming the
argument, so that the object API turns a bad input into a clear message before any numerics run. Only numpy
and math: every layer above the kernels may import this module (the kernels validate nothing).
"""
import math
import numbers

import numpy as np

__all__ = ["ORTHONORMAL_TOL", "LENGTH_MIN", "LENGTH_MAX", "check_real", "check_positive", "check_nonnegative",
           "check_real_type", "check_length", "check_count", "check_omega", "check_choice", "check_range",
           "check_finite", "check_vector", "check_points", "check_query_points", "check_angles", "check_frame",
           "orthonormalised"]

#: Largest accepted deviation of R^T R from the identity (entrywise), for a rotation given in floats.
ORTHONORMAL_TOL = 1e-9
#: A rotation whose R^T R is this close to the identity (entrywise) is orthonormal to round-off and is returned
#: as given: its polar factor differs from it by round-off only (rotation_about's and rotation_to_z's reach
#: 10 eps, measured).
ROUNDOFF_DEVIATION = 64 * np.finfo(float).eps
#: Lengths (radii, finite trims, frame origins' coordinates) are accepted within these magnitudes. The kernels raise
#: coordinates to the 8th power (the torus's implicit function is quartic, and it is squared: Newton's and the
#: certificates' |F|^2); 8th powers of values in [1e-32, 1e32], and of sums of a few of them, stay within about
#: [1e-256, 1e264], clear of overflow (1.8e308) and of the subnormals (below 2.2e-308).
LENGTH_MIN, LENGTH_MAX = 1e-32, 1e32


#: What a bad argument's message says of an integer too large for a float (rather than its hundreds of digits).
TOO_LARGE = "an integer too large for a float"


# --- numbers ------------------------------------------------------------------------------------------------
def check_real(name, value, finite=False, strict=False):
    """``float(value)``, or ValueError naming the argument when it is not a real number (or, with finite=True,
    not a finite one); with strict=True, TypeError naming it when value is not a real number by type (a str, a
    bool, None, a sequence: nothing float() would guess from)."""
    if strict:
        check_real_type(name, value)
    try:
        x = float(value)
    except OverflowError:
        raise ValueError(f"{name} must be finite, got {TOO_LARGE}") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if finite and not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return x


def check_real_type(name, value):
    """value itself when its type is a real number's (int, float, a numpy integer or float scalar or 0-d array), or
    TypeError naming the argument (a bool, a str, None, a sequence)."""
    kind = type(value)
    if kind is float or kind is int:
        return value
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
        return value
    if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf":
        return value
    raise TypeError(f"{name} must be a real number, got {kind.__name__}")


def check_positive(name, value, allow_none=False, strict=False):
    """A finite, strictly positive float (a length, a tolerance, a scale), or None when allowed.

    Raises
    ------
    ValueError
        Naming the argument when it is not a real number, not finite or not positive.
    TypeError
        With strict=True, naming the argument when its type is not a real number's (see check_real).
    """
    if value is None and allow_none:
        return None
    x = check_real(name, value, strict=strict)
    if not (math.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    return x


def check_nonnegative(name, value, strict=False):
    """A finite float >= 0 (an offset, a rate that may vanish), or ValueError naming the argument (TypeError with
    strict=True, as check_real)."""
    x = check_real(name, value, strict=strict)
    if not (math.isfinite(x) and x >= 0):
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return x


def check_length(name, value, allow_zero=False):
    """A length (a radius, a surface's shape parameter) as a float within [LENGTH_MIN, LENGTH_MAX] (or 0 with
    allow_zero).

    Raises
    ------
    TypeError
        Naming the argument when its type is not a real number's (a bool, a str, None, a sequence).
    ValueError
        Naming the argument when it is not positive (>= 0 with allow_zero) and finite, or lies outside the
        supported lengths.
    """
    x = (check_nonnegative if allow_zero else check_positive)(name, value, strict=True)
    if not (LENGTH_MIN <= x <= LENGTH_MAX or (allow_zero and x == 0.0)):
        raise ValueError(f"{name} must lie within [{LENGTH_MIN:g}, {LENGTH_MAX:g}] (the supported lengths), "
                         f"got {value!r}")
    return x


def check_count(name, value, minimum=1, maximum=None):
    """value itself when it is an integer >= minimum (and <= maximum when given: a number of samples, points,
    workers), not a bool, or ValueError naming the argument."""
    if not (isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)) and value >= minimum
            and (maximum is None or value <= maximum)):
        kind = {0: "a non-negative integer", 1: "a positive integer"}.get(minimum, f"an integer >= {minimum}")
        most = "" if maximum is None else f" and at most {maximum}"
        raise ValueError(f"{name} must be {kind}{most}, got {value!r}")
    return value


def check_omega(omega):
    """A driver's rate omega (rad per unit time) as a finite, non-zero float, or ValueError naming it (TypeError
    when its type is no real number's: a str, a bool)."""
    check_real_type("omega", omega)
    try:
        value = float(omega)
    except OverflowError:
        raise ValueError(f"omega must be finite and non-zero, got {TOO_LARGE}") from None
    except (TypeError, ValueError):
        raise ValueError(f"omega must be a real number (rad per unit time), got {omega!r}") from None
    if not math.isfinite(value) or value == 0:
        raise ValueError(f"omega must be finite and non-zero, got {omega!r}")
    return value


def check_choice(name, value, choices):
    """The choice equal to value (one of choices: a branch 1.0 is the choice 1; a bool is no number here), or
    ValueError naming the argument."""
    number = isinstance(value, (bool, np.bool_)) and not any(isinstance(c, bool) for c in choices)
    try:
        found = not number and value in choices
    except (TypeError, ValueError):                  # (an array, whose == is elementwise)
        found = False
    if not found:
        allowed = (" or ".join(repr(c) for c in choices) if len(choices) == 2
                   else "one of " + ", ".join(repr(c) for c in choices))
        raise ValueError(f"{name} must be {allowed}, got {value!r}")
    return choices[list(choices).index(value)]


def check_range(name, value, length=False):
    """(lo, hi) floats with lo < hi (either may be infinite, never NaN); None means unbounded. With length=True
    (a trim of a length parameter) the finite ends lie within LENGTH_MAX of 0, and a finite width is at least
    LENGTH_MIN; or ValueError naming the argument."""
    if value is None:
        return -math.inf, math.inf
    try:
        lo, hi = (float(x) for x in value)
    except OverflowError:
        raise ValueError(f"{name} must have finite or infinite float ends, got {TOO_LARGE}") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (min, max), got {value!r}") from None
    if math.isnan(lo) or math.isnan(hi):
        raise ValueError(f"{name} must not contain NaN, got {value!r}")
    if not lo < hi:
        raise ValueError(f"{name} must satisfy min < max, got ({lo}, {hi})")
    if length and ((math.isfinite(lo) and abs(lo) > LENGTH_MAX) or (math.isfinite(hi) and abs(hi) > LENGTH_MAX)
                   or hi - lo < LENGTH_MIN):
        raise ValueError(f"{name} must have finite ends within {LENGTH_MAX:g} of 0 and a width of at least "
                         f"{LENGTH_MIN:g} (the supported lengths), got ({lo}, {hi})")
    return lo, hi


# --- arrays -------------------------------------------------------------------------------------------------
def check_finite(name, value):
    """value as a float array of any shape with every entry finite, or ValueError naming the argument (TypeError
    naming it when value is no array of real numbers: as_float_array)."""
    arr = as_float_array(name, value)
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} must be finite")
    return arr


def check_point_array(name, value):
    """Points (..., 3) of any leading shape as a finite float array, or ValueError (TypeError) naming the
    argument."""
    arr = check_finite(name, value)
    if arr.shape[-1:] != (3,):
        raise ValueError(f"{name} must have shape (..., 3), got {arr.shape}")
    return arr


def check_query_points(name, value):
    """Points (..., 3) to measure against a surface or a curve, as a float array: finite, each coordinate within
    LENGTH_MAX of 0 (the supported lengths: farther, the squares of the distances overflow); or ValueError
    (TypeError) naming the argument."""
    arr = check_point_array(name, value)
    if arr.size and float(np.max(np.abs(arr))) > LENGTH_MAX:
        raise ValueError(f"{name} must have coordinates within {LENGTH_MAX:g} of 0 (the supported lengths), got "
                         f"{float(np.max(np.abs(arr))):g}")
    return arr


def check_vector(name, value, length=3):
    """value as a finite float array of shape (length,): a point or a direction, or one value per point of a
    polyline; or ValueError naming the argument (and its first entry that is not finite), TypeError naming it
    when value is no array of real numbers (a str, an object)."""
    arr = as_float_array(name, value)
    if arr.shape != (length,):
        raise ValueError(f"{name} must have shape ({length},), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        bad = int(np.argmax(~np.isfinite(arr)))
        raise ValueError(f"{name} must be finite: entry {bad} is {arr[bad]}")
    return arr


def check_points(name, value, count=None, allow_empty=False):
    """Finite points (N, 3) as a float array: N >= 1 unless allow_empty, N == count when given; or
    ValueError naming the argument (and the first row that is not finite; TypeError naming it for values that are no
    real numbers: as_float_array)."""
    pts = as_float_array(name, value)
    if pts.ndim != 2 or pts.shape[1] != 3 or (len(pts) == 0 and not allow_empty):
        least = "" if allow_empty else " with N >= 1"
        raise ValueError(f"{name} must have shape (N, 3){least}, got {pts.shape}")
    if count is not None and len(pts) != count:
        raise ValueError(f"{name} must have {count} rows (one per point), got {len(pts)}")
    if not np.all(np.isfinite(pts)):
        bad = int(np.argmax(~np.all(np.isfinite(pts), axis=1)))
        raise ValueError(f"{name} must be finite: row {bad} is {pts[bad].tolist()}")
    return pts


def check_angles(name, values):
    """Angles (radians) as a finite 1-D float array (a scalar is one angle), or ValueError naming the argument
    (also for an empty one: a motion has at least one position)."""
    refuse_not_real(name, values)
    try:
        angles = np.atleast_1d(np.asarray(values, dtype=float))
    except OverflowError:
        raise ValueError(f"{name} must be a finite 1-D array, got {TOO_LARGE}") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be real numbers (radians), got {values!r}") from None
    if angles.ndim != 1 or not np.all(np.isfinite(angles)):
        raise ValueError(f"{name} must be a finite 1-D array")
    if angles.size == 0:
        raise ValueError(f"{name} is empty: give at least one angle")
    return angles


#: Kinds of numpy arrays that are no real numbers (complex, bool, str, bytes).
NOT_REAL = {"c": "complex", "b": "bool", "U": "str", "S": "bytes"}


def refuse_not_real(name, value):
    """TypeError naming the argument when value holds complex, bool or str values (an array, a list or tuple of
    them, or one of them), which numpy would cast to floats (dropping imaginary parts, reading True as 1, parsing
    '1')."""
    kind = value.dtype.kind if isinstance(value, np.ndarray) else None
    if kind is None and isinstance(value, (list, tuple)):
        try:
            kind = np.asarray(value).dtype.kind
        except (TypeError, ValueError, OverflowError):
            kind = None
    if kind in NOT_REAL:
        raise TypeError(f"{name} must be an array of real numbers, got {NOT_REAL[kind]} values")
    if isinstance(value, (complex, np.complexfloating, bool, np.bool_, str, bytes)):
        raise TypeError(f"{name} must be an array of real numbers, got {type(value).__name__}")


def as_float_array(name, value):
    """np.asarray(value, dtype=float), copied where it is read-only (a curve's own arrays: the kernels are compiled
    for writable arrays, and numba would compile them again for read-only ones), or TypeError naming the argument
    when value is not real numbers (a str, None, an object, complex or bool values: numpy would drop the imaginary
    parts or read True as 1)."""
    if isinstance(value, str) or value is None:
        raise TypeError(f"{name} must be an array of real numbers, got {type(value).__name__}")
    refuse_not_real(name, value)
    try:
        arr = np.asarray(value, dtype=float)
        return arr if arr.flags.writeable else arr.copy()
    except OverflowError:
        raise ValueError(f"{name} must be finite, got {TOO_LARGE}") from None
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be an array of real numbers, got {type(value).__name__}") from None


# --- frames -------------------------------------------------------------------------------------------------
def check_frame(origin, rotation):
    """Validate and return (origin (3,), rotation (3, 3)) of a frame as float arrays, the rotation orthonormalised
    (the nearest proper rotation: see orthonormalised).

    Raises
    ------
    ValueError
        If either is not finite, has the wrong shape, or rotation is not orthonormal (within ORTHONORMAL_TOL)
        and right-handed; or a coordinate of origin is larger than LENGTH_MAX.
    TypeError
        If either is not an array of real numbers.
    """
    origin = check_vector("origin", origin)
    if not (abs(origin[0]) <= LENGTH_MAX and abs(origin[1]) <= LENGTH_MAX and abs(origin[2]) <= LENGTH_MAX):
        raise ValueError(f"origin must have coordinates within {LENGTH_MAX:g} of 0 (the supported lengths), "
                         f"got {origin.tolist()}")
    return origin, orthonormalised("rotation", rotation, ORTHONORMAL_TOL)


def orthonormalised(name, rotation, tol, advice=""):
    """The proper rotation nearest to rotation (3, 3) (its polar factor, U V^T of its SVD U S V^T) when
    max |R^T R - I| <= tol; rotation itself as a float array when it is orthonormal to round-off already
    (ROUNDOFF_DEVIATION).

    Parameters
    ----------
    name : str
        The argument's name, for the messages.
    rotation : array_like (3, 3)
        Columns = local x, y, z in global coordinates.
    tol : float
        Largest accepted max |R^T R - I| (entrywise): the caller's own (ORTHONORMAL_TOL for a frame).
    advice : str
        Appended to the message when rotation is too far from orthonormal (how to give a better one).

    Returns
    -------
    ndarray (3, 3)
        Orthonormal to round-off, determinant +1; within about max |R^T R - I| / 2 of rotation (entrywise).

    Raises
    ------
    ValueError
        Naming the argument when rotation is not a finite (3, 3) array, is farther than tol from orthonormal
        (with the measured deviation), or is a reflection (det < 0).

    References
    ----------
    N. J. Higham, Functions of Matrices, SIAM 2008, Theorem 8.4 (the polar factor is the nearest orthogonal
    matrix in the Frobenius norm).
    """
    rot = as_float_array(name, rotation)
    if rot.shape != (3, 3):
        raise ValueError(f"{name} must have shape (3, 3), got {rot.shape}")
    if not np.all(np.isfinite(rot)):
        raise ValueError(f"{name} must be finite")
    deviation = float(np.max(np.abs(rot.T @ rot - np.eye(3))))
    if deviation > tol:
        raise ValueError(f"{name} must be orthonormal: max |R^T R - I| = {deviation:.3g} > {tol:g}{advice}")
    if np.linalg.det(rot) < 0:
        raise ValueError(f"{name} must be right-handed (det = +1), got a reflection (det = -1)")
    if deviation <= ROUNDOFF_DEVIATION:
        return rot
    u, _, vt = np.linalg.svd(rot)
    return u @ vt
