"""Every status a Curve or a TracingError carries, what it means, and the messages that go with them: one table.

A status is a short code (a plain string, scipy's ``OdeResult.status`` style); the message is a sentence on where
and why. The integration loop (spatialkin.tracing.march.ivp) ends each branch with one of the end statuses below and a
message naming the arc length and the point; everything else that writes a status or a message takes it from
here.
"""
import textwrap

#: Line width of the status list written into docstrings (describe).
DOC_WIDTH = 116

CLOSED = "closed"
SINGULAR = "singular"
BOUNDARY = "boundary"
MAX_LENGTH = "max_length"
FAILED = "failed"
CONTACT = "contact"
TANGENT = "tangent"
NO_START = "no_start"

#: status -> what it means, for a Curve (CURVE_STATUSES) and for a TracingError (FAILED, NO_START, or the status of
#: the case it could not handle).
MEANINGS = {
    CLOSED: "a closed loop: the last point is the first (exactly), ``length`` is the period",
    SINGULAR: "an end at a singular point that was not passed (branches cross, the surfaces touch, or a "
              "parametrisation degenerates: the apex of a cone, the axis point of a horn or spindle torus)",
    BOUNDARY: "an end exactly on a trim edge of a surface (length 0: the faces meet in one point of their edges)",
    MAX_LENGTH: "an end at max_length without closing",
    FAILED: "the integration or the Newton correction failed (a TracingError's; the message says where)",
    CONTACT: "a single point where the surfaces touch (length 0)",
    TANGENT: "a circle or a segment along which the surfaces touch, in closed form (the tracer cannot follow it: "
             "the normals are parallel all along)",
    NO_START: "no intersection point was found near the start given (a TracingError only)",
}

#: The statuses a Curve can carry ('failed' is a TracingError's only: a curve that cannot be traced to its end
#: raises, saying where and why).
CURVE_STATUSES = (CLOSED, SINGULAR, BOUNDARY, MAX_LENGTH, CONTACT, TANGENT)

#: Precedence of an open curve's status when its two ends differ: the first listed wins.
END_PRECEDENCE = (SINGULAR, BOUNDARY, MAX_LENGTH)

#: event -> (status, message template): the messages written outside the integration loop. An open curve's
#: status comes from its ends (END_PRECEDENCE), hence None for "open".
MESSAGES = {
    "open": (None, "start end: {start}; finish end: {finish}"),
    "contact": (CONTACT, "the surfaces touch at {point}"),
    "edge_point": (BOUNDARY, "the faces meet in this one point {point} of their edges"),
    "tangent": (TANGENT, "the surfaces touch all along this {shape}"),
    "axis_circle": (CLOSED, "a circle about the surfaces' common axis, in closed form"),
    "singular_start": (SINGULAR, "start {point} is a singular point of the intersection (normals parallel, "
                                 "sin = {sin:.2g}): no tangent to follow"),
    "nothing_traced": (None, "nothing could be traced from {point}: {message}"),
    "no_start": (NO_START, "no intersection point found near start {point}: Newton on M1 = M2 did not converge"),
    "off_curve": (FAILED, "the start {point} lies off the curve, within the gap tolerance of both surfaces where they "
                          "nearly touch: the march from it went round a loop through {rejoin} that does not pass it"),
    "branch_failed": (FAILED, "the curve could not be traced past {point}: {message}"),
    "runs_over_itself": (FAILED, "the curve runs over itself: its end {point} lies {gap:.2g} from its own path at "
                                 "s = {s:.6g} (a jump across a singular point landed on a branch followed already: "
                                 "a loop through that point shorter than the jump)"),
    "outside_trims": (NO_START, "the component through start {point} lies outside the trims of the surfaces"),
    # the ends of a branch (spatialkin.tracing.march.ivp)
    "closed": (CLOSED, "closed on its start after s = {s:.12g}"),
    "closed_in_jump": (CLOSED, "closed on its start, within a jump, after s = {s:.12g}"),
    "edge": (BOUNDARY, "reached the edge {edge} of surface {surface} at s = {s:.6g}"),
    "leaves_edge": (BOUNDARY, "starts on an edge, leaving the surface, at s = {s:.6g}"),
    "max_length": (MAX_LENGTH, "stopped at max_length = {max_length:.6g} without closing"),
    "newton_singular": (SINGULAR, "singular point (normals nearly parallel, sin = {sin:.2g}; Newton cannot separate "
                                  "the branches) at s = {s:.6g}, point {point}"),
    "not_passed": (SINGULAR, "{what}, not passed, at s = {s:.6g}, point {point}, sin of the normals' angle "
                             "{sin:.2g}"),
    "solver_singular": (SINGULAR, "singular point (normals parallel) near s = {s:.6g}"),
    "newton_failed": (FAILED, "Newton correction failed at s = {s:.6g}"),
    "stalled": (FAILED, "the segment's budget of {budget} right-hand-side evaluations ran out at s = {s:.6g}, near "
                        "point {point} (the budget is per segment: a shorter max_length asks for less)"),
    "solver_failed": (FAILED, "solve_ivp failed at s = {s:.6g}: {message}"),
    "too_many_segments": (FAILED, "more than {count} segments"),
    "lapped": (FAILED, "went round a loop that does not pass the start (the start lies off the curve, where the "
                       "surfaces nearly touch) at s = {s:.6g}, point {point}"),
}


def check_status(status):
    """The status, if the table knows it; ValueError otherwise."""
    if status not in MEANINGS:
        raise ValueError(f"unknown status {status!r}; known: {', '.join(MEANINGS)}")
    return status


def outcome(event, **fields):
    """(status, message) of an event of MESSAGES, its template filled with fields."""
    status, template = MESSAGES[event]
    return status, template.format(**fields)


def open_outcome(start_status, start_message, finish_status, finish_message):
    """(status, message) of an open curve from those of its two ends (start end: the backward branch)."""
    status = min((start_status, finish_status), key=END_PRECEDENCE.index)
    return status, outcome("open", start=start_message, finish=finish_message)[1]


def describe(statuses, indent, width=DOC_WIDTH):
    """The numpydoc list ``- 'status': meaning`` of the given statuses, indented by `indent` spaces and wrapped at
    `width` characters."""
    pad = " " * indent
    return "\n".join(textwrap.fill(f"- ``'{s}'``: {MEANINGS[s]}", width, initial_indent=pad,
                                   subsequent_indent=pad + "  ") for s in statuses)
