"""Run by installed.cmake (not by pytest): the module installed under the
prefix given as argv[1] imports from there and evaluates a field."""
import pathlib
import sys

import magfoam as mf

assert pathlib.Path(mf.__file__).resolve().is_relative_to(pathlib.Path(sys.argv[1]).resolve()), mf.__file__
s = mf.System()
s.add_body("m", box=[0.01] * 3, Br=1.0, magnetization=[0, 0, 1])
print(mf.__file__, mf.modules()["field"], s.field([0, 0, 0])[2])
