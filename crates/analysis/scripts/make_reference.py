#!/usr/bin/env python3
"""Regenerates the reference data of vsrlab-analysis's tests (crates/analysis/tests/data/).

- iris.csv, wine.csv, digits.csv: scikit-learn's bundled data sets, rows shuffled once with
  numpy's RandomState(0) so that unshuffled k-fold splits mix the classes; last column = class.
- forest_reference.json: scikit-learn RandomForestClassifier(n_estimators=100,
  max_features='sqrt', random_state=s) 5-fold (KFold, unshuffled, on the shuffled rows) mean
  accuracy for s = 0..9, and its mean over the seeds, per data set.
- mannwhitney_reference.json: scipy.stats.mannwhitneyu(x, y) (defaults: two-sided,
  use_continuity=True, method='auto') on fixed samples, with and without ties, small and large.

Usage (from the repository root):
    python3 -m venv crates/analysis/scripts/.venv
    crates/analysis/scripts/.venv/bin/pip install scikit-learn scipy numpy
    crates/analysis/scripts/.venv/bin/python crates/analysis/scripts/make_reference.py
"""
import json
import os

import numpy as np
import scipy
import sklearn
from scipy.stats import mannwhitneyu
from sklearn.datasets import load_digits, load_iris, load_wine
from sklearn.ensemble import RandomForestClassifier
from sklearn.model_selection import KFold, cross_val_score

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "tests", "data")
SEEDS = range(10)


def fmt(v):
    v = float(v)
    return str(int(v)) if v.is_integer() else repr(v)


def export(name, loader):
    d = loader()
    order = np.random.RandomState(0).permutation(len(d.target))
    x, y = d.data[order], d.target[order]
    path = os.path.join(DATA, f"{name}.csv")
    with open(path, "w") as f:
        f.write(",".join([f"f{i}" for i in range(x.shape[1])] + ["class"]) + "\n")
        for row, c in zip(x, y):
            f.write(",".join(fmt(v) for v in row) + f",{int(c)}\n")
    return x, y


def forest(x, y):
    scores = []
    for s in SEEDS:
        clf = RandomForestClassifier(n_estimators=100, max_features="sqrt", random_state=s)
        scores.append(float(np.mean(cross_val_score(clf, x, y, cv=KFold(n_splits=5, shuffle=False)))))
    return scores


def mann_whitney_cases():
    rng = np.random.RandomState(42)
    cases = {
        "small-exact": ([1.1, 2.3, 0.4, 5.6, 3.3], [2.2, 7.1, 6.5, 4.4]),
        "small-exact-separated": ([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]),
        "small-vs-large-exact": (list(rng.normal(0.3, 1, 6)), list(rng.normal(0, 1, 40))),
        "eight-each-exact": (list(rng.normal(0.8, 1, 8)), list(rng.normal(0, 1, 8))),
        "small-ties": ([1, 2, 2, 3, 5], [2, 3, 3, 4, 6, 6]),
        "ten-each-no-ties": (list(rng.normal(0.5, 1, 10)), list(rng.normal(0, 1, 10))),
        "ten-each-ties": (list(rng.randint(0, 6, 10).astype(float)), list(rng.randint(1, 7, 10).astype(float))),
        "large-no-ties": (list(rng.normal(0.2, 1, 120)), list(rng.normal(0, 1, 150))),
        "large-ties": (list(rng.randint(0, 20, 200).astype(float)), list(rng.randint(2, 22, 180).astype(float))),
        "identical": ([3.0, 3.0, 3.0], [3.0, 3.0]),
        "far-apart-large": (list(rng.normal(0, 1, 30)), list(rng.normal(5, 1, 30))),
    }
    out = []
    for name, (x, y) in cases.items():
        r = mannwhitneyu(x, y)
        out.append({"name": name, "x": [float(v) for v in x], "y": [float(v) for v in y],
                    "u": float(r.statistic), "p": float(r.pvalue)})
    return out


def main():
    os.makedirs(DATA, exist_ok=True)
    ref = {"sklearn": sklearn.__version__, "numpy": np.__version__, "seeds": list(SEEDS),
           "protocol": "RandomForestClassifier(n_estimators=100, max_features='sqrt', random_state=s); "
                       "cross_val_score with KFold(n_splits=5, shuffle=False) on the stored row order",
           "datasets": {}}
    for name, loader in [("iris", load_iris), ("wine", load_wine), ("digits", load_digits)]:
        x, y = export(name, loader)
        scores = forest(x, y)
        ref["datasets"][name] = {"rows": int(len(y)), "features": int(x.shape[1]),
                                 "classes": int(len(set(y))), "accuracy_per_seed": scores,
                                 "mean_accuracy": float(np.mean(scores))}
        print(f"{name}: sklearn mean 5-fold accuracy {np.mean(scores):.4f}")
    with open(os.path.join(DATA, "forest_reference.json"), "w") as f:
        json.dump(ref, f, indent=1)
    mw = {"scipy": scipy.__version__, "call": "scipy.stats.mannwhitneyu(x, y) with defaults",
          "cases": mann_whitney_cases()}
    with open(os.path.join(DATA, "mannwhitney_reference.json"), "w") as f:
        json.dump(mw, f, indent=1)
    print(f"{len(mw['cases'])} Mann-Whitney cases written")


if __name__ == "__main__":
    main()
