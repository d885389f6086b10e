"""One rule for one situation: a caption says the motion leaves at a rate the exact threshold calls stable.

Figs. 10 RHS, 11 RHS and 18 RHS are the same situation: the panel's rate lies on the stable side
of the exact linear threshold (:mod:`.thresholds`), yet the caption says theta leaves (exceeds
pi/2, spirals out); the full equations leave only from a start more than a finite offset from the
equilibrium.  What the caption implies about the rate (unstable, unlike the other panel) is wrong
in every such case; whether its figure is right depends on the start alone.  So, in the claims and
in the thresholds table alike:

* the rate is linearly unstable: not this situation (the run decides, confirmed or erratum);
* the caption's start leaves: **qualified** -- the figure is reproduced, the threshold it implies
  is not; the qualification states the exact threshold and the offset needed;
* the caption's start stays: **erratum** -- the paper's own start does not give its figure;
* the run cannot be read (its two measures disagree), or it disagrees with the bisection of the
  offset (a start beyond the bracket that stays, or within it that leaves): **not checkable**.

"The caption's start" is the start as the caption gives it: a stated offset (Fig. 10: Delta theta =
.0002, its sign unstated, read as +), or, where the caption says only that the body was started
*near* its equilibrium (Fig. 11: "near its equilibrium angle theta_0"; Fig. 18: "near theta_0 =
0"), the offset the paper itself uses for such a start, stated in the claim's reading.
"""
from __future__ import annotations

from typing import Optional

QUALIFIED, ERRATUM, NOT_CHECKABLE = "qualified", "erratum", "not-checkable"  # the words of verify.claims.base

#: The rule in one sentence, for the report.
RULE = ("One rule for every caption that says the motion leaves at a rate the exact linear threshold calls stable "
        "(Figs. 10 RHS, 11 RHS, 18 RHS): what it implies about the rate is wrong, and the verdict follows the "
        "caption's start -- qualified when the run from it leaves (the figure is reproduced; the threshold and the "
        "offset needed are stated), erratum when it stays (the paper's own start does not give the figure). A start "
        "given only as 'near' the equilibrium is read with the offset the paper itself uses for such a start.")


def finite_offset_verdict(linearly_stable: bool, leaves_from_start: Optional[bool], start_offset: Optional[float] = None,
                          bracket: Optional[tuple] = None) -> Optional[str]:
    """The verdict of the rule of this module, or None when the rate is linearly unstable (not this situation).

    Parameters
    ----------
    linearly_stable : bool
        The panel's rate lies on the stable side of the exact linear threshold.
    leaves_from_start : bool or None
        The run from the caption's start leaves (two measures agreeing), stays (False), or its
        measures disagree (None).
    start_offset : float, optional
        The caption's start, as an offset from the equilibrium towards leaving.
    bracket : (float, float), optional
        (stays at, leaves at): the bisection of the smallest such offset that leaves.  Given, it
        must agree with the run: a start beyond it that stays, or within it that leaves, is not
        checkable.
    """
    if not linearly_stable:
        return None
    if leaves_from_start is None:
        return NOT_CHECKABLE
    if bracket is not None:
        lo, hi = bracket
        if (leaves_from_start and not start_offset >= hi) or (not leaves_from_start and not start_offset <= lo):
            return NOT_CHECKABLE
    return QUALIFIED if leaves_from_start else ERRATUM
