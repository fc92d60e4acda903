"""A case file a tool writes, held to the one the repository keeps: the same text but for its
numbers, which must agree to a relative tolerance. The tools evaluate closed forms and series
with numpy and scipy, whose exp, logarithms, trigonometry and Bessel functions the libraries pick
by the CPU's vector units (FMA or not, AVX2 or AVX-512), so another machine rounds their last bits
differently. Roots bisected to adjacent doubles and the series' exponentials carry that further,
and the lid velocities divide differences of settlements up to 500 times smaller than the
settlements: written on a machine with FMA, the radial-consolidation lid's velocities differed from
the kept ones by up to 4.3e-11 relative, Mandel's by 2e-13. Each test gives its bound from what it
saw; a lid moved by 1e-9 of its motion differs by nothing the verification cases can see (their
tolerances are 1e-3 and more)."""
import re

import pytest

NUMBER = re.compile(r"-?\d+\.\d*(?:e[-+]?\d+)?|-?\d+e[-+]?\d+")


def assert_same_case(written, kept, relative):
    """`written` is `kept` but for numbers within `relative` of each other."""
    assert NUMBER.sub("#", written) == NUMBER.sub("#", kept)
    assert [float(x) for x in NUMBER.findall(written)] == pytest.approx(
        [float(x) for x in NUMBER.findall(kept)], rel=relative, abs=0.0)
