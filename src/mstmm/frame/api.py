"""The frame solver users call: the undamped frame's count (:mod:`.solve`) or the damped
frame's search (:mod:`.damped`), by what the frame carries."""

from __future__ import annotations

from .damped import DampedFrameSolution, is_damped, solve_damped_frame
from .model import Frame
from .solve import FrameSolution, solve_undamped_frame

__all__ = ["solve_frame"]


def solve_frame(
    frame: Frame,
    modes: int | None = None,
    band: tuple[float, float] | None = None,
    *,
    shapes: bool = True,
) -> FrameSolution | DampedFrameSolution:
    """The lowest ``modes`` natural frequencies of ``frame`` (default 10), or all in
    ``band`` (rad/s), and their mode shapes: each with its exact multiplicity
    (:func:`.solve.solve_undamped_frame`), or, with dashpots (an absorber's ``c``) or loss
    factors, the damped roots ``w_d + i sigma`` (:func:`.damped.solve_damped_frame`)."""
    if is_damped(frame):
        return solve_damped_frame(frame, modes, band, shapes=shapes)
    return solve_undamped_frame(frame, modes, band, shapes=shapes)
