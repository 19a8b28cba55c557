"""Plane frames, trees and closed loops of members (issue 43; docs/frames.md).

A frame scene (TOML) has ``[[nodes]]`` and ``[[members]]`` instead of a ``[beam]``
(:mod:`mstmm.frame.reading`); each member carries axial (rod) motion and in-plane bending
with every segment term a beam declares. Its natural frequencies come from the members'
exact dynamic stiffness assembled at the joints and counted by Wittrick-Williams, so that
no root is missed and each repeated root has its exact multiplicity
(:mod:`mstmm.frame.solve`); dashpots and loss factors give damped roots
(:mod:`mstmm.frame.damped`).
"""

from .api import solve_frame
from .damped import DampedFrameSolution
from .model import Absorber, Frame, FrameSegment, Member, Node
from .reading import frame_from_dict, frame_from_file, is_frame, load_frame
from .response import frf
from .solve import FrameSolution

__all__ = [
    "Absorber",
    "DampedFrameSolution",
    "Frame",
    "FrameSegment",
    "FrameSolution",
    "Member",
    "Node",
    "frame_from_dict",
    "frame_from_file",
    "frf",
    "is_frame",
    "load_frame",
    "solve_frame",
]
