"""The sim-to-real study's leave-one-record-out choice of simulator settings never
looks at the record it scores (benchmarks/sim2real.py)."""


import pandas as pd
import pytest
from _bench import load_benchmark

pytest.importorskip("sklearn")
sim2real = load_benchmark("sim2real", "sim2real_bench")


def _pred(rows):
    return pd.DataFrame(rows, columns=["variant", "model", "test", "record", "y_true", "y_pred"])


def test_loro_choice_ignores_the_held_out_record():
    # record r1 has 3 segments, r2 one; variant "a" is right on r1 only, "b" on r2 only.
    # Chosen with r1 in view, "a" would win for r1 (3/4 of all segments) and score it
    # right; held out, r1 gets "b" (the best on r2) and r2 gets "a" (the best on r1):
    # both wrong, the honest score of choosing settings on records is 0 here
    rows = []
    for variant, right in (("a", "r1"), ("b", "r2")):
        for rec, label, n in (("r1", "inner", 3), ("r2", "outer", 1)):
            rows += [(variant, "m", "real DE", rec, label,
                      label if rec == right else "ball")] * n
    sel = sim2real.loro_selected(_pred(rows), "m")
    assert dict(zip(sel.record, sel.chosen, strict=False)) == {"r1": "b", "r2": "a"}
    assert sim2real.score(sel)["accuracy_nio"] == 0.0


def test_goal_score_counts_a_ball_answer_as_an_error_and_reports_ball_apart():
    rows = [("v", "m", "t", "r1", "healthy", "ball"), ("v", "m", "t", "r2", "inner", "inner"),
            ("v", "m", "t", "r3", "ball", "ball"), ("v", "m", "t", "r4", "outer", "outer")]
    s = sim2real.score(_pred(rows))
    assert s["n_goal"] == 3
    assert s["accuracy_nio"] == pytest.approx(2 / 3)
    assert s["recall_ball"] == 1.0 and s["recall_healthy"] == 0.0
