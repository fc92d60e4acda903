"""tools/sweep_table.py: columns parsed, scaled, rounded and labelled; unreached values as "-";
an unknown column refused naming what the sweep has."""
import math
import pathlib
import sys

import pandas as pd
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tools"))
import sweep_table as st  # noqa: E402


def test_a_column_is_name_scale_digits_label():
    assert st.parse_column("tip_F_y") == ("tip_F_y", 1.0, None, "tip_F_y")
    assert st.parse_column("tip_F_y:1e-3:2") == ("tip_F_y", 1e-3, 2, "tip_F_y")
    assert st.parse_column("tip_F_y:1e-3:2:tip (kN/rad)") == ("tip_F_y", 1e-3, 2, "tip (kN/rad)")
    assert st.parse_column("time::3") == ("time", 1.0, 3, "time")


def test_rows_are_scaled_rounded_and_unreached_values_are_dashes():
    frame = pd.DataFrame({"amplitude": [207250.0, 414500.0], "time": [0.1234, math.nan],
                          "force": [-26512.0, 3999.6]})
    columns = [st.parse_column(c) for c in ("amplitude:1e-3:2:M (kN m/rad)", "time::3", "force:1e-3:1")]
    assert st.table(frame, columns) == [
        "| M (kN m/rad) | time | force |",
        "|---|---|---|",
        "| 207.25 | 0.123 | -26.5 |",
        "| 414.50 | - | 4.0 |",
    ]


def test_an_unknown_column_is_refused_naming_the_sweeps_columns():
    frame = pd.DataFrame({"time": [0.1]})
    with pytest.raises(SystemExit, match="no column tiem .*has: time"):
        st.table(frame, [st.parse_column("tiem")])
