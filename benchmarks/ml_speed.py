"""Wall time of the hand-written estimators against scikit-learn's, measured side by side.

The sweep lives in :mod:`ebantenna.bench.ml_speed`, so that ``ebantenna bench`` can gather
it into one report; this script runs it alone. Run: ``python benchmarks/ml_speed.py --help``.
"""

from ebantenna.bench.ml_speed import main

if __name__ == "__main__":
    main()
